"""Polishing patches (``polyloops.segment.polish``): every move it makes keeps the patches' cell
complex, checked against the complex computed from scratch by independent code; it never
lowers what it maximises; a polished layout or labelling is certified as the one it came from."""

from collections import Counter

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.core.directions import Direction
from polyloops.io.examples import load_example
from polyloops.segment.labellings import fidelity, graphcut_labels, naive_labels
from polyloops.segment.layout import lay_out
from polyloops.segment.polish import Fans, edge_costs, move_keeps, polish, polish_labels, polish_layout, worth
from polyloops.segment.run import _certify, segment_mesh
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.shapes.meshes import _subdivide, ellipsoid
from polyloops.surface.construct import labelled_mesh_from_polycube
from polyloops.surface.mesh import LabelledMesh
from strategies import polycubes


def complex_of(triangles: np.ndarray, patch: np.ndarray):
    """The cell complex of the patches, from scratch: per patch its Euler characteristic and
    number of boundary curves; per pair of patches beside each other the number of curves
    they share; the sets of patches met at the corners (vertices met by three or more)."""
    patch = np.asarray(patch)
    meets: dict[int, set[int]] = {}
    for t, tri in enumerate(triangles.tolist()):
        for v in tri:
            meets.setdefault(v, set()).add(int(patch[t]))
    corners = Counter(frozenset(s) for s in meets.values() if len(s) >= 3)
    owner = {}
    for t, (a, b, c) in enumerate(triangles.tolist()):
        owner[a, b] = owner[b, c] = owner[c, a] = t
    shared: dict[frozenset[int], list[tuple[int, int]]] = {}
    for (u, v), t in owner.items():
        f, g = int(patch[t]), int(patch[owner[v, u]])
        if f < g:
            shared.setdefault(frozenset((f, g)), []).append((u, v))
    curves = {}
    for pair, edges in shared.items():  # the shared edges' pieces, joined at vertices not corners
        parent = {e: e for e in range(len(edges))}

        def root(e, parent=parent):
            while parent[e] != e:
                e = parent[e]
            return e
        at: dict[int, list[int]] = {}
        for i, (u, v) in enumerate(edges):
            for w in (u, v):
                if len(meets[w]) < 3:
                    at.setdefault(w, []).append(i)
        for ids in at.values():
            for i in ids[1:]:
                parent[root(i)] = root(ids[0])
        curves[pair] = len({root(i) for i in range(len(edges))})
    shapes = {}
    for p in np.unique(patch).tolist():
        mine = triangles[patch == p]
        edges = {(min(u, v), max(u, v)) for a, b, c in mine.tolist() for u, v in ((a, b), (b, c), (c, a))}
        shapes[p] = len(np.unique(mine)) - len(edges) + len(mine)
    return shapes, curves, corners


def _fine_polycube_mesh(q, times: int):
    """A polycube's surface subdivided ``times``, each triangle's label, and its face (two
    triangles a face, each triangle's four children in order)."""
    m = labelled_mesh_from_polycube(q)
    points, tris = np.array(m.points, dtype=float), np.array(m.triangles)
    labels = np.array([int(d) for d in m.labels])
    face = np.repeat(np.arange(len(q.faces)), 2)
    for _ in range(times):
        points, tris = _subdivide(points, tris)
        labels, face = np.repeat(labels, 4), np.repeat(face, 4)
    return points, tris, labels, face


@settings(max_examples=12, deadline=None)
@given(polycubes(max_size=4), st.integers(0, 2**32 - 1))
def test_every_move_keeps_the_complex_computed_from_scratch(q, seed):
    """On a polycube's subdivided surface, its faces as patches (as in a layout), random worths:
    after every move ``polish`` makes, each patch is still a disc, each pair of patches shares
    as many curves, the corners meet the same patches, and the corners followed are where they
    are."""
    points, tris, labels, patch = _fine_polycube_mesh(q, 2)
    direction = np.zeros(patch.max() + 1, dtype=np.int64)
    direction[patch] = labels
    rng = np.random.default_rng(seed)
    value = rng.uniform(0, 1, (len(tris), 6))
    before = complex_of(tris, patch)
    assert all(chi == 1 for chi in before[0].values())
    fans = Fans(tris)
    corner_of = {}
    for v in range(len(points)):
        runs = {int(patch[t]) for t in fans.fan(v)}
        if len(runs) >= 3:
            corner_of[v] = frozenset(runs)
    steps, now, corners = 0, patch.copy(), list(corner_of)
    while True:  # one move at a time, each checked
        done = polish(tris, value, now, direction, corners, max_moves=1)
        if done.moves == 0:
            break
        steps += 1
        assert done.gain > 0
        now, corners = done.patch, list(done.corners)
        assert complex_of(tris, now) == before
        for v, was in zip(corners, corner_of.values(), strict=True):
            assert {int(now[t]) for t in fans.fan(v)} == was
        if steps >= 40:
            break


def _mesh(points, tris, labels) -> LabelledMesh:
    return LabelledMesh(tuple(map(tuple, points.tolist())), tuple(map(tuple, tris.tolist())),
                        tuple(Direction(int(k)) for k in labels))


