"""The first stage listed directly: the two-axis arrangements ``B`` as square-tiled surfaces.

**What ``B`` is.**  ``B`` is a cellular arrangement whose crossing graph is bipartite (two
classes of loops, every crossing between a loop of each) and whose loops each have two
different zones on their sides.  Number its darts four a crossing counter-clockwise so that
darts ``4v`` and ``4v + 2`` lie on ``v``'s loop of the first class and ``4v + 1``, ``4v + 3`` on
its loop of the second (possible at every crossing, as two loops of one class never cross).
Then every edge joins two darts of the same parity, and conversely any pairing ``twin`` of the
darts that keeps parity is such an arrangement when it is connected: walking straight on (from
``d`` to ``twin(d) + 2``) never leaves a parity, so the loops of each parity are simple and
pairwise disjoint, and a map given by its rotation and twin is cellular on the orientable
surface its faces give (``V - E + F = 2 - 2g`` with ``V = n`` crossings, ``E = 2n``).  Dually,
each crossing is a square of a surface tiled by squares, each dart a side of its square, and
the faces of ``B`` are the vertices of the tiling.

**Each ``B`` once.**  A root is a square, one of its four darts, and one of the two
orientations: ``8n`` roots.  From a root the map is labelled breadth first: squares numbered in
the order they are first reached, each square's darts numbered from the dart it was reached by,
which gets the reaching dart's number plus two (mod 4), counter-clockwise (clockwise in the
mirror orientation).  The labelled map's ``twin`` array is its *code* from that root, and two
maps are the same ``B`` (up to homeomorphism, the mirror and the swap of the classes
included: a root on a dart of the second class swaps them) exactly when they have the same
least code.  The search writes a code position by position (``twin`` of dart ``d``, darts in
order): the dart is joined to a new square, the next number, at the dart number the rule gives,
or to a free dart of the same parity further on.  Every labelled map breadth first from a root
is written exactly once, and a leaf is kept when no root gives a smaller code, so each ``B`` is
kept exactly once.  McKay's orderly test comes early: the code's first ``4k`` positions are fixed
once ``k`` squares are complete, and a root whose breadth-first code, as far as it is known,
is already smaller ends the branch.

**Cuts** (each keeps every ``B`` of the target genus):

- *Genus.*  The squares glued so far form a connected surface with boundary, a subsurface of
  the final one, so its genus is at most the target.  Its Euler characteristic is
  ``C + m - A/2`` (``C`` closed vertices, ``m`` squares, ``A`` joined darts) and its boundary
  components ``b`` are the cycles of the boundary walk, so its genus is ``(2 - b - chi) / 2``.
- *Vertices.*  The final map has ``n + 2 - 2g`` vertices; every vertex not yet closed has at
  least two corners (no face of ``B`` has one side: its two darts would differ in parity).
- *Zones.*  A class's zones are the faces joined across the other class's edges: in the tiling,
  vertices joined by the sides the other class's loops cross.  Joins only merge them, so a loop
  with the same zone on both sides (the ends of a side its loop crosses) stays so.

:func:`square_bases` runs the compiled search (``_squares.c``) when the part ``squares`` is in
use, else :class:`_Search`, the same steps in Python.

>>> [len(square_bases(n, 2)[0]) for n in range(5, 9)]
[0, 2, 0, 23]
"""

from __future__ import annotations

import array
from dataclasses import dataclass

from polyloops.core import compiled

__all__ = ["SquareStats", "square_bases"]


@dataclass(frozen=True)
class SquareStats:
    """What a listing did: the ``B`` it found, nodes of the search, leaves (closed surfaces with
    every square), leaves of a lower genus than the target, branches ended as not canonical,
    and (in a share) the subtrees split among the shares."""

    kept: int = 0
    nodes: int = 0
    leaves: int = 0
    lower_genus: int = 0
    not_canonical: int = 0
    subtrees: int = 0


