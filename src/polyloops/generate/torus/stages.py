"""The torus search: arrangements of loops on the torus built one loop at a time.

**Any connected arrangement.**  As on the sphere (:mod:`polyloops.generate.loops.arrangements`),
every connected arrangement with at least two loops has a loop whose deletion leaves it
connected, so it is reached from a single loop by adding curves, and McKay's canonical
construction path makes the search a tree.  What is new on the torus is that the arrangements
met on the way need not be cellular: the states are marked maps
(:mod:`~polyloops.generate.torus.arrangement`) and a new curve is drawn arc by arc through their
faces (:mod:`~polyloops.generate.torus.drawing`).  A child is kept when its new loop is the
canonical loop to delete (among loops whose deletion leaves the arrangement connected, those
with fewest crossings, and of these the first in the canonical numbering of the marked map).
:func:`torus_arrangements` lists every cellular arrangement so (``colours`` keeps those whose
crossing graph that many colours colour).

**The two stages of the polycube search** (``docs/searches.md`` proves them).  The first lists
the two-axis arrangements ``B`` (:func:`two_axis_bases`, :func:`first_stage`); the second adds
the third axis.  This module holds the second stage loop by loop (:func:`second_stage`: each
child kept when its new loop is the canonical third-axis loop to delete; every state is
cellular), the twin kept for the tests of the region search
(:mod:`~polyloops.generate.torus.regions`).  Both stages run in C when the compiled part
``torus`` is in use (``_torus.c``: the same children as the Python search, tested), the first
for the marked search without a regions' bound and with two colours or none.

>>> from collections import Counter
>>> sorted(Counter(a.crossings for a in torus_arrangements(3)).items())
[(1, 1), (2, 2), (3, 5)]
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, fields
from functools import lru_cache

from polyloops.core import compiled
from polyloops.generate.torus.arrangement import (
    ANNULUS,
    HANDLE,
    THIRD,
    TorusArrangement,
    arrangement_of_twin,
    axis_classes,
    canonical,
    piece_mark,
    piece_of_mark,
    regions_of_base,
    rot4,
    twin_bytes,
)
from polyloops.generate.torus.cuts import (
    Facts,
    axis_runs,
    balanced,
    deficit,
    facts_of,
    orientable,
    zones_split_every_loop,
)
from polyloops.generate.torus.drawing import Drawing, connected_without, finish_curve, roots

__all__ = ["TorusSearchStats", "compiled_search_available", "first_stage", "forget_first_stage",
           "second_stage", "share_of_first_stage", "torus_arrangements", "torus_children", "two_axis_bases"]


@dataclass
class TorusSearchStats:
    """What a search did: curves closed, children over the bound, not canonical, or with a
    crossing graph the colours cannot colour; states kept, and targets among them."""

    closed: int = 0
    over_bound: int = 0
    not_canonical: int = 0
    not_colourable: int = 0
    inconsistent_sides: int = 0  # second stage: third-axis loops that no orientation fits
    not_rectilinear: int = 0  # second stage: a new loop whose crossings run in fewer than 4 runs
    states: int = 0
    targets: int = 0
    region_choices: int = 0  # region search: regions cut (a region's chords chosen)
    one_way: int = 0  # region search: pieces that force a level graph's cycle one way round
    third_axes: int = 0  # region search: third axes built (each region crossed once a loop)

    def add(self, other: TorusSearchStats) -> None:
        """Add another search's counts to these."""
        for f in fields(self):
            setattr(self, f.name, getattr(self, f.name) + getattr(other, f.name))


def compiled_search_available() -> bool:
    """Whether the compiled torus search runs: built (it needs a C compiler) and not switched to
    its Python twin (:mod:`polyloops.core.compiled`)."""
    return compiled.in_use("torus")


