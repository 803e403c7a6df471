"""Loop moves (Section 4 of the paper): every valid loop addition and removal.

**Addition.**  A new Delta-loop runs along a simple cycle ``C`` of corners (length >= 3),
walked in one direction; its ``+`` side is on the right.  It crosses the loop segments of
``C`` (the paper's edge-graph ``G_L`` has an arc between two segments that bound the same
region, so a cycle of segments through distinct regions is a cycle of corners).  Each
corner ``v`` of ``C`` splits into ``v-`` (left) and ``v+`` (right) joined by a new ``+Delta``
edge; each edge of ``C`` is doubled, with a new quad between the copies.  The split of a
region is valid (an arc of ``G_V^Delta``) exactly when neither edge of ``C`` at ``v`` has
axis Delta, an existing ``+Delta`` edge at ``v`` lies on the right and an existing
``-Delta`` edge on the left.  The paper proves that an addition never creates a cycle in a
level graph, so these local tests decide validity; the tests check that claim.

**Removal.**  Removing a Delta-loop contracts its rungs (the edges it crosses), merging each
rung's two ends, and deletes its faces; the two edges along each deleted face become one.
It is valid when every merged corner is a region of degree >= 3 with distinct directions
that is still a disk (the rungs merging it form a tree, and no face or edge meets it twice),
and the Delta-graph with the loop's arc contracted has no cycle through the merged zone
(one depth-first search from it).

Numbering.  After an addition, corner ``v`` of ``C`` keeps its id as ``v-``, and ``v+`` gets
id ``n + i`` for the ``i``-th corner of the walk (``n`` = old number of corners); old faces
keep their index and the new quads follow in walk order.  After a removal, each merged
group of corners takes the lowest id among them, faces of the loop are dropped, and ids of
corners and faces are then renumbered consecutively in their old order.

>>> from polyloops.io.examples import load_example
>>> cube = load_example("cube").dualize()
>>> sorted(count_additions(cube).items())
[('X', 2), ('Y', 2), ('Z', 2)]
>>> [removable(cube, lp.id) for lp in cube.loops]
[False, False, False]
"""

from __future__ import annotations

import math
import random
from collections import defaultdict
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass
from functools import cached_property
from itertools import chain, islice

from polyloops.core import compiled, removal_arrays
from polyloops.core.arrays import use_arrays
from polyloops.core.directions import Axis, Direction
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.errors import PolyloopsError
from polyloops.core.structure import LabelError, LoopStructure
from polyloops.core.zones import LevelArcs, closes_cycle, level_arcs_of

# -- additions -------------------------------------------------------------------------------


@dataclass(frozen=True)
class Addition:
    """A loop to add: its axis and the corners it walks past (its ``+`` side on the right)."""

    axis: Axis
    cycle: tuple[int, ...]

    def segments(self, ls: LoopStructure) -> list[int]:
        """The loop segments (edge ids) it crosses, in walk order."""
        m = ls.map
        k = len(self.cycle)
        return [m.edge_id(m.dart(self.cycle[i], self.cycle[(i + 1) % k])) for i in range(k)]

    def to_json(self, ls: LoopStructure) -> dict[str, object]:
        """A JSON-ready dict: the axis, the cycle of corners and the segments the new loop crosses."""
        return {"axis": str(self.axis), "corners": list(self.cycle), "segments": self.segments(ls)}


def _split_ok(ls: LoopStructure, axis: Axis, back: int, forward: int) -> bool:
    """The region at the common origin of darts ``back`` and ``forward`` may be split by a
    new ``axis``-loop that enters along ``back`` reversed and leaves along ``forward``."""
    if back == forward:
        return False
    if ls.axis_of_dart(back) == axis or ls.axis_of_dart(forward) == axis:
        return False
    m = ls.map
    plus, minus = Direction.of(axis, 1), Direction.of(axis, -1)
    # Walking in along `back` and out along `forward`, the left side is CCW from forward to back.
    d = m.rotate(forward)
    on_left = set()
    while d != back:
        on_left.add(ls.direction(d))
        d = m.rotate(d)
    if plus in on_left:
        return False
    has_minus = any(ls.direction(x) == minus for x in m.outgoing(m.origin(forward)))
    return not has_minus or minus in on_left


class _Successors(dict):
    """``dart -> darts that may leave after arriving along it``, filled on first use; darts of
    the new loop's own axis are not in it."""

    def __init__(self, ls: LoopStructure, axis: Axis):
        super().__init__()
        self.ls, self.axis = ls, axis

    def __contains__(self, d: object) -> bool:
        return isinstance(d, int) and 0 <= d < self.ls.map.num_darts and self.ls.axis_of_dart(d) != self.axis

    def __missing__(self, d: int) -> list[int]:
        if d not in self:
            raise KeyError(d)
        m = self.ls.map
        back = m.twin[d]
        out = [f for f in m.outgoing(m.target(d)) if _split_ok(self.ls, self.axis, back, f)]
        self[d] = out
        return out

    def get(self, d, default=None):
        try:
            return self[d]  # fills the entry (dict.get would not)
        except KeyError:
            return default


