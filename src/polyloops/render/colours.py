"""The paper's colours: X purple, Y orange, Z green; the - side lighter than the + side."""

from __future__ import annotations

from polyloops.core.directions import Axis, Direction

AXIS_COLOUR = {Axis.X: "#7b3294", Axis.Y: "#e66101", Axis.Z: "#1a9641"}
LIGHT_COLOUR = {Axis.X: "#c2a5cf", Axis.Y: "#fdb863", Axis.Z: "#a6dba0"}


def direction_colour(d: Direction) -> str:
    """Darker for the + direction, lighter for the - direction."""
    return AXIS_COLOUR[d.axis] if d.sign > 0 else LIGHT_COLOUR[d.axis]
