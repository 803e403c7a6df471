"""Merging whole charts (:mod:`polyloops.segment.merge`): the charts and fidelity each merge is
said to leave are those computed from scratch, every step returned is certified, and a run keeps
a merged result only where it scores better and is not below its floor."""

import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.core.directions import Direction
from polyloops.io.examples import load_example
from polyloops.segment.labellings import chart_indices, fidelity, label_vectors
from polyloops.segment.merge import merge_options, merges
from polyloops.segment.run import FREE, _candidate, _kept_labelling, _merged
from polyloops.segment.search import SearchSettings
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.surface.construct import labelled_mesh_from_polycube
from strategies import polycubes
from test_segment_graft import _noisy
from test_segment_repair import _fine


def _directions(labels: np.ndarray) -> tuple[Direction, ...]:
    return tuple(Direction(int(k)) for k in labels)


@settings(max_examples=12, deadline=None)
@given(polycubes(max_size=4), st.integers(0, 2**32 - 1), st.booleans())
def test_each_merge_leaves_the_charts_and_fidelity_computed_from_scratch(q, seed, guided):
    """Twin: each chart relabelled as a neighbour, the labelling's charts counted and its
    fidelity (or agreement with a guide) summed again."""
    s, labels = _fine(q)
    rng = np.random.default_rng(seed)
    own = _noisy(np.array([int(d) for d in labels]), s, rng, 4)
    target = label_vectors(_directions(_noisy(own, s, rng, 4))) if guided else None
    chart = chart_indices(s, own)
    options = merge_options(s, own, target)
    assert options == sorted(options, key=lambda o: (-o[0], o[1], o[2], o[3]))
    pairs, _ = s.adjacency
    beside: dict[int, set[int]] = {}  # per chart, the labels of the charts beside it
    for a, b in np.concatenate([pairs, pairs[:, ::-1]]).tolist():
        if chart[a] != chart[b]:
            beside.setdefault(int(chart[a]), set()).add(int(own[b]))
    for after, charts, c, label in options:
        assert label in beside[c] and label != own[chart == c][0]
        trial = own.copy()
        trial[chart == c] = label
        assert charts == chart_indices(s, trial).max() + 1 < chart.max() + 1
        assert after == pytest.approx(fidelity(s, _directions(trial), target))
    assert {(c, t) for _, _, c, t in options} == {
        (c, t) for c, labels in beside.items() for t in labels if t != own[chart == c][0]}


@settings(max_examples=6, deadline=None)
@given(polycubes(max_size=4), st.sampled_from([-1.0, 0.9]))
def test_every_step_is_certified_fewer_charts_and_no_less_faithful_than_least(q, least):
    s, labels = _fine(q)
    current = np.array([int(d) for d in labels])
    before = chart_indices(s, current).max() + 1
    for step in merges(s, current, least):
        report = check_segmentation(s.labelled(_directions(step.labels)))
        assert report.valid is True and report.polycube is not None
        assert step.charts == len(report.segmentation.charts) < before
        assert step.fidelity == pytest.approx(fidelity(s, _directions(step.labels)))
        # each triangle labelled by its own face's normal: at the bound, no merge gains
        assert least <= step.fidelity <= fidelity(s, _directions(current)) + 1e-12
        current, before = step.labels, step.charts


def test_the_l_shape_merges_into_the_box():
    """The L's notch faces relabelled as the faces beside them: the box's six charts, valid."""
    m = labelled_mesh_from_polycube(load_example("l-shape"))
    s = surface_of(m.points, m.triangles)
    steps = merges(s, np.array([int(d) for d in m.labels]), least=-1.0)
    assert [step.charts for step in steps] == [6]
    assert steps[0].report.polycube.map.num_corners == 8


@pytest.mark.parametrize("price, floor, lose, merged", [
    (0.05, None, None, True), (0.0, None, None, False), (0.05, 0.95, None, False),
    (0.05, None, 0.08, True), (0.05, None, 0.06, False), (0.05, None, FREE, False)])
def test_a_run_keeps_a_merge_only_where_it_scores_better_above_the_floor(price, floor, lose, merged):
    """The L's merge into the box loses 0.071 of fidelity and saves two loops: kept only where the
    price pays for it and neither the floor nor the loss allowed (``lose``) forbids it."""
    m = labelled_mesh_from_polycube(load_example("l-shape"))
    s = surface_of(m.points, m.triangles)
    began = time.monotonic()
    best = _kept_labelling(s, m.labels, "the L", began)
    assert best is not None and best.charts == 8
    knobs = SearchSettings(budget=5.0, seed=0, planes=9, price=price)
    row = _candidate(best, knobs, 0.0)
    got = _merged(best, row, knobs, began, floor, lose)
    if not merged:
        assert got is None
        return
    assert got is not None
    candidate, result = got
    assert result.certified and result.charts == 6 and result.loops == 3 < best.loops
    assert candidate.score is not None and row.score is not None and candidate.score > row.score
    assert result.start == "the L, merged (1 chart relabelled)"


def test_with_a_guide_a_merge_is_scored_by_its_agreement_and_reports_the_area_changed():
    m = labelled_mesh_from_polycube(load_example("l-shape"))
    s = surface_of(m.points, m.triangles)
    began = time.monotonic()
    best = _kept_labelling(s, m.labels, "the L", began)
    assert best is not None
    knobs = SearchSettings(budget=5.0, price=0.05, guide=label_vectors(m.labels))
    row = _candidate(best, knobs, 0.0)
    assert row.agreement == pytest.approx(1.0)
    got = _merged(best, row, knobs, began, None)
    assert got is not None
    candidate, result = got
    assert result.charts == 6 and candidate.agreement is not None and result.guide_changed is not None
    # the notch's faces, relabelled across: what is labelled otherwise agrees not at all
    assert result.guide_changed == pytest.approx(1.0 - candidate.agreement)
    assert candidate.score == pytest.approx(candidate.agreement - 0.05 * result.loops)
