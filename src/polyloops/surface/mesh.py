"""The labelled triangle mesh: a closed triangle mesh with one direction label per triangle.

This is what polycube labelling methods produce, and what a polycube segmentation is: triangles
counter-clockwise seen from outside, each labelled ``+X, -X, +Y, -Y, +Z`` or ``-Z``
(:class:`~polyloops.core.directions.Direction`).  Files of meshes and labels are read and written
by :mod:`polyloops.io.labelled_mesh`.

>>> mesh = LabelledMesh(((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)), ((0, 1, 2),),
...                     (Direction.PZ,))
>>> len(mesh.triangles), str(mesh.labels[0])
(1, '+Z')
"""

from __future__ import annotations

from dataclasses import dataclass

from polyloops.core.directions import Direction
from polyloops.core.errors import PolyloopsError

__all__ = ["LabelledMesh", "MeshError", "Point", "Triangle"]

Point = tuple[float, float, float]
Triangle = tuple[int, int, int]


class MeshError(PolyloopsError, ValueError):
    """A labelled mesh whose parts do not fit together (labels and triangles in different
    numbers)."""


@dataclass(frozen=True)
class LabelledMesh:
    """Triangles over ``points`` (counter-clockwise seen from outside) and a label each."""

    points: tuple[Point, ...]
    triangles: tuple[Triangle, ...]
    labels: tuple[Direction, ...]

    def __post_init__(self) -> None:
        if len(self.labels) != len(self.triangles):
            raise MeshError(f"{len(self.labels)} labels for {len(self.triangles)} triangles")