class _AdditionGraph:
    """``G_V^Delta`` on darts: from the dart that arrived at a corner to the darts that may leave."""

    def __init__(self, ls: LoopStructure, axis: Axis):
        self.ls, self.axis = ls, axis
        # Built as the search reaches each dart, so that a first answer costs only what the
        # search visits (the whole graph is built only for ``pred``).
        self.succ = _Successors(ls, axis)

    @cached_property
    def pred(self) -> dict[int, list[int]]:
        """The reverse of ``succ``: the darts that may arrive before leaving along a dart."""
        pred: dict[int, list[int]] = defaultdict(list)
        for d in range(self.ls.map.num_darts):
            if d in self.succ:
                for e in self.succ[d]:
                    pred[e].append(d)
        return pred

    def ok(self, arrive: int, leave: int) -> bool:
        return arrive in self.succ and leave in self.succ[arrive]

    def cycles(self, max_length: int | None = None, stop: Callable[[], bool] | None = None,
               starts: Iterable[int] | None = None) -> Iterator[tuple[int, ...]]:
        """Every simple cycle of corners (each once, walked in its direction), as corners,
        starting at its lowest corner; with ``max_length``, only those of at most that many
        corners.  A bounded search also skips every step from which the walk cannot get back
        to its start within the bound (a breadth-first search per start gives the distance
        back, ignoring simplicity: a lower bound), so it costs little more than the cycles it
        finds.  ``stop()`` is asked now and then; when it says so, :class:`SearchStopped` is
        raised.  ``starts``: only the cycles whose lowest corner is one of these (in
        increasing order)."""
        m = self.ls.map
        limit = m.num_corners if max_length is None else max_length
        if limit < 3:
            return
        ticks = [0]
        for start in (range(m.num_corners) if starts is None else starts):
            firsts = [d for d in m.outgoing(start)
                      if self.ls.axis_of_dart(d) != self.axis and m.target(d) > start]
            if not firsts:
                continue
            back = self._distances_back(start, limit) if max_length is not None else None
            for first in firsts:
                if back is not None and 1 + back.get(first, limit + 1) > limit:
                    continue
                yield from self._extend(start, first, limit, back, stop, ticks)

    def _distances_back(self, start: int, limit: int) -> dict[int, int]:
        """For darts between corners above ``start``: the fewest darts, this one excluded, that
        lead back to ``start`` (at most ``limit``)."""
        m = self.ls.map
        pred = self.pred
        closing = (m.twin[d] for d in m.outgoing(start))
        dist = {d: 1 for d in closing if d in self.succ and m.origin(d) > start}
        frontier = list(dist)
        while frontier and min(dist[d] for d in frontier) < limit:
            nxt_frontier = []
            for e in frontier:
                for d in pred.get(e, ()):
                    if d not in dist and m.origin(d) >= start and m.target(d) > start:
                        dist[d] = dist[e] + 1
                        nxt_frontier.append(d)
            frontier = nxt_frontier
        return {d: k - 1 for d, k in dist.items()}  # darts after d, the closing one included

    def _extend(self, start: int, first: int, limit: int, back: dict[int, int] | None,
                stop: Callable[[], bool] | None, ticks: list[int]) -> Iterator[tuple[int, ...]]:
        """The cycles from ``start`` that begin with dart ``first``, depth first.

        A walk can wall itself off from ``start`` (on a surface numbered without locality, the
        corners above ``start`` lie everywhere, and a depth-first walk wanders), and then
        everything below it is fruitless: exponentially many walks, none closing.  So after
        every ``num_darts`` steps the search works out which darts can still get back to
        ``start`` avoiding the walk's corners (:meth:`_can_return`), and steps only onto those
        until the walk is shorter than it was then.  That only cuts walks that cannot close, so
        the cycles and their order are the same (a test compares the two searches)."""
        m = self.ls.map
        path = [first]
        on_path = {start, m.target(first)}
        stack = [iter(self.succ[first])]
        far = limit + 1
        returning: set[int] | None = None  # darts that can get back, for walks of the path
        returning_depth = 0                # extending the path as it was this long
        steps, every = 0, PRUNE_EVERY if PRUNE_EVERY is not None else m.num_darts
        while stack:
            if stop is not None:
                ticks[0] += 1
                if ticks[0] % 4096 == 0 and stop():
                    raise SearchStopped
            steps += 1
            if steps >= every and returning is None:
                steps = 0
                # Back up to the deepest walk that can still close (a walk that can close
                # shortened by a step still can: walk on along it), then step only where the
                # way back stays open.
                keep = self._deepest_open(start, first, path)
                while len(path) > keep:
                    stack.pop()
                    on_path.discard(m.target(path.pop()))
                if not path:
                    return
                returning, returning_depth = self._can_return(start, first, on_path), len(path)
            nxt = next(stack[-1], None)
            if nxt is None:
                stack.pop()
                on_path.discard(m.target(path.pop()))
                if len(path) < returning_depth:
                    returning = None  # the walk is shorter: the set may have grown
                continue
            w = m.target(nxt)
            if w == start:
                if len(path) >= 2 and self.ok(nxt, first):
                    yield (start, *(m.target(d) for d in path))
                continue
            if w < start or w in on_path or len(path) + 2 > limit:
                continue
            if back is not None and len(path) + 1 + back.get(nxt, far) > limit:
                continue
            if returning is not None and nxt not in returning:
                continue
            path.append(nxt)
            on_path.add(w)
            stack.append(iter(self.succ[nxt]))

    def _deepest_open(self, start: int, first: int, path: list[int]) -> int:
        """The largest ``j`` such that ``path[j - 1]`` can get back to ``start`` avoiding the
        corners the walk reached before it (0 when not even ``first`` can), by bisection: if
        the walk of ``j`` darts can close, so can the walk of fewer."""
        m = self.ls.map

        def open_(j: int) -> bool:
            avoid = {m.target(d) for d in path[:j - 1]}
            return path[j - 1] in self._can_return(start, first, avoid)

        low, high = 0, len(path)  # open_(low) holds (for 0, trivially); find the last that does
        while low < high:
            mid = (low + high + 1) // 2
            if open_(mid):
                low = mid
            else:
                high = mid - 1
        return low

    def _can_return(self, start: int, first: int, avoid: set[int]) -> set[int]:
        """The darts from which a walk can reach ``start`` through corners above it and not in
        ``avoid``, arriving so that it may leave along ``first`` (turns as the graph allows,
        corners possibly repeated: a superset of the darts that begin a simple way back)."""
        m = self.ls.map
        pred = self.pred
        seen = {e for e in (m.twin[d] for d in m.outgoing(start))
                if m.origin(e) > start and m.origin(e) not in avoid and self.ok(e, first)}
        frontier = list(seen)
        while frontier:
            e = frontier.pop()
            for d in pred.get(e, ()):
                t = m.target(d)
                if d not in seen and t > start and t not in avoid:
                    seen.add(d)
                    frontier.append(d)
        return seen


