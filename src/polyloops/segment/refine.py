"""A surface refined so that curves on it run along its edges: cut by planes, edges split.

A loop of axis X labelled on a surface runs round the X axis; the plane sections ``x = c`` are
such curves.  :func:`cut` splits every triangle a plane crosses, so that each section is a
union of closed paths of edges; a vertex remembers the planes it lies on (a new vertex on an
edge lies on the planes both ends lie on, and on the cutting plane), so that an edge lies on a
plane exactly when both its ends do (a triangle meets a plane in a straight segment).  The
vertex where sections of two axes cross lies on both.  :func:`split_edges` cuts edges at their
midpoints (to make room for paths between a region's corner and its sides).  Every triangle
keeps the input triangle it lies in (``parent``).

>>> from polyloops.shapes.meshes import octahedron
>>> from polyloops.segment.surface import surface_of
>>> r = cut(Refined.of(surface_of(*octahedron())), [Plane(0, 0.1), Plane(1, -0.2)])
>>> len(r.triangles) > 8, sorted(len(c) for c in r.sections(0)), r.crossing_vertices(0, 1)
(True, [6], 2)
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from polyloops.segment.surface import Surface

__all__ = ["Plane", "Refined", "cut", "split_edges"]


@dataclass(frozen=True)
class Plane:
    """The plane ``coordinate[axis] = value`` (axis 0, 1, 2 for X, Y, Z)."""

    axis: int
    value: float


@dataclass(frozen=True, eq=False)
class Refined:
    """A refined surface: points, triangles (counter-clockwise from outside), ``parent`` (per
    triangle, the input triangle it lies in), ``planes`` (the cutting planes, in order) and
    ``on`` (per vertex, the indices of the planes it lies on)."""

    points: np.ndarray
    triangles: np.ndarray
    parent: np.ndarray
    planes: tuple[Plane, ...]
    on: tuple[frozenset[int], ...]

    @classmethod
    def of(cls, surface: Surface) -> Refined:
        """The surface itself, not yet cut."""
        n = len(surface.points)
        return cls(surface.points, surface.triangles, np.arange(len(surface.triangles)), (),
                   (frozenset(),) * n)

    @cached_property
    def surface(self) -> Surface:
        """The refined triangles as a surface (areas and normals)."""
        return Surface(self.points, self.triangles)

    @cached_property
    def vertex_normals(self) -> np.ndarray:
        """Per vertex, the unit area-weighted mean of its triangles' normals."""
        s = self.surface
        out = np.zeros((len(self.points), 3))
        for k in range(3):
            np.add.at(out, self.triangles[:, k], s.normals * s.areas[:, None])
        length = np.linalg.norm(out, axis=1)
        return out / np.maximum(length, 1e-300)[:, None]

    @cached_property
    def owner(self) -> dict[tuple[int, int], int]:
        """Per directed edge ``(u, v)``, the triangle that runs it (the one on its left)."""
        out = {}
        for t, (a, b, c) in enumerate(self.triangles.tolist()):
            out[a, b] = out[b, c] = out[c, a] = t
        return out

    @cached_property
    def adjacency(self) -> tuple[np.ndarray, np.ndarray]:
        """Per edge (each once): the two triangles beside it (k x 2), and its key
        ``u * (n + 1) + v`` with ``u < v`` (:meth:`edge_key`)."""
        pairs, ends = self.surface.adjacency
        return pairs, self.edge_key(ends[:, 0], ends[:, 1])

    def edge_key(self, u: np.ndarray | int, v: np.ndarray | int) -> np.ndarray:
        """The key of edge ``(u, v)`` (``u < v``) in :attr:`adjacency`."""
        return np.asarray(u, dtype=np.int64) * (len(self.points) + 1) + np.asarray(v, dtype=np.int64)

    @cached_property
    def incident(self) -> dict[int, list[int]]:
        """Per vertex, the triangles round it."""
        out: dict[int, list[int]] = {}
        for t, tri in enumerate(self.triangles.tolist()):
            for v in tri:
                out.setdefault(v, []).append(t)
        return out

    @cached_property
    def _plane_vertices(self) -> dict[int, np.ndarray]:
        on: dict[int, list[int]] = {}
        for v, planes in enumerate(self.on):
            for p in planes:
                on.setdefault(p, []).append(v)
        return {p: np.array(vs, dtype=np.int64) for p, vs in on.items()}

    def edges_on(self, plane: int) -> list[tuple[int, int]]:
        """The edges on ``plane``, each once as ``(u, v)`` with ``u < v``."""
        mark = np.zeros(len(self.points), dtype=bool)
        mark[self._plane_vertices.get(plane, np.zeros(0, dtype=np.int64))] = True
        _, ends = self.surface.adjacency
        u, v = ends[:, 0], ends[:, 1]
        both = mark[u] & mark[v]
        return sorted(zip(u[both].tolist(), v[both].tolist(), strict=True))

    @cached_property
    def _sections(self) -> dict[int, list[tuple[int, ...]]]:
        return {}  # filled by sections(), plane by plane

    def sections(self, plane: int) -> list[tuple[int, ...]]:
        """The closed curves of ``plane``'s section, each as its cycle of vertices.

        Raises
        ------
        ValueError
            When the section is not a union of disjoint closed curves (a plane through a
            vertex of the input can make it so; the planes are chosen to avoid that).
        """
        if plane not in self._sections:
            self._sections[plane] = self._curves(plane)
        return self._sections[plane]

    def _curves(self, plane: int) -> list[tuple[int, ...]]:
        around: dict[int, list[int]] = {}
        for u, v in self.edges_on(plane):
            around.setdefault(u, []).append(v)
            around.setdefault(v, []).append(u)
        if any(len(ns) != 2 for ns in around.values()):
            raise ValueError(f"the section by plane {plane} is not a union of disjoint closed curves")
        out, seen = [], set()
        for start in sorted(around):
            if start in seen:
                continue
            cycle, prev, here = [start], -1, start
            seen.add(start)
            while True:
                a, b = around[here]
                nxt = b if a == prev else a
                if nxt == start:
                    break
                cycle.append(nxt)
                seen.add(nxt)
                prev, here = here, nxt
            out.append(tuple(cycle))
        return out

    def crossing_vertices(self, p: int, q: int) -> int:
        """How many vertices lie on both planes ``p`` and ``q``."""
        return sum(1 for s in self.on if p in s and q in s)


