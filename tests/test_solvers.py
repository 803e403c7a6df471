"""The orientation solvers agree with each other and with the Definition-4 checker."""

import itertools
import json
from pathlib import Path

import pytest
from hypothesis import event, given, settings

from polyloops.cli import main
from polyloops.io.examples import load_example
from polyloops.io.formats import dumps, loads
from polyloops.shapes.voxels import polycube_from_voxels
from polyloops.solvers import SOLVERS, OrientationProblem, axis_flip_factor, explain, make_solver, orient
from polyloops.solvers.base import count, count_naively, solve
from polyloops.verify import check_polycube_loop_structure
from strategies import labelled_structures, pillar_cells, polycubes

FIXTURE = Path(__file__).parent / "fixtures" / "pillars-genus18.json"


def all_solutions(problem, name):
    return sorted(make_solver(name).solutions(problem))


def agree(ls, limit=256):
    """Found, count and (when few enough) every solution agree across the three solvers."""
    problem = OrientationProblem(ls)
    found = {name: solve(make_solver(name), problem) is not None for name in SOLVERS}
    counts = {name: count(make_solver(name), problem) for name in SOLVERS}
    assert len(set(found.values())) == 1, found
    assert len(set(counts.values())) == 1, counts
    n = counts["sat"]
    assert (n > 0) == found["sat"]
    if n <= limit:
        lists = {name: all_solutions(problem, name) for name in SOLVERS}
        assert lists["brute"] == lists["sat"] == lists["smt"]
        assert len(lists["sat"]) == n == count_naively(make_solver("brute"), problem)
        for signs in lists["sat"][:: max(1, n // 16)]:  # the checker on a spread of them
            assert check_polycube_loop_structure(ls.with_signs(signs)).valid
    if n:
        assert n % axis_flip_factor(problem) == 0
        assert explain(problem) is None
    else:
        assert explain(problem) is not None
    return problem, n


@given(labelled_structures())
def test_solvers_agree(ls):
    problem, n = agree(ls)
    event("solvable" if n else "unsolvable")
    event(f"acyclicity bites: {n < 2 ** problem.k}" if n else "-")


@settings(max_examples=15)
@given(polycubes(max_size=3))
def test_solutions_are_exactly_the_valid_orientations(q):
    """The slow obvious twin: try all 2^loops sign vectors with the Definition-4 checker."""
    ls = q.dualize().forget_orientation()
    if len(ls.loops) > 11:
        return
    valid = sorted(signs for signs in itertools.product((1, -1), repeat=len(ls.loops))
                   if check_polycube_loop_structure(ls.with_signs(signs)).valid)
    assert all_solutions(OrientationProblem(ls), "sat") == valid


@given(polycubes())
def test_the_polycube_orientation_is_found(q):
    ls = q.dualize()
    problem = OrientationProblem(ls)
    assert ls.signs in set(make_solver("sat").solutions(problem))
    if q.genus == 0:  # Corollary: level graphs are trees, every choice is acyclic
        assert count(make_solver("sat"), problem) == 2 ** problem.k


def test_acyclicity_bites_on_pillars():
    ls = polycube_from_voxels(pillar_cells(0, 0, 3)).dualize().forget_orientation()
    problem, n = agree(ls)
    assert 0 < n < 2 ** problem.k


def test_fixture_is_what_the_builder_makes():
    built = polycube_from_voxels(pillar_cells(7, 7, 7)).dualize().forget_orientation()
    assert FIXTURE.read_text() == dumps(built)


def test_fixture_genus_2_and_k_20():
    ls = loads(FIXTURE.read_text())
    assert not ls.oriented and ls.genus >= 2
    problem, n = agree(ls, limit=1024)
    assert problem.k >= 20
    assert 0 < n < 2 ** problem.k


def test_unsat_witnesses():
    torus = OrientationProblem(load_example("torus-cycle"))
    why = explain(torus)
    assert why.condition == "5" and why.witness["cycles"]
    for cycle in why.witness["cycles"]:
        assert len(cycle["zones"]) == len(cycle["loops"]) >= 1
    crossing = explain(OrientationProblem(load_example("self-crossing")))
    assert crossing.condition == "3" and crossing.witness["odd_cycle"]
    assert explain(OrientationProblem(load_example("degree-two"))).condition == "local"


def test_orient_api():
    result = orient(load_example("ring").dualize().forget_orientation(), solver="smt")
    assert result.found and check_polycube_loop_structure(result.structure).valid
    assert not orient(load_example("torus-cycle")).found


def test_cli_count_json(capsys):
    assert main(["orient", "example:ring", "--count", "--json", "--solver", "brute"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["count"] == 8 and data["count_modulo_axis_flips"] == 1 and data["k"] == 4


def test_cli_no_orientation(capsys):
    assert main(["orient", "example:torus-cycle"]) == 1
    err = capsys.readouterr().err
    assert "no orientation" in err and "X" in err and err.count("\n") == 1


def test_cli_all_to_file(capsys, tmp_path):
    out = tmp_path / "all.jsonl"
    assert main(["orient", "example:l-shape", "--all", "-o", str(out)]) == 0
    lines = out.read_text().splitlines()
    assert len(lines) == 8
    for line in lines:
        assert check_polycube_loop_structure(loads(line)).valid


@pytest.mark.parametrize("solver", sorted(SOLVERS))
def test_cli_one(capsys, solver):
    assert main(["orient", "example:box-2x1x1", "--solver", solver]) == 0
    ls = loads(capsys.readouterr().out)
    assert ls.oriented and check_polycube_loop_structure(ls).valid


def check_blocking_cycles(problem):
    """When no choice of sides is acyclic, the cycles the core names close for every choice
    (checked over all 2^k choices), and dropping any one of them leaves a choice that avoids
    the rest (deletion-minimal).  Returns whether the problem had no acyclic choice."""
    from polyloops.solvers.sat import SatSolver

    cycles = SatSolver().blocking_cycles(problem)
    choices = [problem.signs_from_choices(c) for c in itertools.product((1, -1), repeat=problem.k)]

    def closes(signs, cycle):
        axis, arcs = cycle
        return set(arcs) <= set(problem.arcs(signs, axis))

    acyclic = [s for s in choices if problem.find_cycle(s) is None]
    if cycles is None:
        assert acyclic
        return False
    assert not acyclic and cycles
    assert all(any(closes(s, c) for c in cycles) for s in choices)
    for i in range(len(cycles)):
        rest = cycles[:i] + cycles[i + 1:]
        assert any(not any(closes(s, c) for c in rest) for s in choices)
    return True


def test_blocking_cycles_of_the_examples():
    from polyloops.core.duality import DualityError
    from polyloops.core.polycube import Polycube
    from polyloops.io.examples import EXAMPLES

    unsat = []
    for name in sorted(EXAMPLES):
        structure = load_example(name)
        if isinstance(structure, Polycube):
            try:
                structure = structure.dualize()
            except DualityError:  # a polycube that does not dualize: nothing to orient
                continue
        problem = OrientationProblem(structure)
        if not (problem.odd_cycles or problem.local_violations) and problem.k <= 12 \
                and check_blocking_cycles(problem):
            unsat.append(name)
    assert "torus-cycle" in unsat


@settings(max_examples=40, deadline=None)
@given(labelled_structures())
def test_blocking_cycles_on_random_structures(ls):
    problem = OrientationProblem(ls)
    if not (problem.odd_cycles or problem.local_violations) and problem.k <= 10:
        check_blocking_cycles(problem)
