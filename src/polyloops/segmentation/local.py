"""The local criteria that labelling methods check, each a necessary condition.

- ``opposite-labels``: a boundary between charts of opposite labels (``+X`` next to ``-X``);
  faces of a polycube that share a creased edge have perpendicular normals.
- ``few-boundaries``: a chart with at most three boundaries; a rectilinear polygon has at
  least four corners, and each corner ends a boundary.
- ``closed-boundary``: a boundary that is a closed curve without corners; an edge of a
  polycube is straight, so cannot close up.
- ``chart-handle``: a chart with a handle; a region of a plane has none.
- ``corner``: a corner whose cyclic sequence of chart labels no polycube corner has (the
  chart views of the 126 configurations, :func:`~polyloops.generate.corners.chart_corners`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from polyloops.core.corners import canonical_rotation
from polyloops.core.directions import Direction
from polyloops.generate.corners import chart_label_cycles
from polyloops.segmentation.charts import Segmentation


@dataclass(frozen=True)
class LocalViolation:
    """One local criterion a labelled mesh breaks, where."""

    rule: str
    message: str
    charts: tuple[int, ...] = ()
    boundaries: tuple[int, ...] = ()
    corners: tuple[int, ...] = ()

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict of the violation."""
        return {"rule": self.rule, "message": self.message, "charts": list(self.charts),
                "boundaries": list(self.boundaries), "corners": list(self.corners)}


@dataclass(frozen=True)
class LocalResult:
    """Every local criterion's violations."""

    violations: tuple[LocalViolation, ...] = field(default_factory=tuple)

    @property
    def valid(self) -> bool:
        """Whether no local criterion is broken."""
        return not self.violations

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict of the result."""
        return {"valid": self.valid, "violations": [v.to_json() for v in self.violations]}


def labels_around(seg: Segmentation, corner: int) -> tuple[Direction, ...]:
    """The chart labels around a corner, counter-clockwise."""
    return tuple(seg.charts[chart].label for _, _, chart in seg.corners[corner].sides)


def check_local(seg: Segmentation) -> LocalResult:
    """The local criteria of labelling methods: opposite labels, few boundaries per chart, closed
    boundaries, handles, corner label sequences no polycube corner has."""
    out: list[LocalViolation] = []
    for b in seg.boundaries:
        left, right = seg.charts[b.left].label, seg.charts[b.right].label
        if left == -right:
            message = f"boundary {b.id} lies between chart {b.left} ({left}) and chart {b.right} ({right})"
            out.append(LocalViolation("opposite-labels", message, (b.left, b.right), (b.id,)))
        if b.closed:
            message = f"boundary {b.id} (charts {b.left} and {b.right}) is a closed curve without corners"
            out.append(LocalViolation("closed-boundary", message, (b.left, b.right), (b.id,)))
    for c in seg.charts:
        sides = [side for cycle in c.cycles for side in cycle]
        if len(sides) < 4 and not any(seg.boundaries[b].closed for b, _ in sides):
            out.append(LocalViolation("few-boundaries", f"chart {c.id} ({c.label}) has {len(sides)} "
                                      "boundaries; a polycube face has at least 4", (c.id,),
                                      tuple(b for b, _ in sides)))
        if c.genus > 0:
            out.append(LocalViolation("chart-handle", f"chart {c.id} ({c.label}) has {c.genus} handle(s); "
                                      "a region of a plane has none", (c.id,)))
    allowed = chart_label_cycles()
    for corner in seg.corners:
        labels = labels_around(seg, corner.id)
        if canonical_rotation(labels) not in allowed:
            shown = " ".join(str(d) for d in labels)
            message = (f"corner {corner.id} (mesh vertex {corner.vertex}) has charts {shown} around it, "
                       "which no polycube corner has")
            out.append(LocalViolation("corner", message,
                                      tuple(ch for _, _, ch in corner.sides),
                                      tuple(b for b, _, _ in corner.sides), (corner.id,)))
    return LocalResult(tuple(out))