PRUNE_EVERY: int | None = None  # steps between prunes; None: the map's darts (tests set 1)


class SearchStopped(PolyloopsError):
    """A cycle search was told to stop (a time limit); what it found so far stands."""


def separates_zone(ls: LoopStructure, move: Addition) -> bool:
    """Whether the new loop cuts its ``axis``-zone in two (so its arc is not a self-loop).

    The cycle's edges have other axes, so its corners lie in one zone ``Z``.  After the
    addition, two corners are in one zone when edges of other axes join them; the new loop's
    rungs have its own axis.  So ``Z`` stays connected exactly when ``v-`` and ``v+`` of a
    corner of the cycle are still joined: a union-find over the zone's edges with each edge at
    a cycle corner attached to the copy on its side.  A zone of genus 0 is a planar surface,
    where every simple closed curve separates (Jordan), so only zones with a handle are
    searched.
    """
    m = ls.map
    cyc = move.cycle
    zones = ls.zones(move.axis)
    zone = zones.zone_of[cyc[0]]
    if zones.genera[zone] == 0:
        return True
    k = len(cyc)
    darts = [m.dart(cyc[i], cyc[(i + 1) % k]) for i in range(k)]
    plus_id = {v: m.num_corners + i for i, v in enumerate(cyc)}
    # The copy of its origin that each dart leaves from, for darts at cycle corners.
    copy: dict[int, int] = {}
    for i, v in enumerate(cyc):
        forward, back = darts[i], m.twin[darts[i - 1]]
        d = m.rotate(back)
        while d != forward:  # strictly between back and forward (CCW): the right side
            copy[d] = plus_id[v]
            d = m.rotate(d)
    parts: DisjointSets[int] = DisjointSets()
    for c in range(m.num_corners):
        if zones.zone_of[c] != zone:
            continue
        for d in m.outgoing(c):
            if ls.axis_of_dart(d) == move.axis or d in darts or m.twin[d] in darts:
                continue
            parts.union(copy.get(d, c), copy.get(m.twin[d], m.target(d)))
    for i in range(k):  # each edge of the cycle is doubled: one copy per side
        u, w = cyc[i], cyc[(i + 1) % k]
        parts.union(u, w)
        parts.union(plus_id[u], plus_id[w])
    return parts.find(cyc[0]) != parts.find(plus_id[cyc[0]])


def additions(ls: LoopStructure, axis: Axis | None = None, limit: int | None = None,
              max_length: int | None = None, stop: Callable[[], bool] | None = None
              ) -> Iterator[Addition]:
    """Every valid loop addition (one per combinatorial class), lazily.

    A simple cycle of the paper's graph ``G_V^Delta`` is valid when its loop also separates its
    zone (:func:`separates_zone`); that is the only level-graph cycle an addition can close.

    Parameters
    ----------
    ls:
        A polycube loop structure.
    axis:
        The label of the new loops, or ``None`` for all three (X, then Y, then Z).
    limit:
        Stop after this many.
    max_length:
        Keep loops past at most this many corners (each adds that many corners).
    stop:
        Asked now and then during the search; when it returns true, :class:`SearchStopped` is
        raised (the additions yielded so far stand).

    Returns
    -------
    Iterator[Addition]

    Raises
    ------
    SearchStopped
        When ``stop()`` said so.
    ValueError
        When ``ls`` has no sides.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> [len(list(additions(box, a))) for a in Axis]
    [3, 6, 6]
    """
    n = 0
    for a in (Axis if axis is None else [axis]):
        for move in valid_additions(ls, a, max_length, stop):
            if limit is not None and n >= limit:
                return
            n += 1
            yield move


def valid_additions(ls: LoopStructure, axis: Axis, max_length: int | None = None,
                     stop: Callable[[], bool] | None = None,
                     graph: _AdditionGraph | None = None) -> Iterator[Addition]:
    """The valid ``axis``-additions: the cycles of the addition graph (``graph``, built here if
    not given; at most ``max_length`` corners) whose loops separate their zone.  ``stop()`` is
    asked now and then, and :class:`SearchStopped` raised when it says so.

    >>> from polyloops.io.examples import load_example
    >>> sum(1 for _ in valid_additions(load_example("cube").dualize(), Axis.X))
    2
    """
    if not ls.oriented:
        raise ValueError("loop moves need an oriented loop structure")
    for cycle in (graph or _AdditionGraph(ls, axis)).cycles(max_length, stop):
        move = Addition(axis, cycle)
        if separates_zone(ls, move):
            yield move




