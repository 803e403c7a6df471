"""Writing triangle and quad meshes through meshio (OBJ, STL, PLY, OFF, VTK, MEDIT ``.mesh``
and whatever else meshio writes), each through the shared writer."""

from __future__ import annotations

import math
import os
import warnings

from polyloops.core.polycube import Polycube
from polyloops.io.exchange import quad_mesh_document
from polyloops.io.files import write_atomic, writing
from polyloops.io.formats import Document, FormatError
from polyloops.io.labelled_mesh import triangle_obj_text
from polyloops.surface.mesh import LabelledMesh


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


def write_polycube_mesh(q: Polycube, path: str | os.PathLike[str], file_format: str) -> None:
    """Write a polycube's quads through meshio (``file_format``: ``ply``, ``off``, ``vtk``,
    ``vtu``, ``medit``, ``gmsh``), or two triangles a quad for ``stl``, which holds only
    triangles; through :func:`polyloops.io.files.writing`, so nothing is left half-written.
    Corners are the polycube's integer positions, faces counter-clockwise seen from outside."""
    import meshio
    import numpy as np

    if file_format == "off":  # meshio writes triangles only to OFF; the format holds polygons
        lines = ["OFF", f"{len(q.positions)} {len(q.faces)} 0"]
        lines += [f"{x} {y} {z}" for x, y, z in q.positions]
        lines += ["4 " + " ".join(map(str, f)) for f in q.faces]
        write_atomic(path, "\n".join(lines) + "\n")
        return
    points = np.asarray(q.positions, dtype=float)
    quads = np.asarray([list(f) for f in q.faces], dtype=np.int32)
    if file_format == "stl":
        cells = [("triangle", np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]))]
    else:
        cells = [("quad", quads)]
    extra = {"binary": False} if file_format == "stl" else {}
    suffix = {"medit": ".mesh", "gmsh": ".msh"}.get(file_format, f".{file_format}")
    with writing(path, suffix=suffix) as pending:
        meshio.write(pending.path, meshio.Mesh(points, cells), file_format=file_format, **extra)


def read_polycube_mesh(data: bytes, file_format: str) -> Document:
    """A polycube document from the bytes of a quad mesh that meshio reads (PLY, OFF, VTK,
    VTU, MEDIT, Gmsh): its quads, coordinates snapped as for OBJ
    (:func:`polyloops.io.exchange.quad_mesh_document`).

    Raises
    ------
    FormatError
        When meshio cannot read the bytes, or the mesh has faces other than quads.
    """
    if file_format == "off":
        return _read_off(data)
    if file_format == "ply":
        _check_ply_header(data)
    import contextlib
    import io
    import tempfile

    import meshio
    import numpy as np

    suffix = {"medit": ".mesh", "gmsh": ".msh"}.get(file_format, f".{file_format}")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, f"mesh{suffix}")
        with open(path, "wb") as fh:
            fh.write(data)
        try:
            quiet = io.StringIO()
            with (warnings.catch_warnings(), contextlib.redirect_stdout(quiet),
                  contextlib.redirect_stderr(quiet)):
                warnings.simplefilter("ignore")  # meshio prints and warns; the error says it all
                mesh = meshio.read(path, file_format=file_format)
        except Exception as err:  # meshio raises many kinds (ReadError, ValueError, KeyError, ...)
            raise FormatError(f"not a {file_format.upper()} mesh meshio can read ({type(err).__name__}: "
                              f"{str(err)[:120]})") from None
    coords = np.asarray(mesh.points, dtype=float)
    if coords.ndim != 2 or coords.shape[0] == 0 or coords.shape[1] < 3 or not np.isfinite(coords).all():
        raise FormatError("needs finite 3D coordinates")
    faces: list[tuple[int, list[int]]] = []
    for block in mesh.cells:
        if block.type not in ("quad", "vertex", "line"):
            raise FormatError(f"has {block.type} cells; a polycube is read from quads")
        if block.type == "quad":
            for row in np.asarray(block.data):
                ids = [int(i) for i in row]
                if any(not 0 <= i < len(coords) for i in ids):
                    raise FormatError(f"face {len(faces) + 1} uses a vertex that does not exist")
                faces.append((len(faces) + 1, ids))
    points = [(float(x), float(y), float(z)) for x, y, z in coords[:, :3]]
    return quad_mesh_document(points, faces, where="face")


def _read_off(data: bytes) -> Document:
    """Object File Format text: ``OFF``, then ``V F E``, V lines of coordinates, F lines
    ``n i1 .. in`` (meshio reads triangles only, and a polycube's faces are quads)."""
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise FormatError(f"not UTF-8 text ({err.reason} at byte {err.start})") from None
    lines = [(i + 1, line.split("#")[0].split()) for i, line in enumerate(text.splitlines())]
    lines = [(i, words) for i, words in lines if words]
    if not lines or lines[0][1][0] not in ("OFF", "COFF", "NOFF"):
        raise FormatError("an OFF file starts with 'OFF'")
    head = lines[0][1][1:] or (lines[1][1] if len(lines) > 1 else [])
    body = lines[1:] if lines[0][1][1:] else lines[2:]
    try:
        n_vertices, n_faces = int(head[0]), int(head[1])
    except (IndexError, ValueError):
        raise FormatError("the counts line must be 'V F E' (integers)") from None
    if n_vertices < 0 or n_faces < 0 or n_vertices + n_faces > len(body):
        raise FormatError(f"announces {n_vertices} vertices and {n_faces} faces, but {len(body)} lines "
                          "follow")
    points = []
    for number, words in body[:n_vertices]:
        try:
            x, y, z = (float(w) for w in words[:3])
        except ValueError:
            raise FormatError(f"line {number}: a vertex is 'x y z' (numbers)") from None
        if not all(math.isfinite(c) for c in (x, y, z)):
            raise FormatError(f"line {number}: vertex coordinates must be finite")
        points.append((x, y, z))
    faces = []
    for number, words in body[n_vertices:n_vertices + n_faces]:
        try:
            ids = [int(w) for w in words[1:1 + int(words[0])]]
        except ValueError:
            raise FormatError(f"line {number}: a face is 'n i1 .. in' (integers)") from None
        if any(not 0 <= i < len(points) for i in ids):
            raise FormatError(f"line {number}: a face uses a vertex that does not exist")
        faces.append((number, ids))
    return quad_mesh_document(points, faces)


def _check_ply_header(data: bytes) -> None:
    """What meshio's PLY reader assumes and does not check: a header that ends (without
    ``end_header`` it reads forever) and element counts the file can hold."""
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise FormatError("not a PLY file: it must start with 'ply' and its header end with 'end_header'")
    for line in data[:end].decode("ascii", "replace").splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == "element":
            if not words[2].isdigit():
                raise FormatError(f"PLY header: the count of {words[1]!r} is not an integer")
            if int(words[2]) > len(data):
                raise FormatError(f"PLY header: {words[2]} {words[1]} elements in a file of "
                                  f"{len(data)} bytes")
