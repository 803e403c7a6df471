"""The checkers: the paper's theorems as properties, and each invalid example for its own reason."""

import pytest
from hypothesis import event, given

from polyloops.core.duality import DualityError, primalize
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.loops import OddFaceError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.io.examples import EXAMPLES, load_example
from polyloops.verify import (
    check_polycube,
    check_polycube_faces,
    check_polycube_loop_structure,
    check_theorem3,
    genus_balance,
    verify,
)
from polyloops.verify.loop_structure import crossing_violations
from polyloops.verify.report import ReportBuilder
from strategies import perturbed_structures, polycubes


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_examples_validity(name):
    assert verify(load_example(name)).valid == EXAMPLES[name].valid


EXPECTED_REASON = {
    # name: (condition, a word of the message, witness key)
    "torus-cycle": ("5", "X-graph has a cycle", "zones"),
    "degree-two": ("2", "bounded by 2 segments", "region"),
    "double-plus-x": ("3", "side +", "region"),
    "self-crossing": ("3", "crosses itself", "loop"),
}


@pytest.mark.parametrize("name", sorted(EXPECTED_REASON))
def test_invalid_examples_fail_for_their_own_reason(name):
    condition, words, key = EXPECTED_REASON[name]
    report = check_polycube_loop_structure(load_example(name))
    conditions = {v.condition for v in report.violations}
    assert conditions == {condition}
    assert any(words in v.message and key in v.witness for v in report.violations)


def test_double_plus_x_reports_every_corner():
    report = check_polycube_loop_structure(load_example("double-plus-x"))
    assert len(report.violations) == 4  # the four corners of the middle square


def test_by_construction_is_said_not_skipped():
    report = verify(load_example("cube").dualize())
    statuses = {(c.definition, c.condition): c.status for c in report.checks}
    assert statuses[("Definition 4", "4")] == "holds by construction"
    assert statuses[("Definition 3", "1")] == "holds by construction"
    assert ("Theorem 3", "X") in statuses


@given(polycubes())
def test_theorem3_on_random_polycubes(q):
    ls = q.dualize()
    event(f"genus {ls.genus}")
    for b in genus_balance(ls):
        assert b.holds, b
    assert check_theorem3(ls).valid


@given(perturbed_structures())
def test_theorems_1_and_2_on_perturbed_structures(ls):
    """Definition 4 holds exactly when primalize gives a polycube that Definition 1 accepts
    (flipping loops can give the mirror of a polycube's structure, whose polycube comes out
    inside out: it is checked turned outward, as the file convention asks)."""
    valid4 = check_polycube_loop_structure(ls).valid
    try:
        q = primalize(ls)
        valid1 = check_polycube(q.outward()).valid
    except DualityError:
        valid1 = False
    event(f"valid={valid4}")
    assert valid4 == valid1
    if valid4:
        assert check_theorem3(ls).valid


@given(perturbed_structures())
def test_theorem3_whenever_loops_of_one_axis_are_disjoint(ls):
    rb = ReportBuilder("loop-structure", "Theorem 3")
    if not crossing_violations(rb, ls):
        assert check_theorem3(ls).valid


@given(perturbed_structures())
def test_labelled_view_forgets_only_sides(ls):
    labelled = ls.forget_orientation()
    report = check_polycube_loop_structure(labelled)
    # Without sides, only crossings can be detected, and they are exactly those of the oriented one.
    oriented = check_polycube_loop_structure(ls)
    crossing = [v for v in oriented.violations if "cross" in v.message]
    assert [v.message for v in report.violations] == [v.message for v in crossing]


def test_definition1_reports_every_kind_of_violation():
    # A cube with a corner moved off its lines and a repeated direction.
    q = load_example("cube")
    pos = list(q.positions)
    pos[7] = (2, 2, 2)
    report = check_polycube(Polycube(q.map, tuple(pos)))
    assert {v.condition for v in report.violations} == {"3"}
    assert len(report.violations) == 3  # the three edges at corner 7
    flat = [(0, 0, 0)] * 8
    report = check_polycube(Polycube(q.map, tuple(flat)))
    assert {v.condition for v in report.violations} == {"3"}


def test_definition1_on_a_non_closed_mesh():
    q = load_example("cube")
    report = check_polycube_faces(q.faces[:-1], q.positions)
    assert not report.valid
    assert {v.condition for v in report.violations} == {"closed"}
    statuses = {c.condition: c.status for c in report.checks}
    assert statuses["manifold"] == statuses["connected"] == "not checked"


def test_definition1_overlap():
    # The pillow as a polycube: degree 2, and quads that are not rectangles.
    faces = [[0, 1, 2, 3], [3, 2, 1, 0]]
    report = check_polycube_faces(faces, [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
    assert {v.condition for v in report.violations} == {"2"}
    report = check_polycube_faces(faces, [(0, 0, 0), (1, 0, 0), (2, 0, 0), (1, 0, 0)])
    assert "4" in {v.condition for v in report.violations}


def test_three_loops_in_a_hexagon():
    # A hexagonal prism's two hexagons: three loops meet in each (Condition 1 / Definition 3 condition 2).
    top = [0, 1, 2, 3, 4, 5]
    bottom = [6 + c for c in reversed(top)]
    sides = [[(i + 1) % 6, i, i + 6, (i + 1) % 6 + 6] for i in range(6)]
    m = HalfEdgeMap.from_faces([top, bottom, *sides])
    assert len(m.loop_system.loops) >= 1
    ls = LoopStructure(m, tuple(0 for _ in m.loop_system.loops), tuple(1 for _ in m.loop_system.loops))
    report = verify(ls)
    assert {(v.definition, v.condition) for v in report.violations} >= {("Definition 3", "2"),
                                                                        ("Definition 4", "1")}


def test_odd_faces_have_no_loops():
    tetra = [[0, 1, 2], [0, 3, 1], [1, 3, 2], [0, 2, 3]]
    with pytest.raises(OddFaceError):
        _ = HalfEdgeMap.from_faces(tetra).loop_system


@pytest.mark.parametrize("kind, genus", [("blob", 0), ("frame1", 1), ("frame2", 2)])
def test_strategies_cover_genus_0_to_2(kind, genus):
    from strategies import random_polycube

    for seed in range(10):
        q = random_polycube(seed, kind, 8)
        assert q.genus == genus
        assert check_polycube(q).valid


@given(perturbed_structures())
def test_level_graph_witnesses_equal_a_search_over_the_whole_graph(ls):
    """Each strongly connected part's witness cycle, searched within the part, is the cycle a
    search over the whole level graph (restricted to the part's arcs) finds: the same zones
    and loops in the same order, and one per part that has a cycle."""
    import networkx as nx

    from polyloops.core.directions import Axis
    from polyloops.core.zones import find_directed_cycle
    from polyloops.verify.loop_structure import cycle_violations

    if not ls.oriented:
        return
    expected = []
    for axis in Axis:
        g = ls.level_graph(axis)
        for part in nx.strongly_connected_components(g):
            cycle = find_directed_cycle(g.number_of_nodes(), list(g.subgraph(part).edges(keys=True)))
            if cycle is not None:
                expected.append((str(axis), [u for u, _, _ in cycle], [k for _, _, k in cycle]))
    event(f"parts with a cycle: {min(len(expected), 3)}")
    found = [(v.witness["axis"], v.witness["zones"], v.witness["loops"])
             for v in cycle_violations(ReportBuilder("loop-structure", "Definition 4"), ls)]
    assert found == expected