def count_valid_additions(ls: LoopStructure, axis: Axis, limit: int | None = None,
                          deadline: float | None = None) -> tuple[int, bool]:
    """How many valid ``axis``-additions there are, without building them: at most ``limit``,
    and by ``deadline`` (a :func:`time.monotonic` time); returns the count and whether it is
    complete (``False``: a lower bound, stopped by the limit or the deadline).

    Cycles in zones of genus 0 always separate their zone (see :func:`separates_zone`), so
    there the cycles of the addition graph are counted (compiled, ``_cycles.c``, when built);
    cycles in zones with a handle are listed and tested one by one.  A cycle lies in the zone
    of its corners, and is counted from its lowest corner, so the two parts do not overlap.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> [count_valid_additions(box, a) for a in Axis]
    [(3, True), (6, True), (6, True)]
    """
    import time

    if not ls.oriented:
        raise ValueError("loop moves need an oriented loop structure")
    m = ls.map
    zones = ls.zones(axis)
    handled = [zones.genera[zones.zone_of[c]] > 0 for c in range(m.num_corners)]
    plain = [c for c in range(m.num_corners) if not handled[c]]
    graph = _AdditionGraph(ls, axis)

    def expired() -> bool:
        return deadline is not None and time.monotonic() > deadline

    found = 0
    if expired():
        return 0, False
    counting = compiled.in_use("cycles")  # the compiled count of the addition graph's cycles
    if counting:
        found, status = _count_compiled(graph, plain, limit, deadline)
        if status:
            return found, False
    # What is left to list: the plain zones' cycles (when not counted above), then the cycles
    # in zones with a handle that separate their zone.
    handle_cycles = (c for c in graph.cycles(None, expired, [c for c in range(m.num_corners) if handled[c]])
                     if separates_zone(ls, Addition(axis, c)))
    listed = handle_cycles if counting else chain(graph.cycles(None, expired, plain), handle_cycles)
    try:
        for _ in listed:
            if limit is not None and found >= limit:
                return found, False
            found += 1
    except SearchStopped:
        return found, False
    return found, True


@dataclass(frozen=True)
class AdditionEstimate:
    """An estimate of the number of valid additions of one label from random walks: the mean
    of the walks' estimates, a 95% interval for it (normal approximation: the mean plus or
    minus 1.96 standard errors, so only as good as the walks are many), and the walks taken."""

    estimate: float
    low: float
    high: float
    walks: int

    @property
    def made(self) -> bool:
        """Whether any walk was taken: with none (the time ran out first) there is no estimate,
        not an estimate of 0."""
        return self.walks > 0

    def to_json(self) -> dict[str, float | int | None]:
        """A JSON-ready dict of the estimate (``null`` values when no walk was taken: JSON has
        no infinity)."""
        if not self.made:
            return {"estimate": None, "low": None, "high": None, "walks": 0}
        finite = {k: (v if math.isfinite(v) else None) for k, v in
                  (("estimate", self.estimate), ("low", self.low), ("high", self.high))}
        return {**finite, "walks": self.walks}


def estimate_additions(ls: LoopStructure, axis: Axis, walks: int = 2000, seed: int = 0,
                       stop: Callable[[], bool] | None = None) -> AdditionEstimate:
    """Estimate how many valid ``axis``-additions there are without counting them: Knuth's
    estimator on the search tree of :meth:`_AdditionGraph.cycles` (a walk from the root picks
    one child uniformly at each step; the product of the numbers of children along the walk,
    times the valid closings met at each step, is an unbiased estimate of the count).  For
    layouts too large to count.  ``walks`` walks, reproducible for a ``seed``; ``stop()``
    ends them early (the estimate then rests on fewer walks).

    >>> from polyloops.io.examples import load_example
    >>> est = estimate_additions(load_example("box-2x1x1").dualize(), Axis.Z, walks=500)
    >>> est.low <= 6 <= est.high, est.walks
    (True, 500)
    """
    import math

    if not ls.oriented:
        raise ValueError("loop moves need an oriented loop structure")
    g = _AdditionGraph(ls, axis)
    m = ls.map
    n = m.num_corners
    zones = ls.zones(axis)
    roots = [(c, d) for c in range(n) for d in m.outgoing(c) if d in g.succ and m.target(d) > c]
    rng = random.Random(seed)
    samples: list[float] = []
    while roots and len(samples) < walks and not (stop is not None and stop()):
        start, first = rng.choice(roots)
        weight, total = float(len(roots)), 0.0
        path, on_path = [first], {start, m.target(first)}
        handle = zones.genera[zones.zone_of[start]] > 0
        while True:
            options = []
            for e in g.succ[path[-1]]:
                w = m.target(e)
                if w == start:
                    if len(path) >= 2 and g.ok(e, first) and (not handle or separates_zone(
                            ls, Addition(axis, (start, *(m.target(d) for d in path))))):
                        total += weight
                elif w > start and w not in on_path and len(path) + 2 <= n:
                    options.append(e)
            if not options:
                break
            weight *= len(options)
            e = rng.choice(options)
            path.append(e)
            on_path.add(m.target(e))
        samples.append(total)
    k = len(samples)
    mean = sum(samples) / k if k else 0.0
    spread = math.sqrt(sum((x - mean) ** 2 for x in samples) / (k - 1)) if k > 1 else math.inf
    half = 1.96 * spread / math.sqrt(k) if k else math.inf
    return AdditionEstimate(mean, max(0.0, mean - half), mean + half, k)


