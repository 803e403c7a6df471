"""A surface refined so that curves on it run along its edges: cut by planes, edges split.

A loop of axis X labelled on a surface runs round the X axis; the plane sections ``x = c`` are
such curves.  The planes cut the surface's *heights*: per vertex, the coordinates themselves, or
those of a polycube-like deformation of the surface (:mod:`~polyloops.segment.deform`), whose
level sets follow a thin handle or a tilted arm where planes would not; either way a section is
a closed curve of the surface, with the side of greater level its ``+`` side, and everything
measured (areas, normals, lengths) stays on the surface's own points.  :func:`cut` splits every
triangle a plane crosses, so that each section is a
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
    triangle, the input triangle it lies in), ``planes`` (the cutting planes, in order), ``on``
    (per vertex, the indices of the planes it lies on) and ``heights`` (per vertex, the
    coordinates the planes cut: the points, or a deformation of them)."""

    points: np.ndarray
    triangles: np.ndarray
    parent: np.ndarray
    planes: tuple[Plane, ...]
    on: tuple[frozenset[int], ...]
    heights: np.ndarray

    @classmethod
    def of(cls, surface: Surface, heights: np.ndarray | None = None) -> Refined:
        """The surface itself, not yet cut, its planes to cut ``heights`` (default: the points)."""
        n = len(surface.points)
        lv = surface.points if heights is None else np.asarray(heights, dtype=float)
        if lv.shape != surface.points.shape:
            raise ValueError(f"heights of shape {lv.shape} for {n} points")
        return cls(surface.points, surface.triangles, np.arange(len(surface.triangles)), (),
                   (frozenset(),) * n, lv)

    @property
    def deformed(self) -> bool:
        """Whether the planes cut other heights than the points."""
        return self.heights is not self.points

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
        self.heights = None if not r.deformed else [tuple(p) for p in r.heights.tolist()]
        self.on = list(r.on)
        self.mid: dict[tuple[int, int], int] = {}

    def point_on(self, u: int, v: int, t: float, plane: int | None) -> int:
        key = (min(u, v), max(u, v))
        if key not in self.mid:
            pu, pv = self.points[u], self.points[v]
            self.mid[key] = len(self.points)
            self.points.append(tuple(a + t * (b - a) for a, b in zip(pu, pv, strict=True)))
            if self.heights is not None:  # the same point of the edge, in the heights
                lu, lv = self.heights[u], self.heights[v]
                self.heights.append(tuple(a + t * (b - a) for a, b in zip(lu, lv, strict=True)))
            extra = frozenset() if plane is None else frozenset({plane})
            self.on.append((self.on[u] & self.on[v]) | extra)
        return self.mid[key]

    def done(self, r: Refined, triangles: list[tuple[int, int, int]], parent: list[int],
             planes: tuple[Plane, ...]) -> Refined:
        points = np.array(self.points, dtype=float)
        heights = points if self.heights is None else np.array(self.heights, dtype=float)
        return Refined(points, np.array(triangles, dtype=np.int64).reshape(-1, 3),
                       np.array(parent, dtype=np.int64), planes, tuple(self.on), heights)


def _clear_of_vertices(r: Refined, plane: Plane) -> Plane:
    """``plane`` moved a hair's breadth when a vertex lies on it (so no section passes through
    a vertex and every cut point is a new vertex)."""
    coords = r.heights[:, plane.axis]
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
    """``r`` cut by one plane: each crossed triangle (a, b, c), with ``a`` alone on its side,
    becomes (a, ab, ca), (ab, b, c), (ab, c, ca); a new point per crossed edge, shared by the
    two triangles beside it and numbered in the order the triangles meet it."""
    index = len(r.planes)
    sd = r.heights[:, plane.axis] - plane.value
    side = sd > 0
    sides = side[r.triangles]
    crossed = sides.any(axis=1) & ~sides.all(axis=1)
    tri = r.triangles[crossed]
    s3 = sides[crossed]
    alone = (s3 != np.roll(s3, -1, axis=1)) & (s3 != np.roll(s3, -2, axis=1))
    k = np.argmax(alone, axis=1)
    rows = np.arange(len(tri))
    a, b, c = tri[rows, k], tri[rows, (k + 1) % 3], tri[rows, (k + 2) % 3]
    # the crossed edges in the order they are met: (a, b) then (c, a), triangle by triangle
    u = np.column_stack([a, c]).ravel()
    v = np.column_stack([b, a]).ravel()
    n = len(r.points)
    key = np.minimum(u, v).astype(np.int64) * n + np.maximum(u, v)
    unique, first, inverse = np.unique(key, return_index=True, return_inverse=True)
    rank = np.empty(len(unique), dtype=np.int64)
    rank[np.argsort(first, kind="stable")] = np.arange(len(unique))
    new_id = n + rank[inverse.ravel()]
    fu, fv = u[np.sort(first)], v[np.sort(first)]  # each new point from its first meeting
    t = (sd[fu] / (sd[fu] - sd[fv]))[:, None]
    points = np.concatenate([r.points, r.points[fu] + t * (r.points[fv] - r.points[fu])])
    heights = points if not r.deformed else np.concatenate(
        [r.heights, r.heights[fu] + t * (r.heights[fv] - r.heights[fu])])
    mark = frozenset({index})
    on = r.on + tuple((r.on[x] & r.on[y]) | mark for x, y in zip(fu.tolist(), fv.tolist(), strict=True))
    ab, ca = new_id[0::2], new_id[1::2]
    pieces = np.stack([np.column_stack([a, ab, ca]), np.column_stack([ab, b, c]),
                       np.column_stack([ab, c, ca])], axis=1).reshape(-1, 3)
    triangles = np.concatenate([r.triangles[~crossed], pieces]).astype(np.int64)
    parent = np.concatenate([r.parent[~crossed], np.repeat(r.parent[crossed], 3)]).astype(np.int64)
    return Refined(points, triangles, parent, (*r.planes, plane), on, heights)


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
