"""Loop additions on zones with a handle (positive genus), where the paper's acyclicity
argument fails: a loop around the handle leaves its zone connected and its arc is a self-loop."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.core.directions import Axis
from polyloops.core.moves import (
    Addition,
    _AdditionGraph,
    add_loop,
    additions,
    count_additions,
    is_valid_addition,
    removals,
    remove_loop,
    separates_zone,
)
from polyloops.io.examples import BRIDGED_RING_CUBES, load_example
from polyloops.shapes.voxels import polycube_from_voxels
from polyloops.verify import check_polycube, check_polycube_loop_structure
from strategies import bridged_ring, handle_zone_polycubes
from test_moves import brute_additions

BRIDGED = BRIDGED_RING_CUBES  # the counterexample: example:bridged-ring


def local_cycles(ls, axis):
    """Every simple cycle of G_V^axis: the paper's candidates, before the separation test."""
    return [Addition(axis, c) for c in _AdditionGraph(ls, axis).cycles()]


def has_self_loop(ls, axis):
    return any(u == v for u, v in ls.level_graph(axis).edges())


def test_strategy_makes_zones_with_a_handle():
    assert sorted(BRIDGED) == sorted(bridged_ring(3, 3, 1, []))
    for holes in (1, 2):
        ls = polycube_from_voxels(bridged_ring(3, 3, holes, [])).dualize()
        assert ls.genus == holes
        assert max(ls.zones(Axis.Z).genera) > 0


def test_the_counterexample():
    ls = polycube_from_voxels(BRIDGED).dualize()
    assert ls.genus == 1 and ls.zones(Axis.Z).total_genus == 1
    candidates = local_cycles(ls, Axis.Z)
    bad = [mv for mv in candidates if not check_polycube_loop_structure(add_loop(ls, mv)).valid]
    assert bad, "the paper's local test alone admits loops around the handle"
    for mv in bad:
        assert has_self_loop(add_loop(ls, mv), Axis.Z)
        assert not separates_zone(ls, mv) and not is_valid_addition(ls, mv)
    listed = list(additions(ls, Axis.Z))
    assert len(listed) == len(candidates) - len(bad) == count_additions(ls)["Z"]
    assert set(listed) == {mv for mv in brute_additions(ls) if mv.axis == Axis.Z}


def test_cli_add_refuses_a_loop_around_the_handle(tmp_path, capsys):
    ls = load_example("bridged-ring").dualize()
    bad = next(mv for mv in local_cycles(ls, Axis.Z) if not separates_zone(ls, mv))
    out = tmp_path / "out.json"
    move = "Z:" + ",".join(map(str, bad.cycle))
    assert main(["add", "example:bridged-ring", move, "-o", str(out)]) == 1
    assert "not a valid loop addition" in capsys.readouterr().err
    assert not out.exists()


@settings(max_examples=15)
@given(handle_zone_polycubes(), st.integers(0, 10**6))
def test_separation_is_exactly_no_self_loop(q, start):
    """The separation test agrees with inserting the loop and looking at the level graph."""
    ls = q.dualize()
    for axis in Axis:
        cycles = local_cycles(ls, axis)
        for mv in (cycles[start % len(cycles):] + cycles)[:25]:
            assert separates_zone(ls, mv) == (not has_self_loop(add_loop(ls, mv), axis))


@settings(max_examples=3)
@given(handle_zone_polycubes().filter(lambda q: q.map.num_corners <= 44))
def test_additions_equal_brute_force_on_handle_zones(q):
    ls = q.dualize()
    assert set(additions(ls)) == brute_additions(ls)


@pytest.mark.slow
@settings(max_examples=12)
@given(handle_zone_polycubes())
def test_additions_equal_brute_force_on_handle_zones_larger(q):
    ls = q.dualize()
    assert set(additions(ls)) == brute_additions(ls)


@settings(max_examples=15)
@given(handle_zone_polycubes(max_bumps=1), st.lists(st.integers(0, 10**6), min_size=1, max_size=4))
def test_moves_on_handle_zones_keep_a_polycube(q, picks):
    ls = q.dualize()
    for p in picks:
        options = [("add", mv) for a in Axis for mv in additions(ls, a, limit=20)]
        options += [("remove", i) for i in removals(ls)]
        kind, arg = options[p % len(options)]
        ls = add_loop(ls, arg) if kind == "add" else remove_loop(ls, arg)
        assert check_polycube_loop_structure(ls).valid
    assert check_polycube(ls.primalize()).valid