def _count_compiled(graph: _AdditionGraph, starts: list[int], limit: int | None,
                    deadline: float | None) -> tuple[int, int]:
    """The compiled count of the graph's cycles from ``starts``: (count, status)."""
    import time
    from array import array

    m = graph.ls.map
    allowed = bytes(d in graph.succ for d in range(m.num_darts))
    indptr, succ = array("i", [0]), array("i")
    for d in range(m.num_darts):
        if allowed[d]:
            succ.extend(graph.succ[d])
        indptr.append(len(succ))
    out_indptr, out_darts = array("i", [0]), array("i")
    for c in range(m.num_corners):
        out_darts.extend(m.outgoing(c))
        out_indptr.append(len(out_darts))
    target = array("i", (m.target(d) for d in range(m.num_darts)))
    seconds = -1.0 if deadline is None else max(0.0, deadline - time.monotonic())
    cycles = compiled.require("cycles")
    return cycles.count(indptr.tobytes(), succ.tobytes(), target.tobytes(), out_indptr.tobytes(),
                        out_darts.tobytes(), allowed, array("i", starts).tobytes(),
                        -1 if limit is None else limit, seconds)


def addition_index(axis: Axis, i: int) -> str:
    """The name of the ``i``-th valid ``axis``-addition: ``"Y3"``.  Indices carry their axis,
    so a listing of one label and a listing of all three name each addition the same way."""
    return f"{axis.name}{i}"


def addition_at(ls: LoopStructure, index: str | int) -> Addition | None:
    """The addition named ``"Y3"`` (the fourth valid Y-loop in :func:`additions` order), or by
    a plain integer ``n``, the ``n``-th of the listing of all labels (X, then Y, then Z);
    ``None`` when there is no such addition.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> count_additions(box)
    {'X': 3, 'Y': 6, 'Z': 6}
    >>> addition_at(box, "Y0") == addition_at(box, 3)  # the three X-additions come first
    True
    """
    if isinstance(index, int):
        return next(islice(additions(ls), index, None), None) if index >= 0 else None
    text = index.strip().upper()
    if len(text) < 2 or text[0] not in "XYZ" or not text[1:].isdigit():
        raise ValueError(f"{index!r} is not an addition index such as Y3")
    return next(islice(additions(ls, Axis.parse(text[0])), int(text[1:]), None), None)


def count_additions(ls: LoopStructure, limit: int | None = None,
                    axes: Sequence[Axis] = tuple(Axis)) -> dict[str, int]:
    """The number of valid additions per label (of ``axes`` only, at most ``limit`` each),
    counted without building them (:func:`count_valid_additions`)."""
    return {a.name: count_valid_additions(ls, a, limit)[0] for a in axes}


def shortest_additions(ls: LoopStructure, axis: Axis, k: int,
                       stop: Callable[[], bool] | None = None) -> list[Addition]:
    """The ``k`` valid ``axis``-additions past the fewest corners (ties in :func:`additions`
    order), found by bounded searches of growing length, without listing longer loops.  When
    an axis has fewer than ``k`` valid loops the last searches are as long as a full listing;
    ``stop()`` is asked now and then, and :class:`SearchStopped` raised when it says so.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> [len(mv.cycle) for mv in additions(box, Axis.Y)]
    [4, 6, 4, 6, 4, 4]
    >>> [len(mv.cycle) for mv in shortest_additions(box, Axis.Y, 5)]
    [4, 4, 4, 4, 6]
    """
    found: list[Addition] = []
    if k <= 0:
        return found
    graph = _AdditionGraph(ls, axis)
    for length in range(3, ls.map.num_corners + 1):
        found.extend(mv for mv in valid_additions(ls, axis, length, stop, graph) if len(mv.cycle) == length)
        if len(found) >= k:
            break
    return found[:k]


SATURATED = 200  # walks in a row that find nothing new: the sample stops


def sample_additions(ls: LoopStructure, axis: Axis, n: int, seed: int = 0,
                     attempts: int | None = None, stop: Callable[[], bool] | None = None) -> list[Addition]:
    """Up to ``n`` different valid ``axis``-additions found by random self-avoiding walks in the
    addition graph (closing the loop as soon as it can): reproducible for a seed, quick on
    large structures, but not uniformly distributed (short loops are favoured).  Stops after
    ``attempts`` walks (default ``200 * n``), after 200 walks in a row that find nothing new
    (a structure with fewer valid loops than asked), or when ``stop()`` says so; each result
    is an addition that :func:`additions` also lists, named the same way (its cycle starts at
    its lowest corner).

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> picked = sample_additions(box, Axis.Z, 3, seed=1)
    >>> len(picked), all(is_valid_addition(box, mv) for mv in picked)
    (3, True)
    """
    if not ls.oriented:
        raise ValueError("loop moves need an oriented loop structure")
    rng = random.Random(seed)
    g = _AdditionGraph(ls, axis)
    m = ls.map
    darts = [d for d in range(m.num_darts) if g.succ.get(d)]
    found: dict[tuple[int, ...], Addition] = {}
    fruitless = 0
    for _ in range(200 * n if attempts is None else attempts):
        if len(found) >= n or not darts or fruitless >= SATURATED or (stop is not None and stop()):
            break
        fruitless += 1
        first = rng.choice(darts)
        start = m.origin(first)
        path, on_path = [first], {start, m.target(first)}
        while True:
            nexts = g.succ[path[-1]]
            if len(path) >= 2 and any(m.target(e) == start and g.ok(e, first) for e in nexts):
                move = Addition(axis, canonical_cycle([start, *(m.target(d) for d in path)]))
                if move.cycle not in found and separates_zone(ls, move):
                    found[move.cycle] = move
                    fruitless = 0
                break
            options = [e for e in nexts if m.target(e) not in on_path]
            if not options:
                break
            e = rng.choice(options)
            path.append(e)
            on_path.add(m.target(e))
    return list(found.values())


