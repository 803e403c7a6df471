"""A loop structure embedded on a surface, read off it: regions, crossings, the quad mesh.

The loops are closed paths of edges of a refined surface (:mod:`~polyloops.segment.refine`),
each a section by a plane perpendicular to its axis.  Cutting the surface along them leaves the
*regions* (connected sets of triangles; each must be a disc); a vertex on two loops is a
*crossing*.  Reading round each crossing gives the four regions round it, counter-clockwise:
the faces of the primal quad mesh (:meth:`polyloops.core.structure.LoopStructure.from_edge_labels`,
a corner per region, a quad per crossing), and each quad edge crosses one loop, whose ``+`` side
is the side of greater coordinate along its axis.  :func:`read_structure` returns the
structure with the embedding it came from, or the reason it is no loop structure.

>>> from polyloops.shapes.meshes import sphere
>>> from polyloops.segment.refine import Plane, Refined, cut
>>> from polyloops.segment.surface import surface_of
>>> r = cut(Refined.of(surface_of(*sphere(3))), [Plane(0, 0.01), Plane(1, 0.02), Plane(2, 0.03)])
>>> e = read_structure(r, [SurfaceLoop(p, r.sections(p)[0]) for p in range(3)])
>>> e.structure.genus, len(e.region_triangles), len(e.crossings)
(0, 8, 6)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from polyloops.core.directions import Axis, Direction
from polyloops.core.errors import PolyloopsError
from polyloops.core.moves import Addition
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.segment.refine import Refined

__all__ = ["Embedded", "Loop", "NotAStructure", "PathLoop", "SurfaceLoop", "cycle_edges", "kernel_addition",
           "read_structure"]


class NotAStructure(PolyloopsError, ValueError):
    """Loops on a surface that are no loop structure (a region that is not a disc, a loop or
    region without crossings, two regions meeting twice); the message says which."""


def cycle_edges(vs: tuple[int, ...]) -> set[tuple[int, int]]:
    """The edges of a cycle of vertices, each as ``(u, v)`` with ``u < v``."""
    return {(min(a, b), max(a, b)) for a, b in zip(vs, vs[1:] + vs[:1], strict=True)}


@dataclass(frozen=True)
class SurfaceLoop:
    """A closed curve of a plane's section: the plane's index in ``Refined.planes`` and the
    curve's cycle of vertices; its ``+`` side is the side of greater height (``Refined.heights``)."""

    plane: int
    vertices: tuple[int, ...]

    def edges(self) -> set[tuple[int, int]]:
        """The curve's edges, each as ``(u, v)`` with ``u < v``."""
        return cycle_edges(self.vertices)

    def axis_in(self, r: Refined) -> int:
        """The loop's axis (0, 1, 2 for X, Y, Z)."""
        return r.planes[self.plane].axis

    def plus_side(self, r: Refined, t: int, edge: tuple[int, int]) -> bool:
        """Whether triangle ``t``, beside the loop's ``edge``, lies on its ``+`` side."""
        plane = r.planes[self.plane]
        return bool(r.heights[r.triangles[t]].mean(axis=0)[plane.axis] > plane.value)

    def forward(self, r: Refined) -> tuple[int, ...]:
        """The vertices in the order that keeps the ``+`` side on the right."""
        vs = list(self.vertices)
        u, v = vs[0], vs[1]
        return tuple(vs) if self.plus_side(r, r.owner[v, u], (u, v)) else tuple(vs[::-1])


@dataclass(frozen=True)
class PathLoop:
    """A closed path of mesh edges drawn for a loop of ``axis`` (not a plane section): its
    vertices in the order that keeps its ``+`` side on the right (:mod:`~polyloops.segment.paths`)."""

    axis: int
    vertices: tuple[int, ...]

    def edges(self) -> set[tuple[int, int]]:
        """The path's edges, each as ``(u, v)`` with ``u < v``."""
        return cycle_edges(self.vertices)

    def axis_in(self, r: Refined) -> int:
        """The loop's axis (0, 1, 2 for X, Y, Z)."""
        return self.axis

    def plus_side(self, r: Refined, t: int, edge: tuple[int, int]) -> bool:
        """Whether triangle ``t``, beside the loop's ``edge``, lies on its ``+`` side (the right)."""
        u, w = edge
        vs = self.vertices
        i = vs.index(u)
        if vs[(i + 1) % len(vs)] != w:
            u, w = w, u  # the path runs w -> u
        return r.owner[w, u] == t  # the triangle on the right of u -> w runs w -> u

    def forward(self, r: Refined) -> tuple[int, ...]:
        """The vertices, ``+`` side on the right."""
        return self.vertices


