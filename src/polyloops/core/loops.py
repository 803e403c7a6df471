"""Loops: the strips of faces of a map.

A loop enters a face through one edge and leaves through the opposite one: in
a quad, edge ``i`` continues to edge ``i + 2``; in a ``2k``-gon, to edge
``i + k`` (so ``k`` loops meet in it).  The loops of a map are therefore the
orbits of the permutation ``cross(d) = twin(next^k(d))`` on darts.

Each crossed edge is recorded by the dart that points from the left to the
right of the walk.  (Dart ``d`` lies in the face on its left; the loop walks
into that face, so ``d`` points to the walker's right.)  The reverse walk is
the orbit of the twins, and a loop is stored once, walking the orbit that
contains its lowest dart.  Loops are numbered by that dart.

>>> from polyloops.core.halfedge import HalfEdgeMap
>>> m = HalfEdgeMap.from_faces([[0, 1, 2, 3], [3, 2, 1, 0]])
>>> [(lp.id, lp.edges) for lp in m.loop_system.loops]
[(0, (0, 2)), (1, (1, 3))]
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property
from itertools import pairwise
from typing import TYPE_CHECKING

from polyloops.core.arrays import gc_paused
from polyloops.core.errors import PolyloopsError

if TYPE_CHECKING:
    from polyloops.core.halfedge import HalfEdgeMap


class OddFaceError(PolyloopsError, ValueError):
    """A face with an odd number of sides has no opposite edges, so no loops."""


@dataclass(frozen=True)
class Loop:
    """One loop: its crossings in walking order.

    ``darts[i]`` is the crossed edge, pointing from the left of the walk to its
    right; ``faces[i]`` is the face (loop intersection) entered through it.
    """

    id: int
    darts: tuple[int, ...]
    faces: tuple[int, ...]
    edges: tuple[int, ...]

    def __len__(self) -> int:
        return len(self.darts)

    @property
    def self_crossings(self) -> tuple[int, ...]:
        """Faces that this loop passes through more than once."""
        return tuple(sorted(f for f, n in Counter(self.faces).items() if n > 1))


@dataclass(frozen=True)
class LoopSystem:
    """All loops of a map, with the loop and walking side of every dart."""

    loops: tuple[Loop, ...]
    loop_of_dart: tuple[int, ...]
    # +1 if the dart points from the left to the right of its loop's stored walk, else -1.
    side_of_dart: tuple[int, ...]

    @cached_property
    def loop_array(self):
        """``loop_of_dart`` as a numpy array."""
        import numpy as np

        return np.asarray(self.loop_of_dart, dtype=np.int64)

    @cached_property
    def side_array(self):
        """``side_of_dart`` as a numpy array."""
        import numpy as np

        return np.asarray(self.side_of_dart, dtype=np.int64)

    def loops_of_face(self, m: HalfEdgeMap, f: int) -> tuple[int, ...]:
        """The loops crossing in face ``f``, one per pair of opposite edges."""
        darts = list(m.face_darts(f))
        return tuple(self.loop_of_dart[d] for d in darts[: len(darts) // 2])


def trace_loops(m: HalfEdgeMap) -> LoopSystem:
    """Trace every loop of ``m``; raise :class:`OddFaceError` on an odd face."""
    from polyloops.core.arrays import use_arrays

    if use_arrays(m.num_darts):
        return _trace_loops_arrays(m)
    return _trace_loops_tuples(m)


def _odd_face(m: HalfEdgeMap) -> None:
    for f, face in enumerate(m.faces):
        if len(face) % 2:
            raise OddFaceError(f"face {f} has {len(face)} sides; loops need faces with an even number")


@gc_paused
def _trace_loops_arrays(m: HalfEdgeMap) -> LoopSystem:
    """:func:`trace_loops` with the crossing permutation and its cycles computed on arrays."""
    import numpy as np

    from polyloops.core.arrays import cycles

    a = m.arrays
    lengths = np.diff(np.append(a.face_start, m.num_darts))
    if np.any(lengths % 2):
        _odd_face(m)
    half = (lengths // 2)[a.face_of]
    e = np.arange(m.num_darts)
    for step in range(int(half.max())):
        e = np.where(step < half, a.next[e], e)
    cross = a.twin[e]
    count, cycle_of = cycles(cross)
    lowest = np.full(count, m.num_darts, dtype=np.int64)
    np.minimum.at(lowest, cycle_of, np.arange(m.num_darts))
    # A loop is a cycle and the cycle of its twins; it walks the one with the lower dart.
    other = cycle_of[a.twin[lowest]]
    stored = np.flatnonzero(lowest < lowest[other])  # cycles that are a loop's stored walk
    starts = lowest[stored]  # increasing, so loops are numbered by their lowest dart
    # Each stored orbit in walking order from its lowest dart, by list ranking: cut every
    # orbit before its start, then halve distances to the cut by pointer jumping (as many
    # rounds as the longest loop has binary digits), and place each dart at its offset.
    darts = np.arange(m.num_darts)
    stored_cycle = np.zeros(count, dtype=bool)
    stored_cycle[stored] = True
    mine = stored_cycle[cycle_of]
    start_of = lowest[cycle_of]
    nxt = np.where(mine & (cross != start_of), cross, darts)
    rank = (nxt != darts).astype(np.int64)  # darts to the end of the walk
    while np.any(nxt[nxt] != nxt):
        rank += rank[nxt]
        nxt = nxt[nxt]
    length = np.bincount(cycle_of[mine], minlength=count)[stored]
    bounds_arr = np.concatenate([[0], np.cumsum(length)])
    slot = np.empty(count, dtype=np.int64)
    slot[stored] = np.arange(len(stored))
    walk = np.empty(int(bounds_arr[-1]), dtype=np.int64)
    members = np.flatnonzero(mine)
    k_of = slot[cycle_of[members]]
    walk[bounds_arr[k_of] + (length[k_of] - 1 - rank[members])] = members
    order = walk.tolist()
    bounds = bounds_arr.tolist()
    lengths_of = np.diff(bounds)
    ids = np.repeat(np.arange(len(starts)), lengths_of)
    loop_of = np.empty(m.num_darts, dtype=np.int64)
    side = np.empty(m.num_darts, dtype=np.int64)
    loop_of[walk], loop_of[a.twin[walk]] = ids, ids
    side[walk], side[a.twin[walk]] = 1, -1
    faces_all = a.face_of[walk].tolist()
    edges_all = a.edge_id[walk].tolist()
    loops = [Loop(k, tuple(order[i:j]), tuple(faces_all[i:j]), tuple(edges_all[i:j]))
             for k, (i, j) in enumerate(pairwise(bounds))]
    return LoopSystem(tuple(loops), tuple(loop_of.tolist()), tuple(side.tolist()))


def _trace_loops_tuples(m: HalfEdgeMap) -> LoopSystem:
    half: list[int] = []
    for f, face in enumerate(m.faces):
        if len(face) % 2:
            raise OddFaceError(f"face {f} has {len(face)} sides; loops need faces with an even number")
        half.append(len(face) // 2)
    n = m.num_darts
    cross = [0] * n
    for d in range(n):
        e = d
        for _ in range(half[m.face_of[d]]):
            e = m.next[e]
        cross[d] = m.twin[e]
    loop_of = [-1] * n
    side = [0] * n
    loops: list[Loop] = []
    for d in range(n):
        if loop_of[d] >= 0:
            continue
        orbit = [d]
        e = cross[d]
        while e != d:
            orbit.append(e)
            e = cross[e]
        k = len(loops)
        for e in orbit:
            loop_of[e] = loop_of[m.twin[e]] = k
            side[e], side[m.twin[e]] = 1, -1
        faces = tuple(m.face_of[e] for e in orbit)
        loops.append(Loop(k, tuple(orbit), faces, tuple(m.edge_id(e) for e in orbit)))
    return LoopSystem(tuple(loops), tuple(loop_of), tuple(side))


def same_axis_meetings(m: HalfEdgeMap, axes: Sequence[int]) -> Iterator[tuple[int, int, int, int]]:
    """Condition 3's raw material: for each corner and each two darts leaving it across loops
    ``l1, l2`` with the same label, ``(l1, e1, l2, e2)``, where ``e = +1`` when the corner lies
    on the left of the loop.  The two darts point in different directions exactly when the
    loops' signs satisfy ``s_l1 * s_l2 = -e1 * e2`` (the paper's side graph joins side
    ``(l1, e1)`` to side ``(l2, e2)``).  Both the orientation solvers and the catalog's parity
    test read Condition 3 from here.

    >>> from polyloops.io.examples import load_example
    >>> ls = load_example("l-shape").dualize()
    >>> sorted(set(same_axis_meetings(ls.map, ls.axes)))
    [(0, -1, 3, 1), (2, 1, 4, 1)]
    """
    system = m.loop_system
    loop_of, side_of = system.loop_of_dart, system.side_of_dart
    for c in range(m.num_corners):
        darts = m.outgoing(c)
        for i, d1 in enumerate(darts):
            l1 = loop_of[d1]
            for d2 in darts[i + 1:]:
                l2 = loop_of[d2]
                if axes[l1] == axes[l2]:
                    # side_of_dart = +1: the dart points left to right, so its origin is on the left.
                    yield l1, side_of[d1], l2, side_of[d2]
