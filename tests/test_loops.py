"""Loops as strips of faces."""

from hypothesis import given

from polyloops.io.examples import load_example
from strategies import polycubes


@given(polycubes())
def test_every_edge_in_exactly_one_loop(q):
    m = q.map
    system = m.loop_system
    crossed = sorted(e for lp in system.loops for e in lp.edges)
    assert crossed == list(range(m.num_edges))
    # Each quad is crossed twice, by the loops of its two pairs of opposite edges.
    assert sum(len(lp) for lp in system.loops) == 2 * m.num_faces


@given(polycubes())
def test_loop_walks_between_opposite_edges(q):
    m = q.map
    for lp in m.loop_system.loops:
        for i, d in enumerate(lp.darts):
            nxt = lp.darts[(i + 1) % len(lp)]
            # d enters face f; the loop leaves through the opposite dart, whose twin is next.
            assert m.face_of[d] == lp.faces[i]
            assert m.twin[nxt] == m.next[m.next[d]]


def test_polycube_loops_do_not_cross_themselves():
    for name in ("cube", "box-2x1x1", "l-shape", "ring"):
        assert not any(lp.self_crossings for lp in load_example(name).map.loop_system.loops)


def test_self_crossing_example_has_a_self_crossing_loop():
    ls = load_example("self-crossing")
    assert [lp.id for lp in ls.loops if lp.self_crossings] == [0]
