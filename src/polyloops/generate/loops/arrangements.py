"""Candidate maps without plantri: arrangements of loops, built one loop at a time.

The dual of a quad mesh is an *arrangement*: a 4-regular map on the sphere whose crossings are
the quads, whose regions are the corners and whose straight-ahead walks are the loops.  A
genus-0 polycube's arrangement has simple loops, regions of 3 to 6 sides, and a simple quad
mesh (no region on both sides of an edge, no two regions sharing two edges): these *candidate
maps* are what the catalog's per-map work needs, and exactly the maps plantri's filter keeps.

This module generates them directly, by McKay's canonical construction path.  A connected
arrangement with at least two loops has a loop whose deletion leaves it connected (a non-cut
vertex of the graph of crossing loops), so every candidate map is reached from the single
loop by adding simple closed curves.  A child is kept only when its new loop is its
*canonical loop to delete* (among loops whose deletion leaves it connected, those with the
fewest crossings, and of these the one met first in the canonical numbering), so each
arrangement is built once, from one parent, and the search is a tree that splits into
independent subtrees (``res``/``mod``).  Deleting a loop keeps loops simple but not region
sizes, so intermediate arrangements have bigons and large regions; a counting bound prunes
those that cannot grow into a candidate within the corner budget (``docs/searches.md`` proves
it).  Arrangements whose graph of crossing loops is not 3-colourable carry no polycube, nor
does anything built from them, so they are not built either (cut 4, :attr:`Cuts.colour`); and no
corner of a genus-0 polycube meets a strip twice, so a region with several sides on one loop
must still be cut into pieces, which joins the counting bound, and a candidate map has no such
region (cut 5, :attr:`Cuts.meet`).  The search itself is the compiled extension ``_arrangements``.

>>> from collections import Counter
>>> sorted(Counter(a.corners for a in candidate_arrangements(16)).items())
[(8, 1), (12, 1), (16, 2)]
>>> cube = next(candidate_arrangements(8))
>>> cube.crossings, cube.quad_mesh().num_corners
(6, 8)
"""

from __future__ import annotations

import array
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import asdict, astuple, dataclass, field, fields
from functools import cached_property

from polyloops.core import compiled
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import HalfEdgeMap, permutation_orbits


class ArrangementError(PolyloopsError, ValueError):
    """Arrays that are not an arrangement of simple loops, or a generator that cannot run."""


@dataclass(frozen=True)
class Cuts:
    """The cuts of the search that can be switched off (``docs/searches.md``).  The catalog's
    records are the same with any of them; without them the search builds more arrangements
    and classifies more candidate maps (the tests compare every setting with plantri)."""

    # Cut 4: arrangements whose crossing graph is not 3-colourable carry no polycube, nor does
    # any arrangement built from them; they are not built.  The candidate maps are then those of
    # plantri's filter whose crossing graph is 3-colourable.
    colour: bool = True
    # Cut 5: no corner of a genus-0 polycube meets a strip twice, so a region with k sides on one
    # loop must still be cut into k pieces; this joins cut 1's bound, and a candidate map has no
    # region with two sides on one loop.  Off, the candidate maps are cut 4's alone.
    meet: bool = True


ALL_CUTS = Cuts()


def compiled_generator_available() -> bool:
    """Whether the compiled arrangement search runs: built (it needs a C compiler) and not
    switched off (:mod:`polyloops.core.compiled`)."""
    return compiled.in_use("arrangements")


def _module():
    part = compiled.load("arrangements")
    if part is None:
        raise ArrangementError(f"the compiled arrangement search {compiled.why_not('arrangements')}; "
                               "the plantri generator makes the same catalog without it")
    return part


def _pack(values: tuple[int, ...] | list[int]) -> bytes:
    return array.array("H", values).tobytes()


def _unpack(data: bytes) -> tuple[int, ...]:
    return tuple(array.array("H", data))


