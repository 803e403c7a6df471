"""Labelled meshes built from the kernel's objects (no file, no check).

>>> from polyloops.shapes.builders import box
>>> mesh = labelled_mesh_from_polycube(box(1, 1, 1))
>>> len(mesh.triangles), sorted({str(d) for d in mesh.labels})
(12, ['+X', '+Y', '+Z', '-X', '-Y', '-Z'])
"""

from __future__ import annotations

from collections.abc import Sequence

from polyloops.core.directions import Direction
from polyloops.core.polycube import Polycube
from polyloops.surface.mesh import LabelledMesh

__all__ = ["labelled_mesh_from_polycube"]


def labelled_mesh_from_polycube(q: Polycube, labels: Sequence[Direction] | None = None) -> LabelledMesh:
    """Each quad cut into two triangles, labelled by its normal (or by ``labels``, one per
    quad, to make deliberately wrong labellings)."""
    triangles = []
    normals = []
    for f, (a, b, c, d) in enumerate(q.faces):
        triangles += [(a, b, c), (a, c, d)]
        label = labels[f] if labels is not None else q.face_normal(f)
        if label is None:
            raise ValueError(f"face {f} is not axis-aligned, so it has no label")
        normals += [label, label]
    points = tuple((float(x), float(y), float(z)) for x, y, z in q.positions)
    return LabelledMesh(points, tuple(triangles), tuple(normals))
