"""SMT (z3): a Boolean per side-graph component and an integer potential per zone.

A loop oriented from zone ``u`` to zone ``v`` asserts ``potential(u) < potential(v)``, so a
model exists exactly when some choice leaves every level graph acyclic (potentials are a
topological numbering).  All solutions are enumerated by blocking each model's Booleans.
"""

from __future__ import annotations

from collections.abc import Iterator

import z3

from polyloops.solvers.base import Signs, feasible_locally
from polyloops.solvers.problem import OrientationProblem


class SmtSolver:
    """Condition 5 as integer zone potentials in z3: one boolean per side-graph component and
    one integer level per zone, each loop's ``+`` zone above its ``-`` zone; a model is a
    valid orientation, and each is blocked to list the next."""

    name = "smt"

    def solutions(self, problem: OrientationProblem) -> Iterator[Signs]:
        """Every valid sign vector, each once."""
        if not feasible_locally(problem):
            return
        s = z3.Solver()
        choice = [z3.Bool(f"c{i}") for i in range(problem.k)]
        where = {}
        for i, comp in enumerate(problem.components):
            for loop, rel in zip(comp.loops, comp.relative, strict=True):
                where[loop] = (choice[i], rel)
        for axis in problem.checked_axes:
            n = problem.zone_counts[axis]
            pot = [z3.Int(f"p{axis.name}{z}") for z in range(n)]
            for p in pot:
                s.add(p >= 0, p < n)
            for loop in problem.loops_of_axis[axis]:
                left, right = problem.loop_zones[loop]
                if loop in where:
                    var, rel = where[loop]
                    positive = var if rel > 0 else z3.Not(var)  # the loop's sign is +1
                else:  # a loop outside a restricted problem keeps its sign
                    positive = z3.BoolVal(problem.signs_from_choices([1] * problem.k)[loop] > 0)
                s.add(z3.If(positive, pot[left] < pot[right], pot[right] < pot[left]))
        while s.check() == z3.sat:
            model = s.model()
            values = [z3.is_true(model.eval(c, model_completion=True)) for c in choice]
            yield problem.signs_from_choices([1 if v else -1 for v in values])
            if not choice:
                return
            s.add(z3.Or([c != z3.BoolVal(v) for c, v in zip(choice, values, strict=True)]))
