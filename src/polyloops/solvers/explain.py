"""Why a labelled loop structure has no orientation: a condition no sides can mend, an odd
cycle of sides (Condition 3), or a set of level-graph cycles one of which closes for every
choice of sides (Condition 5).

>>> from polyloops.io.examples import load_example
>>> explain(OrientationProblem(load_example("torus-cycle"))).condition
'5'
>>> explain(OrientationProblem(load_example("l-shape").dualize())) is None
True
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from polyloops.solvers.problem import OrientationProblem
from polyloops.solvers.sat import SatSolver


@dataclass(frozen=True)
class Explanation:
    """Why no orientation exists."""

    condition: str
    reason: str
    witness: dict[str, Any] = field(default_factory=dict)


def explain(problem: OrientationProblem) -> Explanation | None:
    """The reason no orientation exists, or ``None`` if one does.

    Parameters
    ----------
    problem:
        An orientation problem.

    Returns
    -------
    Explanation or None
        Its ``condition`` is ``"3"`` (an odd cycle of sides), ``"local"`` (a condition no sides
        can mend) or ``"5"`` (level-graph cycles, one of which closes for every choice), with
        a ``witness``.

    Notes
    -----
    Nothing is raised for a built problem.

    >>> from polyloops.io.examples import load_example
    >>> [explain(OrientationProblem(load_example(n))).condition
    ...  for n in ("self-crossing", "degree-two", "torus-cycle")]
    ['3', 'local', '5']
    """
    if problem.odd_cycles:
        odd = problem.odd_cycles[0]
        return Explanation("3", odd.describe(),
                           {"axis": str(odd.axis), "odd_cycle": [[loop, side] for loop, side in odd.sides]})
    if problem.local_violations:
        return Explanation("local", problem.local_violations[0],
                           {"violations": problem.local_violations})
    cycles = SatSolver().blocking_cycles(problem)
    if cycles is None:
        return None
    parts = []
    for axis, arcs in cycles:
        zones = [a[0] for a in arcs]
        parts.append({"axis": str(axis), "zones": zones, "loops": [a[2] for a in arcs]})
    if len(parts) == 1:
        p = parts[0]
        reason = (f"the {p['axis']}-graph cycle through zones {p['zones']} along loops {p['loops']} "
                  "closes for every choice of sides")
    else:
        reason = (f"every choice of sides closes one of {len(parts)} level-graph cycles: "
                  + "; ".join(f"{p['axis']} zones {p['zones']}" for p in parts))
    return Explanation("5", reason, {"cycles": parts})
