"""The catalog's move graph: every removal named right, additions above as its reverse, and a
way down to the cube from every class, each step one move from the one before."""

from functools import cache
from itertools import pairwise

import pytest

from polyloops.catalog.census import read_catalog
from polyloops.core.canonical import canonical_form
from polyloops.core.moves import remove_loop
from polyloops.io.formats import to_data
from polyloops.reach.move_graph import move_graph
from polyloops.verify import check_polycube_loop_structure

THROUGH = 26  # includes the non-incremental polycube P26.20, whose way down is a detour


@cache
def graph():
    census = read_catalog().through(THROUGH)
    return census, move_graph(census)


def test_removals_name_the_class_each_loop_leaves():
    """Each class's removable loops, tried one by one with the full checker, and the class
    each leaves, found by signature in the catalog (not through the move graph's code)."""
    census, g = graph()
    by_signature = {e.signature: e.name for e in census}
    for entry in census:
        ls = entry.structure()
        expected = []
        for lp in ls.loops:
            try:
                smaller = remove_loop(ls, lp.id)
            except ValueError:  # not even a surface
                continue
            if check_polycube_loop_structure(smaller).valid:
                expected.append((lp.id, by_signature[canonical_form(smaller, "full").signature]))
        assert [(r.loop, r.leaves) for r in g.removals[entry.name]] == expected, entry.name
        assert (len(expected) == 0) == entry.record.irreducible


def test_additions_above_are_the_removals_reversed():
    _, g = graph()
    pairs = {(a, r.leaves) for a, found in g.removals.items() for r in found}
    assert pairs == {(a, b) for b, above in g.above.items() for a in above}


def test_every_class_has_a_way_down_of_single_moves():
    """From every class a way to the cube: each step the move applied to the step before, up
    to renumbering (exactly, within a detour), a polycube loop structure, and a catalog class's
    step in the class's own numbering (its representative)."""
    census, g = graph()
    for entry in census:
        descent = g.descents[entry.name]
        assert descent.steps[0].name == entry.name and descent.steps[-1].name == "P8.1"
        for before, step in zip(descent.steps, descent.steps[1:], strict=False):
            after = step.move.apply(before.structure)
            assert canonical_form(after, "full").signature == canonical_form(step.structure, "full").signature
            assert check_polycube_loop_structure(step.structure).valid
            if step.name is not None:
                assert to_data(step.structure) == to_data(census[step.name].structure())
    detour = g.descents["P26.20"]
    corners = [s.structure.map.num_corners for s in detour.steps]
    assert corners[1] > corners[0] and corners[-1] == 8  # it climbs first: P26.20 is irreducible


@pytest.mark.slow
def test_every_class_of_the_shipped_catalog_has_a_way_down():
    """The whole shipped catalog (about 20 s): a way down from every class."""
    census = read_catalog()
    g = move_graph(census)
    assert set(g.descents) == {e.name for e in census}
    assert all(d.steps[-1].name == "P8.1" for d in g.descents.values())


def test_distances_from_the_cube_are_the_search_s():
    """The breadth-first distances among the catalog's classes through 22 corners are the
    distances of reach's own search of the move graph (all 48 symmetries, bound 22): the same
    number of classes at each distance; each path's steps are one move apart."""
    from collections import Counter

    from polyloops.io.examples import load_example
    from polyloops.reach.search import explore

    census = read_catalog().through(22)
    g = move_graph(census)
    found = explore(load_example("cube").dualize(), 22, mode="full")
    assert Counter(g.distance.values()) == Counter(found.by_distance)
    for entry in census:
        path = g.path_from_cube(entry.name)
        assert len(path) - 1 == g.distance[entry.name] and path[0] == "P8.1"
        for a, b in pairwise(path):
            assert b in {r.leaves for r in g.removals[a]} or a in {r.leaves for r in g.removals[b]}