def square_bases(crossings: int, genus: int, res: int = 0, mod: int = 1, split: int | None = None,
                 keep: bool = True) -> tuple[list[bytes], SquareStats]:
    """Every ``B`` with ``crossings`` crossings on the surface of ``genus``, once each, as its
    ``twin`` array of uint16 (bytes), and the search's statistics.  With ``mod > 1``, share
    ``res``: the subtrees met when ``split`` edges are joined (as many as the crossings unless
    given: tens of thousands of subtrees with 12 to 16 crossings) are dealt round the shares.
    Without ``keep`` the list is empty and only the statistics are counted
    (:class:`SquareStats`, ``kept`` among them).

    >>> twins, stats = square_bases(4, 1)
    >>> [list(array.array("H", t)) for t in twins]  # two loops of each class, crossing twice each
    [[6, 11, 4, 9, 2, 15, 0, 13, 14, 3, 12, 1, 10, 7, 8, 5]]
    >>> stats.kept, stats.nodes
    (1, 36)
    """
    if not 1 <= crossings <= 24 or genus < 0 or not 0 <= res < mod:
        raise ValueError("crossings 1..24, genus >= 0, 0 <= res < mod")
    # every branch to a B passes an open node with `split` edges joined when split < 2n
    split = min(crossings if split is None else max(split, 0), 2 * crossings - 1)
    part = compiled.load("squares")
    if part is not None:
        found, counts = part.bases(crossings, genus, res, mod, split, keep)
        if keep:
            return found, SquareStats(len(found), *counts)
        return [], SquareStats(found, *counts)
    search = _Search(crossings, genus, res, mod, split, keep)
    search.run()
    return search.out, SquareStats(search.kept, search.nodes, search.leaves, search.lower_genus,
                                   search.not_canonical, search.seen)


def _rot(d: int) -> int:
    return (d & ~3) | ((d + 1) & 3)


def _irot(d: int) -> int:
    return (d & ~3) | ((d + 3) & 3)


