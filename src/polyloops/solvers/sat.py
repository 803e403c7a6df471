"""SAT (python-sat): one variable per side-graph component, acyclicity by lazy cycle cuts.

Condition 3 is built into the variables: a component's loops take their signs from its
one variable, so every assignment meets Condition 3.  Condition 5 is added lazily: solve,
look for a directed cycle in a level graph, and if there is one add the clause "some loop on
this cycle points the other way"; repeat.  An eager encoding would need an order on the
zones of each axis (``O(zones^2)`` transitivity clauses, or bit-vector levels); level graphs
of real structures have few cycles, so a handful of cuts usually suffices and the lazy loop
stays small.  Each cut removes only assignments that contain that cycle, so no solution is
lost, and every assignment returned has been checked acyclic.
"""

from __future__ import annotations

from collections.abc import Iterator

from pysat.solvers import Solver as PySatSolver

from polyloops.core.directions import Axis
from polyloops.solvers.base import Signs, feasible_locally
from polyloops.solvers.problem import OrientationProblem

Arc = tuple[int, int, int]


class SatSolver:
    """One boolean per side-graph component (Condition 3 holds by construction); solutions
    come from a SAT solver (pysat, Glucose by default), and each level-graph cycle found in a
    model is cut by a clause, until the model has none (Condition 5).  Every solution is then
    blocked to list the next."""

    name = "sat"

    def __init__(self, backend: str = "glucose4"):
        self.backend = backend

    @staticmethod
    def _component_of(problem: OrientationProblem) -> dict[int, tuple[int, int]]:
        """loop -> (variable, relative sign)."""
        out = {}
        for var, comp in enumerate(problem.components, start=1):
            for loop, rel in zip(comp.loops, comp.relative, strict=True):
                out[loop] = (var, rel)
        return out

    @staticmethod
    def _cut(problem: OrientationProblem, where: dict[int, tuple[int, int]], arcs: list[Arc],
             signs: Signs) -> list[int]:
        """Clause: some loop on the cycle takes the opposite sign (loops outside a restricted
        problem cannot flip, so they add nothing; an empty clause means no way out)."""
        clause = set()
        for _, _, loop in arcs:
            if loop not in where:
                continue
            var, rel = where[loop]
            wanted = -signs[loop] * rel  # the component choice that flips this loop
            clause.add(var if wanted > 0 else -var)
        return sorted(clause)

    def _signs(self, problem: OrientationProblem, model: list[int]) -> Signs:
        choice = {abs(lit): (1 if lit > 0 else -1) for lit in model}
        return problem.signs_from_choices([choice.get(v, 1) for v in range(1, problem.k + 1)])

    def solutions(self, problem: OrientationProblem) -> Iterator[Signs]:
        """Every valid sign vector, each once."""
        if not feasible_locally(problem):
            return
        where = self._component_of(problem)
        with PySatSolver(name=self.backend) as s:
            if problem.k:
                s.add_clause([1, -1])  # declare the variables
                for v in range(2, problem.k + 1):
                    s.add_clause([v, -v])
            while s.solve():
                model = s.get_model() or []
                signs = self._signs(problem, model)
                found = problem.find_cycle(signs)
                if found is not None:
                    cut = self._cut(problem, where, found[1], signs)
                    if not cut:
                        return
                    s.add_clause(cut)
                    continue
                yield signs
                if not problem.k:
                    return
                # Block this assignment of the component variables.
                s.add_clause([-lit for lit in model if abs(lit) <= problem.k])

    def blocking_cycles(self, problem: OrientationProblem) -> list[tuple[Axis, list[Arc]]] | None:
        """If no acyclic choice exists: a small set of cycles whose cuts are unsatisfiable
        together (deletion-minimal), else ``None``.  Each cut is guarded by a selector
        variable and assumed, so the solver's unsatisfiable core names the cuts that matter,
        and :func:`minimal_core` shrinks it in the same solver."""
        where = self._component_of(problem)
        cuts: dict[int, tuple[Axis, list[Arc]]] = {}  # selector variable -> its cycle
        with PySatSolver(name=self.backend) as s:
            while s.solve(assumptions=list(cuts)):
                signs = self._signs(problem, s.get_model() or [])
                found = problem.find_cycle(signs)
                if found is None:
                    return None
                clause = self._cut(problem, where, found[1], signs)
                if not clause:
                    return [found]
                selector = problem.k + 1 + len(cuts)
                cuts[selector] = found
                s.add_clause([-selector, *clause])
            core = minimal_core(s, [lit for lit in s.get_core() or [] if lit in cuts])
        return [cuts[selector] for selector in core]


def minimal_core(solver: PySatSolver, core: list[int], limit: int | None = 200) -> list[int]:
    """Drop the assumptions of an unsatisfiable core that it does not need (deletion, in the
    solver that found it), leaving a core from which no assumption can be dropped; a core
    larger than ``limit`` (``None``: no limit) is returned as it is, sorted."""
    if limit is not None and len(core) > limit:
        return sorted(core)
    keep = sorted(core)
    for lit in list(keep):
        trial = [x for x in keep if x != lit]
        if not solver.solve(assumptions=trial):
            keep = trial
    return keep
