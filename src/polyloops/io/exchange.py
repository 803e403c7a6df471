"""Peers' file formats: DualCube's Abstract Polycube Graph and Wavefront OBJ quad meshes.

**Abstract Polycube Graph** (``.graph`` or ``.apg``, text).  Lines starting with ``/`` are
comments.  A header ``F E V`` (faces, edges, corners), then ``F`` lines of four 0-based
corner ids, clockwise seen from outside, then ``E`` lines ``u v AXIS [LENGTH]``: going from
``u`` to ``v`` moves in the ``+`` direction of ``AXIS``, and ``LENGTH``, when given, is the
edge's target length.  Reading gives a polycube when every edge has a positive integer
length and the lengths agree (the corners then get the positions they imply); otherwise a
loop structure, with a note that says why (coordinates can then come from
:func:`~polyloops.core.duality.primalize`).  Writing reverses the faces again and writes
each edge from its lower to its higher end with its length (a loop structure is written
without lengths).

**OBJ quad meshes.**  ``v x y z`` and ``f a b c d`` lines (1-based or negative indices,
``a/b/c`` forms allowed, other lines ignored).  Every face must be a quad and every edge
parallel to an axis; real coordinates are replaced by their rank among the distinct values
on their axis (values closer than ``1e-9`` times the mesh's extent are one value), which
keeps the polycube's order type (Definition 2).  Vertices no face uses are dropped.

Both readers return a :class:`~polyloops.io.formats.Document`, so building and its errors
are shared with the JSON format; problems in the text raise :class:`ExchangeError` naming
the line.

>>> from polyloops.io.examples import load_example
>>> l_shape = load_example("l-shape")
>>> parse_apg(apg_text(l_shape)).build() == l_shape
True
>>> parse_obj(to_obj(l_shape)).build() == l_shape
True
"""

from __future__ import annotations

import math
from collections import deque

import numpy as np

from polyloops.core.directions import Axis, Direction
from polyloops.core.polycube import Polycube
from polyloops.io.formats import Document, FormatError, Structure, to_obj

__all__ = ["ExchangeError", "apg_text", "parse_apg", "parse_obj", "to_obj"]


class ExchangeError(FormatError):
    """A file that does not follow a peer's format; the message names the line."""


def _content_lines(text: str, comment: str) -> list[tuple[int, list[str]]]:
    """Non-blank, non-comment lines as (1-based line number, words)."""
    out = []
    for number, line in enumerate(text.splitlines(), 1):
        stripped = line.strip()
        if stripped and not stripped.startswith(comment):
            out.append((number, stripped.split()))
    return out


def _ints(words: list[str], number: int, what: str) -> list[int]:
    try:
        return [int(w) for w in words]
    except ValueError:
        raise ExchangeError(f"line {number}: {what} must be integers, not {' '.join(words)!r}") from None


def parse_apg(text: str) -> Document:
    """Read an Abstract Polycube Graph; see the module docstring."""
    lines = _content_lines(text, "/")
    if not lines:
        raise ExchangeError("empty: expected a header line 'F E V'")
    number, header = lines[0]
    if len(header) != 3:
        raise ExchangeError(f"line {number}: the header must be 'F E V' (three counts)")
    n_faces, n_edges, n_corners = _ints(header, number, "the header's counts")
    if min(n_faces, n_edges, n_corners) < 1:
        raise ExchangeError(f"line {number}: the counts must be positive")
    if len(lines) != 1 + n_faces + n_edges:
        raise ExchangeError(f"the header announces {n_faces} faces and {n_edges} edges, but "
                            f"{len(lines) - 1} lines follow")
    faces = []
    for number, words in lines[1:1 + n_faces]:
        ids = _ints(words, number, "a face's corners")
        if len(ids) != 4:
            raise ExchangeError(f"line {number}: a face has 4 corners, not {len(ids)}")
        if any(not 0 <= c < n_corners for c in ids):
            raise ExchangeError(f"line {number}: corner ids run from 0 to {n_corners - 1}")
        faces.append(ids[::-1])  # clockwise there, counter-clockwise here
    # Every allocation below is sized by what the file holds, never by the header alone.
    used = len({c for face in faces for c in face})
    if used != n_corners:
        raise ExchangeError(f"line {lines[0][0]}: the header announces {n_corners} corners, but the faces "
                            f"use {used}")
    labels: dict[tuple[int, int], Direction | Axis] = {}
    lengths: dict[tuple[int, int], float] = {}
    for number, words in lines[1 + n_faces:]:
        if len(words) not in (3, 4):
            raise ExchangeError(f"line {number}: an edge is 'u v AXIS [LENGTH]'")
        u, v = _ints(words[:2], number, "an edge's corners")
        if any(not 0 <= c < n_corners for c in (u, v)):
            raise ExchangeError(f"line {number}: corner ids run from 0 to {n_corners - 1}")
        try:
            axis = Axis.parse(words[2].upper())
        except ValueError:
            raise ExchangeError(f"line {number}: unknown axis {words[2]!r} (expected X, Y or Z)") from None
        if (u, v) in labels or (v, u) in labels:
            raise ExchangeError(f"line {number}: edge ({u}, {v}) is listed twice")
        labels[(u, v)] = Direction.of(axis, 1)
        if len(words) == 4:
            try:
                lengths[(u, v)] = float(words[3])
            except ValueError:
                raise ExchangeError(f"line {number}: the length {words[3]!r} is not a number") from None
    positions, why = _positions_from_lengths(n_corners, labels, lengths)
    if positions is not None:
        return Document("polycube", faces, positions=positions)
    return Document("loop-structure", faces, labels=labels,
                    notes=(f"{why}; read as a loop structure (primalize gives its polycube)",))