Loop = SurfaceLoop | PathLoop


@dataclass(frozen=True, eq=False)
class Embedded:
    """A loop structure and its embedding: ``region`` per triangle (the structure's corner),
    ``crossings`` (per quad face of the structure, the vertex where its two loops cross),
    ``sectors`` (per crossing, the four regions round it counter-clockwise, each with the spoke
    edge that ends its sector) and the loops."""

    refined: Refined
    loops: tuple[Loop, ...]
    region: np.ndarray
    crossings: tuple[int, ...]
    structure: LoopStructure

    @cached_property
    def polycube(self) -> Polycube:
        """The polycube primalized from :attr:`structure` (kept: the layout and the score ask)."""
        return self.structure.primalize()

    def structure_loop(self, k: int) -> int:
        """The loop of :attr:`structure` that curve ``k`` of :attr:`loops` is (the one through
        the same crossings)."""
        faces = {f for f, v in enumerate(self.crossings) if v in set(self.loops[k].vertices)}
        return next(i for i, lp in enumerate(self.structure.loops) if set(lp.faces) == faces)

    @property
    def region_triangles(self) -> list[np.ndarray]:
        """Per region, its triangles."""
        order = np.argsort(self.region, kind="stable")
        bounds = np.searchsorted(self.region[order], np.arange(self.region.max() + 2))
        return [order[bounds[i]:bounds[i + 1]] for i in range(len(bounds) - 1)]


def regions_of(r: Refined, loop_edges: set[tuple[int, int]]) -> np.ndarray:
    """Per triangle, its region: triangles joined across the edges not in ``loop_edges``."""
    pairs, keys = r.adjacency
    cut = r.edge_key(*np.array(sorted(loop_edges), dtype=np.int64).reshape(-1, 2).T)
    keep = ~np.isin(keys, cut)
    m = len(r.triangles)
    graph = coo_matrix((np.ones(int(keep.sum())), (pairs[keep, 0], pairs[keep, 1])), shape=(m, m))
    _, labels = connected_components(graph, directed=False)
    return labels


def read_structure(r: Refined, loops: Sequence[Loop]) -> Embedded:
    """The loop structure the ``loops`` make on ``r``, oriented by the planes' sides.

    Raises
    ------
    NotAStructure
        When the loops cut the surface into something other than discs meeting at crossings.
    """
    loop_of_edge: dict[tuple[int, int], int] = {}
    for i, lp in enumerate(loops):
        for e in lp.edges():
            loop_of_edge[e] = i
    region = regions_of(r, set(loop_of_edge))
    on_loops: dict[int, list[int]] = {}
    for i, lp in enumerate(loops):
        for v in lp.vertices:
            on_loops.setdefault(v, []).append(i)
    crossings = sorted(v for v, ls in on_loops.items() if len(ls) > 1)
    crossed = {i for v in crossings for i in on_loops[v]}
    if len(crossed) < len(loops):
        raise NotAStructure(f"{len(loops) - len(crossed)} loops cross no other loop")
    if any(len(on_loops[v]) > 2 for v in crossings):
        raise NotAStructure("three loops meet at one point")
    _check_discs(r, region)
    owner = r.owner
    faces, labels = [], {}
    for v in crossings:
        sectors = _sectors_round(v, r.incident[v][0], r.triangles, owner, loop_of_edge)
        if len(sectors) != 4:
            raise NotAStructure(f"a crossing with {len(sectors)} sectors round it")
        face = [int(region[t]) for t, _ in sectors]
        if len(set(face)) != 4:
            raise NotAStructure("a region meets a crossing twice")
        faces.append(face)
        for k in range(4):
            _, spoke = sectors[k]
            t_next = sectors[(k + 1) % 4][0]
            lp = loops[loop_of_edge[spoke]]
            plus = lp.plus_side(r, t_next, spoke)
            labels[face[k], face[(k + 1) % 4]] = Direction.of(Axis(lp.axis_in(r)), 1 if plus else -1)
    if len(set(region.tolist())) != len({c for f in faces for c in f}):
        raise NotAStructure("a region touches no crossing")
    try:
        structure = LoopStructure.from_edge_labels(faces, _once(labels))
    except (PolyloopsError, ValueError) as err:
        raise NotAStructure(f"the crossings do not make a quad mesh: {err}") from None
    return Embedded(r, tuple(loops), region, tuple(crossings), structure)


