"""Files of labelled triangle meshes (the model is :class:`polyloops.surface.mesh.LabelledMesh`).

This is what polycube labelling methods produce: a triangle mesh (OBJ, STL or MEDIT
``.mesh``; meshio reads the last two and keeps the order of the faces) and a labels file of one
integer per triangle, in face order, ``0..5`` meaning ``+X, -X, +Y, -Y, +Z, -Z`` (the
encoding of the LIHPC ``labeling.txt`` and DualCube ``.flag`` files, and of
:class:`~polyloops.core.directions.Direction`).  Triangles are counter-clockwise seen from
outside.

>>> from polyloops.io.examples import load_example
>>> mesh = labelled_mesh_from_polycube(load_example("cube"))
>>> len(mesh.triangles), sorted({str(d) for d in mesh.labels})
(12, ['+X', '+Y', '+Z', '-X', '-Y', '-Z'])
>>> parse_labels(labels_text(mesh), 12) == mesh.labels
True
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Sequence

from polyloops.core.directions import Direction
from polyloops.io.exchange import obj_polygons, obj_triangles
from polyloops.io.formats import FormatError
from polyloops.surface.construct import labelled_mesh_from_polycube  # noqa: F401  (the doctest's)
from polyloops.surface.mesh import LabelledMesh, MeshError, Point, Triangle

__all__ = ["LabelledMeshError", "labels_text", "parse_labels", "read_labelled_mesh", "read_labels",
           "read_triangle_mesh", "triangle_obj_text"]

MESH_SUFFIXES = (".obj", ".stl", ".mesh")


class LabelledMeshError(FormatError, MeshError):
    """A mesh or labels file that cannot be read; the message names the line or face, and
    ``where`` the file (when known)."""

    def __init__(self, message: str, where: str | None = None):
        super().__init__(message)
        self.where = where


def parse_labels(text: str, count: int | None = None) -> tuple[Direction, ...]:
    """One integer ``0..5`` per non-blank line (``#`` starts a comment); ``count``, when
    given, is the number of triangles they must match."""
    labels = []
    for number, line in enumerate(text.splitlines(), 1):
        word = line.split("#", 1)[0].strip()
        if not word:
            continue
        try:
            value = int(word)
        except ValueError:
            raise LabelledMeshError(f"line {number}: a label is an integer 0..5, not {word!r}") from None
        if not 0 <= value <= 5:
            raise LabelledMeshError(f"line {number}: label {value} is not in 0..5 (+X, -X, +Y, -Y, +Z, -Z)")
        labels.append(Direction(value))
    if count is not None and len(labels) != count:
        raise LabelledMeshError(f"{len(labels)} labels for {count} triangles (one label per triangle)")
    return tuple(labels)


def labels_text(mesh: LabelledMesh) -> str:
    """The labels file: one integer per line."""
    return "".join(f"{int(d)}\n" for d in mesh.labels)


def read_triangle_mesh(path: str | os.PathLike[str]) -> tuple[tuple[Point, ...], tuple[Triangle, ...]]:
    """Points and triangles of an OBJ, STL or MEDIT ``.mesh`` file, faces in file order.

    OBJ is read with numpy when it is plain (:func:`~polyloops.io.exchange.obj_triangles`),
    otherwise by the same reader as OBJ quad meshes (so errors name the line); STL and
    ``.mesh`` by meshio.  Only triangles may bound the surface: other faces are refused, and
    the volume and line cells a ``.mesh`` file may hold are ignored.
    """
    if os.fspath(path).lower().endswith(".obj"):
        with open(path, encoding="utf-8-sig", errors="replace") as fh:  # a byte-order mark is not text
            text = fh.read()
        fast = obj_triangles(text)
        if fast is not None:
            points, triangles = list(map(tuple, fast[0].tolist())), list(map(tuple, fast[1].tolist()))
        else:
            points, faces = obj_polygons(text)
            for number, ids in faces:
                if len(ids) != 3:
                    raise LabelledMeshError(f"line {number}: a face must be a triangle, not a {len(ids)}-gon")
            triangles = [(a, b, c) for _, (a, b, c) in faces]
    else:
        points, triangles = _read_with_meshio(path)
    if not triangles:
        raise LabelledMeshError("has no triangles")
    return tuple(points), tuple(triangles)


def _check_text_stl(data: bytes) -> None:
    """Name the first malformed line of an ASCII STL file (meshio does not say where)."""
    if len(data) >= 84 and len(data) == 84 + 50 * int.from_bytes(data[80:84], "little"):
        return  # binary STL, even if its header starts with "solid"
    if not data.lstrip().lower().startswith(b"solid"):
        return
    shapes = {"solid": None, "endsolid": None, "outer": None, "endloop": 0, "endfacet": 0,
              "facet": 4, "vertex": 3}  # numbers expected after the keyword(s)
    for number, line in enumerate(data.decode("utf-8", errors="replace").splitlines(), 1):
        words = line.split()
        if not words:
            continue
        key = words[0].lower()
        if key not in shapes:
            raise LabelledMeshError(f"line {number}: unexpected {words[0]!r} in an ASCII STL file")
        want = shapes[key]
        numbers = words[2:] if key == "facet" else words[1:]
        if key == "facet" and (len(words) < 2 or words[1].lower() != "normal"):
            raise LabelledMeshError(f"line {number}: a facet line is 'facet normal nx ny nz'")
        if want is not None and key in ("facet", "vertex"):
            want -= key == "facet"
            try:
                ok = len(numbers) == want and all(map(math.isfinite, map(float, numbers)))
            except ValueError:
                ok = False
            if not ok:
                raise LabelledMeshError(f"line {number}: {key} needs {want} finite numbers")


def _read_with_meshio(path: str | os.PathLike[str]) -> tuple[list[Point], list[Triangle]]:
    import meshio
    import numpy as np

    if os.fspath(path).lower().endswith(".stl"):
        with open(path, "rb") as fh:
            _check_text_stl(fh.read())

    try:
        with warnings.catch_warnings():  # meshio's test for binary STL overflows on text files
            warnings.simplefilter("ignore", RuntimeWarning)
            mesh = meshio.read(os.fspath(path))
    except Exception as err:  # meshio raises many kinds of errors for malformed files
        message = " ".join(str(err).split()) or type(err).__name__
        raise LabelledMeshError(f"not a readable triangle mesh: {message}") from None
    triangles: list[Triangle] = []
    for block in mesh.cells:
        if block.type == "triangle":
            triangles.extend((int(a), int(b), int(c)) for a, b, c in np.asarray(block.data))
        elif block.type in ("quad", "polygon"):
            raise LabelledMeshError(f"has {block.type} faces; a labelled mesh is made of triangles")
    if not triangles:
        raise LabelledMeshError("has no triangles")
    coords = np.asarray(mesh.points, dtype=float)
    if coords.ndim != 2 or coords.shape[1] < 3 or not np.isfinite(coords).all():
        raise LabelledMeshError("needs finite 3D coordinates")
    points = [(float(x), float(y), float(z)) for x, y, z in coords[:, :3]]
    for i, tri in enumerate(triangles):
        if any(not 0 <= c < len(points) for c in tri):
            raise LabelledMeshError(f"triangle {i + 1} uses a vertex that does not exist")
    return points, triangles


def triangle_obj_text(mesh: LabelledMesh) -> str:
    """The triangles as Wavefront OBJ text (the labels go in their own file)."""
    lines = [f"v {x:g} {y:g} {z:g}" for x, y, z in mesh.points]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in mesh.triangles]
    return "\n".join(lines) + "\n"


def read_labelled_mesh(mesh: str | os.PathLike[str], labels: str | os.PathLike[str]) -> LabelledMesh:
    """A labelled mesh from its two files, each read once through :mod:`polyloops.io.files`:
    the triangles (OBJ, STL or MEDIT ``.mesh`` by extension; ``-``, standard input, as OBJ or
    STL text by its first word) and the labels (one integer per triangle).

    Raises
    ------
    InputError
        When a file cannot be read (the message names it).
    LabelledMeshError
        For content that is not a triangle mesh or a labels file; ``where`` says which file.
    """
    import tempfile

    from polyloops.io.files import check_regular, read_bytes

    name = os.fspath(mesh)
    if name == "-":  # standard input: a file name is needed by meshio, so keep it in one
        data = read_bytes(name)
        suffix = ".stl" if data.lstrip(b"\xef\xbb\xbf \t\r\n").lower().startswith(b"solid") else ".obj"
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "mesh" + suffix)
            with open(path, "wb") as fh:
                fh.write(data)
            points, triangles = _triangles(name, path)
    else:
        check_regular(name)  # a regular file of reasonable size (meshio would read a FIFO forever)
        points, triangles = _triangles(name, name)
    return LabelledMesh(points, triangles, read_labels(labels, len(triangles)))


def read_labels(path: str | os.PathLike[str], count: int) -> tuple[Direction, ...]:
    """A labels file (one integer ``0..5`` per triangle, ``count`` of them), read through
    :mod:`polyloops.io.files`.

    Raises
    ------
    InputError
        When the file cannot be read (the message names it).
    LabelledMeshError
        When it is not a labels file for ``count`` triangles; ``where`` names the file.
    """
    from polyloops.io.files import read_text

    try:
        return parse_labels(read_text(path), count)
    except LabelledMeshError as err:
        raise LabelledMeshError(str(err), where=os.fspath(path)) from None


def _triangles(name: str, path: str) -> tuple[tuple[Point, ...], tuple[Triangle, ...]]:
    try:
        points, triangles = read_triangle_mesh(path)
    except FormatError as err:  # LabelledMeshError among them
        raise LabelledMeshError(str(err), where=name) from None
    except OSError as err:
        raise LabelledMeshError(f"cannot read: {err.strerror or err}", where=name) from None
    except OverflowError:
        raise LabelledMeshError("a vertex index too large for any mesh", where=name) from None
    return used_vertices(points, triangles, name)


def used_vertices(points: Sequence[Point], triangles: Sequence[Triangle],
                  name: str = "mesh") -> tuple[tuple[Point, ...], tuple[Triangle, ...]]:
    """The mesh with the vertices no triangle uses left out (a file may list spare vertices
    anywhere), renumbered in order; a triangle that repeats a vertex is refused by number.

    >>> used_vertices([(0, 0, 0), (9, 9, 9), (1, 0, 0), (0, 1, 0)], [(0, 2, 3)])
    (((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 1, 2),))
    >>> used_vertices([(0, 0, 0), (1, 0, 0)], [(0, 0, 1)])
    Traceback (most recent call last):
    ...
    polyloops.io.labelled_mesh.LabelledMeshError: triangle 1 repeats a vertex ([1, 1, 2]): a degenerate ...
    """
    for k, t in enumerate(triangles):
        if len(set(t)) != 3:
            raise LabelledMeshError(f"triangle {k + 1} repeats a vertex ({[v + 1 for v in t]}): a degenerate "
                                    "triangle has no normal", where=name)
    used = sorted({v for t in triangles for v in t})
    if len(used) == len(points):
        return tuple(points), tuple(tuple(t) for t in triangles)  # type: ignore[misc]
    new = {v: i for i, v in enumerate(used)}
    return (tuple(points[v] for v in used),
            tuple((new[a], new[b], new[c]) for a, b, c in triangles))
