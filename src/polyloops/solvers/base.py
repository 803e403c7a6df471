"""One interface for the orientation solvers.

Every solver yields the valid sign vectors of a problem (one sign per loop, ``+1`` when the
loop's ``+`` side is on the right of its stored walk).  ``solve`` takes the first,
``count`` counts them.  When there is none, :func:`polyloops.solvers.explain.explain` says why.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Protocol

from polyloops.core.directions import Axis
from polyloops.solvers.problem import OrientationProblem

Signs = tuple[int, ...]


class Solver(Protocol):
    """What every orientation solver offers: its name and the valid sign vectors of a problem."""

    name: str

    def solutions(self, problem: OrientationProblem) -> Iterator[Signs]:
        """Every valid sign vector, each once."""
        ...


def solve(solver: Solver, problem: OrientationProblem) -> Signs | None:
    """The first valid sign vector, or ``None`` when there is none."""
    if not feasible_locally(problem):
        return None
    return next(solver.solutions(problem), None)


def count(solver: Solver, problem: OrientationProblem) -> int:
    """The number of valid orientations, without listing them all.

    Conditions 3 and 5 involve one axis at a time, so the count is a product over the axes;
    within an axis, a component whose loops are all bridges of the level graph doubles the
    count, and only the other components are enumerated by the solver.
    """
    if not feasible_locally(problem):
        return 0
    total = 1
    for axis in Axis:
        free = problem.bridge_components(axis)
        rest = [c for c in problem.components_of(axis) if c not in free]
        n = sum(1 for _ in solver.solutions(problem.restricted(axis, rest)))
        total *= n * 2 ** len(free)
    return total


def count_naively(solver: Solver, problem: OrientationProblem) -> int:
    """The number of valid orientations by listing every one (exponential; for tests)."""
    if not feasible_locally(problem):
        return 0
    return sum(1 for _ in solver.solutions(problem))


def feasible_locally(problem: OrientationProblem) -> bool:
    """Conditions 1-4 can be met by some choice of sides."""
    return problem.colourable and not problem.local_violations


def axis_flip_factor(problem: OrientationProblem) -> int:
    """How many orientations each class of axis flips holds: flipping every loop of one axis
    keeps validity, so ``2^(axes that have loops)``.

    Parameters
    ----------
    problem:
        An orientation problem.

    Returns
    -------
    int

    Raises
    ------
    AttributeError
        When ``problem`` is not an :class:`OrientationProblem`.

    >>> from polyloops.io.examples import load_example
    >>> axis_flip_factor(OrientationProblem(load_example("cube").dualize()))
    8
    """
    return 2 ** sum(1 for a in Axis if problem.loops_of_axis[a])
