"""Grafting patches of other labellings into a valid one (:mod:`polyloops.segment.graft`): the
patches are the components a plain graph search finds, what comes out is valid by a check of
its own and never less faithful, the score rises by what is reported, islands are never tried,
and the run keeps a grafted result only as its own, better-scoring row."""

import time

import networkx as nx
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.core.directions import Direction
from polyloops.core.duality import dualize
from polyloops.segment import PRICE
from polyloops.segment.graft import LEAST, graft_labels, patches
from polyloops.segment.labellings import DIRECTION_VECTORS, fidelity, graphcut_labels
from polyloops.segment.run import Candidate, _grafted, _kept_labelling
from polyloops.segment.search import SearchSettings
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.shapes.meshes import ellipsoid
from strategies import polycubes
from test_segment_repair import _fine


def _value(s):
    return (s.normals @ DIRECTION_VECTORS.T) * s.areas[:, None]


def _noisy(own: np.ndarray, s, rng: np.random.Generator, spots: int) -> np.ndarray:
    """``own`` with the triangles round a few random vertices given one random label each."""
    out = own.copy()
    for v in rng.choice(len(s.points), size=min(spots, len(s.points)), replace=False):
        out[np.flatnonzero((s.triangles == v).any(axis=1))] = rng.integers(0, 6)
    return out


def _band(s, own: np.ndarray) -> np.ndarray:
    """``own`` with the triangles of its first label along a chart of another label given that
    label: the same charts and corners where it is valid, less faithful."""
    pairs, _ = s.adjacency
    a = int(own[0])
    b = next(int(own[t]) for t in pairs[own[pairs[:, 0]] == a, 1] if own[t] != a)
    out = own.copy()
    out[pairs[(own[pairs[:, 0]] == a) & (own[pairs[:, 1]] == b), 0]] = b
    return out


@settings(max_examples=15, deadline=None)
@given(polycubes(max_size=4), st.integers(0, 2**32 - 1))
def test_patches_are_the_components_a_plain_graph_search_finds(q, seed):
    """Twin: the connected sets of triangles (through edges) that the donor labels alike and
    otherwise than the labelling, with their gains, found by networkx on a graph built edge by
    edge; those gaining more than the least, best first."""
    s, labels = _fine(q)
    rng = np.random.default_rng(seed)
    own = _noisy(np.array([int(d) for d in labels]), s, rng, 3)
    donor = _noisy(own, s, rng, 6)
    value = _value(s)
    g = nx.Graph()
    differs = [t for t in range(len(own)) if own[t] != donor[t]]
    g.add_nodes_from(differs)
    pairs, _ = s.adjacency
    for a, b in pairs.tolist():
        if own[a] != donor[a] and own[b] != donor[b] and donor[a] == donor[b]:
            g.add_edge(a, b)
    slow = {}
    for comp in nx.connected_components(g):
        gain = sum(value[t, donor[t]] - value[t, own[t]] for t in comp)
        if gain > LEAST * s.areas.sum():
            slow[frozenset(comp)] = gain
    fast = patches(s, own, donor, value)
    assert {frozenset(w.tolist()): pytest.approx(gain) for gain, w in fast} == slow
    assert [gain for gain, _ in fast] == sorted((gain for gain, _ in fast), reverse=True)


@settings(max_examples=10, deadline=None)
@given(polycubes(max_size=4), st.integers(0, 2**32 - 1), st.sampled_from([0.0, PRICE, 0.01]))
def test_grafting_gives_a_valid_labelling_never_less_faithful_and_reports_its_rise(q, seed, price):
    """From a valid labelling (a polycube's, with a band of one face moved onto its neighbour
    where that stays valid), with noisy donors: the checker, run again here, finds the result
    valid; the fidelity never falls; the reported rise is the fidelity gained less the price of
    the loops added (counted on the checker's polycubes)."""
    s, labels = _fine(q)
    own = np.array([int(d) for d in labels])
    start = _band(s, own)
    if check_segmentation(s.labelled([Direction(int(d)) for d in start])).valid is not True:
        start = own
    rng = np.random.default_rng(seed)
    donors = [_noisy(own, s, rng, 4), own]
    begin = [Direction(int(d)) for d in start]
    done = graft_labels(s, begin, donors, price)
    again = check_segmentation(s.labelled(list(done.labels)))
    assert again.valid is True and again.polycube is not None
    assert len(dualize(again.polycube).loops) == done.loops
    before = check_segmentation(s.labelled(begin))
    assert before.polycube is not None
    gained = fidelity(s, done.labels) - fidelity(s, begin)
    assert gained >= -1e-12
    added = done.loops - len(dualize(before.polycube).loops)
    assert done.gain == pytest.approx(gained - price * added, abs=1e-9)
    assert (done.kept == 0) == (done.labels == tuple(begin))
    if done.kept:
        assert done.gain > 0
    if price == 0.0 and not np.array_equal(start, own):
        assert done.kept  # the band given back, at least


