"""Orientation solvers for labelled loop structures: exhaustive, SAT and SMT, one interface.

What lives here: the problem (:mod:`~polyloops.solvers.problem`: side-graph components from the
kernel's parity system, zones, level graphs), the solvers (:mod:`~polyloops.solvers.brute`,
:mod:`~polyloops.solvers.sat` with lazy cycle cuts and unsatisfiable cores,
:mod:`~polyloops.solvers.smt`), counting (:mod:`~polyloops.solvers.base`) and explanations of
failure (:mod:`~polyloops.solvers.explain`).  It imports the kernel, ``io`` and ``verify``.

>>> from polyloops.io.examples import load_example
>>> labelled = load_example("ring").dualize().forget_orientation()
>>> result = orient(labelled, solver="sat")
>>> result.found, result.structure is not None
(True, True)
>>> counts = [count_orientations(labelled, s) for s in SOLVERS]
>>> len(set(counts)) == 1
True
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from polyloops.core.structure import LoopStructure
from polyloops.solvers.base import Signs, Solver, axis_flip_factor, count, solve
from polyloops.solvers.brute import BruteForceSolver
from polyloops.solvers.explain import Explanation, explain
from polyloops.solvers.problem import OrientationProblem
from polyloops.solvers.sat import SatSolver
from polyloops.solvers.smt import SmtSolver

SOLVERS: dict[str, type] = {"brute": BruteForceSolver, "sat": SatSolver, "smt": SmtSolver}


def make_solver(name: str) -> Solver:
    """An orientation solver by name.

    Parameters
    ----------
    name:
        ``brute`` (exhaustive), ``sat`` (SAT with lazy cycle cuts) or ``smt`` (z3 with zone
        potentials).

    Returns
    -------
    Solver

    Raises
    ------
    ValueError
        For an unknown name.

    >>> make_solver("sat").name
    'sat'
    """
    try:
        return SOLVERS[name]()
    except KeyError:
        raise ValueError(f"unknown solver {name!r}; choose from {', '.join(SOLVERS)}") from None


@dataclass(frozen=True)
class OrientResult:
    """What :func:`orient` found: the oriented structure, or why there is none."""

    problem: OrientationProblem
    structure: LoopStructure | None
    explanation: Explanation | None

    @property
    def found(self) -> bool:
        """Whether an orientation was found."""
        return self.structure is not None


def orient(ls: LoopStructure, solver: str = "sat") -> OrientResult:
    """One orientation of a labelled loop structure that makes it a polycube loop structure (its
    sides are ignored if it has them), or the reason there is none.

    Parameters
    ----------
    ls:
        A loop structure.
    solver:
        ``sat`` (default), ``smt`` or ``brute``; all give a valid answer when there is one.

    Returns
    -------
    OrientResult
        ``structure`` is the oriented structure, or ``None`` with an ``explanation``.

    Raises
    ------
    ValueError
        For an unknown solver.

    >>> from polyloops.io.examples import load_example
    >>> orient(load_example("ring").dualize().forget_orientation()).found
    True
    >>> orient(load_example("torus-cycle")).explanation.condition
    '5'
    """
    problem = OrientationProblem(ls)
    signs = solve(make_solver(solver), problem)
    if signs is None:
        return OrientResult(problem, None, explain(problem))
    return OrientResult(problem, problem.structure.with_signs(signs), None)


def all_orientations(ls: LoopStructure, solver: str = "sat") -> Iterator[LoopStructure]:
    """Every orientation that makes ``ls`` a polycube loop structure, each once.

    Parameters
    ----------
    ls:
        A loop structure (sides ignored).
    solver:
        ``sat`` (default), ``smt`` or ``brute``.

    Returns
    -------
    Iterator[LoopStructure]

    Raises
    ------
    ValueError
        For an unknown solver.

    >>> from polyloops.io.examples import load_example
    >>> len(list(all_orientations(load_example("cube").dualize())))
    8
    """
    problem = OrientationProblem(ls)
    for signs in make_solver(solver).solutions(problem):
        yield problem.structure.with_signs(signs)


def count_orientations(ls: LoopStructure, solver: str = "sat") -> int:
    """The number of orientations that make ``ls`` a polycube loop structure, counted without
    listing them all (a product over the axes; bridge components double the count).

    Parameters
    ----------
    ls:
        A loop structure (sides ignored).
    solver:
        ``sat`` (default), ``smt`` or ``brute``.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        For an unknown solver.

    >>> from polyloops.io.examples import load_example
    >>> count_orientations(load_example("l-shape").dualize())
    8
    """
    return count(make_solver(solver), OrientationProblem(ls))


__all__ = [
    "SOLVERS", "BruteForceSolver", "Explanation", "OrientResult", "OrientationProblem", "SatSolver",
    "Signs", "SmtSolver", "all_orientations", "axis_flip_factor", "count_orientations", "explain",
    "make_solver", "orient",
]
