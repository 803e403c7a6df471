"""Additions drawn as cheapest paths (:mod:`polyloops.segment.paths`): valid by construction."""

from __future__ import annotations

import itertools

from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.core.canonical import canonical_form
from polyloops.core.directions import Axis
from polyloops.core.moves import add_loop, valid_additions
from polyloops.segment.certify import layout_problem
from polyloops.segment.embedded import PathLoop, kernel_addition, read_structure
from polyloops.segment.layout import lay_out
from polyloops.segment.paths import addition_path
from polyloops.segment.search import candidate_loops, start_state
from polyloops.segment.surface import surface_of
from polyloops.shapes.meshes import ellipsoid
from polyloops.verify import check_polycube_loop_structure


def cube_on(a, b, c, jitter=0.0, seed=0):
    r, loops, _ = candidate_loops(surface_of(*ellipsoid(a, b, c, level=3, jitter=jitter, seed=seed)), 3)
    return read_structure(r, [loops[i] for i in start_state(r, loops)])


@settings(max_examples=4, deadline=None)
@given(st.floats(0.7, 2.0), st.floats(0.7, 2.0), st.floats(0.7, 2.0), st.floats(0, 0.03), st.integers(0, 50))
def test_a_path_drawn_for_a_valid_addition_is_that_addition(a, b, c, jitter, seed):
    """For every valid addition of the cube (both levels of additions: from the cube and
    from each structure one addition away), the path drawn for it, read off the surface,
    gives exactly the kernel's add_loop (labelled canonical forms), a polycube loop
    structure, and the path's own walk is the addition it was drawn for."""
    e = cube_on(a, b, c, jitter, seed)
    drawn = 0
    for axis in Axis:
        for move in itertools.islice(valid_additions(e.structure, axis), 4):
            path = addition_path(e, move)
            if path is None:
                continue
            after = read_structure(e.refined, [*e.loops, path])
            kernel = add_loop(e.structure, move)
            assert canonical_form(after.structure, "labelled") == canonical_form(kernel, "labelled")
            assert check_polycube_loop_structure(after.structure).valid
            walked = kernel_addition(e, path)
            k = walked.cycle.index(move.cycle[0])
            assert walked.axis == move.axis and walked.cycle[k:] + walked.cycle[:k] == move.cycle
            drawn += 1
            if drawn == 1:  # and once more from there
                for second in itertools.islice(valid_additions(after.structure, Axis((axis + 1) % 3)), 2):
                    path2 = addition_path(after, second)
                    if path2 is not None:
                        again = read_structure(e.refined, [*after.loops, path2])
                        assert canonical_form(again.structure, "labelled") == \
                            canonical_form(add_loop(after.structure, second), "labelled")
    assert drawn >= 3


def test_a_structure_with_drawn_loops_is_laid_out_and_certified():
    e = cube_on(1.6, 1.0, 0.8)
    move = next(valid_additions(e.structure, Axis.X))
    path = addition_path(e, move)
    assert isinstance(path, PathLoop)
    lay = lay_out(e.refined, [*e.loops, path])
    assert layout_problem(lay) is None


def test_a_cycle_through_a_region_twice_gets_no_path():
    e = cube_on(1.5, 1.0, 0.8)
    move = next(valid_additions(e.structure, Axis.X))
    twice = type(move)(move.axis, (*move.cycle, move.cycle[0], move.cycle[1]))
    assert addition_path(e, twice) is None


def test_a_drawn_loop_follows_its_edges_when_they_are_cut():
    """The layout cuts edges in its way; a drawn loop then runs through their middles and the
    structure read off the finer surface is the same."""
    from polyloops.segment.layout import relocate
    from polyloops.segment.refine import split_edges

    e = cube_on(1.4, 1.0, 0.9)
    path = addition_path(e, next(valid_additions(e.structure, Axis.Y)))
    before = read_structure(e.refined, [*e.loops, path])
    finer = split_edges(e.refined, sorted(path.edges())[::2])
    moved = relocate(finer, [*e.loops, path])
    assert len(moved[-1].vertices) == len(path.vertices) + len(sorted(path.edges())[::2])
    assert set(path.vertices) <= set(moved[-1].vertices)
    after = read_structure(finer, moved)
    assert canonical_form(after.structure, "labelled") == canonical_form(before.structure, "labelled")