def is_valid_addition(ls: LoopStructure, move: Addition) -> bool:
    """Whether adding this loop (any rotation of its cycle) leaves a polycube loop structure:
    the local tests at its corners and the separation of its zone."""
    m = ls.map
    cyc = move.cycle
    k = len(cyc)
    if k < 3 or len(set(cyc)) != k:
        return False
    try:
        darts = [m.dart(cyc[i], cyc[(i + 1) % k]) for i in range(k)]
    except KeyError:
        return False
    g = _AdditionGraph(ls, move.axis)
    return (all(ls.axis_of_dart(d) != move.axis for d in darts)
            and all(g.ok(darts[i - 1], darts[i]) for i in range(k))
            and separates_zone(ls, move))


def add_loop(ls: LoopStructure, move: Addition, *, checked: bool = True) -> LoopStructure:
    """Insert the loop of an addition (see the module docstring for the numbering of the result).
    It does not check validity: use :func:`is_valid_addition` or take moves from
    :func:`additions`.  With ``checked=False`` (for moves :func:`additions` gave, on a valid
    structure) the result is built without re-checking that it is a loop structure at all.

    Parameters
    ----------
    ls:
        An oriented loop structure.
    move:
        The addition: its axis and the cycle of corners the new loop walks past.
    checked:
        Check that the result is a loop structure (the default); see :func:`_child`.

    Returns
    -------
    LoopStructure
        With ``len(move.cycle)`` more corners and one more loop.

    Raises
    ------
    MapError, LabelError
        When the cycle does not describe a loop that can be inserted.

    >>> from polyloops.io.examples import load_example
    >>> cube = load_example("cube").dualize()
    >>> bigger = add_loop(cube, next(additions(cube, Axis.X)))
    >>> bigger.map.num_corners, len(bigger.loops)
    (12, 4)
    """
    m = ls.map
    cyc = move.cycle
    k = len(cyc)
    n = m.num_corners
    plus_id = {v: n + i for i, v in enumerate(cyc)}
    darts = [m.dart(cyc[i], cyc[(i + 1) % k]) for i in range(k)]
    # Which copy of a corner of C each face keeps: the faces on the left keep v, the right v+.
    keeps_plus: set[tuple[int, int]] = set()  # (face, corner)
    for i, v in enumerate(cyc):
        forward, back = darts[i], m.twin[darts[i - 1]]
        d = back
        while d != forward:  # faces from back round to forward (CCW) lie on the right
            keeps_plus.add((m.face_of[d], v))
            d = m.rotate(d)
    faces = [[plus_id[c] if (f, c) in keeps_plus else c for c in face] for f, face in enumerate(m.faces)]
    for i in range(k):
        u, w = cyc[i], cyc[(i + 1) % k]
        faces.append([w, u, plus_id[u], plus_id[w]])
    labels: dict[tuple[int, int], Direction] = {}
    for f, face in enumerate(faces[: m.num_faces]):
        for j, d in enumerate(m.face_darts(f)):
            labels.setdefault((face[j], face[(j + 1) % len(face)]), ls.direction(d))
    for v in cyc:
        labels[(v, plus_id[v])] = Direction.of(move.axis, 1)
    return _child(faces, labels, checked)


VERIFY_CHILDREN = False  # True: every move's result is checked, even where the caller vouches for it


def _child(faces: list[list[int]], labels: dict[tuple[int, int], Direction], checked: bool) -> LoopStructure:
    """The structure a move leaves.  A move that the move tests accepted, from a valid
    structure, yields a surface and labels that agree along each loop, so a caller that knows
    this (the reachability search) asks for ``checked=False`` and the result is built without
    re-checking (:meth:`~polyloops.core.structure.LoopStructure.from_trusted_edge_labels`);
    :data:`VERIFY_CHILDREN` restores every check, and a test compares the two builds."""
    if checked or VERIFY_CHILDREN:
        return LoopStructure.from_edge_labels(faces, _one_per_edge(labels))
    return LoopStructure.from_trusted_edge_labels(faces, labels)


def _one_per_edge(labels: dict[tuple[int, int], Direction]) -> dict[tuple[int, int], Direction]:
    out: dict[tuple[int, int], Direction] = {}
    for (u, v), d in labels.items():
        if (v, u) not in out:
            out[(u, v)] = d
    return out


# -- removals --------------------------------------------------------------------------------


@dataclass(frozen=True)
class RemovalCheck:
    """Whether removing a loop leaves a polycube loop structure, and if not, why."""

    loop: int
    valid: bool
    reason: str = ""


def _removal_groups(ls: LoopStructure, loop: int) -> tuple[DisjointSets, list[tuple[int, int]], set[int]]:
    m = ls.map
    lp = ls.loops[loop]
    rungs = [(m.origin(d), m.target(d)) for d in lp.darts]
    groups = DisjointSets(range(m.num_corners))
    for u, v in rungs:
        groups.union(u, v)
    return groups, rungs, set(lp.faces)