class _ChildSearch:
    """One parent's children, by drawing every new curve from every start (the Python search;
    :func:`torus_children` documents what it finds).  The curve is drawn depth first on one
    :class:`~polyloops.generate.torus.drawing.Drawing`, each step undone after its branch."""

    def __init__(self, parent: TorusArrangement | int, max_crossings: int, colours: int | None,
                 regions: bool, stats: TorusSearchStats, every_start: bool = False, genus: int = 1):
        self.max_crossings, self.colours, self.regions, self.stats = max_crossings, colours, regions, stats
        self.every_start = every_start  # the first stage's curves drawn from every start (a twin)
        self.layered = not isinstance(parent, int) and bool(parent.layer)
        self.base_crossings = 0  # second stage: crossings of B, and of the third axis with each class
        self.third_with = [0, 0]
        self.klass: list[int] | None = None
        # loops that may be deleted (connectedness kept; second stage: the third axis) and their crossings
        self.deletable: list[tuple[int, int]] = []
        rot: Sequence[int]
        twin: Sequence[int]
        marks: Sequence[tuple[str, int]]
        if isinstance(parent, int):
            rot, twin, marks = roots(genus)[parent]
            loop: Sequence[int] = [0, 0]
            layer: Sequence[int] = [0, 0]
            region: Sequence[int] = [0, 0]
            self.parent_crossings = 0
        else:
            rot = [rot4(d) for d in range(len(parent.twin))]
            twin, marks, loop = parent.twin, parent.marks, parent.loop_of
            layer = parent.layer or [0] * len(twin)
            region = regions_of_base(parent) if self.layered else [0] * len(twin)
            self.parent_crossings = parent.crossings
            if self.layered:
                self._count_crossings(parent)
            lc = parent.loop_crossings()
            self.deletable = [(lp, lc[lp]) for lp in self._may_delete(parent)]
        self.w = Drawing(rot, twin, marks, loop, layer, region, 1 if self.layered else 0)
        self.budget = max_crossings - self.parent_crossings
        self.found: dict[tuple, tuple[TorusArrangement, Facts]] = {}
        self.met: dict[int, int] = {}  # the curve's crossings with each parent loop
        self.visited: set[int] = set()  # second stage: the regions of B the curve has passed
        # Second stage: crossing the start edge again would leave a face of two sides, a piece of
        # an edge of B and the new loop, which later third-axis loops (they cross only B, each
        # region once) can only cut into more such faces, so nothing grows from it.
        self.start_edge: set[int] = set()
        self.root = isinstance(parent, int)
        self.banned: set[int] = set()  # a single loop: the piece the curve never crosses
        self.least = -1  # first stage: the curve's start edge, below which it crosses none

    def _count_crossings(self, parent: TorusArrangement) -> None:
        self.klass = klass = axis_classes(parent)
        for v in range(parent.crossings):
            k1, k2 = sorted((klass[parent.loop_of[4 * v]], klass[parent.loop_of[4 * v + 1]]))
            if k2 == THIRD:
                self.third_with[k1] += 1
            else:
                self.base_crossings += 1

    def _may_delete(self, a: TorusArrangement) -> list[int]:
        """The loops of ``a`` the canonical construction may delete."""
        if self.layered:
            return sorted(a.third_loops())
        adj = a.crossing_graph()
        return [lp for lp in range(a.num_loops) if connected_without(adj, lp)]

    def run(self) -> list[tuple[TorusArrangement, Facts]]:
        """The children, each once, ordered by code; the counts go to the statistics."""
        w = self.w
        # The curve starts at a point on a parent edge and enters the face on the left of that
        # edge.  In the first stage one dart an edge (a curve walked the other way round enters
        # the face on the twin's left, and it is the same loop), and the least edge the curve
        # crosses (self.least): every test on the way is a test of the whole curve, whichever
        # way and wherever it was begun, so each curve is still drawn.
        for y0 in range(len(w.rot)):
            if w.layer[y0] or (not self.layered and not self.every_start and w.twin[y0] < y0):
                continue
            snap = w.snapshot()
            t0 = w.twin[y0]
            p1, p2 = w.subdivide(y0)
            # A single loop: its point of degree 2 only marks where it is and may lie in any gap
            # between the curve's points; in the gap before the first (the piece from y0 to p2
            # is never crossed), so each curve is drawn once a start, not once a start and a gap.
            self.banned = {y0, p2} if self.root and not self.every_start else set()
            self.least = -1 if self.layered or self.every_start else y0
            if self.layered:  # the start edge's two pieces, which the curve does not cross again
                self.start_edge.update((y0, t0, p1, p2))
                self.visited.add(w.region[p1])
            self.met[w.loop[y0]] = 1
            self._extend(p1, p2, 1)
            self.visited.clear()
            self.start_edge.clear()
            self.met.clear()
            w.restore(snap)
        kids = [self.found[k] for k in sorted(self.found)]
        self.stats.states += len(kids)
        self.stats.targets += sum(f.target for _, f in kids)
        return kids

    def _unbalanced(self) -> bool:
        # B is the two-axis arrangement with fewest crossings: the third axis ends crossing
        # each class of B at least as often as B crosses itself.
        assert self.klass is not None
        with_class = list(self.third_with)
        for lp, k in self.met.items():
            with_class[self.klass[lp]] += k
        return self.base_crossings + sum(max(c, self.base_crossings) for c in with_class) > self.max_crossings

    def _hopeless(self, cr: int) -> bool:
        if self.layered and self._unbalanced():
            return True
        # A parent loop that stays deletable with fewer crossings than the curve makes the curve
        # not canonical, and the curve only grows.  In the first stage a loop stays deletable
        # when the curve meets another loop too; in the second every third-axis loop does.
        met = self.met
        crossed = len(met)
        return any((self.layered or crossed > (met.get(lp, 0) > 0)) and cr > c + met.get(lp, 0)
                   for lp, c in self.deletable)

    def _chords(self, x: int, y: int) -> Iterator[None]:
        """Draw the chord from x to y in each way the faces allow, yielding after each and
        restoring the drawing after each."""
        w = self.w
        face = w.face(x)
        i = w.mark_index(face)
        kind = w.marks[i][0] if i is not None else None
        if i is not None and kind not in (ANNULUS, HANDLE):
            yield from self._piece_chords(x, y, i)
            return
        snap = w.snapshot()
        if y not in set(face):  # across the annulus, from one end to the other
            assert kind == ANNULUS
            w.chord(x, y)
            w.marks = []
            yield
            w.restore(snap)
            return
        for option in {None: (None,), HANDLE: ("a", "b", "both"), ANNULUS: ("a", "b")}[kind]:
            a, b = w.chord(x, y)
            if option == "both":
                w.marks = [(ANNULUS, a), (ANNULUS, b)]
            elif option is not None:
                assert i is not None and kind is not None
                w.marks = list(w.marks)
                w.marks[i] = (kind, a if option == "a" else b)
            yield
            w.restore(snap)

    def _piece_chords(self, x: int, y: int, i: int) -> Iterator[None]:
        """:meth:`_chords` through a piece of genus ``h`` with ``b`` boundaries (mark ``i`` on
        the face of ``x``), on a surface of genus 2 or more.  Up to a homeomorphism of the piece
        that keeps its boundary, an arc is fixed by what cutting along it leaves: between two
        boundaries, one piece with one boundary fewer; from a boundary back to it, either one
        piece of genus ``h - 1`` with one boundary more (the arc does not separate), or two
        pieces, of genus ``h1`` and ``h - h1``, the new boundary on each side of the arc with a
        share of the other boundaries (a piece of genus 0 with one boundary is a disc)."""
        w = self.w
        snap = w.snapshot()
        h, piece = piece_of_mark(w.marks[i][0])
        mine = [k for k, (kind, _) in enumerate(w.marks) if piece_of_mark(kind)[1] == piece]
        rest = [m for k, m in enumerate(w.marks) if k not in mine]
        fresh = 1 + max(int(piece_of_mark(kind)[1]) for kind, _ in w.marks)
        if y not in set(w.face(x)):  # to another boundary of the piece: the two become one
            j = w.mark_index(w.face(y))
            a, _ = w.chord(x, y)
            kept = [m for k, m in enumerate(w.marks) if k in mine and k not in (i, j)]
            w.marks = rest + kept + ([(w.marks[i][0], a)] if h or kept else [])  # else now a disc
            yield
            w.restore(snap)
            return
        others = [k for k in mine if k != i]
        if h >= 1:  # not separating
            a, b = w.chord(x, y)
            kind = piece_mark(h - 1, fresh)
            w.marks = rest + [(kind, w.marks[k][1]) for k in others] + [(kind, a), (kind, b)]
            yield
            w.restore(snap)
        for h1 in range(h + 1):
            for mask in range(1 << len(others)):
                a, b = w.chord(x, y)
                sides = ([k for n, k in enumerate(others) if mask >> n & 1],
                         [k for n, k in enumerate(others) if not mask >> n & 1])
                marks = list(rest)
                for genus, new, side, name in ((h1, a, sides[0], fresh), (h - h1, b, sides[1], fresh + 1)):
                    if genus or side:  # else a disc
                        kind = piece_mark(genus, name)
                        marks += [(kind, w.marks[k][1]) for k in side] + [(kind, new)]
                w.marks = marks
                yield
                w.restore(snap)

    def _keep(self, child: TorusArrangement, curve: int) -> None:
        """Keep ``child`` when it can still grow into a target and its new loop (through dart
        ``curve``) is the canonical one to delete."""
        stats = self.stats
        facts = facts_of(child, self.regions, self.colours)
        if facts.bound > self.max_crossings:
            stats.over_bound += 1
            return
        if not facts.colourable:
            stats.not_colourable += 1
            return
        if self.layered and not orientable(child):
            stats.inconsistent_sides += 1
            return
        if self.layered and axis_runs(child, child.loop_of[curve]) < 4:
            stats.not_rectilinear += 1
            return
        lc = child.loop_crossings()
        may = self._may_delete(child)
        least = min(lc[lp] for lp in may)
        wanted = child.loop_of[curve]
        if lc[wanted] != least:
            stats.not_canonical += 1
            return
        code, accepted = canonical(child, wanted, frozenset(lp for lp in may if lc[lp] == least))
        if not accepted:
            stats.not_canonical += 1
            return
        self.found.setdefault(code, (TorusArrangement(child.twin, child.marks, child.layer, code), facts))

    def _extend(self, x: int, end: int, cr: int) -> None:
        """Continue the curve from the point of dart ``x`` into the face on its left; ``end`` is
        the starting point's dart on the other side, ``cr`` the crossings so far."""
        w, stats = self.w, self.stats
        if self._hopeless(cr):
            return
        later = (w.needs({x, end}, self.regions, self.klass) + 1) // 2  # what the closed faces still need
        if self.parent_crossings + cr + later > self.max_crossings:
            stats.over_bound += 1
            return
        face = w.face(x)
        i = w.mark_index(face)
        targets = list(face)
        if i is not None and w.marks[i][0] == ANNULUS:
            other = next(d for k, (_, d) in enumerate(w.marks) if k != i)
            targets += w.face(other)
        elif i is not None and w.marks[i][0] != HANDLE:  # the piece's other boundaries
            piece = piece_of_mark(w.marks[i][0])[1]
            for k, (kind, d) in enumerate(w.marks):
                if k != i and piece_of_mark(kind)[1] == piece:
                    targets += w.face(d)
        if end in targets:
            for _ in self._chords(x, end):
                stats.closed += 1
                self._keep(*finish_curve(w, self.layered))
        if cr >= self.budget or (self.layered and w.region[x] == w.region[end]):
            return  # (second stage: in the last region of B the curve only closes)
        for y in targets:
            lp = w.loop[y]
            if lp < 0 or w.layer[y] or y in self.start_edge or y in self.banned or w.edge[y] < self.least:
                continue  # the curve does not cross itself, nor (second stage) the third axis
            if self.layered:
                there = w.region[w.twin[y]]
                if there in self.visited or (there == w.region[end] and end not in w.face(w.twin[y])):
                    continue  # B's regions once each, the last one entered only to close
            snap = w.snapshot()
            q1, q2 = w.subdivide(y)
            self.met[lp] = self.met.get(lp, 0) + 1
            if self.layered:
                self.visited.add(w.region[q2])
            for _ in self._chords(x, q1):
                self._extend(q2, end, cr + 1)
            if self.layered:
                self.visited.discard(w.region[q2])
            self.met[lp] -= 1
            if not self.met[lp]:
                del self.met[lp]
            w.restore(snap)


