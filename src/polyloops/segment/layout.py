"""Primalization on the surface: corners, paths and patches, and the labels they give.

Each region (a corner of the polycube) gets a corner vertex inside it (where the boundaries
between its patches of different directions are cheapest together), and each of its sides (a
segment of a loop, dual to a polycube edge) a point in its middle that both regions beside it
share.  Paths inside the region join the corner to the points of its sides, meeting only at the
corner (:func:`~polyloops.segment.flow.disjoint_paths`, the shortest such), so they cut the
region into one sector per crossing on its boundary.  The four sectors round a crossing make
the patch of the polycube's face dual to it, and its triangles get that face's normal as label.
Where a region leaves no room (a side that is one edge, a region without an inner vertex, paths
that cannot keep apart) the surface is refined there and the structure read again.

>>> from polyloops.shapes.meshes import sphere
>>> from polyloops.segment.refine import Plane, Refined, cut
>>> from polyloops.segment.surface import surface_of
>>> from polyloops.segment.embedded import SurfaceLoop
>>> r = cut(Refined.of(surface_of(*sphere(3))), [Plane(0, 0.01), Plane(1, 0.02), Plane(2, 0.03)])
>>> lay = lay_out(r, [SurfaceLoop(p, r.sections(p)[0]) for p in range(3)])
>>> len(set(lay.labels)), len(lay.paths)
(6, 8)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from itertools import pairwise

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components, dijkstra

from polyloops.core.directions import Direction
from polyloops.core.errors import PolyloopsError
from polyloops.core.polycube import Polycube
from polyloops.segment.embedded import Embedded, Loop, NotAStructure, PathLoop, SurfaceLoop, read_structure
from polyloops.segment.flow import disjoint_paths
from polyloops.segment.labellings import naive_label_indices
from polyloops.segment.refine import Refined, split_edges

__all__ = ["Layout", "lay_out"]

MAX_ROUNDS = 6  # refinements before a layout is given up (each at least halves the edges in the way)
CORNER_TRIES = 4  # corner vertices tried in a region before it is refined
FEATURE_DISCOUNT = 0.2  # a length of path along a change of the per-triangle label costs this much
DEPTH_WEIGHT = 0.25  # how much being deep inside a region counts beside agreeing with its faces
JOIN_WEIGHT = 1.0  # per typical edge length of the label boundaries to the corner, against agreement


@dataclass(frozen=True, eq=False)
class Layout:
    """A labelled layout: the embedded structure it lays out, the polycube primalized from it,
    per region its corner vertex and paths, per triangle its patch (the crossing's face index)
    and label."""

    embedded: Embedded
    polycube: Polycube
    corners: tuple[int, ...]
    paths: tuple[tuple[tuple[int, ...], ...], ...]
    patch: np.ndarray
    labels: tuple[Direction, ...]


def relocate(r: Refined, loops: Sequence[Loop]) -> list[Loop]:
    """The same loops on a further refined ``r`` (a refinement keeps the old vertices and puts
    a new one in the middle of each edge it cuts)."""
    out: list[Loop] = []
    for lp in loops:
        if isinstance(lp, SurfaceLoop):
            mark = lp.vertices[0]
            out.append(next(SurfaceLoop(lp.plane, c) for c in r.sections(lp.plane) if mark in c))
            continue
        vs: list[int] = []
        for a, b in zip(lp.vertices, lp.vertices[1:] + lp.vertices[:1], strict=True):
            vs.append(a)
            if (a, b) not in r.owner:  # cut: its middle is the one vertex beside both ends
                around_a = {v for t in r.incident[a] for v in r.triangles[t].tolist()}
                around_b = {v for t in r.incident[b] for v in r.triangles[t].tolist()}
                middle = [v for v in around_a & around_b
                          if np.allclose(r.points[v], (r.points[a] + r.points[b]) / 2)]
                vs.append(middle[0])
        out.append(PathLoop(lp.axis, tuple(vs)))
    return out


def lay_out(r: Refined, loops: Sequence[Loop], follow_labels: bool = True) -> Layout:
    """The layout of the structure the ``loops`` make on ``r`` (refined where needed);
    ``follow_labels``: the sides split and the paths drawn where the per-triangle labels
    change (see :func:`_split_point`), else at the sides' middles and by length alone.

    Raises
    ------
    NotAStructure
        When the loops make no polycube loop structure, or no layout was found.
    """
    for _ in range(MAX_ROUNDS):
        e = read_structure(r, loops)
        try:
            polycube = e.polycube
        except (ValueError, PolyloopsError) as err:
            raise NotAStructure(f"the structure has no polycube: {err}") from None
        attempt = _attempt(e, follow_labels)
        if isinstance(attempt, set):
            r = split_edges(r, attempt)
            loops = relocate(r, loops)
            continue
        corners, paths, patch = attempt
        labels = tuple(_normal(polycube, int(f)) for f in patch)
        return Layout(e, polycube, corners, paths, patch, labels)
    raise NotAStructure(f"no layout after {MAX_ROUNDS} refinements")


def _normal(q: Polycube, f: int) -> Direction:
    d = q.face_normal(f)
    if d is None:
        raise NotAStructure(f"face {f} of the primalized polycube is not axis-parallel")
    return d


def _boundary_cycle(tris: np.ndarray, region: np.ndarray, g: int, mine: np.ndarray,
                    owner: dict[tuple[int, int], int]) -> list[int]:
    """Region ``g``'s boundary (its triangles ``mine``), counter-clockwise round the region
    (the region on the left)."""
    nxt = {}
    for t in mine.tolist():
        a, b, c = tris[t].tolist()
        for u, v in ((a, b), (b, c), (c, a)):
            if region[owner[v, u]] != g:
                nxt[u] = v
    start = min(nxt)
    cycle, v = [start], nxt[start]
    while v != start:
        cycle.append(v)
        v = nxt[v]
    return cycle


Paths = tuple[tuple[tuple[int, ...], ...], ...]  # per region, its paths (vertex sequences)


def _attempt(e: Embedded, follow_labels: bool = True) -> tuple[tuple[int, ...], Paths, np.ndarray] | set:
    """Corners, paths and patches, or the edges to split first."""
    r = e.refined
    tris, pts = r.triangles, r.points
    owner = r.owner
    crossing_face = {v: f for f, v in enumerate(e.crossings)}
    count = int(e.region.max()) + 1
    triangles_of = e.region_triangles
    cycles = [_boundary_cycle(tris, e.region, g, triangles_of[g], owner) for g in range(count)]
    # the point in the middle of each side, the same from both regions beside it
    to_split: set[tuple[int, int]] = set()
    middle: dict[frozenset[int], int] = {}
    sides: list[list[tuple[int, int]]] = []  # per region: (crossing that starts the side, its middle)
    on_boundary = np.zeros(len(pts), dtype=bool)
    for cycle in cycles:
        on_boundary[cycle] = True

    def reaches_inside(v: int) -> bool:
        """Whether ``v`` has a neighbour inside each region round it (on a side, a path can
        leave it into both regions beside the side)."""
        inside: dict[int, bool] = {}
        for t in r.incident[v]:
            g = int(e.region[t])
            inside[g] = inside.get(g, False) or any(not on_boundary[w] for w in tris[t].tolist())
        return all(inside.values())

    for cycle in cycles:
        at = [i for i, v in enumerate(cycle) if v in crossing_face]
        mine = []
        for j, i in enumerate(at):
            end = at[(j + 1) % len(at)]
            arc = cycle[i:end + 1] if end > i else cycle[i:] + cycle[:end + 1]
            key = frozenset(arc)
            if key not in middle:
                point = (_split_point(e, arc, crossing_face, reaches_inside) if follow_labels
                         else _middle(arc, pts, reaches_inside))
                if point is None:  # room for a path to leave the side: split the triangles at it
                    to_split |= _all_edges(tris[[t for v in arc for t in r.incident[v]]])
                    continue
                middle[key] = point
            mine.append((cycle[i], middle[key]))
        sides.append(mine)
    if to_split:
        return to_split
    corners, paths = [], []
    patch = np.full(len(tris), -1, dtype=np.int64)
    naive = naive_label_indices(r.surface) if follow_labels else None
    for g in range(count):
        found = _region_layout(e, triangles_of[g], cycles[g], sides[g], owner, crossing_face, naive)
        if isinstance(found, set):
            to_split |= found
            continue
        corner, region_paths, sector_face = found
        corners.append(corner)
        paths.append(region_paths)
        for t, f in sector_face.items():
            patch[t] = f
    if to_split:
        return to_split
    return tuple(corners), tuple(paths), patch


def _split_point(e: Embedded, arc: list[int], crossing_face: dict[int, int],
                 usable: Callable[[int], bool]) -> int | None:
    """Where the paths of the two regions beside a side meet it: the patch of the crossing at
    one end of the side runs up to this point, the other's on from it, so the point is chosen
    where the triangles along the side agree best with that split (the per-triangle labels
    change there), the one nearest the middle among equals (:func:`_middle`); ``None`` when
    no inner vertex is usable."""
    r = e.refined
    first, last = (e.polycube.face_normal(crossing_face[v]) for v in (arc[0], arc[-1]))
    if first is None or last is None or first == last:
        return _middle(arc, r.points, usable)
    ends = (first, last)
    surface = r.surface
    beside = np.array([[r.owner[u, v], r.owner[v, u]] for u, v in pairwise(arc)])
    weight = surface.areas[beside]  # per edge of the side, its two triangles
    agree = [(weight * (surface.normals[beside] @ np.array(d.vector, dtype=float))).sum(axis=1) for d in ends]
    score = split_scores(agree[0], agree[1])
    inner = [i for i in range(1, len(arc) - 1) if usable(arc[i])]
    if not inner:
        return None
    best = max(score[i] for i in inner)
    near = {arc[i] for i in inner if score[i] >= best - SPLIT_TOLERANCE * float(weight.sum())}
    return _middle(arc, r.points, near.__contains__)


def split_scores(first: np.ndarray, last: np.ndarray) -> np.ndarray:
    """For a side of ``k`` edges, whose ``i``-th edge's triangles agree ``first[i]`` with the
    patch at its first end and ``last[i]`` with the one at its last end: the agreement of
    splitting at each of its ``k + 1`` vertices (the edges before the split with the first
    patch, the rest with the last), by two running sums.

    >>> split_scores(np.array([1.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])).tolist()  # best: after two
    [1.0, 2.0, 3.0, 2.0]
    """
    return (np.concatenate([[0.0], np.cumsum(first)])
            + np.concatenate([np.cumsum(last[::-1])[::-1], [0.0]]))


SPLIT_TOLERANCE = 0.02  # splits within this share of the side's triangles' area of the best are equal


def _middle(arc: list[int], pts: np.ndarray, usable: Callable[[int], bool]) -> int | None:
    """The inner vertex of ``arc`` nearest the middle of its length among the ``usable`` ones
    (the same either way round); ``None`` when there is none."""
    if tuple(arc[::-1]) < tuple(arc):
        arc = arc[::-1]
    lengths = np.linalg.norm(np.diff(pts[arc], axis=0), axis=1)
    along = np.concatenate([[0.0], np.cumsum(lengths)])
    inner = [i for i in range(1, len(arc) - 1) if usable(arc[i])]
    if not inner:
        return None
    return arc[min(inner, key=lambda i: (abs(along[i] - along[-1] / 2), i))]


def _region_layout(e: Embedded, mine: np.ndarray, cycle: list[int], sides: list[tuple[int, int]],
                   owner: dict[tuple[int, int], int], crossing_face: dict[int, int],
                   naive: np.ndarray | None = None
                   ) -> tuple[int, tuple[tuple[int, ...], ...], dict[int, int]] | set:
    """The corner, paths and sector faces of one region (or the edges to split first); with
    ``naive`` (per triangle, its per-triangle label) the paths are drawn along its changes."""
    r = e.refined
    tris, pts = r.triangles, r.points
    local_tris = tris[mine]
    verts = np.unique(local_tris)
    index = np.full(len(pts), -1, dtype=np.int64)
    index[verts] = np.arange(len(verts))
    pairs = np.concatenate([local_tris[:, [0, 1]], local_tris[:, [1, 2]], local_tris[:, [2, 0]]])
    pairs = np.unique(np.sort(pairs, axis=1), axis=0)  # the region's edges, each once
    lengths = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    boundary = np.zeros(len(pts), dtype=bool)
    boundary[cycle] = True
    ends = np.zeros(len(pts), dtype=bool)
    ends[[m for _, m in sides]] = True
    inner = verts[~boundary[verts]]
    if len(inner) == 0:
        return _all_edges(local_tris)
    lu, lv = index[pairs[:, 0]], index[pairs[:, 1]]
    both_ways = (np.concatenate([lu, lv]), np.concatenate([lv, lu]))
    size = (len(verts), len(verts))
    graph = coo_matrix((np.concatenate([lengths, lengths]), both_ways), shape=size).tocsr()
    dist = dijkstra(graph, indices=index[cycle], min_only=True)
    # paths run inside the region: an edge with an end on the boundary only to a side's middle
    bu, bv = boundary[pairs[:, 0]], boundary[pairs[:, 1]]
    usable = ~(bu & bv) & (~bu | ends[pairs[:, 0]]) & (~bv | ends[pairs[:, 1]])
    costs = lengths
    if naive is not None:
        # an edge where the per-triangle labels change is cheap: the fidelity-best boundary
        # between two patches runs where the normal is as near one's direction as the other's
        changes = np.array([naive[owner[a, b]] != naive[owner[b, a]] for a, b in pairs.tolist()], dtype=bool)
        costs = lengths * np.where(changes, FEATURE_DISCOUNT, 1.0)
    edges = list(zip(lu[usable].tolist(), lv[usable].tolist(), costs[usable].tolist(), strict=True))
    degree = np.bincount(np.concatenate([lu[usable], lv[usable]]), minlength=len(verts))
    targets = [int(index[m]) for _, m in sides]
    # the corner: an inner vertex with a way out to each side, where the surface's normal best
    # agrees with its faces' directions (a corner of a polycube points along their sum), deep
    # inside the region where that ties
    far = dist[index[inner]]
    agree = r.vertex_normals[inner] @ _direction_sum(e, sides, crossing_face)
    score = agree + DEPTH_WEIGHT * far / max(float(far.max()), 1e-300)
    if naive is not None:
        # where the labels change between two sectors, the patches' boundary runs from the
        # side's middle to the corner: the corner sits where those boundaries are cheapest
        # together (on a crease, the corner between an X and a Z face lies on it; the normal
        # alone cannot tell, being as near both directions on either side)
        ends_of = [int(index[m]) for j, (_, m) in enumerate(sides)
                   if _turns(e, crossing_face, sides[j][0], sides[(j + 1) % len(sides)][0])]
        if ends_of:
            along = coo_matrix((np.concatenate([costs, costs]), both_ways), shape=size).tocsr()
            joined = dijkstra(along, indices=ends_of).sum(axis=0)[index[inner]]
            score = score - joined / max(float(np.median(lengths)), 1e-300) * JOIN_WEIGHT
    order = [int(v) for v in inner[np.lexsort((-inner, -score))] if degree[index[v]] >= len(sides)]
    found = None
    for corner in order[:CORNER_TRIES]:
        found = disjoint_paths(len(verts), edges, int(index[corner]), targets)
        if found is not None:
            break
    if found is None:
        return _all_edges(local_tris)
    region_paths = tuple(tuple(int(verts[i]) for i in p) for p in found)
    cut = {(min(p[i], p[i + 1]), max(p[i], p[i + 1])) for p in region_paths for i in range(len(p) - 1)}
    # sectors: the region's triangles joined across edges on no path and no boundary
    local = {int(t): i for i, t in enumerate(mine.tolist())}
    rows, cols = [], []
    for t, (a, b, c) in zip(mine.tolist(), local_tris.tolist(), strict=True):
        for u, v in ((a, b), (b, c), (c, a)):
            other = owner[v, u]
            if other in local and (min(u, v), max(u, v)) not in cut:
                rows.append(local[t])
                cols.append(local[other])
    adjacency = coo_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(mine), len(mine)))
    n_sectors, sector = connected_components(adjacency, directed=False)
    if n_sectors != len(sides):
        return _all_edges(local_tris)
    face_of_sector: dict[int, int] = {}
    for c, _ in sides:
        touching = {int(sector[local[t]]) for t in r.incident[c] if t in local}
        if len(touching) != 1:
            return _all_edges(local_tris)
        s = touching.pop()
        if s in face_of_sector:
            return _all_edges(local_tris)
        face_of_sector[s] = crossing_face[c]
    return corner, region_paths, {t: face_of_sector[int(sector[i])] for t, i in local.items()}


def _turns(e: Embedded, crossing_face: dict[int, int], a: int, b: int) -> bool:
    """Whether the faces of crossings ``a`` and ``b`` face different ways (the labels change
    between their sectors)."""
    return e.polycube.face_normal(crossing_face[a]) != e.polycube.face_normal(crossing_face[b])


def _direction_sum(e: Embedded, sides: list[tuple[int, int]], crossing_face: dict[int, int]) -> np.ndarray:
    """The unit sum of the directions of a region's faces (those of the crossings on its
    boundary), or zero when they cancel."""
    polycube = e.polycube
    total = np.zeros(3)
    for c, _ in sides:
        d = polycube.face_normal(crossing_face[c])
        if d is not None:
            total[d.axis] += d.sign
    length = float(np.linalg.norm(total))
    return total / length if length > 1e-9 else total


def _all_edges(local_tris: np.ndarray) -> set[tuple[int, int]]:
    """Every edge of a region's triangles: split them all to make room."""
    out = set()
    for a, b, c in local_tris.tolist():
        for u, v in ((a, b), (b, c), (c, a)):
            out.add((min(u, v), max(u, v)))
    return out
