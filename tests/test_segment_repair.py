"""Repair of a labelling by local remedies (:mod:`polyloops.segment.repair`): what it returns
the checker finds valid, and it undoes what a local change broke."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.core.directions import Direction
from polyloops.segment.labellings import graphcut_labels
from polyloops.segment.repair import repair_labels
from polyloops.segment.run import _direct, segment_mesh
from polyloops.segment.starts import Charts
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.shapes.meshes import _subdivide, ellipsoid
from polyloops.surface.construct import labelled_mesh_from_polycube
from strategies import polycubes


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
    monkeypatch.setattr(repair, "_rounds", lambda *a: None if not a[-1] else first(*a))
    s = surface_of(*ellipsoid(1.0, 0.6, 0.05, level=3))
    labels = graphcut_labels(s)
    assert check_segmentation(s.labelled(labels)).valid is False
    done = repair.repair_labels(s, labels)
    assert done is not None and done.rounds >= 1
    assert check_segmentation(s.labelled(done.labels)).valid is True