def torus_children(parent: TorusArrangement | int, max_crossings: int, colours: int | None = None,
                   regions: bool = False, stats: TorusSearchStats | None = None, *,
                   every_start: bool = False, genus: int = 1) -> list[tuple[TorusArrangement, Facts]]:
    """The canonical children of ``parent`` that can still grow into a target with at most
    ``max_crossings`` crossings, each once, in a fixed order.

    ``parent`` is a state, or an int: the single loop, essential (0) or not (1); on a surface
    of ``genus`` 2 or more, the single loops of :func:`~polyloops.generate.torus.drawing.roots`
    (the first stage only; compiled through genus 4).  A parent
    with a ``layer`` is in the second stage: the new loop is of the third axis, crosses no loop
    of it and each region of ``B`` at most once.  ``colours`` keeps children whose crossing
    graph is that colourable; ``regions`` counts the crossings the faces need to become corners
    of a candidate map (3 to 6 sides, no two on one loop) in the bound.  ``every_start`` (the
    Python search, a twin for the tests) draws each curve of the first stage from every start,
    both ways round from every edge it crosses and round a single loop with the mark in every
    gap: the same children come out."""
    stats = stats if stats is not None else TorusSearchStats()
    layered = not isinstance(parent, int) and bool(parent.layer)
    if compiled_search_available() and not every_start:
        if layered and regions and colours is None:
            assert not isinstance(parent, int)
            return _compiled_children(parent, max_crossings, stats)
        if not layered and not regions and colours in (None, 2) and genus <= 4:
            return _compiled_first_children(parent, max_crossings, colours or 0, stats, genus)
    return _ChildSearch(parent, max_crossings, colours, regions, stats, every_start, genus).run()


