"""Drawing a new curve on a state of the torus search, arc by arc through its faces.

An arc through a disc face is fixed by its ends; through a marked face it is one of a few kinds,
each fixed up to a homeomorphism of the face that keeps its boundary (so the arrangements are
the same):

- in ``H``, an arc between two points of its boundary cuts off a disc on either side (the
  handle stays in the other piece), or does not separate (the face becomes an annulus: both
  pieces of the rotation system become its ends);
- in an annulus end, an arc back to the same end cuts off a disc on either side; an arc to the
  other end crosses the annulus, which becomes a disc (the rotation system becomes a torus).

:class:`Drawing` holds the parent's rotation system while the curve is drawn (points of degree
2 where the curve crosses an edge, chords through the faces) and :func:`finish_curve` turns it
into the child.
"""

from __future__ import annotations

from collections.abc import Sequence

from polyloops.core.halfedge import permutation_orbits
from polyloops.generate.torus.arrangement import (
    ANNULUS,
    HANDLE,
    MARK_NEED,
    THIRD,
    TorusArrangement,
    piece_mark,
    piece_of_mark,
    pieces_need,
)
from polyloops.generate.torus.cuts import bad_face, face_need, layered_need

__all__ = ["ROOTS", "Drawing", "connected_without", "finish_curve", "roots"]

ROOTS = (  # a single loop, as a point of degree 2 on it: essential, or bounding a disc
    ((1, 0), (1, 0), ((ANNULUS, 0), (ANNULUS, 1))),
    ((1, 0), (1, 0), ((HANDLE, 1),)),
)

Root = tuple[tuple[int, ...], tuple[int, ...], tuple[tuple[str, int], ...]]