class _Builder:
    """Points and triangles being refined; new points on edges shared between neighbours."""

    def __init__(self, r: Refined):
        self.points = [tuple(p) for p in r.points.tolist()]
        self.on = list(r.on)
        self.mid: dict[tuple[int, int], int] = {}

    def point_on(self, u: int, v: int, t: float, plane: int | None) -> int:
        key = (min(u, v), max(u, v))
        if key not in self.mid:
            pu, pv = self.points[u], self.points[v]
            self.mid[key] = len(self.points)
            self.points.append(tuple(a + t * (b - a) for a, b in zip(pu, pv, strict=True)))
            extra = frozenset() if plane is None else frozenset({plane})
            self.on.append((self.on[u] & self.on[v]) | extra)
        return self.mid[key]

    def done(self, r: Refined, triangles: list[tuple[int, int, int]], parent: list[int],
             planes: tuple[Plane, ...]) -> Refined:
        return Refined(np.array(self.points, dtype=float), np.array(triangles, dtype=np.int64).reshape(-1, 3),
                       np.array(parent, dtype=np.int64), planes, tuple(self.on))


def _clear_of_vertices(r: Refined, plane: Plane) -> Plane:
    """``plane`` moved a hair's breadth when a vertex lies on it (so no section passes through
    a vertex and every cut point is a new vertex)."""
    coords = r.points[:, plane.axis]
    scale = max(float(np.ptp(coords)), 1e-12)
    value = plane.value
    for _ in range(64):
        if np.min(np.abs(coords - value)) > 1e-9 * scale:
            return Plane(plane.axis, value)
        value += 1e-7 * scale
    return Plane(plane.axis, value)