def _compiled_children(parent: TorusArrangement, max_crossings: int, stats: TorusSearchStats
                       ) -> list[tuple[TorusArrangement, Facts]]:
    """:func:`torus_children` of a second-stage state, by the compiled search (one of each
    child, ordered by its code)."""
    out = []
    kids = _layered_children(twin_bytes(parent), bytes(parent.layer), max_crossings, stats)
    for (twin, layer), flags in kids:
        child = arrangement_of_twin(twin, layer)
        code = (twin + layer,)
        out.append((TorusArrangement(child.twin, (), child.layer, code), Facts(0, bool(flags & 1), True)))
    return out


def _layered_children(twin: bytes, layer: bytes, max_crossings: int, stats: TorusSearchStats
                      ) -> list[tuple[tuple[bytes, bytes], int]]:
    """The compiled second stage's children of one state, one of each, ordered by code, as
    ``((twin, layer), flags)``; its counts added to ``stats``."""
    found, counts = compiled.require("torus").children(twin, layer, max_crossings)
    _, closed, over, inconsistent, rejected, straight = counts
    stats.closed += closed
    stats.over_bound += over
    stats.inconsistent_sides += inconsistent
    stats.not_canonical += rejected
    stats.not_rectilinear += straight
    kids = sorted({(t, y): flags for t, y, flags in found}.items())
    stats.states += len(kids)
    stats.targets += sum(flags & 1 for _, flags in kids)
    return kids


