"""Exhaustive search over the choices of the side-graph components."""

from __future__ import annotations

from collections.abc import Iterator
from itertools import product

from polyloops.solvers.base import Signs, feasible_locally
from polyloops.solvers.problem import OrientationProblem


class BruteForceSolver:
    """Try every choice of every component, one axis at a time.

    Conditions 3 and 5 involve one axis at a time, so a choice is valid exactly when its
    part for each axis is; the search tries all ``2^k_axis`` parts of each axis (in the order
    of ``itertools.product((1, -1), ...)``) and yields the product of the valid ones.
    Cost: ``sum over axes of 2^k_axis`` acyclicity checks of ``O(loops + zones)`` each.
    """

    name = "brute"

    def solutions(self, problem: OrientationProblem) -> Iterator[Signs]:
        """Every valid sign vector, each once."""
        if not feasible_locally(problem):
            return
        per_axis: list[list[tuple[int, ...]]] = []
        for axis in problem.checked_axes:
            comps = [c for c in problem.components if c.axis == axis]
            sub = problem.restricted(axis, comps)
            valid = [choices for choices in product((1, -1), repeat=len(comps))
                     if sub.is_solution(sub.signs_from_choices(choices))]
            if not valid:
                return
            per_axis.append(valid)
        order = [c for axis in problem.checked_axes for c in problem.components if c.axis == axis]
        position = {id(c): i for i, c in enumerate(problem.components)}
        for parts in product(*per_axis):
            flat = [x for part in parts for x in part]
            choices = [0] * len(problem.components)
            for comp, x in zip(order, flat, strict=True):
                choices[position[id(comp)]] = x
            yield problem.signs_from_choices(choices)