def test_every_move_allowed_keeps_the_complex_and_the_refused_would_break_it():
    """On a cube's surface after random polishing (jagged patch edges), every move of every
    triangle to a patch beside it: each one allowed keeps the complex computed from scratch, and
    among those refused some would change it (a patch pinched, cut, or a corner made or lost)."""
    _, tris, labels, patch = _fine_polycube_mesh(load_example("cube"), 2)
    direction = np.zeros(patch.max() + 1, dtype=np.int64)
    direction[patch] = labels
    value = np.random.default_rng(7).uniform(0, 1, (len(tris), 6))
    patch = polish(tris, value, patch, direction, max_moves=60).patch
    fans = Fans(tris)
    here = complex_of(tris, patch)
    breaking = 0
    for t in range(len(tris)):
        for g in {int(patch[u]) for u in fans.neighbours(t)} - {int(patch[t])}:
            trial = patch.copy()
            trial[t] = g
            same = complex_of(tris, trial) == here
            if move_keeps(fans, patch.tolist(), t, g) is not None:
                assert same
            breaking += not same
    assert breaking > 0


def _energy(surface, labels, patch) -> float:
    """What polishing lowers: the worth given up (area times 1 - n . label) and the cost of the
    patch edges."""
    worths = worth(surface)
    lost = float((surface.areas - worths[np.arange(len(patch)), [int(d) for d in labels]]).sum())
    fans = Fans(surface.triangles)
    costs = edge_costs(surface)
    return lost + float((costs * (np.asarray(patch)[fans.across] != np.asarray(patch)[:, None])).sum()) / 2


def test_a_polished_layout_is_certified_and_lowers_the_energy():
    """A search's structure on an ellipsoid, laid out again and polished: the same polycube,
    certified by both checks, a lower energy (and without the edges' cost, a higher fidelity),
    its corners where three patches or more meet; the run kept the polished labels."""
    result = segment_mesh(*ellipsoid(2.0, 1.0, 0.7, level=3), budget=1, direct=False)
    assert result.layout is not None
    drawn = lay_out(result.layout.embedded.refined, result.layout.embedded.loops)
    again = polish_layout(drawn)
    assert again.polycube is drawn.polycube
    assert not isinstance(_certify(again), str)
    surface = drawn.embedded.refined.surface
    assert _energy(surface, again.labels, again.patch) < _energy(surface, drawn.labels, drawn.patch)
    assert fidelity(surface, again.labels) == pytest.approx(result.fidelity)
    faithful = polish_layout(drawn, compactness=0.0)
    assert fidelity(surface, faithful.labels) > fidelity(surface, drawn.labels)
    fans = Fans(drawn.embedded.refined.triangles)
    for v in again.corners:
        assert len({int(again.patch[t]) for t in fans.fan(v)}) >= 3


def test_polished_labels_keep_the_checkers_verdict():
    """A graph-cut labelling, polished without the edges' cost: the checker's verdict, its
    charts and corners stay, and the fidelity rises; a per-triangle labelling has nothing to
    move."""
    points, tris = ellipsoid(1.5, 1, 0.7, level=3)
    s = surface_of(points, tris)
    labels = graphcut_labels(s, 0.3)
    polished, moved = polish_labels(s, labels, compactness=0.0)
    a, b = (check_segmentation(_mesh(points, tris, [int(d) for d in ls])) for ls in (labels, polished))
    assert a.valid == b.valid and len(a.segmentation.charts) == len(b.segmentation.charts)
    assert len(a.segmentation.corners) == len(b.segmentation.corners)
    assert fidelity(s, polished) > fidelity(s, labels) and moved > 0
    assert polish_labels(s, naive_labels(s), compactness=0.0)[1] == 0


@settings(max_examples=10, deadline=None)
@given(polycubes(max_size=5))
def test_on_a_polycube_its_own_structure_could_reach_fidelity_one(q):
    """On a polycube's own surface and its own loops (the level start), the search's score
    (each triangle the best direction among its region's faces) is 1: every triangle lies in a
    face of its region's corner.  The scouting's estimate (the rough layout, each triangle the
    face of its nearest crossing, polished) lies between the rough layout's fidelity and 1:
    polishing keeps the rough patches' complex, which need not be the polycube's."""
    from polyloops.segment.levels import level_grid
    from polyloops.segment.polish import polished_fidelity
    from polyloops.segment.search import _Scorer, nearest_faces

    m = labelled_mesh_from_polycube(q)
    s = surface_of(np.array(m.points, dtype=float), np.array(m.triangles))
    g = level_grid(s)
    r = g.embedded.refined
    assert _Scorer(r).fidelity(g.embedded) == pytest.approx(1.0)
    q2 = g.embedded.polycube
    rough = [q2.face_normal(int(f)) for f in nearest_faces(r, g.embedded)]
    assert fidelity(r.surface, rough) - 1e-9 <= polished_fidelity(r, g.embedded) <= 1 + 1e-9