def test_an_island_is_never_tried_and_the_checker_refuses_one():
    """A fan of triangles inside one chart, labelled otherwise, is a chart whose only neighbour
    is that chart: the checker refuses it (no polycube face has one neighbour), and grafting
    does not spend a check on it."""
    s = surface_of(*ellipsoid(2.0, 1.0, 0.7, level=3))
    good = np.array([int(d) for d in graphcut_labels(s)])
    # a vertex all of whose triangles, and their neighbours, are in one chart
    def ring(v: int) -> np.ndarray:  # the triangles sharing a vertex with those round v
        return np.flatnonzero(np.isin(s.triangles, s.triangles[(s.triangles == v).any(axis=1)]).any(axis=1))

    inner = next(v for v in range(len(s.points)) if len(set(good[ring(v)].tolist())) == 1)
    fan = np.flatnonzero((s.triangles == inner).any(axis=1))
    island = good.copy()
    island[fan] = (good[fan[0]] + 2) % 6  # a label of another axis
    assert check_segmentation(s.labelled([Direction(int(d)) for d in island])).valid is False
    target = s.normals.copy()
    target[fan] = DIRECTION_VECTORS[island[fan]]  # the donor's label is what is wanted there
    done = graft_labels(s, [Direction(int(d)) for d in good], [island], 0.0, target=target)
    assert done.tried == 0 and done.kept == 0


def test_the_run_keeps_a_grafted_result_as_its_own_row_scoring_better():
    """``_grafted``: the run's result (here a valid labelling made less faithful) with a
    graph-cut labelling's patches grafted: certified, on the same input triangles, a row of its
    own whose score is above the result's row and whose start says it was grafted."""
    s = surface_of(*ellipsoid(2.0, 1.0, 0.7, level=3))
    good = np.array([int(d) for d in graphcut_labels(s)])
    worse = _band(s, good)
    best = _kept_labelling(s, [Direction(int(d)) for d in worse], "the test's labelling", time.monotonic())
    assert best is not None
    knobs = SearchSettings(5.0, 0, 9, PRICE, None)
    row = Candidate(best.start, True, fidelity=best.fidelity, loops=best.loops, price=PRICE,
                    score=best.fidelity - PRICE * best.loops)
    got = _grafted(s, best, row, [good], knobs, time.monotonic())
    assert got is not None
    new_row, result = got
    assert result.certified and result.face_map == best.face_map
    assert new_row.score is not None and row.score is not None and new_row.score > row.score
    assert new_row.start.startswith("the test's labelling, grafted (") and result.fidelity > best.fidelity
    assert _grafted(s, best, row, [], knobs, time.monotonic()) is None  # no donors: nothing


def test_with_a_guide_the_share_changed_is_what_the_labels_written_differ_by():
    """With an invalid guide (a thin plate's graph-cut labelling), whatever the run keeps
    (grafted from the guide or not), ``guide_changed`` is the share of the area whose label,
    read through each output triangle's input triangle, is not the guide's."""
    from polyloops.segment.run import segment_mesh

    points, triangles = ellipsoid(1.0, 0.6, 0.05, level=3)
    s = surface_of(points, triangles)
    guide = graphcut_labels(s)
    run = segment_mesh(points, triangles, budget=0.5, guide=guide)
    out = surface_of(np.asarray(run.mesh.points), np.asarray(run.mesh.triangles))
    wanted = np.array([int(guide[p]) for p in run.face_map])
    got = np.array([int(d) for d in run.mesh.labels])
    share = float(out.areas[got != wanted].sum() / out.areas.sum())
    assert run.certified and run.guide_changed == pytest.approx(share)
    assert sum(c.kept for c in run.candidates) == 1