def _compiled_first_children(parent: TorusArrangement | int, max_crossings: int, colours: int,
                             stats: TorusSearchStats, genus: int = 1) -> list[tuple[TorusArrangement, Facts]]:
    """:func:`torus_children` of a state of the marked search (no layer, no regions' bound), by
    the compiled search (one of each child, ordered by its code)."""
    _torus = compiled.require("torus")
    if isinstance(parent, int):
        found, counts = _torus.first_children(b"", parent, max_crossings, colours, genus)
    else:
        found, counts = _torus.first_children(twin_bytes(parent), list(parent.marks), max_crossings, colours,
                                              genus)
    _, closed, over, rejected, uncolourable = counts
    stats.closed += closed
    stats.over_bound += over
    stats.not_canonical += rejected
    stats.not_colourable += uncolourable
    kids: dict[tuple, tuple[TorusArrangement, Facts]] = {}
    for twin, marks, flags in found:
        key = (twin, tuple(marks))
        if key not in kids:
            child = TorusArrangement(arrangement_of_twin(twin).twin, tuple(marks), (), key)
            split = bool(flags & 2) if flags & 1 and colours == 2 else None
            kids[key] = (child, Facts(0, bool(flags & 1), True, split))
    out = [kids[k] for k in sorted(kids)]
    stats.states += len(out)
    stats.targets += sum(f.target for _, f in out)
    return out


def torus_arrangements(max_crossings: int, colours: int | None = None, regions: bool = False,
                       on_stats: Callable[[TorusSearchStats], None] | None = None, genus: int = 1
                       ) -> Iterator[TorusArrangement]:
    """Every cellular arrangement of simple loops on the torus (the surface of ``genus``) with at
    most ``max_crossings`` crossings and a crossing graph that ``colours`` colours colour, once
    up to homeomorphism, mirror images identified; with ``regions``, only the candidate maps
    (regions of 3 to 6 sides, none with two sides on one loop or on both sides of an edge, a
    simple quad mesh)."""
    for a, _ in _targets(max_crossings, colours, regions, on_stats, genus):
        yield a


def _targets(max_crossings: int, colours: int | None, regions: bool,
             on_stats: Callable[[TorusSearchStats], None] | None, genus: int = 1
             ) -> Iterator[tuple[TorusArrangement, Facts]]:
    """:func:`torus_arrangements` with what the search knows of each."""
    stats = TorusSearchStats()
    stack: list[tuple[TorusArrangement, Facts] | int] = list(reversed(range(len(roots(genus)))))
    while stack:
        node = stack.pop()
        parent = node if isinstance(node, int) else node[0]
        if not isinstance(node, int) and node[1].target:
            yield node
        stack.extend(reversed(torus_children(parent, max_crossings, colours, regions, stats, genus=genus)))
    if on_stats:
        on_stats(stats)


