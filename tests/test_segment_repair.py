"""Repair of a labelling by local remedies (:mod:`polyloops.segment.repair`): what it returns
the checker finds valid, and it undoes what a local change broke."""

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.core.directions import Direction
from polyloops.segment.labellings import graphcut_labels, naive_labels
from polyloops.segment.repair import repair_labels
from polyloops.segment.run import _direct, segment_mesh
from polyloops.segment.starts import Charts
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.shapes.meshes import _subdivide, ellipsoid, sphere
from polyloops.surface.construct import labelled_mesh_from_polycube
from strategies import polycubes

DUALCUBE = Path(__file__).resolve().parents[2] / "shared" / "segmentations" / "dualcube"


def _fine(q):
    """``q``'s surface subdivided twice, each triangle labelled by its face's normal."""
    m = labelled_mesh_from_polycube(q)
    points, triangles = np.array(m.points, dtype=float), np.array(m.triangles)
    labels = list(m.labels)
    for _ in range(2):
        points, triangles = _subdivide(points, triangles)
        labels = [d for d in labels for _ in range(4)]
    return surface_of(points, triangles), labels


@settings(max_examples=8, deadline=None)
@given(polycubes(max_size=4), st.data())
def test_an_island_in_a_face_is_joined_back(q, data):
    """A fan of triangles round a vertex inside a face, labelled otherwise, is an island (a
    chart with a closed boundary, or too few): the repair gives back the polycube's labelling."""
    s, labels = _fine(q)
    own = np.array([int(d) for d in labels])
    lowest = np.full(len(s.points), 6)
    highest = np.full(len(s.points), -1)
    for k in range(3):
        np.minimum.at(lowest, s.triangles[:, k], own)
        np.maximum.at(highest, s.triangles[:, k], own)
    pure = lowest == highest  # every triangle round the vertex has one label
    inside = [v for v in range(len(s.points))
              if pure[np.unique(s.triangles[(s.triangles == v).any(axis=1)])].all()]
    v = data.draw(st.sampled_from(inside))
    fan = np.flatnonzero((s.triangles == v).any(axis=1))
    other = data.draw(st.sampled_from([d for d in Direction if int(d) != own[fan[0]]]))
    broken = list(labels)
    for t in fan:
        broken[t] = other
    done = repair_labels(s, broken)
    assert done is not None and done.report.valid is True
    assert list(done.labels) == list(labels)  # (an opposite island first gets a strip, then joins)


def test_a_valid_labelling_is_returned_as_it_is():
    s, labels = _fine(polycubes_box())
    done = repair_labels(s, labels)
    assert done is not None and done.rounds == 0 and done.charts == 0 and list(done.labels) == labels


def polycubes_box():
    from polyloops.shapes.builders import box

    return box(2, 1, 1)


def test_a_thin_plate_gets_a_strip_round_its_rim_and_seeds_a_search():
    """A thin plate's graph-cut labelling meets +Z and -Z at the rim; the strip the repair puts
    there makes it valid, and it is a candidate and a seed of the run."""
    points, triangles = ellipsoid(1.0, 0.6, 0.05, level=3)
    s = surface_of(points, triangles)
    cut = graphcut_labels(s)
    done = repair_labels(s, cut)
    assert done is not None and done.report.valid is True and done.charts >= 1
    found = _direct(s, 0.0)
    assert found is not None and found[1] is Charts.REPAIRED
    assert found[0].start.startswith("the graph-cut labelling, repaired")
    run = segment_mesh(points, triangles, budget=0.5)
    assert run.certified and run.fidelity >= found[0].fidelity
    assert "the loops of the valid repaired graph-cut labelling" in {c.start for c in run.candidates}


