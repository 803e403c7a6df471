"""A fixed oblique view of 3D points, for drawing without matplotlib's 3D toolkit."""

from __future__ import annotations

import math
from collections.abc import Sequence

Vec = Sequence[float]


class View:
    """An orthographic camera looking along ``-direction`` (azimuth and elevation in degrees)."""

    def __init__(self, azimuth: float = 35.0, elevation: float = 25.0):
        az, el = math.radians(azimuth), math.radians(elevation)
        # Camera axes: right, up, and toward the viewer.
        self.toward = (math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el))
        self.right = (-math.sin(az), math.cos(az), 0.0)
        self.up = (-math.sin(el) * math.cos(az), -math.sin(el) * math.sin(az), math.cos(el))

    def project(self, p: Vec) -> tuple[float, float]:
        """The 2D picture coordinates of a 3D point seen from this view."""
        return (sum(a * b for a, b in zip(p, self.right, strict=True)),
                sum(a * b for a, b in zip(p, self.up, strict=True)))

    def depth(self, p: Vec) -> float:
        """Larger is nearer to the viewer."""
        return sum(a * b for a, b in zip(p, self.toward, strict=True))

    def facing(self, normal: Vec) -> float:
        """Positive when a face with this outward normal faces the viewer."""
        return self.depth(normal)
