"""The surface conditions shared by every definition: closed, oriented, manifold, connected."""

from __future__ import annotations

from polyloops.core.halfedge import MapProblem
from polyloops.verify.report import ReportBuilder, Violation

# MapProblem.kind -> (condition name, statement)
SURFACE_CONDITIONS = {
    "closed": "every edge lies in exactly two faces",
    "orientable": "the faces are oriented consistently",
    "manifold": "the faces at each corner form one fan",
    "connected": "the surface is connected",
}
_CONDITION_OF_KIND = {
    "boundary-edge": "closed",
    "branching-edge": "closed",
    "orientation": "orientable",
    "non-manifold-corner": "manifold",
    "disconnected": "connected",
}


def add_surface_checks(rb: ReportBuilder, problems: tuple[MapProblem, ...] | None) -> None:
    """Record the surface conditions; ``problems`` is ``None`` when the map was built."""
    found: dict[str, list[Violation]] = {name: [] for name in SURFACE_CONDITIONS}
    for p in problems or ():
        found[_CONDITION_OF_KIND[p.kind]].append(rb.violation(_CONDITION_OF_KIND[p.kind], p.message,
                                                              **p.witness))
    for name, statement in SURFACE_CONDITIONS.items():
        # The map builder stops before the fan and component checks when edges are bad.
        skipped = problems and name in ("manifold", "connected") and any(
            p.kind in ("boundary-edge", "branching-edge", "orientation") for p in problems)
        if skipped:
            rb.given(name, statement, "not checked: the edges do not form a closed oriented surface",
                     status="not checked")
        else:
            rb.condition(name, statement, found[name])
