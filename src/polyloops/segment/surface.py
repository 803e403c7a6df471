"""The input of ``polyloops segment``: a closed, oriented, connected manifold triangle mesh.

:func:`surface_of` checks what the constructor relies on and names the first problem it finds
(a :class:`SurfaceError`): coordinates that are not finite numbers, triangles that repeat a
vertex or name one that does not exist, an edge with other than two triangles (open or
non-manifold), two triangles that run an edge the same way (not oriented), a vertex whose
triangles do not form one fan (non-manifold), several pieces, no area at all.

>>> from polyloops.shapes.meshes import octahedron
>>> s = surface_of(*octahedron())
>>> s.genus, len(s.triangles), round(s.area, 3)
(0, 8, 6.928)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from polyloops.core.directions import Direction
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.errors import PolyloopsError
from polyloops.surface.mesh import LabelledMesh

__all__ = ["Surface", "SurfaceError", "surface_of"]


class SurfaceError(PolyloopsError, ValueError):
    """A mesh that is not a closed, oriented, connected manifold surface with some area."""


@dataclass(frozen=True, eq=False)
class Surface:
    """A checked triangle mesh: ``points`` (n x 3 floats), ``triangles`` (m x 3 vertex indices,
    counter-clockwise seen from outside)."""

    points: np.ndarray
    triangles: np.ndarray

    @cached_property
    def _as_tuples(self) -> tuple[tuple[tuple[float, float, float], ...], tuple[tuple[int, int, int], ...]]:
        return (tuple((x, y, z) for x, y, z in self.points.tolist()),
                tuple((a, b, c) for a, b, c in self.triangles.tolist()))

    def labelled(self, labels: Sequence[Direction]) -> LabelledMesh:
        """This surface with a label per triangle, as the checker takes it (the points and
        triangles converted once per surface)."""
        points, triangles = self._as_tuples
        return LabelledMesh(points, triangles, tuple(labels))

    @cached_property
    def _cross(self) -> np.ndarray:
        p = self.points[self.triangles]
        return np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])

    @cached_property
    def areas(self) -> np.ndarray:
        """Per triangle, its area."""
        return 0.5 * np.linalg.norm(self._cross, axis=1)

    @cached_property
    def normals(self) -> np.ndarray:
        """Per triangle, its unit normal (zero for a triangle without area)."""
        length = np.linalg.norm(self._cross, axis=1)
        out = np.zeros_like(self._cross)
        ok = length > 0
        out[ok] = self._cross[ok] / length[ok, None]
        return out

    @cached_property
    def adjacency(self) -> tuple[np.ndarray, np.ndarray]:
        """Per edge, each once: the two triangles beside it (k x 2, the one that runs it from
        its lower vertex first) and its two vertices (k x 2, lower first)."""
        tris = self.triangles
        directed = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
        owner = np.tile(np.arange(len(tris)), 3)
        n = len(self.points)
        key = directed[:, 0] * n + directed[:, 1]
        order = np.argsort(key)
        other = owner[order[np.searchsorted(key[order], directed[:, 1] * n + directed[:, 0])]]
        mine = directed[:, 0] < directed[:, 1]
        return np.stack([owner[mine], other[mine]], axis=1), directed[mine]

    @property
    def area(self) -> float:
        """The total area."""
        return float(self.areas.sum())

    def area_centroid(self, heights: np.ndarray | None = None) -> np.ndarray:
        """The area-weighted mean of the triangles' centroids, placed by ``heights`` (per
        vertex; the points by default)."""
        hv = self.points if heights is None else heights
        return (hv[self.triangles].mean(axis=1) * self.areas[:, None]).sum(axis=0) / self.areas.sum()

    @property
    def genus(self) -> int:
        """The genus, from Euler's formula (the surface is closed and connected)."""
        v, f = len(self.points), len(self.triangles)
        return (2 - (v - 3 * f // 2 + f)) // 2


def surface_of(points: Sequence[Sequence[float]] | np.ndarray, triangles: Sequence[Sequence[int]] | np.ndarray
               ) -> Surface:
    """The checked surface; vertices no triangle uses are dropped (STL files repeat none,
    OBJ files may list spare ones).

    Raises
    ------
    SurfaceError
        Naming the first problem found.
    """
    pts = np.asarray(points, dtype=float)
    tris = np.asarray(triangles, dtype=np.int64)
    if len(tris) == 0:
        raise SurfaceError("no triangles")
    if pts.ndim != 2 or pts.shape[1] != 3 or tris.ndim != 2 or tris.shape[1] != 3:
        raise SurfaceError("points must be n x 3 coordinates and triangles m x 3 indices")
    if tris.min() < 0 or tris.max() >= len(pts):
        raise SurfaceError(f"a triangle names a vertex outside 0..{len(pts) - 1}")
    used = np.unique(tris)
    if not np.isfinite(pts[used]).all():
        bad = int(used[~np.isfinite(pts[used]).all(axis=1)][0])
        raise SurfaceError(f"vertex {bad} has a coordinate that is not a finite number")
    index = np.full(len(pts), -1, dtype=np.int64)
    index[used] = np.arange(len(used))
    pts, tris = pts[used], index[tris]
    for t, (a, b, c) in enumerate(tris.tolist()):
        if len({a, b, c}) < 3:
            raise SurfaceError(f"triangle {t} repeats a vertex")
    _check_edges(tris)
    _check_fans(tris, len(pts))
    surface = Surface(pts, tris)
    if surface.area <= 0:
        raise SurfaceError("the triangles have no area")
    return surface


def _check_edges(tris: np.ndarray) -> None:
    """Each directed edge once, and its reverse once: closed, manifold along edges, oriented."""
    directed = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    keys = directed[:, 0] * (directed.max() + 1) + directed[:, 1]
    order = np.argsort(keys, kind="stable")
    repeated = np.nonzero(keys[order][1:] == keys[order][:-1])[0]
    if len(repeated):
        u, v = directed[order[repeated[0]]]
        raise SurfaceError(f"two triangles run edge {u}-{v} the same way (not oriented, or non-manifold)")
    reverse = directed[:, 1] * (directed.max() + 1) + directed[:, 0]
    missing = ~np.isin(reverse, keys)
    if missing.any():
        u, v = directed[np.nonzero(missing)[0][0]]
        raise SurfaceError(f"edge {u}-{v} has a triangle on one side only (the mesh is open)")


def _check_fans(tris: np.ndarray, n: int) -> None:
    """The triangles round each vertex form one fan (a vertex where two cones touch is not a
    manifold point), and the surface is one piece."""
    nxt: dict[tuple[int, int], int] = {}  # (vertex, one neighbour) -> the next neighbour round it
    for a, b, c in tris.tolist():
        nxt[a, b], nxt[b, c], nxt[c, a] = c, a, b
    degree = np.bincount(tris.ravel(), minlength=n)
    seen = np.zeros(n, dtype=bool)
    for (v, w) in nxt:
        if seen[v]:
            continue
        seen[v] = True
        count, u = 0, w
        while True:
            u = nxt[v, u]
            count += 1
            if u == w:
                break
        if count != degree[v]:
            raise SurfaceError(f"vertex {v} joins two fans of triangles (not a manifold point)")
    joined = DisjointSets(range(n))
    for a, b, c in tris.tolist():
        joined.union(a, b)
        joined.union(a, c)
    pieces = len({joined.find(v) for v in range(n)})
    if pieces > 1:
        raise SurfaceError(f"the mesh is {pieces} separate pieces")