def _positions_from_lengths(n: int, labels: dict[tuple[int, int], Direction | Axis],
                            lengths: dict[tuple[int, int], float]
                            ) -> tuple[list[tuple[int, int, int]] | None, str]:
    """Positions implied by the edge lengths, or ``None`` and the reason they imply none."""
    if len(lengths) < len(labels):
        return None, "not every edge has a length"
    if any(not (x > 0 and math.isfinite(x) and x == int(x)) for x in lengths.values()):
        return None, "the lengths are not all positive integers"
    adjacency: list[list[tuple[int, tuple[int, int, int]]]] = [[] for _ in range(n)]
    for (u, v), d in labels.items():
        assert isinstance(d, Direction)
        k = int(lengths[(u, v)])
        x, y, z = d.vector
        adjacency[u].append((v, (k * x, k * y, k * z)))
        adjacency[v].append((u, (-k * x, -k * y, -k * z)))
    pos: list[tuple[int, int, int] | None] = [None] * n
    for root in range(n):
        if pos[root] is not None:
            continue
        pos[root] = (0, 0, 0)
        queue = deque([root])
        while queue:
            u = queue.popleft()
            pu = pos[u]
            assert pu is not None
            for v, step in adjacency[u]:
                want = (pu[0] + step[0], pu[1] + step[1], pu[2] + step[2])
                if pos[v] is None:
                    pos[v] = want
                    queue.append(v)
                elif pos[v] != want:
                    return None, f"the lengths conflict around corner {v}"
    return [p for p in pos if p is not None], ""


def apg_text(obj: Structure) -> str:
    """The Abstract Polycube Graph of a polycube (with lengths) or of an oriented loop
    structure (without)."""
    m = obj.map
    lines = ["/ written by polyloops: faces clockwise seen from outside; u v AXIS [LENGTH], u to v is +AXIS",
             f"{m.num_faces} {m.num_edges} {m.num_corners}"]
    lines += [" ".join(str(c) for c in reversed(face)) for face in m.faces]
    for d in m.edge_darts:
        u, v = m.origin(d), m.target(d)
        if isinstance(obj, Polycube):
            pu, pv = obj.positions[u], obj.positions[v]
            delta = [b - a for a, b in zip(pu, pv, strict=True)]
            axis = next(i for i, x in enumerate(delta) if x)
            if delta[axis] < 0:
                u, v = v, u
            lines.append(f"{u} {v} {Axis(axis).name} {abs(delta[axis])}")
        else:
            if not obj.oriented:
                raise ValueError("an Abstract Polycube Graph needs edge directions: orient the structure")
            direction = obj.direction(d)
            if direction.sign < 0:
                u, v = v, u
            lines.append(f"{u} {v} {direction.axis.name}")
    return "\n".join(lines) + "\n"


def obj_polygons(text: str) -> tuple[list[tuple[float, float, float]], list[tuple[int, list[int]]]]:
    """The vertices and the faces (with their line numbers, as 0-based vertex ids) of a
    Wavefront OBJ text; other lines are ignored."""
    vertices: list[tuple[float, float, float]] = []
    faces: list[tuple[int, list[int]]] = []
    text = text.removeprefix("\ufeff")  # a byte-order mark would hide the first line's keyword
    for number, words in _content_lines(text, "#"):
        if words[0] == "v":
            if len(words) < 4:
                raise ExchangeError(f"line {number}: a vertex is 'v x y z'")
            try:
                xyz = tuple(float(w) for w in words[1:4])
            except ValueError:
                raise ExchangeError(f"line {number}: vertex coordinates must be numbers") from None
            if not all(math.isfinite(x) for x in xyz):
                raise ExchangeError(f"line {number}: vertex coordinates must be finite")
            vertices.append(xyz)  # type: ignore[arg-type]
        elif words[0] == "f":
            ids = []
            for w in words[1:]:
                head = w.split("/")[0]
                try:
                    i = int(head)
                except ValueError:
                    raise ExchangeError(f"line {number}: face corner {w!r} is not a vertex index") from None
                i = i - 1 if i > 0 else len(vertices) + i  # negative: counted back from here
                if not 0 <= i < len(vertices) or head == "0":
                    raise ExchangeError(f"line {number}: vertex {head} does not exist (yet)")
                ids.append(i)
            faces.append((number, ids))
    return vertices, faces


