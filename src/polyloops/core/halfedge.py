"""The half-edge map: one closed, oriented surface shared by every view.

A map is given by its faces, each a cyclic list of corner ids listed
counter-clockwise as seen from outside.  Face ``f`` with corners
``(c0, c1, ..., ck-1)`` owns the darts ``c0->c1, c1->c2, ..., ck-1->c0``; dart
``d`` lies in the face on its left.  Darts are numbered face by face, so the
numbering is a pure function of the face list.

Edges are named by their two corners, so a map built from a face list has no
loops and no multiple edges, and no face visits a corner twice.  Everything
else that can go wrong with a face list (an edge in one or in three faces,
faces oriented inconsistently, a corner whose faces form two fans, two
components) is collected into one :class:`MapError` with every witness.

>>> m = HalfEdgeMap.from_faces([[0, 1, 2, 3], [3, 2, 1, 0]])
>>> m.num_corners, m.num_edges, m.num_faces, m.genus
(4, 4, 2, 0)
>>> [m.target(d) for d in m.outgoing(0)]
[1, 3]
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from itertools import chain
from typing import TYPE_CHECKING

from polyloops.core.arrays import gc_paused, use_arrays
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.errors import PolyloopsError

if TYPE_CHECKING:
    from polyloops.core.arrays import MapArrays
    from polyloops.core.loops import LoopSystem


@dataclass(frozen=True)
class MapProblem:
    """One reason a face list is not a closed, connected, oriented surface."""

    kind: str  # "boundary-edge", "branching-edge", "orientation", "non-manifold-corner", "disconnected"
    message: str
    witness: dict[str, object] = field(default_factory=dict)


class MapError(PolyloopsError, ValueError):
    """A face list that does not describe a closed, connected, oriented surface."""

    def __init__(self, problems: Sequence[MapProblem]):
        self.problems = tuple(problems)
        first = self.problems[0].message if self.problems else "invalid map"
        more = f" (and {len(self.problems) - 1} more problems)" if len(self.problems) > 1 else ""
        super().__init__(first + more)


class FaceListError(PolyloopsError, ValueError):
    """A face list that cannot even be read as polygons over corner ids."""


def permutation_orbits(perm: Sequence[int]) -> list[list[int]]:
    """The orbits of a permutation of ``0..n-1``, each from its lowest element, by that element.

    >>> permutation_orbits([2, 0, 1, 4, 3, 5])
    [[0, 2, 1], [3, 4], [5]]
    """
    seen = [False] * len(perm)
    out = []
    for d in range(len(perm)):
        if not seen[d]:
            orbit, e = [], d
            while not seen[e]:
                seen[e] = True
                orbit.append(e)
                e = perm[e]
            out.append(orbit)
    return out


def faces_from_next(nxt: Sequence[int], origin: Sequence[int]) -> list[list[int]]:
    """Faces as corner lists from darts: the orbits of ``nxt``, each dart read as its
    ``origin``.  The one place where a face list is read off a dart permutation (signatures,
    plantri's batches and planar code all come here).

    >>> m = HalfEdgeMap.from_faces([[0, 1, 2, 3], [3, 2, 1, 0]])
    >>> faces_from_next(m.next, m.origin_of)
    [[0, 1, 2, 3], [3, 2, 1, 0]]
    """
    return [[int(origin[d]) for d in orbit] for orbit in permutation_orbits(nxt)]


def _face_darts(faces: Sequence[Sequence[int]]
                ) -> tuple[list[int], list[int], list[int], list[int], list[int]]:
    """A face list's darts, face after face: each dart's origin, face, next and previous dart
    around its face, and each face's first dart."""
    origin: list[int] = []
    face_of: list[int] = []
    nxt: list[int] = []
    prv: list[int] = []
    face_start: list[int] = []
    for f, face in enumerate(faces):
        base = len(origin)
        face_start.append(base)
        k = len(face)
        origin.extend(face)
        face_of.extend([f] * k)
        nxt.extend(range(base + 1, base + k))
        nxt.append(base)
        prv.append(base + k - 1)
        prv.extend(range(base, base + k - 1))
    return origin, face_of, nxt, prv, face_start


def _validate_faces(faces: Sequence[Sequence[int]]) -> tuple[tuple[int, ...], ...]:
    out: list[tuple[int, ...]] = []
    if not faces:
        raise FaceListError("no faces")
    for f, face in enumerate(faces):
        t = tuple(face)
        if len(t) < 3:
            raise FaceListError(f"face {f} has {len(t)} corners; a face needs at least 3")
        if len(set(t)) != len(t):
            raise FaceListError(f"face {f} visits a corner twice: {list(t)}")
        if any(not isinstance(c, int) or isinstance(c, bool) or c < 0 for c in t):
            raise FaceListError(f"face {f} has a corner id that is not a non-negative integer")
        out.append(t)
    used = {c for t in out for c in t}
    n = len(used)
    if max(used) != n - 1:  # then some id below n is unused; find it in O(n), whatever the ids
        missing = next(c for c in range(n) if c not in used)
        raise FaceListError(f"corner ids must be 0..{n - 1} for {n} corners; corner {missing} is in no face")
    return tuple(out)


@dataclass(frozen=True, eq=False)
class HalfEdgeMap:
    """A closed, connected, oriented combinatorial map (immutable).

    Darts are integers ``0..2E-1``.  ``next[d]`` follows ``d`` around its face,
    ``twin[d]`` is the same edge in the other direction, and
    ``rotate(d) = twin[prev[d]]`` turns counter-clockwise around ``origin(d)``.
    """

    faces: tuple[tuple[int, ...], ...]
    num_corners: int
    # The dart permutations as tuples (origin_of, face_of, next, prev, twin, face_start), or,
    # for a map built by the array kernels, as arrays: the tuples are then made on first use.
    _tuples: tuple[tuple[int, ...], ...] | None = field(default=None, repr=False)
    _given_arrays: MapArrays | None = field(default=None, repr=False)

    def _dart_tuple(self, i: int, name: str) -> tuple[int, ...]:
        if self._tuples is not None:
            return self._tuples[i]
        return tuple(getattr(self._given_arrays, name).tolist())

    @cached_property
    def origin_of(self) -> tuple[int, ...]:
        """Per dart, the corner it leaves."""
        return self._dart_tuple(0, "origin")

    @cached_property
    def face_of(self) -> tuple[int, ...]:
        """Per dart, the face on its left (the face it runs around, counter-clockwise)."""
        return self._dart_tuple(1, "face_of")

    @cached_property
    def next(self) -> tuple[int, ...]:
        """Per dart, the next dart around its face."""
        return self._dart_tuple(2, "next")

    @cached_property
    def prev(self) -> tuple[int, ...]:
        """Per dart, the previous dart around its face."""
        return self._dart_tuple(3, "prev")

    @cached_property
    def twin(self) -> tuple[int, ...]:
        """Per dart, the dart along the same edge in the other direction."""
        return self._dart_tuple(4, "twin")

    @cached_property
    def face_start(self) -> tuple[int, ...]:
        """Per face, its first dart (a face's darts are consecutive)."""
        return self._dart_tuple(5, "face_start")

    # -- construction -----------------------------------------------------------------
    @classmethod
    def from_faces(cls, faces: Iterable[Sequence[int]]) -> HalfEdgeMap:
        """Build the map, or raise :class:`MapError` listing every problem.

        Large face lists go through array kernels (:mod:`polyloops.core.arrays`), which accept
        a valid surface only; anything they would refuse is rebuilt by the tuple code, which
        names every problem.  Both give the same map.
        """
        faces = list(faces)
        if use_arrays(sum(len(f) for f in faces)):
            m = cls._from_valid_faces_arrays(faces)
            if m is not None:
                return m
        return cls._from_faces_tuples(faces)

    @classmethod
    @gc_paused
    def _from_valid_faces_arrays(cls, faces: list[Sequence[int]]) -> HalfEdgeMap | None:
        """The map of a valid face list by array kernels, or ``None`` when anything is off."""
        import numpy as np

        from polyloops.core.arrays import components, cycles

        if not faces or set(map(type, chain.from_iterable(faces))) != {int}:
            return None
        n_faces = len(faces)
        lengths = np.fromiter(map(len, faces), dtype=np.int64, count=n_faces)
        if lengths.min() < 3:
            return None
        origin = np.fromiter(chain.from_iterable(faces), dtype=np.int64, count=int(lengths.sum()))
        if origin.min() < 0:
            return None
        n = int(origin.max()) + 1
        if np.count_nonzero(np.bincount(origin, minlength=n)) != n:
            return None
        face_of = np.repeat(np.arange(n_faces), lengths)
        face_start = np.cumsum(lengths) - lengths
        base = face_start[face_of]
        pos = np.arange(len(origin)) - base
        k = lengths[face_of]
        nxt = base + (pos + 1) % k
        prv = base + (pos - 1) % k
        # A face visits each corner once: no two darts of one face share an origin.
        width = int(lengths[0])
        if np.all(lengths == width) and width <= 8:  # pairs within each row: no sorting
            rows = origin.reshape(-1, width)
            if any(np.any(rows[:, i] == rows[:, j]) for i in range(width) for j in range(i + 1, width)):
                return None
        else:
            order = np.lexsort((origin, face_of))
            f, o = face_of[order], origin[order]
            if np.any((f[1:] == f[:-1]) & (o[1:] == o[:-1])):
                return None
        target = origin[nxt]
        key = origin * n + target
        by_key = np.argsort(key)
        sorted_keys = key[by_key]
        if np.any(sorted_keys[1:] == sorted_keys[:-1]):
            return None  # an edge twice in one direction
        where = np.searchsorted(sorted_keys, target * n + origin)
        where[where == len(key)] = 0
        if not np.array_equal(key[by_key[where]], target * n + origin):
            return None  # an edge in one face only
        twin = by_key[where]
        if cycles(twin[prv])[0] != n:
            return None  # some corner's faces form more than one fan
        if components(n, origin, target)[0] != 1:
            return None
        from polyloops.core.arrays import MapArrays

        darts = np.arange(len(origin))
        lower = np.minimum(darts, twin)
        rank = np.cumsum(darts < twin) - 1
        arrays = MapArrays(origin, target, face_of, nxt, prv, twin, face_start, rank[lower],
                           np.flatnonzero(darts < twin))
        return cls(tuple(map(tuple, faces)), n, _given_arrays=arrays)

    @classmethod
    def from_trusted_faces(cls, faces: Sequence[Sequence[int]]) -> HalfEdgeMap:
        """The map of a face list already known to be a closed connected oriented surface
        (a loop move's result, built from a valid structure): :meth:`from_faces` without its
        checks, for the search's hot path.  Given anything else the result is undefined;
        ``polyloops.core.moves.VERIFY_CHILDREN`` routes moves through :meth:`from_faces`
        instead, and a test compares the two.

        >>> faces = [[0, 1, 2, 3], [3, 2, 1, 0]]
        >>> HalfEdgeMap.from_trusted_faces(faces) == HalfEdgeMap.from_faces(faces)
        True
        """
        fs = tuple(map(tuple, faces))
        if use_arrays(sum(map(len, fs))):
            return cls.from_faces(fs)
        origin, face_of, nxt, prv, face_start = _face_darts(fs)
        dart_of = {(origin[d], origin[nxt[d]]): d for d in range(len(origin))}
        twin = [dart_of[(origin[nxt[d]], origin[d])] for d in range(len(origin))]
        return cls(fs, max(origin) + 1, (tuple(origin), tuple(face_of), tuple(nxt), tuple(prv),
                                         tuple(twin), tuple(face_start)))

    @classmethod
    def _from_faces_tuples(cls, faces: list[Sequence[int]]) -> HalfEdgeMap:
        fs = _validate_faces(faces)
        origin, face_of, nxt, prv, face_start = _face_darts(fs)
        n_darts = len(origin)
        by_pair: dict[tuple[int, int], list[int]] = defaultdict(list)
        for d in range(n_darts):
            by_pair[(origin[d], origin[nxt[d]])].append(d)

        problems: list[MapProblem] = []
        twin = [-1] * n_darts
        for (u, v), ds in by_pair.items():
            back = by_pair.get((v, u), [])
            if u > v and back:
                continue  # reported from the other side
            count = len(ds) + len(back)
            if count != 2:
                kind = "boundary-edge" if count == 1 else "branching-edge"
                problems.append(MapProblem(
                    kind, f"edge ({min(u, v)}, {max(u, v)}) lies in {count} faces, not 2",
                    {"edge": [min(u, v), max(u, v)],
                     "faces": sorted(face_of[d] for d in ds + back)}))
            elif len(ds) == 2 or len(back) == 2:
                problems.append(MapProblem(
                    "orientation",
                    f"faces {face_of[(ds or back)[0]]} and {face_of[(ds or back)[1]]} "
                    f"are oriented inconsistently along edge ({u}, {v})",
                    {"edge": [u, v], "faces": sorted(face_of[d] for d in ds + back)}))
            else:
                twin[ds[0]], twin[back[0]] = back[0], ds[0]
        if problems:
            raise MapError(problems)

        m = cls(fs, max(origin) + 1, (tuple(origin), tuple(face_of), tuple(nxt), tuple(prv),
                                      tuple(twin), tuple(face_start)))
        problems.extend(m._fan_problems())
        problems.extend(m._component_problems())
        if problems:
            raise MapError(problems)
        return m

    def _fan_problems(self) -> list[MapProblem]:
        seen = [False] * self.num_darts
        fans: dict[int, list[list[int]]] = defaultdict(list)
        for d in range(self.num_darts):
            if seen[d]:
                continue
            fan = []
            e = d
            while not seen[e]:
                seen[e] = True
                fan.append(self.face_of[e])
                e = self.rotate(e)
            fans[self.origin_of[d]].append(fan)
        return [
            MapProblem("non-manifold-corner",
                       f"corner {c}: its faces form {len(fl)} fans, not one",
                       {"corner": c, "fans": [sorted(f) for f in fl]})
            for c, fl in sorted(fans.items()) if len(fl) > 1
        ]

    def _component_problems(self) -> list[MapProblem]:
        # The paper: a mesh is connected if every vertex can be reached from any other along edges.
        parts = DisjointSets(range(self.num_corners))
        for d in range(self.num_darts):
            parts.union(self.origin_of[d], self.target(d))
        components = sorted(sorted(p) for p in parts.to_sets())
        if len(components) == 1:
            return []
        return [MapProblem("disconnected", f"the surface has {len(components)} components",
                           {"components": components})]

    # -- sizes ------------------------------------------------------------------------
    @cached_property
    def num_darts(self) -> int:
        """The number of darts (twice the number of edges)."""
        return len(self._given_arrays.origin) if self._tuples is None else len(self._tuples[0])  # type: ignore[union-attr]

    @property
    def num_edges(self) -> int:
        """The number of edges."""
        return self.num_darts // 2

    @property
    def num_faces(self) -> int:
        """The number of faces."""
        return len(self.faces)

    @property
    def euler_characteristic(self) -> int:
        """``V - E + F``."""
        return self.num_corners - self.num_edges + self.num_faces

    @property
    def genus(self) -> int:
        """The genus of the closed orientable surface: ``(2 - chi) / 2``."""
        return (2 - self.euler_characteristic) // 2

    # -- darts ------------------------------------------------------------------------
    def origin(self, d: int) -> int:
        """The corner dart ``d`` leaves."""
        return self.origin_of[d]

    def target(self, d: int) -> int:
        """The corner dart ``d`` reaches."""
        return self.origin_of[self.next[d]]

    def rotate(self, d: int) -> int:
        """The next dart counter-clockwise around ``origin(d)``."""
        return self.twin[self.prev[d]]

    def dart(self, u: int, v: int) -> int:
        """The dart from corner ``u`` to corner ``v``; ``KeyError`` if they are not adjacent."""
        return self._dart_index[(u, v)]

    @cached_property
    def _dart_index(self) -> dict[tuple[int, int], int]:
        return {(self.origin_of[d], self.target(d)): d for d in range(self.num_darts)}

    @cached_property
    def _corner_dart(self) -> tuple[int, ...]:
        first = [-1] * self.num_corners
        for d in range(self.num_darts - 1, -1, -1):
            first[self.origin_of[d]] = d
        return tuple(first)

    def outgoing(self, corner: int) -> list[int]:
        """Darts leaving ``corner`` in counter-clockwise order, from its lowest dart."""
        start = self._corner_dart[corner]
        out = [start]
        d = self.rotate(start)
        while d != start:
            out.append(d)
            d = self.rotate(d)
        return out

    def degree(self, corner: int) -> int:
        """The number of edges at a corner."""
        return len(self.outgoing(corner))

    def face_darts(self, f: int) -> range:
        """The darts of face ``f``, in order around it."""
        return range(self.face_start[f], self.face_start[f] + len(self.faces[f]))

    # -- edges ------------------------------------------------------------------------
    def edge_id(self, d: int) -> int:
        """Edges are numbered by their lower dart, in dart order."""
        return self._edge_ids[d]

    @cached_property
    def arrays(self) -> MapArrays:
        """The dart permutations as numpy arrays (for the array kernels)."""
        from polyloops.core.arrays import MapArrays

        return self._given_arrays if self._given_arrays is not None else MapArrays.of(self)

    @cached_property
    def _edge_ids(self) -> tuple[int, ...]:
        if use_arrays(self.num_darts):
            return tuple(self.arrays.edge_id.tolist())
        ids = [-1] * self.num_darts
        k = 0
        for d in range(self.num_darts):
            if ids[d] < 0:
                ids[d] = ids[self.twin[d]] = k
                k += 1
        return tuple(ids)

    @cached_property
    def edge_darts(self) -> tuple[int, ...]:
        """The lower dart of each edge, indexed by edge id."""
        out = [-1] * self.num_edges
        for d in range(self.num_darts - 1, -1, -1):
            out[self._edge_ids[d]] = d
        return tuple(out)

    def edge_corners(self, e: int) -> tuple[int, int]:
        """The two corners of edge ``e``, from its stored dart's origin."""
        d = self.edge_darts[e]
        return self.origin_of[d], self.target(d)

    # -- loops ------------------------------------------------------------------------
    @cached_property
    def loop_system(self) -> LoopSystem:
        """The loops (strips) of the map; raises ``OddFaceError`` on an odd face."""
        from polyloops.core.loops import trace_loops

        return trace_loops(self)

    # -- value semantics --------------------------------------------------------------
    def __eq__(self, other: object) -> bool:
        return isinstance(other, HalfEdgeMap) and self.faces == other.faces

    def __hash__(self) -> int:
        return hash(self.faces)

    def __repr__(self) -> str:
        return (f"HalfEdgeMap(corners={self.num_corners}, edges={self.num_edges}, "
                f"faces={self.num_faces}, genus={self.genus})")

    def reversed(self) -> HalfEdgeMap:
        """The same surface with every face's orientation reversed (the inverse)."""
        return HalfEdgeMap.from_faces([tuple(reversed(f)) for f in self.faces])