def _once(labels: dict[tuple[int, int], Direction]) -> dict[tuple[int, int], Direction]:
    """Each quad edge labelled once (its two faces label it from both sides, agreeing)."""
    out: dict[tuple[int, int], Direction] = {}
    for (u, v), d in labels.items():
        if (v, u) in out:
            if out[v, u] != -d:
                raise NotAStructure(f"regions {u} and {v} are on inconsistent sides of their loop")
            continue
        out[u, v] = d
    return out


def _sectors_round(v: int, start: int, triangles: np.ndarray, owner: dict[tuple[int, int], int],
                   loop_of_edge: dict[tuple[int, int], int]) -> list[tuple[int, tuple[int, int]]]:
    """Round vertex ``v`` counter-clockwise from triangle ``start``: per sector between loop
    edges, a triangle of it and the loop edge (``(u, w)``, ``u < w``) that ends it."""
    tri = triangles[start].tolist()
    k = tri.index(v)
    spoke = tri[(k + 2) % 3]  # the triangle (v, a, b): the next one round v holds (v, b)
    fan = []  # (triangle, its second spoke)
    t = start
    while True:
        fan.append((t, spoke))
        t = owner[v, spoke]
        tri = triangles[t].tolist()
        spoke = tri[(tri.index(v) + 2) % 3]
        if t == start:
            break
    ends = [i for i, (_, s) in enumerate(fan) if (min(v, s), max(v, s)) in loop_of_edge]
    out = []
    for j, i in enumerate(ends):
        s = fan[i][1]
        first = fan[(ends[j - 1] + 1) % len(fan)][0] if len(ends) > 1 else fan[0][0]
        out.append((first, (min(v, s), max(v, s))))
    return out


def _check_discs(r: Refined, region: np.ndarray) -> None:
    """Every region a disc: Euler characteristic 1 and one boundary curve without pinches."""
    tris = r.triangles
    n = len(r.points) + 1
    count = int(region.max()) + 1
    faces = np.bincount(region, minlength=count)
    pairs, _ = r.adjacency
    a, b = region[pairs[:, 0]], region[pairs[:, 1]]
    inner = a == b
    edges = np.bincount(a[inner], minlength=count) + np.bincount(a[~inner], minlength=count) \
        + np.bincount(b[~inner], minlength=count)
    # int64: region * n passes 2**31 on a finely cut mesh with thousands of regions
    lab = region.astype(np.int64)
    verts = np.bincount(np.unique(np.repeat(lab, 3) * n + tris.ravel()) // n, minlength=count)
    euler = verts - edges + faces
    if (euler != 1).any():
        g = int(np.nonzero(euler != 1)[0][0])
        raise NotAStructure(f"region {g} is not a disc (Euler characteristic {euler[g]})")
    # a pinch: a vertex where the region's boundary passes twice, i.e. two boundary darts of
    # one region leaving one vertex (the first triangle of a pair runs its edge from the lower
    # vertex, the second from the upper: Surface.adjacency)
    pairs, ends = r.surface.adjacency
    differ = region[pairs[:, 0]] != region[pairs[:, 1]]
    starts = np.concatenate([lab[pairs[differ, 0]] * n + ends[differ, 0],
                             lab[pairs[differ, 1]] * n + ends[differ, 1]])
    if len(np.unique(starts)) != len(starts):
        raise NotAStructure("a region touches itself on its boundary")


def kernel_addition(e: Embedded, new: Loop) -> Addition:
    """The kernel's description of adding curve ``new`` to ``e``: its axis and the regions of
    ``e`` it walks through, in order, walked with its ``+`` side (greater coordinate) on the
    right.  :func:`polyloops.core.moves.add_loop` with it must give the structure read off the
    surface with ``new`` added (a self-test of both)."""
    r = e.refined
    owner = r.owner
    vs = list(new.forward(r))
    walk = [int(e.region[owner[a, b]]) for a, b in zip(vs, vs[1:] + vs[:1], strict=True)]
    cycle = [g for i, g in enumerate(walk) if g != walk[i - 1]]
    return Addition(Axis(new.axis_in(r)), tuple(cycle))