def two_axis_bases(max_crossings: int, on_stats: Callable[[TorusSearchStats], None] | None = None,
                   genus: int = 1) -> Iterator[TorusArrangement]:
    """Every cellular arrangement with a bipartite crossing graph and at most ``max_crossings``
    crossings whose loops each have two different zones on their sides: the arrangements ``B``
    of the second stage."""
    for a, facts in _targets(max_crossings, 2, False, on_stats, genus):
        split = facts.split  # the compiled search tells; the Python one leaves it to the test here
        if split is None:
            split = zones_split_every_loop(a)
        if split:
            yield a


@lru_cache(maxsize=4)
def _bases(max_crossings: int, compiled: bool, genus: int, res: int = 0, mod: int = 1,
           ) -> tuple[tuple[bytes, ...], TorusSearchStats]:
    """:func:`share_of_first_stage` (each ``B`` as its ``twin`` array of uint16, compactly:
    2,755,639 through 16 crossings on the torus), kept for the process's later calls.
    ``compiled`` only keys the cache: the part in use lists the same ``B``."""
    from polyloops.generate.torus.squares import square_bases

    stats = TorusSearchStats()
    listed: list[bytes] = []
    for n in range(1, max_crossings + 1):
        twins, counts = square_bases(n, genus, res, mod)
        listed.extend(twins)
        stats.add(TorusSearchStats(closed=counts.leaves, not_canonical=counts.not_canonical,
                                   states=counts.nodes, targets=counts.kept))
    return tuple(listed), stats


def first_stage(max_crossings: int, genus: int = 1) -> tuple[tuple[bytes, ...], TorusSearchStats]:
    """The arrangements ``B`` of :func:`two_axis_bases` on the surface of ``genus`` with at most
    ``max_crossings`` crossings, by crossings, each as its ``twin`` array of uint16 (bytes), and
    the search's statistics (``states``: its nodes, ``closed``: its closed surfaces,
    ``targets``: the ``B``); kept for the process's later calls (:func:`forget_first_stage` drops
    them).  They are listed directly as square-tiled surfaces
    (:func:`~polyloops.generate.torus.squares.square_bases`), not by the marked search of
    :func:`two_axis_bases`, which lists the same arrangements (tested) far more slowly."""
    return _bases(max_crossings, compiled.in_use("squares"), genus)


def share_of_first_stage(max_crossings: int, genus: int, res: int, mod: int
                         ) -> tuple[tuple[bytes, ...], TorusSearchStats]:
    """Share ``res`` of ``mod`` of :func:`first_stage`: the ``B`` of the listing's subtrees dealt
    to it (:func:`~polyloops.generate.torus.squares.square_bases`; the shares together list
    every ``B`` once), and the share's statistics (the listing above the split is walked by
    every share and counted in each)."""
    return _bases(max_crossings, compiled.in_use("squares"), genus, res, mod)


def forget_first_stage() -> None:
    """Drop the first stages :func:`first_stage` and :func:`share_of_first_stage` kept."""
    _bases.cache_clear()


def second_stage(base: TorusArrangement, max_crossings: int, stats: TorusSearchStats
                 ) -> Iterator[TorusArrangement]:
    """The second stage from ``base`` loop by loop: every target state in which ``B`` has the
    fewest crossings of the three two-axis arrangements and no loop of ``B`` lacks third-axis
    crossings (the others are no decomposition of their map); by the compiled search when it
    runs (the same targets, in another order)."""
    if compiled_search_available():
        yield from _second_stage_compiled(base, max_crossings, stats)
        return
    stack = [TorusArrangement(base.twin, (), (0,) * len(base.twin))]
    while stack:
        kids = torus_children(stack.pop(), max_crossings, None, True, stats)
        for kid, facts in kids:
            if facts.target and balanced(kid, base.crossings) and deficit(kid, axis_classes(kid)) == 0:
                yield kid
        stack.extend(kid for kid, _ in reversed(kids))


def _second_stage_compiled(base: TorusArrangement, max_crossings: int, stats: TorusSearchStats
                           ) -> Iterator[TorusArrangement]:
    stack = [(twin_bytes(base), bytes(len(base.twin)))]
    while stack:
        kids = _layered_children(*stack.pop(), max_crossings, stats)
        for (twin, layer), flags in kids:
            if flags == 7:  # a target, balanced, no loop of B lacking (else not a decomposition)
                yield arrangement_of_twin(twin, layer)
        stack.extend(key for key, _ in reversed(kids))