@dataclass(frozen=True)
class Arrangement:
    """A canonical arrangement: its darts numbered four a crossing, counter-clockwise, so that
    ``rot(d) = 4 (d // 4) + (d + 1) % 4``; ``twin`` pairs the two darts of each edge.  ``code``
    is ``twin`` as unsigned 16-bit numbers (the identity of the arrangement: equal codes,
    isomorphic arrangements).

    >>> from polyloops.io.examples import load_example
    >>> a = Arrangement.of(load_example("cube").map)
    >>> a.crossings, a.corners, sorted(a.region_sizes())
    (6, 8, [3, 3, 3, 3, 3, 3, 3, 3])
    >>> [len(loop) for loop in a.loops()]
    [4, 4, 4]
    """

    code: bytes
    candidate: bool = field(default=False, compare=False)

    @classmethod
    def of(cls, m: HalfEdgeMap, cuts: Cuts = ALL_CUTS) -> Arrangement:
        """The canonical arrangement dual to a quad mesh (the same darts: a quad's darts turn
        around its crossing, and ``twin`` crosses an edge; whether it is a candidate map
        depends on ``cuts``).  Raises
        :class:`ArrangementError` unless every face is a quad and every loop is simple."""
        if any(len(f) != 4 for f in m.faces):
            raise ArrangementError("not a quad mesh: a face is not a quad")
        try:
            code, candidate = _module().canonical(_pack(m.next), _pack(m.twin), cuts.meet)
        except ValueError as err:
            raise ArrangementError(str(err)) from None
        return cls(code, bool(candidate))

    @cached_property
    def twin(self) -> tuple[int, ...]:
        """Per dart, the other dart of its edge."""
        return _unpack(self.code)

    @property
    def crossings(self) -> int:
        """The number of crossings (the quads)."""
        return len(self.code) // 8

    @property
    def corners(self) -> int:
        """The number of regions (the corners of the quad mesh): crossings + 2, by Euler."""
        return self.crossings + 2

    @cached_property
    def rot(self) -> tuple[int, ...]:
        """Per dart, the next dart counter-clockwise around its crossing."""
        return tuple(4 * (d // 4) + (d + 1) % 4 for d in range(len(self.twin)))

    @cached_property
    def _regions(self) -> list[list[int]]:
        # The region on the left of d continues with the dart before twin(d) at its crossing.
        irot = [4 * (d // 4) + (d + 3) % 4 for d in range(len(self.twin))]
        return permutation_orbits([irot[t] for t in self.twin])

    def region_sizes(self) -> list[int]:
        """The number of sides of each region."""
        return [len(r) for r in self._regions]

    def loops(self) -> list[list[int]]:
        """Each loop as the crossings it passes, in order."""
        return [[d // 4 for d in darts[::2]] for darts in self.loop_darts()]

    def loop_darts(self) -> list[list[int]]:
        """Each loop's darts, along it: each dart followed by its twin (the way back)."""
        rot, twin = self.rot, self.twin
        seen: set[int] = set()
        out = []
        for d in range(len(twin)):
            if d in seen:
                continue
            darts: list[int] = []
            e = d
            while e not in seen:
                seen.update((e, twin[e]))
                darts.extend((e, twin[e]))
                e = rot[rot[twin[e]]]
            out.append(darts)
        return out

    def without_loop(self, i: int, cuts: Cuts = ALL_CUTS) -> Arrangement:
        """The arrangement with loop ``i`` (in the order of :meth:`loops`) deleted, in canonical
        form (its candidacy under ``cuts``); the other loops run straight through its crossings.  Raises
        :class:`ArrangementError` when what is left is not connected (or is a single loop,
        which has no crossing).

        >>> from polyloops.io.examples import load_example
        >>> cube = Arrangement.of(load_example("cube").map)
        >>> [len(loop) for loop in cube.without_loop(0).loops()]
        [2, 2]
        """
        loops = self.loops()
        if not 0 <= i < len(loops):
            raise ArrangementError(f"no loop {i}: the arrangement has {len(loops)}")
        gone = set(loops[i])
        rot, twin = self.rot, self.twin
        keep = [d for d in range(len(twin)) if d // 4 not in gone]
        if not keep:
            raise ArrangementError("deleting that loop leaves a single loop without crossings")
        index = {d: k for k, d in enumerate(keep)}

        def through(t: int) -> int:
            while t // 4 in gone:  # straight on through a deleted crossing
                t = twin[rot[rot[t]]]
            return t

        new_rot = [index[rot[d]] for d in keep]
        new_twin = [index[through(twin[d])] for d in keep]
        try:
            code, candidate = _module().canonical(_pack(new_rot), _pack(new_twin), cuts.meet)
        except ValueError as err:
            raise ArrangementError(f"deleting loop {i}: {err}") from None
        out = Arrangement(code, bool(candidate))
        if len(out.loops()) != len(loops) - 1:  # a loop that crossed only loop i
            raise ArrangementError(f"deleting loop {i} leaves a loop without crossings")
        return out

    def quad_mesh(self) -> HalfEdgeMap:
        """The dual quad mesh: one quad a crossing, one corner a region."""
        region = {}
        for i, r in enumerate(self._regions):
            for d in r:
                region[d] = i
        # The corner where dart d starts is the region in the angle before d.
        before = [4 * (d // 4) + (d + 3) % 4 for d in range(len(self.twin))]
        return HalfEdgeMap.from_faces([[region[before[d]] for d in range(4 * v, 4 * v + 4)]
                                       for v in range(self.crossings)])


@dataclass(frozen=True)
class SearchStats:
    """What a search did: curves drawn (partial paths), closed curves, closed curves over the
    bound, closed curves that were not the canonical loop to delete, arrangements kept (the
    objects visited), candidate maps among them, closed curves whose arrangement cut 4
    dropped (a crossing graph that is not 3-colourable), and those over cut 5's bound (regions
    with several sides on one loop)."""

    curves: int = 0
    closed: int = 0
    over_bound: int = 0
    not_canonical: int = 0
    arrangements: int = 0
    candidates: int = 0
    not_colourable: int = 0  # closed curves cut 4 dropped (crossing graph not 3-colourable)
    meets_loop_twice: int = 0  # closed curves over cut 5's bound (a region meets a loop twice)

    def __add__(self, other: SearchStats) -> SearchStats:
        return SearchStats(*(a + b for a, b in zip(astuple(self), astuple(other), strict=True)))

    def as_dict(self) -> dict[str, int]:
        """The counts by name (as ``summary.json`` stores them; ``SearchStats(**d)`` reads them)."""
        return asdict(self)


SINGLE_LOOP = (_pack([1, 0]), _pack([1, 0]))  # one loop, one marker vertex on it

IMPLICIT = b""  # a canonical arrangement's rotation, which the search works out itself


def _children(parent: Arrangement | None, max_corners: int, cuts: Cuts
              ) -> tuple[list[Arrangement], tuple[int, ...]]:
    rot, twin = SINGLE_LOOP if parent is None else (IMPLICIT, parent.code)
    found, counts = _module().children(rot, twin, max_corners - 2, cuts.colour, cuts.meet)
    curves, closed, over, rejected, uncolourable, met_twice = counts
    kids, seen = [], set()
    for code, candidate in found:
        if code not in seen:
            seen.add(code)
            kids.append(Arrangement(code, bool(candidate)))
    return kids, (curves, closed, over, rejected, len(kids), sum(k.candidate for k in kids), uncolourable,
                  met_twice)


def children(parent: Arrangement | None, max_corners: int, cuts: Cuts = ALL_CUTS
             ) -> tuple[list[Arrangement], SearchStats]:
    """The canonical children of ``parent`` (``None``: the single loop) that can still grow
    into a candidate map with at most ``max_corners`` corners, each once, in a fixed order."""
    kids, stats = _children(parent, max_corners, cuts)
    return kids, SearchStats(*stats)


@dataclass(frozen=True)
class Frontier:
    """Where a search splits: the arrangements with ``loops`` loops that can still grow (the roots
    of independent subtrees, in a fixed order) and the candidate maps with fewer loops."""

    loops: int
    roots: tuple[Arrangement, ...]
    shallow: tuple[Arrangement, ...]


# With cuts 4 and 5 the candidates gather below few arrangements of three to five loops (at 30
# corners every one below a single root of three loops, and of four); below seven loops they
# spread evenly over the shares (at 30 corners 8,516 roots, 9 to 49 candidates in each of 16
# shares); the top then costs 6.1 s at 32 corners (0.2 s to three loops), the shares minutes.
SPLIT_LOOPS = 7

Expander = Callable[[list["Arrangement | None"], int, Cuts],
                    Iterable[tuple[list["Arrangement"], "SearchStats"]]]


def expand(nodes: list[Arrangement | None], max_corners: int, cuts: Cuts = ALL_CUTS
           ) -> list[tuple[list[Arrangement], SearchStats]]:
    """The children of each node, in order (``None`` is the single loop)."""
    return [children(node, max_corners, cuts) for node in nodes]


def frontier(max_corners: int, loops: int = SPLIT_LOOPS,
             on_stats: Callable[[SearchStats], None] | None = None,
             expander: Expander = expand, cuts: Cuts = ALL_CUTS,
             roots_to: Callable[[list[Arrangement]], None] | None = None,
             slice_size: int | None = None) -> Frontier:
    """The top of the search tree, down to the arrangements with ``loops`` loops: the roots of
    the subtrees that shares of a split search take (see :data:`SPLIT_LOOPS`).  Its first two
    levels (the second and third loops, drawn with the whole budget) are most of the top's
    cost; ``expander`` may spread each level over workers (it must yield :func:`expand`'s
    answer, in order).  With ``roots_to``, the roots are handed to it as they come, in order,
    and not kept (the returned frontier has none), and the top is walked depth first, at most
    ``slice_size`` (:data:`STREAM_SLICE`) arrangements of a level expanded at once: no level
    ever sits in memory whole, and the roots and candidates come in the same order as level by
    level (a level is, in order, the children of each node of the level above)."""
    levels: list[list[Arrangement]] = [[] for _ in range(loops - 1)]  # candidates per level

    def children(nodes: Sequence[Arrangement | None]) -> Iterator[list[Arrangement]]:
        for kids, stats in expander(list(nodes), max_corners, cuts):
            if on_stats:
                on_stats(stats)
            yield kids

    if roots_to is None:
        level: list[Arrangement | None] = [None]
        for depth in range(loops - 1):
            nxt = [kid for kids in children(level) for kid in kids]
            levels[depth] = [node for node in level if node is not None and node.candidate]
            level = list(nxt)
        return Frontier(loops, tuple(node for node in level if node is not None),
                        tuple(node for lv in levels for node in lv))
    out, step = roots_to, slice_size or STREAM_SLICE

    def walk(nodes: Sequence[Arrangement | None], depth: int) -> None:
        for i in range(0, len(nodes), step):
            part = nodes[i:i + step]
            levels[depth].extend(node for node in part if node is not None and node.candidate)
            if depth == loops - 2:
                for kids in children(part):
                    out(kids)
            else:
                walk([kid for kids in children(part) for kid in kids], depth + 1)

    walk([None], 0)
    return Frontier(loops, (), tuple(node for lv in levels for node in lv))


STREAM_SLICE = 20_000  # arrangements of a level expanded at once when the top is streamed


def candidate_arrangements(max_corners: int, res: int = 0, mod: int = 1,
                           on_stats: Callable[[SearchStats], None] | None = None,
                           top: Frontier | None = None, cuts: Cuts = ALL_CUTS) -> Iterator[Arrangement]:
    """Every candidate map with at most ``max_corners`` corners, once up to isomorphism (mirror
    images identified), as its arrangement.  ``res``/``mod`` keeps the subtrees below the
    :func:`frontier` (``top``, computed when not given) whose rank is ``res`` modulo ``mod``;
    candidates above it belong to share 0.  ``on_stats`` sees the statistics of the search,
    one subtree at a time (and those of the frontier when this call computes it and ``res``
    is 0, so that the shares of a split search add up to one search).  ``cuts``: the cuts the
    search makes (a given ``top`` must have been computed with the same)."""
    if not 0 <= res < mod:
        raise ArrangementError("res/mod needs 0 <= res < mod")
    if top is None:
        top = frontier(max_corners, on_stats=on_stats if res == 0 else None, cuts=cuts)
    if res == 0:
        yield from top.shallow
    for rank, root in enumerate(top.roots):
        if rank % mod != res:
            continue
        stack, total = [root], [0] * len(fields(SearchStats))
        while stack:
            node = stack.pop()
            if node.candidate:
                yield node
            kids, stats = _children(node, max_corners, cuts)
            for i, v in enumerate(stats):
                total[i] += v
            stack.extend(reversed(kids))
        if on_stats:  # once a subtree
            on_stats(SearchStats(*total))