def test_an_invalid_guide_that_the_remedies_make_valid_is_a_floor_on_the_agreement():
    """A thin plate's graph-cut labelling as a guide: invalid, repaired by a strip round the
    rim; that repair seeds a search and is a floor: the output agrees with the guide at least as
    well."""
    from polyloops.segment.labellings import fidelity, label_vectors

    points, triangles = ellipsoid(1.0, 0.6, 0.05, level=3)
    s = surface_of(points, triangles)
    guide = graphcut_labels(s)
    done = repair_labels(s, guide)
    assert done is not None
    floor = fidelity(s, done.labels, label_vectors(guide))
    run = segment_mesh(points, triangles, budget=0.5, guide=guide)
    assert "the loops of the valid repaired guide labelling" in {c.start for c in run.candidates}  # a seed
    kept = next(c for c in run.candidates if c.kept)
    assert run.certified and kept.agreement is not None and kept.agreement >= floor - 1e-12
    assert run.guide_changed is not None and run.guide_changed <= 0.2


def test_strips_that_continue_the_charts_at_their_ends_repair_a_thin_plate_too(monkeypatch):
    """The second strategy alone (strips between opposite labels taking the labels of the
    charts at the boundary's ends) repairs the thin plate, and what it returns the checker
    finds valid."""
    from polyloops.segment import repair

    first = repair._rounds
    monkeypatch.setattr(repair, "_rounds", lambda *a: first(*a) if a[-1] is repair.Way.ENDS else None)
    s = surface_of(*ellipsoid(1.0, 0.6, 0.05, level=3))
    labels = graphcut_labels(s)
    assert check_segmentation(s.labelled(labels)).valid is False
    done = repair.repair_labels(s, labels)
    assert done is not None and done.rounds >= 1
    assert check_segmentation(s.labelled(done.labels)).valid is True


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 6), st.integers(2, 4), st.floats(0.0, 3.0), st.integers(0, 2**32 - 1))
def test_the_cheapest_run_of_labels_along_a_strip_is_what_trying_every_run_finds(n, k, switch, seed):
    """Twin: the dynamic programme that labels a strip along its boundary costs what the best
    of all k**n label sequences costs (each position's cost, plus ``switch`` per change)."""
    import itertools

    from polyloops.segment.repair import _cheapest_run

    cost = np.random.default_rng(seed).normal(size=(n, k))

    def total(seq):
        changes = sum(a != b for a, b in itertools.pairwise(seq))
        return sum(cost[i, j] for i, j in enumerate(seq)) + switch * changes

    best = min(total(seq) for seq in itertools.product(range(k), repeat=n))
    got = _cheapest_run(cost, switch)
    assert len(got) == n and total(tuple(int(j) for j in got)) == pytest.approx(best)


def _box():
    """A sphere pushed onto the box [-1, 1] x [-0.8, 0.8] x [-0.5, 0.5], and its labelling by
    the box's faces."""
    points, triangles = sphere(3)
    points = points / np.abs(points).max(axis=1, keepdims=True) * np.array([1.0, 0.8, 0.5])
    s = surface_of(points, triangles)
    return s, np.array([int(d) for d in naive_labels(s)])


def test_a_large_chart_missing_a_side_gets_it_at_the_corner_where_opposite_neighbours_meet():
    """The box with its +X face labelled +Y: its top then meets -Y, +Y (round the end) and -X,
    so a side along X is missing between -Y and +Y; the careful strategy's fill labels the
    triangles round the corner between them +X (the top's far end in X), nothing else."""
    from polyloops.segment.polish import Fans
    from polyloops.segment.repair import _fill

    s, own = _box()
    lab = own.copy()
    lab[lab == 0] = 2  # +X faces labelled +Y
    seg = check_segmentation(s.labelled([Direction(int(d)) for d in lab])).segmentation
    top = next(c for c in seg.charts if c.label is Direction.PZ)
    before = lab.copy()
    assert _fill(s, seg, top.id, np.asarray(top.triangles), lab, Fans(s.triangles)) == 1
    changed = np.flatnonzero(lab != before)
    assert len(changed) and set(lab[changed].tolist()) == {0}
    shared = set.intersection(*(set(s.triangles[t].tolist()) for t in changed))
    assert len(shared) == 1 and s.points[shared.pop(), 0] == pytest.approx(1.0)  # one vertex, at x = 1


