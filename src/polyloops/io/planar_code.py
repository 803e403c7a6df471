"""plantri's *planar code*: genus-0 maps as bytes, in and out.

A file may start with the header ``>>planar_code<<`` or ``>>planar_code le<<`` (two-byte
numbers little-endian) or ``>>planar_code be<<`` (big-endian).  Maps follow one after
another.  A map with at most 255 vertices is written in bytes: the number of vertices ``n``,
then for each vertex ``1..n`` its neighbours in clockwise order seen from outside, each list
ended by ``0``.  A larger map starts with a ``0`` byte and then writes ``n`` and every entry
as a two-byte number.  Planar code names an edge by its two ends, so it holds maps without
loops or multiple edges only.

Faces are traced with plantri's convention: arriving at ``v`` from ``u``, leave towards the
clockwise successor of ``u`` around ``v``; this keeps each face on the left, so faces come
out counter-clockwise seen from outside, as polyloops stores them.

>>> from polyloops.io.examples import load_example
>>> cube = load_example("cube").map
>>> data = planar_code([cube])
>>> data[:15], len(data)
(b'>>planar_code<<', 48)
>>> [m.num_faces for m in read_planar_code(data)]
[6]
"""

from __future__ import annotations

from collections.abc import Iterable

from polyloops.core.halfedge import FaceListError, HalfEdgeMap, MapError, faces_from_next
from polyloops.io.formats import FormatError

__all__ = ["PlanarCodeError", "planar_code", "read_planar_code"]

HEADER = b">>planar_code<<"
HEADER_LE = b">>planar_code le<<"
HEADER_BE = b">>planar_code be<<"


class PlanarCodeError(FormatError):
    """Bytes that are not planar code; the message names the map and the byte offset."""


def read_planar_code(data: bytes) -> list[HalfEdgeMap]:
    """Every map in a planar-code byte string (with or without a header)."""
    order = "little"
    at = 0
    for header, endian in ((HEADER, "little"), (HEADER_LE, "little"), (HEADER_BE, "big")):
        if data.startswith(header):
            at, order = len(header), endian
            break
    maps: list[HalfEdgeMap] = []
    stream = _Numbers(data, at, order)
    while stream.at < len(data):
        start = stream.at
        stream.width = 1
        if data[start] == 0:
            stream.width = 2
            stream.at += 1
        where = f"map {len(maps) + 1} (byte {start})"
        n = stream.take(where)
        if n < 3:
            raise PlanarCodeError(f"{where}: {n} vertices; a map needs 3 or more")
        rotation: list[list[int]] = []
        for _ in range(n):
            neighbours = []
            while (w := stream.take(where)) != 0:
                if w > n:
                    raise PlanarCodeError(f"{where}: vertex {w} does not exist (the map has {n})")
                neighbours.append(w - 1)
            rotation.append(neighbours)
        maps.append(_map_from_rotation(rotation, where))
    return maps


class _Numbers:
    """Reads one- or two-byte numbers from ``data`` onwards from ``at``."""

    def __init__(self, data: bytes, at: int, order: str):
        self.data, self.at, self.order, self.width = data, at, order, 1

    def take(self, where: str) -> int:
        if self.at + self.width > len(self.data):
            raise PlanarCodeError(f"{where}: the data ends inside the map")
        value = int.from_bytes(self.data[self.at:self.at + self.width], self.order)  # type: ignore[arg-type]
        self.at += self.width
        return value


def _map_from_rotation(rotation: list[list[int]], where: str) -> HalfEdgeMap:
    """Trace the faces of a rotation system (clockwise neighbour lists)."""
    position: dict[tuple[int, int], int] = {}
    for u, neighbours in enumerate(rotation):
        if not neighbours:
            raise PlanarCodeError(f"{where}: vertex {u + 1} has no neighbours")
        for i, v in enumerate(neighbours):
            if v == u or (u, v) in position:
                raise PlanarCodeError(f"{where}: vertex {u + 1} lists "
                                      + ("itself" if v == u else f"vertex {v + 1} twice"))
            position[(u, v)] = i
    for u, v in position:
        if (v, u) not in position:
            raise PlanarCodeError(f"{where}: vertex {u + 1} lists {v + 1} but not the other way round")
    # Darts in the order the file lists them; a face turns at v to the neighbour after u.
    index = {dart: i for i, dart in enumerate(position)}
    nxt = [0] * len(index)
    for (u, v), i in index.items():
        around = rotation[v]
        nxt[i] = index[(v, around[(position[(v, u)] + 1) % len(around)])]
    faces = faces_from_next(nxt, [u for u, _ in index])
    try:
        return HalfEdgeMap.from_faces(faces)
    except (MapError, FaceListError) as err:
        raise PlanarCodeError(f"{where}: not a closed connected surface: {err}") from None


def planar_code(maps: Iterable[HalfEdgeMap], two_byte: bool | None = None) -> bytes:
    """Planar code of genus-0 maps without loops or multiple edges, header first.

    Maps of more than 255 corners are written in the two-byte form (little-endian, with the
    header ``>>planar_code le<<``); ``two_byte=True`` writes every map that way.
    """
    maps = list(maps)
    for i, m in enumerate(maps, 1):
        if m.genus != 0:
            raise ValueError(f"map {i} has genus {m.genus}; planar code holds genus-0 maps only")
        ends = [(m.origin(d), m.target(d)) for d in range(m.num_darts)]
        if len(set(ends)) < len(ends) or any(u == v for u, v in ends):
            raise ValueError(f"map {i} has a loop or a multiple edge; planar code cannot name its edges")
    wide = two_byte if two_byte is not None else any(m.num_corners > 255 for m in maps)
    if any(m.num_corners > 65535 for m in maps):
        raise ValueError("planar code holds maps of at most 65535 corners")
    out = bytearray(HEADER_LE if wide else HEADER)
    for m in maps:
        if wide:
            out.append(0)
        width = 2 if wide else 1
        out += m.num_corners.to_bytes(width, "little")
        for corner in range(m.num_corners):
            # outgoing() is counter-clockwise seen from outside; planar code lists clockwise.
            for d in reversed(m.outgoing(corner)):
                out += (m.target(d) + 1).to_bytes(width, "little")
            out += bytes(width)
    return bytes(out)
