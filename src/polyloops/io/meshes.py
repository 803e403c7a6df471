"""Writing triangle and quad meshes through meshio (OBJ, STL, PLY, OFF, VTK, MEDIT ``.mesh``
and whatever else meshio writes), each through the shared writer."""

from __future__ import annotations

import os

from polyloops.core.labelled_mesh import LabelledMesh, triangle_obj_text
from polyloops.io.files import write_atomic, writing


def write_triangle_mesh(path: str | os.PathLike[str], mesh: LabelledMesh) -> None:
    """Write the triangles (format by extension: OBJ, STL or ``.mesh``) through
    :func:`polyloops.io.files.writing`, so a failure leaves nothing half-written."""
    target = os.fspath(path)
    suffix = os.path.splitext(target)[1].lower()
    if suffix == ".obj":
        write_atomic(target, triangle_obj_text(mesh))
        return
    import meshio
    import numpy as np

    out = meshio.Mesh(np.asarray(mesh.points, dtype=float), [("triangle", np.asarray(mesh.triangles))])
    with writing(target, suffix=suffix) as pending:
        if suffix == ".stl":
            meshio.write(pending.path, out, binary=False)
        else:
            meshio.write(pending.path, out)
