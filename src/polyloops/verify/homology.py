"""Zone genera from homology, independently of the zones' Euler-characteristic bookkeeping.

:mod:`polyloops.core.zones` computes a zone's genus from ``V - E + F`` of a retract and the
number of loop sides on its boundary: the same numbers Theorem 3 balances, so checking the
theorem with them can only catch bookkeeping slips.  Here each zone is built as a real surface
with boundary: the polycube surface is cut along every ``Delta``-loop, each face a
``Delta``-loop crosses is split into two halves, each ``Delta``-edge into two half-edges at
its midpoint, and the cut is doubled (one copy of each midpoint and cut segment per side).
For each connected piece ``S`` we compute its first Betti number over GF(2) from the ranks of
its boundary maps, ``b1 = dim ker d1 - rank d2``, and count its boundary circles by tracing the
edges that lie in one face only.  A connected orientable surface with ``b >= 1`` boundary
circles has ``b1 = 2 g + b - 1``, so ``g = (b1 - b + 1) / 2``; a closed piece has
``b1 = 2 g``.

The ranks are exact: ``dim ker d1 = E - V + c`` with ``c`` the connected components of the
1-skeleton, and ``ker d2`` is spanned by the face-connected groups (across edges in two faces)
that touch no edge in one face, since a GF(2) 2-chain without boundary takes one value on such a
group and 0 next to a boundary edge.  :func:`gf2_rank` is the slow twin used by the tests.

>>> from polyloops.io.examples import load_example
>>> from polyloops.core.directions import Axis
>>> ls = load_example("bridged-ring").dualize()
>>> zone_genera(ls, Axis.Z)
(0, 1, 0)
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Hashable, Iterable, Sequence
from dataclasses import dataclass

from polyloops.core.directions import Axis
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.structure import LoopStructure


@dataclass(frozen=True)
class CellComplex:
    """A 2-complex over GF(2): vertices, edges as vertex pairs, faces as lists of edge ids."""

    vertices: tuple[Hashable, ...]
    edges: tuple[tuple[Hashable, Hashable], ...]
    faces: tuple[tuple[int, ...], ...]
    # Each face's corners in order, for the oriented boundary maps over the integers (the
    # GF(2) ranks do not need them).
    rings: tuple[tuple[Hashable, ...], ...] = ()

    def betti1(self) -> int:
        """``dim ker d1 - rank d2`` (exact when every edge lies in at most two faces)."""
        parts: DisjointSets[Hashable] = DisjointSets()
        for v in self.vertices:
            parts.find(v)
        for u, v in self.edges:
            parts.union(u, v)
        components = len({parts.find(v) for v in self.vertices})
        kernel_d1 = len(self.edges) - len(self.vertices) + components
        return kernel_d1 - (len(self.faces) - self.closed_face_groups())

    def faces_of_edge(self) -> dict[int, list[int]]:
        """The faces each edge lies in (at most two on a surface)."""
        out: dict[int, list[int]] = defaultdict(list)
        for f, face in enumerate(self.faces):
            for e in face:
                out[e].append(f)
        if any(len(fs) > 2 for fs in out.values()):
            raise ValueError("an edge lies in more than two faces; the rank formula needs a surface")
        return out

    def closed_face_groups(self) -> int:
        """``dim ker d2``: groups of faces joined across edges in two faces, touching no edge
        that lies in one face only."""
        by_edge = self.faces_of_edge()
        parts: DisjointSets[Hashable] = DisjointSets()
        for f in range(len(self.faces)):
            parts.find(f)
        for fs in by_edge.values():
            if len(fs) == 2:
                parts.union(fs[0], fs[1])
        open_groups = {parts.find(fs[0]) for fs in by_edge.values() if len(fs) == 1}
        return len({parts.find(f) for f in range(len(self.faces))} - open_groups)

    def boundary_circles(self) -> int:
        """Connected components of the edges that lie in exactly one face."""
        parts: DisjointSets[Hashable] = DisjointSets()
        for e, fs in self.faces_of_edge().items():
            if len(fs) == 1:
                u, v = self.edges[e]
                parts.union(u, v)
        return len({parts.find(x) for x in parts.parent})

    def integral_homology(self) -> tuple[int, tuple[int, ...]]:
        """``H_1`` over the integers as (free rank, torsion coefficients), from the Smith normal
        forms (sympy) of the oriented boundary maps: ``rank H_1 = E - rank d1 - rank d2``,
        torsion the invariant factors of ``d2`` above 1.  Exact but slow: the tests' twin of
        :meth:`betti1` on small complexes.  Needs :attr:`rings`.

        >>> annulus = CellComplex((0, 1, 2, 3), ((0, 1), (1, 2), (2, 3), (3, 0)), ((0, 1, 2, 3),),
        ...                       ((0, 1, 2, 3),))
        >>> annulus.integral_homology()  # a disk: no homology
        (0, ())
        """
        from sympy import ZZ, Matrix
        from sympy.matrices.normalforms import smith_normal_form

        if len(self.rings) != len(self.faces):
            raise ValueError("integral homology needs the faces' corner rings")
        index = {v: i for i, v in enumerate(self.vertices)}
        d1 = Matrix.zeros(len(self.vertices), len(self.edges))
        for e, (u, v) in enumerate(self.edges):
            if u != v:
                d1[index[u], e], d1[index[v], e] = -1, 1
        d2 = Matrix.zeros(len(self.edges), len(self.faces))
        for f, (face, ring) in enumerate(zip(self.faces, self.rings, strict=True)):
            for i, e in enumerate(face):
                forward = (ring[i], ring[(i + 1) % len(ring)]) == self.edges[e]
                d2[e, f] += 1 if forward else -1

        def invariants(m: Matrix) -> list[int]:
            if 0 in m.shape:
                return []
            snf = smith_normal_form(m, domain=ZZ)
            return [abs(int(snf[i, i])) for i in range(min(snf.shape)) if snf[i, i] != 0]

        if d2.shape[1] and d1.shape[0] and any(x != 0 for x in d1 * d2):
            raise ValueError("the boundary of a boundary is not zero: the rings are inconsistent")
        rank1, factors2 = len(invariants(d1)), invariants(d2)
        return len(self.edges) - rank1 - len(factors2), tuple(x for x in factors2 if x > 1)

    def genus(self, integral: bool = False) -> int:
        """The genus of a connected orientable surface given as this complex (its first Betti
        number over GF(2), or with ``integral`` over the integers, which also refuses torsion)."""
        b = self.boundary_circles()
        if integral:
            b1, torsion = self.integral_homology()
            if torsion:
                raise ValueError(f"H_1 has torsion {torsion}: not an orientable surface")
        else:
            b1 = self.betti1()
        twice = b1 - b + 1 if b else b1
        if twice % 2 or twice < 0:
            raise ValueError(f"b1 = {b1} with {b} boundary circles is not an orientable surface")
        return twice // 2


def cut_zones(ls: LoopStructure, axis: Axis) -> dict[int, CellComplex]:
    """The surface cut along the ``axis``-loops, one complex per piece, keyed by the zone
    number (:meth:`LoopStructure.zones`) of the corners in it.

    Vertices: corners ``("c", v)``, and a copy ``("m", e, v)`` of the midpoint of each
    ``axis``-edge ``e`` on the side of its end ``v``.  Quads only.
    """
    m = ls.map
    if any(len(face) != 4 for face in m.faces):
        raise ValueError("cut_zones needs a quad map")
    is_cut = [ls.axis_of_dart(d) == axis for d in range(m.num_darts)]
    edges: list[tuple[Hashable, Hashable]] = []
    edge_id: dict[frozenset[Hashable], int] = {}

    def edge(u: Hashable, v: Hashable) -> int:
        key = frozenset((u, v))
        if key not in edge_id:
            edge_id[key] = len(edges)
            edges.append((u, v))
        return edge_id[key]

    faces: list[tuple[int, ...]] = []
    rings: list[tuple[Hashable, ...]] = []
    for f in range(m.num_faces):
        darts = list(m.face_darts(f))
        # Walk the boundary of the face, inserting midpoints of cut edges.
        ring: list[tuple] = []
        for d in darts:
            u = m.origin(d)
            ring.append(("c", u))
            if is_cut[d]:
                e = m.edge_id(d)
                ring += [("m", e, u), ("m", e, m.target(d))]
        # Split the ring at each cut edge: consecutive midpoint copies of one cut edge are not
        # joined; each piece between cuts is closed by a cut segment.
        pieces: list[list[Hashable]] = [[]]
        for i, vertex in enumerate(ring):
            pieces[-1].append(vertex)
            nxt = ring[(i + 1) % len(ring)]
            if vertex[0] == "m" and nxt[0] == "m" and vertex[1] == nxt[1]:
                pieces.append([])
        if len(pieces) > 1:  # the run before the first cut continues the last one
            pieces[0] = pieces.pop() + pieces[0]
        for piece in pieces:
            if not piece:
                continue
            faces.append(tuple(edge(piece[i], piece[(i + 1) % len(piece)]) for i in range(len(piece))))
            rings.append(tuple(piece))
    vertices = sorted({v for uv in edges for v in uv}, key=repr)
    parts: DisjointSets[Hashable] = DisjointSets()
    for v in vertices:
        parts.find(v)
    for a, b in edges:
        parts.union(a, b)
    zones = ls.zones(axis)
    zone_of_root = {parts.find(("c", c)): zones.zone_of[c] for c in range(m.num_corners)}
    grouped_v: dict[int, list[Hashable]] = defaultdict(list)
    for v in vertices:
        grouped_v[zone_of_root[parts.find(v)]].append(v)
    grouped_e: dict[int, list[int]] = defaultdict(list)
    for e, (a, _) in enumerate(edges):
        grouped_e[zone_of_root[parts.find(a)]].append(e)
    grouped_f: dict[int, list[int]] = defaultdict(list)
    for f, face in enumerate(faces):
        grouped_f[zone_of_root[parts.find(edges[face[0]][0])]].append(f)
    out = {}
    for z, vs in grouped_v.items():
        local = {e: i for i, e in enumerate(grouped_e[z])}
        out[z] = CellComplex(tuple(vs), tuple(edges[e] for e in grouped_e[z]),
                             tuple(tuple(local[e] for e in faces[f]) for f in grouped_f[z]),
                             tuple(rings[f] for f in grouped_f[z]))
    return out


def zone_genera(ls: LoopStructure, axis: Axis, integral: bool = False) -> tuple[int, ...]:
    """The genus of every ``axis``-zone, from the homology of the cut surface (over GF(2), or
    with ``integral`` by Smith normal forms over the integers: slow, for the tests)."""
    if integral:
        pieces = cut_zones(ls, axis)
        return tuple(pieces[z].genus(integral=True) for z in sorted(pieces))
    from polyloops.core.arrays import use_arrays

    if use_arrays(ls.map.num_darts) and all(len(face) == 4 for face in ls.map.faces):
        found = _zone_genera_arrays(ls, axis)
        if found is not None:
            return found
    pieces = cut_zones(ls, axis)
    return tuple(pieces[z].genus() for z in sorted(pieces))


def _zone_genera_arrays(ls: LoopStructure, axis: Axis) -> tuple[int, ...] | None:
    """:func:`zone_genera` by counting on arrays: the same cut complex as :func:`cut_zones`
    (vertex, edge and face counts, the components of its 1-skeleton, of its boundary and of
    its faces across interior edges), grouped by zone.  ``None`` for a map whose cut complex
    would merge two cut segments (a face meeting another along two opposite edges): then the
    tuple code builds it."""
    import numpy as np

    from polyloops.core.arrays import all_distinct, components
    from polyloops.core.zones import dart_axes

    m = ls.map
    a = m.arrays
    n_corners, n_darts = m.num_corners, m.num_darts
    cut = dart_axes(ls) == axis
    lower = a.edge_darts
    cut_edges = np.flatnonzero(cut[lower])
    j = np.full(m.num_edges, -1, dtype=np.int64)
    j[cut_edges] = np.arange(len(cut_edges))
    darts = np.arange(n_darts)
    is_lower = lower[a.edge_id] == darts

    def mid(d: np.ndarray, at_target: bool) -> np.ndarray:
        """The midpoint copy of cut dart d's edge on the side of its origin (or target)."""
        end = is_lower[d] == at_target  # end 1 is the lower dart's target
        return n_corners + 2 * j[a.edge_id[d]] + end.astype(np.int64)

    n_vertices = n_corners + 2 * len(cut_edges)
    # Faces: quads the axis does not cross, and two halves of each one it does.
    crossed = np.zeros(m.num_faces, dtype=bool)
    crossed[a.face_of[cut]] = True
    first = a.face_start  # quads: darts first .. first + 3
    whole = np.flatnonzero(~crossed)
    halves = np.flatnonzero(crossed)
    pos = np.where(cut[first[halves]], 0, 1)  # the first cut dart of each crossed face
    d0 = first[halves] + pos
    d1, d2, d3 = d0 + 1, d0 + 2, (d0 + 3 - first[halves]) % 4 + first[halves]
    n_whole = len(whole)
    complex_face = np.full(n_darts, -1, dtype=np.int64)
    complex_face[(first[whole, None] + np.arange(4)).ravel()] = np.repeat(np.arange(n_whole), 4)
    h1 = n_whole + 2 * np.arange(len(halves))  # the half with d1, after d0 and before d2
    h2 = h1 + 1
    complex_face[d1], complex_face[d3] = h1, h2
    half_at_target = np.full(n_darts, -1, dtype=np.int64)
    half_at_origin = np.full(n_darts, -1, dtype=np.int64)
    half_at_target[d0], half_at_origin[d0] = h1, h2
    half_at_target[d2], half_at_origin[d2] = h2, h1
    n_faces = n_whole + 2 * len(halves)
    # Edges: uncut map edges; two half-edges per cut edge; one cut segment per half.
    uncut = lower[~cut[lower]]
    cl = lower[cut_edges]
    ends_a = [a.origin[uncut], a.origin[cl], mid(cl, True)]
    ends_b = [a.target[uncut], mid(cl, False), a.target[cl]]
    seg_a = np.concatenate([mid(d0, True), mid(d2, True)])
    seg_b = np.concatenate([mid(d2, False), mid(d0, False)])
    seg_keys = np.minimum(seg_a, seg_b) * n_vertices + np.maximum(seg_a, seg_b)
    if not all_distinct(seg_keys):
        return None
    edge_a = np.concatenate([*ends_a, seg_a])
    edge_b = np.concatenate([*ends_b, seg_b])
    n_pieces, piece = components(n_vertices, edge_a, edge_b)
    zones = ls.zones(axis)
    zone_of_piece = np.full(n_pieces, -1, dtype=np.int64)
    zone_of_piece[piece[:n_corners]] = np.asarray(zones.zone_of)
    if np.any(zone_of_piece < 0):
        return None
    k = zones.count
    zone_of_vertex = zone_of_piece[piece]
    v = np.bincount(zone_of_vertex, minlength=k)
    e = np.bincount(zone_of_vertex[edge_a], minlength=k)
    c = np.bincount(zone_of_piece, minlength=k)
    face_zone = np.empty(n_faces, dtype=np.int64)
    face_zone[:n_whole] = zone_of_vertex[a.origin[first[whole]]]
    face_zone[h1] = zone_of_vertex[a.target[d0]]
    face_zone[h2] = zone_of_vertex[a.target[d2]]
    f = np.bincount(face_zone, minlength=k)
    # Boundary circles: components of the cut segments (on the midpoint copies).
    n_circles, circle = components(n_vertices, seg_a, seg_b)
    on_rim = np.zeros(n_vertices, dtype=bool)
    on_rim[seg_a] = True
    rim_circles = np.unique(circle[on_rim])
    circle_zone = np.full(n_circles, -1, dtype=np.int64)
    circle_zone[circle[on_rim]] = zone_of_vertex[on_rim]
    b = np.bincount(circle_zone[rim_circles], minlength=k)
    # Face groups across interior edges (uncut edges and half-edges); closed ones touch no segment.
    twin_uncut = a.twin[uncut]
    ct = a.twin[cl]
    adj_a = np.concatenate([complex_face[uncut], half_at_origin[cl], half_at_target[cl]])
    adj_b = np.concatenate([complex_face[twin_uncut], half_at_target[ct], half_at_origin[ct]])
    n_groups, group = components(n_faces, adj_a, adj_b)
    open_group = np.zeros(n_groups, dtype=bool)
    open_group[group[n_whole:]] = True
    group_zone = np.full(n_groups, -1, dtype=np.int64)
    group_zone[group] = face_zone
    closed = np.bincount(group_zone[~open_group], minlength=k)
    b1 = (e - v + c) - (f - closed)
    twice = np.where(b > 0, b1 - b + 1, b1)
    if np.any(twice % 2) or np.any(twice < 0):
        raise ValueError("a zone's b1 and boundary circles do not fit an orientable surface")
    return tuple((twice // 2).tolist())


def gf2_rank(rows: Iterable[Sequence[int]]) -> int:
    """The rank over GF(2) of a 0/1 matrix given by its rows (Gaussian elimination on bit sets)."""
    basis: dict[int, int] = {}  # leading bit -> row
    for row in rows:
        x = sum(1 << j for j, bit in enumerate(row) if bit % 2)
        while x:
            top = x.bit_length() - 1
            if top not in basis:
                basis[top] = x
                break
            x ^= basis[top]
    return len(basis)