def cut(r: Refined, planes: Iterable[Plane]) -> Refined:
    """``r`` cut by each of ``planes`` in turn (each moved off the vertices first; the planes
    used are ``out.planes``)."""
    for plane in planes:
        r = _cut_one(r, _clear_of_vertices(r, plane))
    return r


def _cut_one(r: Refined, plane: Plane) -> Refined:
    index = len(r.planes)
    sd = r.points[:, plane.axis] - plane.value
    side = sd > 0
    b = _Builder(r)
    tris: list[tuple[int, int, int]] = []
    parent: list[int] = []
    crossed = np.nonzero(side[r.triangles].any(axis=1) & ~side[r.triangles].all(axis=1))[0]
    keep = np.ones(len(r.triangles), dtype=bool)
    keep[crossed] = False
    for t in crossed.tolist():
        tri = r.triangles[t].tolist()
        s = [bool(side[v]) for v in tri]
        # the vertex alone on its side first: (a, b, c) counter-clockwise
        k = next(i for i in range(3) if s[i] != s[(i + 1) % 3] and s[i] != s[(i + 2) % 3])
        a, bb, c = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
        p_ab = b.point_on(a, bb, float(sd[a] / (sd[a] - sd[bb])), index)
        p_ca = b.point_on(c, a, float(sd[c] / (sd[c] - sd[a])), index)
        tris += [(a, p_ab, p_ca), (p_ab, bb, c), (p_ab, c, p_ca)]
        parent += [int(r.parent[t])] * 3
    old = [tuple(x) for x in r.triangles[keep].tolist()]
    return b.done(r, old + tris, r.parent[keep].tolist() + parent, (*r.planes, plane))


def split_edges(r: Refined, edges: Iterable[tuple[int, int]]) -> Refined:
    """``r`` with each of ``edges`` cut at its midpoint, the triangles beside them cut to fit
    (a triangle with one cut edge into two, two into three, three into four)."""
    wanted = {(min(u, v), max(u, v)) for u, v in edges}
    if not wanted:
        return r
    b = _Builder(r)
    tris: list[tuple[int, int, int]] = []
    parent: list[int] = []
    for t, tri in enumerate(r.triangles.tolist()):
        cuts = [(min(tri[i], tri[(i + 1) % 3]), max(tri[i], tri[(i + 1) % 3])) in wanted for i in range(3)]
        pieces = _pieces(tri, cuts, b)
        tris += pieces
        parent += [int(r.parent[t])] * len(pieces)
    return b.done(r, tris, parent, r.planes)


def _pieces(tri: Sequence[int], cuts: list[bool], b: _Builder) -> list[tuple[int, int, int]]:
    count = sum(cuts)
    if count == 0:
        return [(tri[0], tri[1], tri[2])]
    if count == 3:
        a, bb, c = tri
        ab, bc, ca = b.point_on(a, bb, 0.5, None), b.point_on(bb, c, 0.5, None), b.point_on(c, a, 0.5, None)
        return [(a, ab, ca), (ab, bb, bc), (ca, bc, c), (ab, bc, ca)]
    if count == 1:
        k = cuts.index(True)
        a, bb, c = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
        m = b.point_on(a, bb, 0.5, None)
        return [(a, m, c), (m, bb, c)]
    k = cuts.index(False)  # two cut: the uncut edge is (c, a) below
    c, a, bb = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
    m1, m2 = b.point_on(a, bb, 0.5, None), b.point_on(bb, c, 0.5, None)
    return [(m1, bb, m2), (a, m1, m2), (a, m2, c)]
