"""Axes and the six axis directions.

An edge of a polycube is parallel to one axis; seen from one of its corners it
points in one of six directions ``+X, -X, +Y, -Y, +Z, -Z``.  In a loop structure
the same information is carried by the loop that crosses the edge: its axis
label and which of its sides is the ``+`` side.

>>> Direction.parse("+Y").axis
<Axis.Y: 1>
>>> str(-Direction.parse("+Y"))
'-Y'
>>> Direction.of(Axis.Z, -1)
Direction.NZ
"""

from __future__ import annotations

from enum import IntEnum


class Axis(IntEnum):
    """One of the three coordinate axes, also the label of a loop."""

    X = 0
    Y = 1
    Z = 2

    def __str__(self) -> str:
        return self.name

    @classmethod
    def parse(cls, text: str) -> Axis:
        """Read ``"X"``, ``"Y"`` or ``"Z"``; raise ``ValueError`` otherwise."""
        try:
            return cls[text]
        except KeyError:
            raise ValueError(f"unknown axis label {text!r} (expected X, Y or Z)") from None


class Direction(IntEnum):
    """A signed axis; ``int(d) == 2 * axis + (0 if positive else 1)``."""

    PX = 0
    NX = 1
    PY = 2
    NY = 3
    PZ = 4
    NZ = 5

    @property
    def axis(self) -> Axis:
        """The axis this direction runs along."""
        return Axis(self >> 1)

    @property
    def sign(self) -> int:
        """``+1`` or ``-1``."""
        return -1 if self & 1 else 1

    def __neg__(self) -> Direction:
        return Direction(self ^ 1)

    def __str__(self) -> str:
        return ("+" if self.sign > 0 else "-") + self.axis.name

    def __repr__(self) -> str:
        return f"Direction.{self.name}"

    @property
    def vector(self) -> tuple[int, int, int]:
        """The unit vector, e.g. ``(0, -1, 0)`` for ``-Y``."""
        v = [0, 0, 0]
        v[self.axis] = self.sign
        return (v[0], v[1], v[2])

    @classmethod
    def of(cls, axis: Axis | int, sign: int) -> Direction:
        return cls(2 * int(axis) + (0 if sign > 0 else 1))

    @classmethod
    def parse(cls, text: str) -> Direction:
        """Read ``"+X"`` ... ``"-Z"``; raise ``ValueError`` otherwise."""
        if len(text) == 2 and text[0] in "+-":
            try:
                return cls.of(Axis.parse(text[1]), 1 if text[0] == "+" else -1)
            except ValueError:
                pass
        raise ValueError(f"unknown direction {text!r} (expected one of +X -X +Y -Y +Z -Z)")

    @classmethod
    def between(cls, p: tuple[int, ...], q: tuple[int, ...]) -> Direction | None:
        """The direction from position ``p`` to ``q`` if they differ in exactly one coordinate."""
        diff = [i for i in range(3) if p[i] != q[i]]
        if len(diff) != 1:
            return None
        i = diff[0]
        return cls.of(i, 1 if q[i] > p[i] else -1)


DIRECTIONS: tuple[Direction, ...] = tuple(Direction)
AXES: tuple[Axis, ...] = tuple(Axis)