def test_the_careful_strategy_alone_repairs_a_thin_plate_and_a_box_with_a_face_mislabelled(monkeypatch):
    """The third strategy alone makes valid, by the checker, the thin plate's graph-cut
    labelling (a strip round the rim) and the box whose +X face is labelled +Y (a strip where it
    meets -Y, a missing side filled)."""
    from polyloops.segment import repair

    first = repair._rounds
    monkeypatch.setattr(repair, "_rounds", lambda *a: first(*a) if a[-1] is repair.Way.CAREFUL else None)
    plate = surface_of(*ellipsoid(1.0, 0.6, 0.05, level=3))
    s, own = _box()
    wrong = own.copy()
    wrong[wrong == 0] = 2
    for surface, labels in ((plate, list(graphcut_labels(plate))), (s, [Direction(int(d)) for d in wrong])):
        assert check_segmentation(surface.labelled(labels)).valid is False
        done = repair.repair_labels(surface, labels)
        assert done is not None and done.rounds >= 1
        assert check_segmentation(surface.labelled(done.labels)).valid is True


@pytest.mark.slow
@pytest.mark.skipif(not DUALCUBE.is_dir(), reason="../shared/segmentations/dualcube is not here")
def test_the_aeroplane_graph_cut_labelling_is_repaired_above_dualcube_fidelity():
    """Half DualCube's aeroplane: its graph-cut labelling (wing and tail tops meeting their
    bottoms) is repaired by the careful strategy, decided valid (the realisation needs one of
    the finer orders of the zones), more faithful than DualCube's own labels (0.9381)."""
    from polyloops.io.exchange import obj_triangles
    from polyloops.segment.labellings import fidelity

    found = obj_triangles((DUALCUBE / "plane.obj").read_text())
    assert found is not None
    s = surface_of(*found)
    done = repair_labels(s, graphcut_labels(s))
    assert done is not None and check_segmentation(s.labelled(done.labels)).valid is True
    assert fidelity(s, done.labels) > 0.9381


@given(st.lists(st.tuples(st.floats(0.5, 1.0), st.integers(0, 60)), min_size=1, max_size=8),
       st.floats(0.5, 1.0), st.sampled_from(list(Charts)))
def test_a_repaired_labelling_bounds_the_result_only_with_the_repaired_floor(rows, floor, which):
    """The floor rule against its statement: rows at least as faithful as the floor stay;
    with ``Floor.VALID`` a repaired labelling (graph-cut or guide) bounds nothing, with
    ``Floor.REPAIRED`` every valid labelling of the mesh does."""
    from types import SimpleNamespace

    from polyloops.segment import Floor
    from polyloops.segment.run import SearchSettings, _above_floor

    knobs = SearchSettings(1.0, 0, 9, 0.001, None)
    made = [(SimpleNamespace(agreement=None), SimpleNamespace(fidelity=f, loops=k)) for f, k in rows]
    repaired = which in (Charts.REPAIRED, Charts.GUIDE)
    for bound in Floor:
        kept = _above_floor(made, floor, which, bound, knobs)  # type: ignore[arg-type]
        bounded = bound is Floor.REPAIRED or not repaired
        assert kept == [r for r in made if not bounded or r[1].fidelity >= floor]
        assert _above_floor(made, None, which, bound, knobs) == made  # type: ignore[arg-type]


@pytest.mark.slow
@pytest.mark.skipif(not DUALCUBE.is_dir(), reason="../shared/segmentations/dualcube is not here")
def test_with_the_valid_floor_the_aeroplane_beats_dualcube_at_fewer_loops():
    """Half DualCube's aeroplane with ``Floor.VALID``: its repaired graph-cut labelling (46
    loops) no longer bounds the result, and a heavier graph-cut labelling, repaired, scores
    better: certified, more faithful than DualCube's labels (0.9381) with fewer loops than
    their realising polycube (33)."""
    from polyloops.io.exchange import obj_triangles
    from polyloops.segment import Floor

    found = obj_triangles((DUALCUBE / "plane.obj").read_text())
    assert found is not None
    done = segment_mesh(*found, workers=2, bound=Floor.VALID)
    assert done.certified and done.fidelity > 0.9381 and done.loops <= 33
    assert check_segmentation(done.mesh).valid is True