def obj_triangles(text: str) -> tuple[np.ndarray, np.ndarray] | None:
    """The vertices and triangles of a plain Wavefront OBJ triangle mesh, read with numpy: the
    fast path of :func:`obj_polygons` for files of ``v x y z`` and ``f a b c`` lines (other
    keywords and comments ignored).  ``None`` for anything else (slashes, negative or forward
    references, other polygons, bad numbers), which :func:`obj_polygons` then reads line by
    line and names the line at fault; where both read a text they agree (tested).

    >>> points, triangles = obj_triangles("v 0 0 0\\nv 1 0 0\\nv 0 1 0\\nf 1 2 3\\n")
    >>> points.shape, triangles.tolist()
    ((3, 3), [[0, 1, 2]])
    """
    text = text.removeprefix("\ufeff")
    vertex_words: list[str] = []
    face_words: list[str] = []
    defined: list[int] = []  # vertices defined before each face
    for line in text.splitlines():
        if line.startswith(("v ", "f ")):
            words = line[2:].split()
            if len(words) != 3:  # a 4-gon and a 2-gon must not pass as two triangles
                return None
            if line[0] == "v":
                vertex_words += words
            else:
                face_words += words
                defined.append(len(vertex_words) // 3)
        elif (words := line.split()) and words[0] in ("v", "f"):
            return None  # indented or tab-separated: the line reader takes these
    try:
        points = np.array(vertex_words, dtype=float).reshape(-1, 3)
        ids = np.array(face_words, dtype=np.int64).reshape(-1, 3)
    except (ValueError, OverflowError):  # OverflowError: an index of 20 digits
        return None
    if not np.isfinite(points).all():
        return None
    if ids.size and (ids.min() < 1 or (ids.max(axis=1) > np.asarray(defined)).any()):
        return None
    return points, ids - 1


def parse_obj(text: str) -> Document:
    """Read a Wavefront OBJ quad mesh as a polycube; see the module docstring."""
    vertices, raw_faces = obj_polygons(text)
    return quad_mesh_document(vertices, raw_faces)


def quad_mesh_document(vertices: list[tuple[float, float, float]],
                       raw_faces: list[tuple[int, list[int]]], where: str = "line") -> Document:
    """A polycube document from a quad mesh: vertices, and faces with the line (or face
    number, ``where``) that names them in errors.  Coordinates are snapped to their ranks on
    each axis (values closer than ``1e-9`` of the mesh's extent are one value), so the
    polycube's corners are integers however the mesh was scaled or moved."""
    for number, ids in raw_faces:
        if len(ids) != 4:
            raise ExchangeError(f"{where} {number}: a face must be a quad, not a {len(ids)}-gon")
    if not raw_faces:
        raise ExchangeError("no faces" + (" ('f' lines)" if where == "line" else ""))
    used = sorted({i for _, ids in raw_faces for i in ids})
    index = {old: new for new, old in enumerate(used)}
    ranks = _ranks([vertices[i] for i in used])
    faces = []
    for number, ids in raw_faces:
        face = [index[i] for i in ids]
        for a, b in zip(face, face[1:] + face[:1], strict=True):
            moved = sum(1 for k in range(3) if ranks[a][k] != ranks[b][k])
            if moved != 1:
                what = "of zero length" if moved == 0 else "not parallel to an axis"
                raise ExchangeError(f"{where} {number}: the edge from vertex {used[a] + 1} to {used[b] + 1} "
                                    f"is {what}")
        faces.append(face)
    return Document("polycube", faces, positions=ranks)


def _ranks(points: list[tuple[float, float, float]]) -> list[tuple[int, int, int]]:
    """Each coordinate replaced by its rank among the distinct values on its axis; values
    closer than ``1e-9`` of the extent (the largest spread on any axis) count as one, so the
    tolerance scales with the mesh (a polycube drawn at 1e-10 or at 1e100 reads the same)."""
    extent = max((max(p[k] for p in points) - min(p[k] for p in points) for k in range(3)), default=0.0)
    if not math.isfinite(extent):
        raise ExchangeError("the coordinates span more than a floating-point number holds")
    tol = 1e-9 * extent
    out = [[0, 0, 0] for _ in points]
    for k in range(3):
        order = sorted(range(len(points)), key=lambda i: points[i][k])
        rank, last = -1, None
        for i in order:
            x = points[i][k]
            if last is None or x - last > tol:
                rank += 1
                last = x
            out[i][k] = rank
    return [(a, b, c) for a, b, c in out]