def check_removal(ls: LoopStructure, loop: int, arcs: LevelArcs | None = None) -> RemovalCheck:
    """Decide locally whether removing ``loop`` leaves a polycube loop structure.

    Touches only the loop's corners, the faces and edges around them, and the loop's level
    graph (``arcs``, shared by :func:`removals` across loops), so testing every loop costs
    the total size of the loops plus one search of a level graph per loop.
    """
    if not ls.oriented:
        raise ValueError("loop moves need an oriented loop structure")
    m = ls.map
    system = m.loop_system
    lp = ls.loops[loop]
    if lp.self_crossings:
        return RemovalCheck(loop, False, "the loop crosses itself")
    rungs = [(m.origin(d), m.target(d)) for d in lp.darts]
    groups: DisjointSets[int] = DisjointSets()
    for u, v in rungs:
        groups.union(u, v)
    members: dict[object, list[int]] = defaultdict(list)
    rung_count: dict[object, int] = defaultdict(int)
    for c in groups.parent:
        members[groups.find(c)].append(c)
    for u, _ in rungs:
        rung_count[groups.find(u)] += 1
    for root, cs in members.items():
        if len(cs) != rung_count[root] + 1:
            return RemovalCheck(loop, False, f"corners {sorted(cs)} would merge around a cycle")
    root_of = {c: groups.find(c) for c in groups.parent}
    strip = set(lp.faces)
    # Faces that survive must not meet a merged corner twice (only faces at merged corners can).
    around = sorted({m.face_of[d] for c in root_of for d in m.outgoing(c)} - strip)
    for f in around:
        roots = [root_of.get(c, ("corner", c)) for c in m.faces[f]]
        if len(set(roots)) != len(roots):
            return RemovalCheck(loop, False, f"face {f} would meet a merged corner twice")
    # Surviving edges at merged corners: the edges along a strip face merge in pairs.
    for root, cs in sorted(members.items(), key=lambda item: min(item[1])):
        by_far: dict[object, list[int]] = defaultdict(list)
        for c in cs:
            for d in m.outgoing(c):
                if system.loop_of_dart[d] != loop:
                    t = m.target(d)
                    by_far[root_of.get(t, ("corner", t))].append(d)
        if root in by_far:
            return RemovalCheck(loop, False, f"an edge would join merged corner {min(cs)} to itself")
        directions = []
        for far, fds in by_far.items():
            if len(fds) == 2:
                d1, d2 = fds
                pair = (m.face_of[d1] == m.face_of[m.twin[d2]] in strip
                        or m.face_of[d2] == m.face_of[m.twin[d1]] in strip)
                if not pair or ls.direction(d1) != ls.direction(d2):
                    return RemovalCheck(loop, False, f"two edges would join corners {min(cs)} and {far}")
            elif len(fds) > 2:
                return RemovalCheck(loop, False, f"edges would join corners {min(cs)} and {far} twice")
            directions.append(ls.direction(fds[0]))
        if len(directions) < 3:
            return RemovalCheck(loop, False, f"merged region {min(cs)} would have {len(directions)} segments")
        if len(set(directions)) != len(directions):
            return RemovalCheck(loop, False, f"merged region {min(cs)} would have a repeated direction")
    # Acyclicity: with the loop's arc u -> v contracted, a cycle through the merged zone is a
    # path from {u, v} back to {u, v} along the other arcs; in an acyclic graph, exactly
    # another path from u to v.
    axis = ls.axes[loop]
    if closes_cycle(ls, loop, arcs or level_arcs_of(ls)):
        return RemovalCheck(loop, False, f"the {axis}-graph would get a cycle through the merged zone")
    return RemovalCheck(loop, True)


def removable(ls: LoopStructure, loop: int) -> bool:
    """Whether removing ``loop`` leaves a polycube loop structure (:func:`check_removal`)."""
    return check_removal(ls, loop).valid


def removals(ls: LoopStructure) -> list[int]:
    """The loops whose removal leaves a polycube loop structure (decided locally, see
    :func:`check_removal`).

    Parameters
    ----------
    ls:
        A polycube loop structure.

    Returns
    -------
    list[int]
        Loop ids; empty when the structure is irreducible.

    Raises
    ------
    ValueError
        When ``ls`` has no sides.

    >>> from polyloops.io.examples import load_example
    >>> removals(load_example("cube").dualize()), removals(load_example("non-incremental").dualize())
    ([], [])
    >>> removals(load_example("box-2x1x1").dualize())
    [2, 3]
    """
    arcs = level_arcs_of(ls)
    if use_arrays(ls.map.num_darts) and removal_arrays.applies(ls):
        return [i for i, ok in enumerate(removal_arrays.removable_loops(ls).tolist()) if ok]
    return [lp.id for lp in ls.loops if check_removal(ls, lp.id, arcs).valid]


