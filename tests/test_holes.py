"""Hole orientation: intersection numbers vanish in genus 0, are antisymmetric, are kept by
every loop move, follow the symmetries of space, and tell rings with different hole axes
apart; reach from those rings never meets."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.core.canonical import signature, transformed
from polyloops.core.directions import Axis
from polyloops.core.holes import PAIRS, hole_orientation, intersection_matrix, invariant_factors
from polyloops.core.moves import add_loop, additions, removals, remove_loop
from polyloops.core.symmetry import SIGNED_PERMUTATIONS
from polyloops.io.examples import load_example
from polyloops.reach.search import explore, from_signature, neighbours
from polyloops.shapes.voxels import polycube_from_voxels
from strategies import handle_zone_polycubes, polycubes, transform_cells

RING = {(x, y, 0) for x in range(3) for y in range(3) if (x, y) != (1, 1)}


def ring_along(axis: Axis):
    """The square ring of eight cubes with its hole along ``axis``."""
    perm = {Axis.Z: (0, 1, 2), Axis.X: (2, 0, 1), Axis.Y: (1, 2, 0)}[axis]
    return polycube_from_voxels(transform_cells(RING, perm, (1, 1, 1))).dualize()


@given(polycubes(kinds=("blob", "smooth"), max_size=8))
def test_genus0_intersections_vanish(q):
    ls = q.dualize()
    for a, b in PAIRS:
        assert all(x == 0 for row in intersection_matrix(ls, a, b) for x in row)


@given(polycubes(kinds=("frame1", "frame2")))
def test_intersection_is_antisymmetric(q):
    ls = q.dualize()
    for a, b in PAIRS:
        ab, ba = intersection_matrix(ls, a, b), intersection_matrix(ls, b, a)
        assert ab == [[-ba[j][i] for j in range(len(ba))] for i in range(len(ab))]


def test_invariant_factors():
    assert invariant_factors([[2, 4], [4, 8]]) == (2,)
    assert invariant_factors([[1, 0], [0, 3], [1, 0]]) == (1, 3)
    assert invariant_factors([[0, 0]]) == () == invariant_factors([])


@settings(max_examples=25)
@given(st.one_of(polycubes(kinds=("frame1", "frame2"), max_size=3), handle_zone_polycubes(max_bumps=1)),
       st.lists(st.integers(0, 10**6), min_size=1, max_size=4))
def test_moves_keep_the_invariant(q, picks):
    ls = q.dualize()
    before = hole_orientation(ls)
    for p in picks:
        options = [("add", mv) for a in Axis for mv in additions(ls, a, limit=15, max_length=8)]
        options += [("remove", i) for i in removals(ls)]
        kind, arg = options[p % len(options)]
        ls = add_loop(ls, arg) if kind == "add" else remove_loop(ls, arg)
        assert hole_orientation(ls) == before


@given(st.sampled_from(SIGNED_PERMUTATIONS))
def test_symmetries_permute_the_pairs(g):
    ls = load_example("two-axis-holes").dualize()
    assert hole_orientation(transformed(ls, g)) == hole_orientation(ls).permuted(g.perm)


def test_rings_with_different_hole_axes_differ():
    invariants = {axis: hole_orientation(ring_along(axis)) for axis in Axis}
    assert len({str(v) for v in invariants.values()}) == 3
    for axis, inv in invariants.items():
        others = "".join(a.name for a in Axis if a != axis)
        assert inv.ranks[others] == 0 and sum(inv.ranks.values()) == 2


@pytest.mark.parametrize("bound", [4])
def test_reach_from_rings_never_meets(bound):
    """Every structure within a few corners' moves of each ring keeps its ring's invariant, so
    the three searches (labelled mode) never meet."""
    reached = {}
    for axis in Axis:
        ring = ring_along(axis)
        seen = set()
        result = explore(ring, ring.map.num_corners + bound, max_depth=2)
        assert result.states > 1
        start = hole_orientation(ring)
        frontier = [ring]
        for _ in range(2):
            nxt = []
            for ls in frontier:
                for _, child in neighbours(ls, ring.map.num_corners + bound):
                    s = signature(child, "labelled")
                    if s not in seen:
                        seen.add(s)
                        nxt.append(child)
                        assert hole_orientation(child) == start
            frontier = nxt
        seen.add(signature(ring, "labelled"))
        assert len(seen) == result.states
        reached[axis] = seen
    assert not reached[Axis.X] & reached[Axis.Y]
    assert not reached[Axis.X] & reached[Axis.Z]
    assert not reached[Axis.Y] & reached[Axis.Z]


def test_bridged_ring_has_no_loop_around_its_hole():
    """Every loop of the bridged ring is null-homologous or goes around a bar, none around the
    hole: all intersection numbers vanish, so no move joins it to a flat ring."""
    assert hole_orientation(load_example("bridged-ring").dualize()).ranks == {"XY": 0, "XZ": 0, "YZ": 0}
    assert hole_orientation(ring_along(Axis.Z)).ranks["XZ"] == 1


def test_genus2_example_with_two_hole_axes():
    ls = load_example("two-axis-holes").dualize()
    assert ls.genus == 2
    assert hole_orientation(ls).ranks == {"XY": 1, "XZ": 1, "YZ": 2}
    assert from_signature(signature(ls, "labelled")) is not None


def test_info_shows_it(capsys):
    assert main(["info", "example:ring"]) == 0
    assert "holes     XY: rank 0; XZ: rank 1 (1); YZ: rank 1 (1)" in capsys.readouterr().out


def test_the_three_minimal_rings_differ_only_by_their_hole():
    """The bundled rings with their hole along X, Y and Z are one polycube up to symmetry, but
    three labelled classes with three hole orientations: along the hole's axis, the loops of
    the two other axes do not meet (rank 0), so no loop moves join any two of them."""
    rings = {axis: load_example(name).dualize() for axis, name in (("X", "ring-x"), ("Y", "ring-y"),
                                                                  ("Z", "ring"))}
    assert len({signature(ls, "full") for ls in rings.values()}) == 1
    assert len({signature(ls, "labelled") for ls in rings.values()}) == 3
    for axis, ls in rings.items():
        ranks = hole_orientation(ls).ranks
        flat = "".join(a for a in "XYZ" if a != axis)  # the pair across the hole
        assert ranks[flat] == 0 and all(r == 1 for pair, r in ranks.items() if pair != flat), (axis, ranks)
        assert ls.map.num_corners == 32