def roots(genus: int) -> tuple[Root, ...]:
    """The single loops on a surface of ``genus``, each up to homeomorphism (a point of degree
    2 on the loop, the faces on the left of darts 0 and 1 its two sides): one that does not
    separate (its sides bound one piece of genus ``genus - 1``), then those that cut off a piece
    of genus ``h`` on the side of dart 0, for ``h = 0 .. genus // 2`` (0: a disc).  On the torus,
    :data:`ROOTS`.

    >>> [marks for _, _, marks in roots(2)]
    [(('g1.0', 0), ('g1.0', 1)), (('g2.0', 1),), (('g1.0', 0), ('g1.1', 1))]
    """
    if genus == 1:
        return ROOTS
    single = ((1, 0), (1, 0))
    out: list[Root] = [(*single, ((piece_mark(genus - 1, 0), 0), (piece_mark(genus - 1, 0), 1)))]
    out.append((*single, ((piece_mark(genus, 0), 1),)))
    for h in range(1, genus // 2 + 1):
        out.append((*single, ((piece_mark(h, 0), 0), (piece_mark(genus - h, 1), 1))))
    return tuple(out)


class Drawing:
    """A parent's rotation system while a curve is drawn on it: darts of any degree, points
    where the curve crosses the parent's edges, chords; per dart its parent loop (-1 on the
    curve), its layer, (second stage) the region of ``B`` it lies in, and the parent edge it
    lies on (its lesser dart; -1 on the curve)."""

    def __init__(self, rot: Sequence[int], twin: Sequence[int], marks: Sequence[tuple[str, int]],
                 loop: Sequence[int], layer: Sequence[int], region: Sequence[int], curve_layer: int):
        self.rot, self.twin, self.marks = list(rot), list(twin), list(marks)
        self.loop, self.layer, self.region = list(loop), list(layer), list(region)
        self.edge = [min(d, t) for d, t in enumerate(twin)]
        self.irot = [0] * len(self.rot)
        for d, r in enumerate(self.rot):
            self.irot[r] = d
        self.curve_layer = curve_layer

    def face(self, d: int) -> list[int]:
        """The darts of the face on the left of ``d``, from ``d`` on."""
        out, e = [], d
        while True:
            out.append(e)
            e = self.irot[self.twin[e]]
            if e == d:
                return out

    def _add(self, loop: int, layer: int, region: int, edge: int = -1) -> int:
        for lst, v in ((self.rot, -1), (self.irot, -1), (self.twin, -1), (self.loop, loop),
                       (self.layer, layer), (self.region, region), (self.edge, edge)):
            lst.append(v)
        return len(self.rot) - 1

    def subdivide(self, y: int) -> tuple[int, int]:
        """A point on the edge of ``y``: darts ``q1`` (on, as ``y`` runs; beside ``y``'s face)
        and ``q2`` (back; beside the other face)."""
        t = self.twin[y]
        q1 = self._add(self.loop[y], self.layer[y], self.region[y], self.edge[y])
        q2 = self._add(self.loop[y], self.layer[y], self.region[t], self.edge[y])
        self.rot[q1], self.rot[q2], self.irot[q1], self.irot[q2] = q2, q1, q2, q1
        self.twin[y], self.twin[q2], self.twin[q1], self.twin[t] = q2, y, t, q1
        return q1, q2

    def chord(self, x: int, y: int) -> tuple[int, int]:
        """An edge of the curve from the origin of ``x`` (right after it, counter-clockwise)
        to that of ``y``."""
        a = self._add(-1, self.curve_layer, self.region[x])
        b = self._add(-1, self.curve_layer, self.region[y])
        for new, at in ((a, x), (b, y)):
            nxt = self.rot[at]
            self.rot[at], self.rot[new], self.irot[new], self.irot[nxt] = new, nxt, at, new
        self.twin[a], self.twin[b] = b, a
        return a, b

    def mark_index(self, face: list[int]) -> int | None:
        """The index in ``marks`` of the mark of ``face`` (``None`` for a disc)."""
        darts = set(face)
        return next((i for i, (_, d) in enumerate(self.marks) if d in darts), None)

    def needs(self, open_darts: set[int], regions: bool, klass: Sequence[int] | None = None) -> int:
        """Twice a lower bound on the crossings still to come from the faces that are not open
        (no dart of ``open_darts``): marked faces, and with ``regions`` faces that are not yet
        regions of a candidate map."""
        marked = {d: kind for kind, d in self.marks}
        total = 0
        pieces: dict[str, list[str]] = {}  # genus 2 or more: a piece's marks, on faces not open
        opened: set[str] = set()  # pieces the curve is in, which it may cut yet for nothing
        for face in permutation_orbits([self.irot[t] for t in self.twin]):
            kind = next((marked[e] for e in face if e in marked), None)
            general = kind is not None and kind not in MARK_NEED
            if open_darts.intersection(face):
                if general:
                    assert kind is not None
                    opened.add(piece_of_mark(kind)[1])
                continue
            if general:
                assert kind is not None
                pieces.setdefault(piece_of_mark(kind)[1], []).append(kind)
            elif kind is not None:
                total += MARK_NEED[kind]
            elif regions:
                sides = [e for e in face if self.rot[self.rot[e]] != e]  # not from a point of degree 2
                bad = bad_face(sides, self.loop, self.twin)
                if klass is None:
                    total += face_need(len(sides), bad)
                else:
                    total += layered_need(len(sides), [klass[self.loop[e]] if self.loop[e] >= 0 else THIRD
                                                       for e in sides], bad)
        return total + sum(pieces_need(kinds) for piece, kinds in pieces.items() if piece not in opened)

    def snapshot(self) -> tuple:
        """The drawing as it is, for :meth:`restore`."""
        return len(self.rot), list(self.rot), list(self.irot), list(self.twin), list(self.marks)

    def restore(self, snap: tuple) -> None:
        """Undo everything drawn since ``snap`` was taken."""
        n, rot, irot, twin, marks = snap
        self.rot, self.irot, self.twin, self.marks = list(rot), list(irot), list(twin), marks
        for lst in (self.loop, self.layer, self.region, self.edge):
            del lst[n:]


def finish_curve(w: Drawing, layered: bool) -> tuple[TorusArrangement, int]:
    """The child a closed curve makes: points of degree 2 smoothed away, darts renumbered four
    a crossing; and a dart of the new loop."""
    index: dict[int, int] = {}
    for orbit in permutation_orbits(w.rot):  # the vertices
        if len(orbit) == 4:
            base = len(index)
            for i, e in enumerate(orbit):
                index[e] = base + i

    def through(t: int) -> int:  # straight on through a point of degree 2
        while t not in index:
            t = w.twin[w.rot[t]]
        return t

    twin = [0] * len(index)
    layer = [0] * len(index)
    for d, i in index.items():
        twin[i] = index[through(w.twin[d])]
        layer[i] = w.layer[d]
    marks = []
    for kind, d in w.marks:
        e = d
        while e not in index:  # a dart of the same face that stays
            e = w.irot[w.twin[e]]
        marks.append((kind, index[e]))
    curve = next(i for d, i in index.items() if w.loop[d] < 0)
    return TorusArrangement(tuple(twin), tuple(marks), tuple(layer) if layered else ()), curve


def connected_without(adj: list[set[int]], skip: int) -> bool:
    """Whether the graph ``adj`` stays connected when vertex ``skip`` is deleted (a loop whose
    deletion leaves an arrangement connected)."""
    rest = [v for v in range(len(adj)) if v != skip]
    if len(rest) <= 1:
        return True
    seen, stack = {rest[0]}, [rest[0]]
    while stack:
        for u in adj[stack.pop()]:
            if u != skip and u not in seen:
                seen.add(u)
                stack.append(u)
    return len(seen) == len(rest)