class _Search:
    """The search of :func:`square_bases` in Python (the compiled part's twin: the same nodes,
    in the same order)."""

    def __init__(self, n: int, genus: int, res: int, mod: int, split: int, keep: bool):
        self.n, self.genus, self.faces = n, genus, n + 2 - 2 * genus
        self.res, self.mod, self.split = res, mod, (2 * split if mod > 1 else -1)
        self.keep = keep
        self.tw: list[int] = []
        # vertices as paths of corners: corner d is followed by rot(twin(d)); an open path's
        # ends point at each other (oe) and know its length
        self.oe: list[int] = []
        self.length: list[int] = []
        self.closed = self.closed_corners = self.joined = 0
        # zones as unions of corners, per class (see _squares.c): parents, undone by history
        self.up: list[list[int]] = [[], []]
        self.history: list[tuple[int, int, int]] = []
        self.kept = self.nodes = self.leaves = self.lower_genus = self.not_canonical = self.seen = 0
        self.out: list[bytes] = []

    @property
    def m(self) -> int:
        return len(self.tw) // 4

    def run(self) -> None:
        if self.faces >= 1:
            self._add_square()
            self._search(0)

    # -- the state ------------------------------------------------------------------------------

    def _find(self, k: int, x: int) -> int:
        while self.up[k][x] != x:
            x = self.up[k][x]
        return x

    def _union(self, k: int, a: int, b: int) -> None:
        a, b = self._find(k, a), self._find(k, b)
        if a != b:  # no ranks: the structure only answers "same zone?", at small sizes
            self.history.append((k, b, self.up[k][b]))
            self.up[k][b] = a

    def _add_square(self) -> None:
        base = len(self.tw)
        for j in range(4):
            self.tw.append(-1)
            self.oe.append(base + j)
            self.length.append(1)
            for k in (0, 1):
                self.up[k].append(base + j)
        self._union(0, base, base + 1)
        self._union(0, base + 2, base + 3)
        self._union(1, base + 3, base)
        self._union(1, base + 1, base + 2)

    def _drop_square(self) -> None:
        del self.tw[-4:], self.oe[-4:], self.length[-4:], self.up[0][-4:], self.up[1][-4:]

    def _link(self, a: int, b: int) -> tuple:
        if self.oe[a] == b:  # the path closes: a vertex
            self.closed += 1
            self.closed_corners += self.length[a]
            return ("closed", a)
        h, t = self.oe[a], self.oe[b]
        undo = ("merged", h, t, self.oe[h], self.oe[t], self.length[h], self.length[t])
        total = self.length[a] + self.length[b]
        self.oe[h], self.oe[t] = t, h
        self.length[h] = self.length[t] = total
        return undo

    def _unlink(self, undo: tuple) -> None:
        if undo[0] == "closed":
            self.closed -= 1
            self.closed_corners -= self.length[undo[1]]
            return
        _, h, t, oh, ot, lh, lt = undo
        self.oe[t], self.length[t] = ot, lt
        self.oe[h], self.length[h] = oh, lh

    def _join(self, d: int, e: int) -> tuple[tuple, tuple, int]:
        mark = len(self.history)
        self.tw[d], self.tw[e] = e, d
        self.joined += 2
        u0 = self._link(d, _rot(e))
        u1 = self._link(e, _rot(d))
        for k in (0, 1):
            self._union(k, d, _irot(e))
            self._union(k, _irot(d), e)
        return u0, u1, mark

    def _unjoin(self, d: int, e: int, undo: tuple[tuple, tuple, int]) -> None:
        u0, u1, mark = undo
        self._unlink(u1)
        self._unlink(u0)
        self.tw[d] = self.tw[e] = -1
        self.joined -= 2
        self._undo_to(mark)

    def _undo_to(self, mark: int) -> None:
        while len(self.history) > mark:
            k, b, old = self.history.pop()
            self.up[k][b] = old

    # -- the cuts -------------------------------------------------------------------------------

    def _one_zone(self) -> bool:
        return any(self._find(0, 4 * v + 3) == self._find(0, 4 * v)
                   or self._find(1, 4 * v) == self._find(1, 4 * v + 1) for v in range(self.m))

    def _hopeful(self) -> bool:
        m = self.m
        seen = [False] * (4 * m)
        b = 0
        for x in range(4 * m):
            if self.tw[x] >= 0 or seen[x]:
                continue
            b += 1
            y = x
            while not seen[y]:
                seen[y] = True
                y = self.oe[_rot(y)]
        chi2 = 2 * (self.closed + m) - self.joined
        if 4 - 2 * b - chi2 > 4 * self.genus:
            return False
        return self.closed + (4 * self.n - self.closed_corners) // 2 >= self.faces

    def _compare_root(self, r: int, o: int, f: int, limit: int) -> int:
        tw = self.tw
        lab = {r: 0}
        sq, fr = [r], {r: o}
        for p in range(limit):
            v, j = sq[p >> 2], p & 3
            x = 4 * v + ((fr[v] - j if f else fr[v] + j) & 3)
            y = tw[x]
            if y < 0:
                return 0
            u, k = y >> 2, y & 3
            if u not in lab:
                lab[u] = len(sq)
                sq.append(u)
                want = (j + 2) & 3
                fr[u] = (k + want) & 3 if f else (k - want) & 3
            jj = (fr[u] - k) & 3 if f else (k - fr[u]) & 3
            code = 4 * lab[u] + jj
            if code != tw[p]:
                return -1 if code < tw[p] else 1
        return 0

    def _canonical_so_far(self, limit: int) -> bool:
        return not any(self._compare_root(r, o, f, limit) < 0
                       for r in range(self.m) for o in range(4) for f in (0, 1) if r or o or f)

    # -- the search -----------------------------------------------------------------------------

    def _leaf(self) -> None:
        self.leaves += 1
        if self.closed != self.faces:
            self.lower_genus += 1
        elif not self._canonical_so_far(4 * self.n):
            self.not_canonical += 1
        else:
            self.kept += 1
            if self.keep:
                self.out.append(array.array("H", self.tw).tobytes())

    def _search(self, d: int) -> None:
        self.nodes += 1
        while d < len(self.tw) and self.tw[d] >= 0:
            d += 1
        if d == len(self.tw):  # every dart of every square joined: closed
            if self.m == self.n:
                self._leaf()
            return
        if d % 4 == 0 and d and not self._canonical_so_far(d):
            self.not_canonical += 1
            return
        if self.joined == self.split:
            self.seen += 1
            if (self.seen - 1) % self.mod != self.res:
                return
        if self.m < self.n:  # a new square, reached through its dart (d + 2) mod 4
            e = 4 * self.m + ((d + 2) & 3)
            mark = len(self.history)
            self._add_square()
            undo = self._join(d, e)
            if not self._one_zone() and self._hopeful():
                self._search(d + 1)
            self._unjoin(d, e, undo)
            self._undo_to(mark)
            self._drop_square()
        for e in range(d + 1, len(self.tw)):
            if self.tw[e] >= 0 or (e ^ d) & 1:
                continue
            undo = self._join(d, e)
            if not self._one_zone() and self._hopeful():
                self._search(d + 1)
            self._unjoin(d, e, undo)