def remove_loop(ls: LoopStructure, loop: int, *, checked: bool = True) -> LoopStructure:
    """Remove a loop (see the module docstring for the numbering of the result).  It does not
    check Definition 4: use :func:`check_removal` or :func:`removals` first.  With
    ``checked=False`` (for a removal they accepted) the result is built without re-checking
    that it is a loop structure at all.

    Parameters
    ----------
    ls:
        An oriented loop structure.
    loop:
        The id of the loop to remove.
    checked:
        Check that the result is a loop structure (the default).

    Returns
    -------
    LoopStructure

    Raises
    ------
    MapError, FaceListError, LabelError
        When the result is not a loop structure at all.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> remove_loop(box, removals(box)[0]).map.num_corners
    8
    """
    m = ls.map
    groups, _, strip = _removal_groups(ls, loop)
    rep = {c: min(g) for g in groups.to_sets() for c in g}
    keep = sorted(set(rep.values()))
    new_id = {c: i for i, c in enumerate(keep)}
    faces = [[new_id[rep[c]] for c in face] for f, face in enumerate(m.faces) if f not in strip]
    labels: dict[tuple[int, int], Direction] = {}
    system = m.loop_system
    for d in range(m.num_darts):
        if system.loop_of_dart[d] == loop:
            continue
        u, v = new_id[rep[m.origin(d)]], new_id[rep[m.target(d)]]
        if (u, v) in labels and labels[(u, v)] != ls.direction(d):
            raise LabelError(f"merged edges ({u}, {v}) disagree in direction")
        labels[(u, v)] = ls.direction(d)
    return _child(faces, labels, checked)


def try_remove(ls: LoopStructure, loop: int) -> LoopStructure | None:
    """``remove_loop``, or ``None`` when the result is not a loop structure."""
    try:
        return remove_loop(ls, loop)
    except PolyloopsError:  # the result is not a loop structure at all
        return None


def parse_cycle(text: str) -> tuple[int, ...]:
    """``"0,1,3,2"`` -> ``(0, 1, 3, 2)``."""
    return tuple(int(x) for x in text.replace(" ", "").split(",") if x)


def canonical_cycle(cycle: Sequence[int]) -> tuple[int, ...]:
    """The rotation that starts at the lowest corner (the direction is kept)."""
    i = cycle.index(min(cycle))
    return tuple(cycle[i:]) + tuple(cycle[:i])


class MoveError(PolyloopsError, ValueError):
    """A move that names nothing: bad syntax, or an index past the end of the listing."""


class InvalidMoveError(MoveError):
    """A well-formed loop addition that is not valid on this structure."""


MOVE_SYNTAX = ("an addition is named by its index in the listing of additions (such as Y3) or as "
               "AXIS:c0,c1,... (its corners)")


def parse_addition(ls: LoopStructure, text: str) -> Addition:
    """The addition ``text`` names on ``ls``: an index from :func:`addition_at` (``Y3``, or a
    plain ``n``), or ``AXIS:c0,c1,...`` (the corners the new loop walks past, ``+`` side on
    the right).

    Raises :class:`MoveError` when ``text`` names no addition, and :class:`InvalidMoveError`
    when it names a loop whose addition is not valid here.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> parse_addition(box, "Y0") == addition_at(box, "Y0")
    True
    >>> parse_addition(box, "Q7")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    polyloops.core.moves.MoveError: move 'Q7': an addition is named by its index in the listing ...
    """
    if ":" in text:
        label, _, corners = text.partition(":")
        try:
            move = Addition(Axis.parse(label.strip().upper()), parse_cycle(corners))
        except ValueError:
            raise MoveError(f"move {text!r}: {MOVE_SYNTAX}") from None
        if not move.cycle:
            raise MoveError(f"move {text!r} names no corners: {MOVE_SYNTAX}")
        missing = [c for c in move.cycle if not 0 <= c < ls.map.num_corners]
        if missing:
            raise MoveError(f"move {text!r}: there is no corner {missing[0]} (corners are 0 to "
                            f"{ls.map.num_corners - 1})")
        if not is_valid_addition(ls, move):
            raise InvalidMoveError(f"move {text!r} is not a valid loop addition here")
        return move
    try:
        found = addition_at(ls, int(text) if text.strip().lstrip("-").isdigit() else text)
    except ValueError:
        raise MoveError(f"move {text!r}: {MOVE_SYNTAX}") from None
    if found is None:
        raise MoveError(f"there is no addition {text}")
    return found


def loop_names(ls: LoopStructure) -> list[str]:
    """Each loop's name as ``add`` and ``remove`` take it: its axis and its rank among the loops
    of that axis, in loop order (``Y0`` is the first Y-loop).

    >>> from polyloops.io.examples import load_example
    >>> loop_names(load_example("box-2x1x1").dualize())
    ['Y0', 'Z0', 'X0', 'X1']
    """
    seen = dict.fromkeys(Axis, 0)
    names = []
    for a in ls.axes:
        names.append(f"{a}{seen[a]}")
        seen[a] += 1
    return names


def parse_removal(ls: LoopStructure, text: str) -> int:
    """The loop id ``text`` names on ``ls``: a loop id (``3``) or an axis and a rank among the
    loops of that axis (``X0``, see :func:`loop_names`).  Raises :class:`MoveError` when it names
    no loop; whether the loop is removable is :func:`check_removal`'s question.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> parse_removal(box, "X1"), parse_removal(box, "3")
    (3, 3)
    """
    word = text.strip().upper()
    if word.isdigit():
        if int(word) < len(ls.loops):
            return int(word)
        raise MoveError(f"there is no loop {text} (loops are 0 to {len(ls.loops) - 1})")
    names = loop_names(ls)
    if word in names:
        return names.index(word)
    if word[:1] in "XYZ" and word[1:].isdigit():
        raise MoveError(f"there is no loop {text} (the {word[0]}-loops are {word[0]}0 to "
                        f"{word[0]}{sum(str(a) == word[0] for a in ls.axes) - 1})")
    raise MoveError(f"loop {text!r}: a loop is named by its id (such as 3) or by its axis and its "
                    "rank among that axis's loops (such as X0)")
