"""The second stage of the torus search region by region: every third axis for a two-axis
arrangement ``B`` at once.

In a polycube loop structure the third axis's loops cut each region of ``B`` (a disc) into a
path of corners (``docs/searches.md``, "Two stages"), so within a region they are parallel
chords: with ``k`` chords and their ``2k`` ends in cyclic order ``P_0 .. P_2k-1`` around the
region, the chords are ``P_(a+i) - P_(a-1-i)`` for one offset ``a`` (``k`` choices).  The
whole third axis is therefore a number of points on each edge of ``B`` and an offset in each
region, and gluing the chords at the points closes them into loops.  This module chooses the
regions one at a time, so that each region's corners (the *pieces* between its chords) are
final as soon as it is chosen:

- every piece has 3 to 6 sides, at most two of each axis, no two on one loop;
- a piece with two sides of one axis of ``B`` lies on the ``+`` side of one and the ``-`` side
  of the other (Condition 3): a parity constraint between the signs of two loops of ``B``;
- the level graph of each axis of ``B`` is fixed by ``B`` (its zones are ``B``'s), and at genus
  1 it has at most one cycle; it can be oriented without a directed cycle exactly when the
  signs do not force every loop of the cycle to run one way round, so a region whose
  constraints force that ends the branch (at genus 2 or more, a region whose constraints force
  any cycle of it one way round);
- the points already placed, with half the points the other regions still need, stay within
  the budget.

Each constraint is a property of every polycube loop structure with that decomposition, and
constraints only accumulate as regions are chosen, so no polycube is lost.  At the end the
loops must cross each region at most once and the map must pass the same final test as the
loop-by-loop search (:func:`polyloops.generate.torus.decompositions.decomposes`) and carry a polycube with
the decomposition's labelling.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

from polyloops.core import compiled
from polyloops.core.disjoint_sets import DisjointSets, ParitySets
from polyloops.generate.torus.arrangement import TorusArrangement, axis_classes, walk_forward
from polyloops.generate.torus.cuts import layered_need
from polyloops.generate.torus.stages import TorusSearchStats

__all__ = ["AxisCycle", "axis_cycles", "forced_one_way", "third_axis_systems"]


@dataclass(frozen=True)
class AxisCycle:
    """A cycle of one axis's level graph in ``B`` (at genus 1 the only one): its loops, each
    with ``+1`` when its reference walk's right side is the next zone round the cycle (so the
    loop's arc runs forward round the cycle exactly when ``sign * rho = +1``)."""

    loops: tuple[tuple[int, int], ...]


def axis_cycles(base: TorusArrangement, klass: list[int]) -> list[AxisCycle]:
    """The cycles of the two level graphs of ``B`` (zones: the regions joined across the
    other axis's edges; an arc per loop): every simple cycle, at most one an axis at genus 1;
    none when there are more than :data:`MAX_CYCLES` (nothing is cut for them)."""
    forward = walk_forward(base)
    out = []
    for axis in (0, 1):
        zones = DisjointSets(range(len(base.faces)))
        for d in range(len(base.twin)):
            if klass[base.loop_of[d]] != axis:
                zones.union(base.face_of[d], base.face_of[base.twin[d]])
        arcs: dict[int, tuple[int, int]] = {}  # loop -> (left zone, right zone) of its reference walk
        for d in range(len(base.twin)):
            lp = base.loop_of[d]
            if klass[lp] == axis and forward[d] == 1 and lp not in arcs:
                arcs[lp] = (zones.find(base.face_of[d]), zones.find(base.face_of[base.twin[d]]))
        out += [AxisCycle(tuple(c)) for c in _every_cycle(arcs)]  # at genus 1, one at most
    return out if len(out) <= MAX_CYCLES else []


MAX_CYCLES = 32  # the compiled search's room for cycles (_regions.c, MAXCYC); more are not cut
LISTED_OPTIONS = 50_000  # the compiled search lists a region's options for a numbering up to this many


def _every_cycle(arcs: dict[int, tuple[int, int]]) -> list[list[tuple[int, int]]]:
    """Every simple cycle of a connected multigraph (an arc per loop, between its zones), each
    walked by :func:`_walk_cycle`; found among the sums of the fundamental cycles of a spanning
    tree (a level graph at genus ``g`` has at most ``g`` independent
    cycles, so at most ``2^g - 1`` sums).  An empty list beyond 12 independent cycles."""
    nodes = sorted({z for ends in arcs.values() for z in ends})
    if not arcs or len(arcs) - len(nodes) + 1 > 12:
        return []
    tree: dict[int, set[int]] = {nodes[0]: set()}  # zone -> the tree's arcs from the root to it
    order = [nodes[0]]
    for z in order:  # grows while read: breadth first
        for lp in sorted(arcs):
            a, b = arcs[lp]
            other = b if z == a else a if z == b else None
            if other is not None and other not in tree:
                tree[other] = tree[z] | {lp}
                order.append(other)
    used = set().union(*tree.values())
    fundamental = [tree[arcs[lp][0]] ^ tree[arcs[lp][1]] | {lp} for lp in sorted(arcs) if lp not in used]
    out = []
    for mask in range(1, 1 << len(fundamental)):
        arcs_in: set[int] = set()
        for i, cyc in enumerate(fundamental):
            if mask >> i & 1:
                arcs_in ^= cyc
        degree: dict[int, int] = {}
        for lp in arcs_in:
            for z in arcs[lp]:
                degree[z] = degree.get(z, 0) + 1
        if any(k != 2 for k in degree.values()):
            continue
        walked = _walk_cycle({lp: arcs[lp] for lp in arcs_in})
        if len(walked) == len(arcs_in):  # connected: one cycle, not several
            out.append(walked)
    return out


def _walk_cycle(live: dict[int, tuple[int, int]]) -> list[tuple[int, int]]:
    """The arcs of a cycle (or of the cycle through the least arc, when ``live`` holds
    several), in order round it from the least arc's left end, each with ``+1`` when walked
    from its left end to its right end."""
    first = min(live)
    out: list[tuple[int, int]] = []
    at, used = live[first][0], set[int]()
    while len(used) < len(live):
        lp = next((lp for lp in sorted(live) if lp not in used and at in live[lp]), -1)
        if lp < 0:
            break  # back at the start of a cycle, with other cycles left
        left, right = live[lp]
        rho = 1 if at == left else -1
        out.append((lp, rho))
        used.add(lp)
        at = right if rho == 1 else left
    return out


def forced_one_way(cycle: AxisCycle, signs: ParitySets[int]) -> bool:
    """Whether the parity constraints force every loop of the cycle to run the same way round
    (a directed cycle in every orientation they allow)."""
    root, first = None, 0
    for lp, rho in cycle.loops:
        r, s = signs.find(lp)
        if root is None:
            root, first = r, s * rho
        elif r != root or s * rho != first:
            return False
    return True


_Chord = tuple[tuple[int, int, bool], tuple[int, int, bool]]  # two ends: (edge, index, reverse)


@dataclass(frozen=True)
class _Side:
    edge: int  # the edge's lower dart: its points are numbered along it
    reverse: bool  # the region walks the edge against its numbering
    loop: int
    axis: int  # 0 or 1, the class in B
    forward: int  # +1 when the dart runs along its loop's reference walk


def compiled_available() -> bool:
    """Whether the compiled region search runs: built and not switched to its Python twin
    (:mod:`polyloops.core.compiled`)."""
    return compiled.in_use("regions")


@dataclass(frozen=True)
class _Setup:
    sides: list[list[_Side]]
    need: list[int]
    order: list[int]
    axis_sides: list[list[int]]
    cycles: list[AxisCycle]


def _setup(base: TorusArrangement, cut_one_way: bool) -> _Setup:
    klass = axis_classes(base)
    forward = walk_forward(base)
    loops = base.loop_of
    faces = base.faces
    sides = [[_Side(min(d, base.twin[d]), d != min(d, base.twin[d]), loops[d], klass[loops[d]], forward[d])
              for d in face] for face in faces]
    need = [layered_need(len(face), [s.axis for s in sides[f]], len({s.loop for s in sides[f]}) < len(face))
            for f, face in enumerate(faces)]
    axis_sides = [[sum(side.axis == k for side in sides[f]) for k in (0, 1)] for f in range(len(faces))]
    cycles = axis_cycles(base, klass) if cut_one_way else []
    return _Setup(sides, need, _region_order(sides), axis_sides, cycles)


def third_axis_systems(base: TorusArrangement, max_crossings: int, stats: TorusSearchStats | None = None,
                       cut_one_way: bool = True) -> Iterator[tuple[tuple[int, ...], tuple[int, ...]]]:
    """Every way to add third-axis loops to ``B`` within ``max_crossings`` crossings whose
    regions all pass the local tests above and whose loops cross each region once, as
    ``(twin, layer)`` of the whole arrangement (``B``'s darts first, then four darts a new
    crossing), before the final test.  With ``cut_one_way`` false the level-graph cut is left
    out (for the tests).  Runs in C when the compiled part ``regions`` is in use
    (:mod:`polyloops.core.compiled`), which lists a region's options once for each numbering of
    its sides (the same third axes and regions chosen; ``docs/searches.md``)."""
    stats = stats if stats is not None else TorusSearchStats()
    if max_crossings < base.crossings:
        return
    setup = _setup(base, cut_one_way)
    if compiled_available():
        yield from _compiled_systems(base, max_crossings, setup, stats)
    else:
        yield from _python_systems(base, max_crossings, setup, stats)


def _compiled_systems(base: TorusArrangement, max_crossings: int, setup: _Setup, stats: TorusSearchStats
                      ) -> Iterator[tuple[tuple[int, ...], tuple[int, ...]]]:
    import array

    _regions = compiled.require("regions")

    edges = sorted({side.edge for region in setup.sides for side in region})
    index = {e: i for i, e in enumerate(edges)}
    axis_of = {side.edge: side.axis for region in setup.sides for side in region}
    spec = [len(setup.sides), len(edges), base.num_loops, base.crossings, max_crossings - base.crossings]
    for e in edges:
        spec += [axis_of[e], base.loop_of[e]]
    for f in setup.order:
        region = setup.sides[f]
        spec += [f, len(region), setup.need[f], *setup.axis_sides[f]]
        for side in region:
            spec += [index[side.edge], int(side.reverse), side.loop, side.axis, side.forward]
    spec.append(len(setup.cycles))
    for cycle in setup.cycles:
        spec.append(len(cycle.loops))
        for lp, rho in cycle.loops:
            spec += [lp, rho]
    # Each numbering of a region met again reuses its listed options (_regions.c); at genus 2
    # the level graphs' cycles cut most options early and numberings seldom recur, so walking
    # directly is faster there (measured: a quarter of the time or less with 32 and 34 crossings).
    listed = LISTED_OPTIONS if base.genus == 1 else 0
    found, counts = _regions.systems(array.array("i", spec).tobytes(), listed)
    for name, value in zip(("region_choices", "over_bound", "inconsistent_sides", "one_way", "closed",
                            "third_axes"), counts, strict=True):
        setattr(stats, name, getattr(stats, name) + value)
    for raw in found:
        points = {e: raw[i] for i, e in enumerate(edges)}
        chords: list[list[_Chord]] = [[] for _ in setup.sides]
        at = len(edges)
        for _ in setup.sides:
            f, k = raw[at], raw[at + 1]
            at += 2
            for _ in range(k):
                c = raw[at:at + 6]
                chords[f].append(((edges[c[0]], c[1], bool(c[2])), (edges[c[3]], c[4], bool(c[5]))))
                at += 6
        built = _build(base, points, chords)
        assert built is not None  # the compiled search checked the loops already
        yield built


def _python_systems(base: TorusArrangement, max_crossings: int, setup: _Setup, stats: TorusSearchStats
                    ) -> Iterator[tuple[tuple[int, ...], tuple[int, ...]]]:
    sides, need, order, axis_sides = setup.sides, setup.need, setup.order, setup.axis_sides
    cycles = setup.cycles
    faces = base.faces
    budget = max_crossings - base.crossings
    axis_of = {side.edge: side.axis for region in sides for side in region}
    loop_of_edge = {side.edge: side.loop for region in sides for side in region}
    loop_axis = {side.loop: side.axis for region in sides for side in region}
    least = base.crossings
    signs: ParitySets[int] = ParitySets(range(base.num_loops))
    points: dict[int, int] = {}  # edge -> its number of points, once a region beside it is chosen
    chords: list[list[_Chord]] = [[] for _ in faces]

    def lower_bound(rest: list[int]) -> tuple[int, int, int]:
        """Half the points the regions in ``rest`` still need, in all and on each axis's
        edges (a region with ``a`` sides of one axis needs ``a - 2`` points on the other's)."""
        total, on = 0, [0, 0]
        for f in rest:
            fixed = [0, 0]
            for side in sides[f]:
                if side.edge in points:
                    fixed[side.axis] += points[side.edge]
            total += max(0, need[f] - fixed[0] - fixed[1])
            for k in (0, 1):
                on[1 - k] += max(0, axis_sides[f][k] - 2 - fixed[1 - k])
        return (total + 1) // 2, (on[0] + 1) // 2, (on[1] + 1) // 2

    def lacking() -> tuple[int, int] | None:
        """The points that loops of ``B`` still lack on each axis's edges (four runs: each
        loop ends with points on two of its edges at least; a point is on one loop), or
        ``None`` when a loop can no longer have them."""
        crossed = [0] * base.num_loops
        open_ = [0] * base.num_loops
        for e, lp in loop_of_edge.items():
            if e not in points:
                open_[lp] += 1
            elif points[e]:
                crossed[lp] += 1
        lack = [0, 0]
        for lp, axis in loop_axis.items():
            if crossed[lp] + open_[lp] < 2:
                return None
            lack[axis] += max(0, 2 - crossed[lp])
        return lack[0], lack[1]

    def fits(placed: list[int], rest: list[int]) -> bool:
        # the third axis ends crossing each axis of B at least as often as B crosses itself
        bound, on0, on1 = lower_bound(rest)
        lack = lacking()
        if lack is None:
            return False
        on0, on1, bound = max(on0, lack[0]), max(on1, lack[1]), max(bound, lack[0] + lack[1])
        ends = [max(placed[0] + on0, least), max(placed[1] + on1, least)]
        return max(placed[0] + placed[1] + bound, ends[0] + ends[1]) <= budget

    def choose(i: int, placed: list[int]) -> Iterator[tuple[tuple[int, ...], tuple[int, ...]]]:
        if i == len(order):
            stats.closed += 1
            built = _build(base, points, chords)
            if built is not None:
                stats.third_axes += 1
                yield built
            return
        f = order[i]
        cap = (budget - max(placed[1], least) - placed[0], budget - max(placed[0], least) - placed[1])
        for counts, region_chords in _region_options(sides[f], points, cap, signs, cycles, stats):
            stats.region_choices += 1
            now = list(placed)
            for e, m in counts.items():
                points[e] = m
                now[axis_of[e]] += m
            if not fits(now, order[i + 1:]):
                stats.over_bound += 1
            else:
                chords[f] = region_chords
                yield from choose(i + 1, now)
                chords[f] = []
            for e in counts:
                del points[e]

    yield from choose(0, [0, 0])


def _region_order(sides: list[list[_Side]]) -> list[int]:
    """The regions in the order they are chosen: each time the one with fewest edges not yet
    numbered (ties: fewer sides, then the lowest), so that few of its points are free and its
    pieces meet the constraints of the regions before it early (measured: three to four times
    fewer regions cut than taking the most numbered sides first)."""
    done: set[int] = set()
    order: list[int] = []
    while len(order) < len(sides):
        best = min((f for f in range(len(sides)) if f not in order),
                   key=lambda f: (sum(s.edge not in done for s in sides[f]), len(sides[f]), f))
        order.append(best)
        done.update(s.edge for s in sides[best])
    return order


def _region_options(sides: list[_Side], points: dict[int, int], cap: tuple[int, int],
                    signs: ParitySets[int], cycles: list[AxisCycle], stats: TorusSearchStats
                    ) -> Iterator[tuple[dict[int, int], list[_Chord]]]:
    """Each way to cut one region by parallel chords whose pieces pass the local tests, the
    edges already numbered keeping their points: the points on its other edges (at most
    ``cap[k]`` on the edges of each axis ``k`` of ``B``) and its chords, yielded while
    ``signs`` holds its pieces' parity constraints (a walk stops as soon as a piece's
    constraints contradict the others or force a level graph's cycle one way round).

    The chords are walked from one end of the path of pieces (a *cap*, between two chord ends
    on different sides): the next chord's ends move on along the boundary, one forwards and
    one backwards, and the walk closes with the other cap.  A piece between two chords has
    four sides of ``B`` at most, so between two chords the two ends move on two sides at most
    in all."""
    s = len(sides)
    fixed = [points.get(side.edge) for side in sides]

    def admit(relations: list[tuple[int, int, int]] | None) -> int | None:
        """Add a piece's constraints: the mark to roll back to, or ``None`` (nothing added)
        when the piece cannot be a corner here."""
        if relations is None:
            return None
        mark = signs.checkpoint()
        if not all(signs.relate(a, b, p) for a, b, p in relations):
            stats.inconsistent_sides += 1
        elif any(forced_one_way(c, signs) for c in cycles):
            stats.one_way += 1
        else:
            return mark
        signs.rollback(mark)
        return None

    if all(m is None or m == 0 for m in fixed):  # no chord: the region is one corner
        mark = admit(_piece(sides, list(range(s)), 0))
        if mark is not None:
            yield {side.edge: 0 for side in sides if side.edge not in points}, []
            signs.rollback(mark)
    seen: set[tuple] = set()
    count = [0] * s
    lefts: list[int] = []  # the sides of the chords' ends, from the first cap
    rights: list[int] = []

    def span(i: int, j: int) -> list[int]:
        return [(i + q) % s for q in range((j - i) % s + 1)]

    def place(i: int) -> bool:
        count[i] += 1
        bound = fixed[i]
        return bound is None or count[i] <= bound

    def walk(used: int) -> Iterator[tuple[dict[int, int], list[_Chord]]]:
        iL, iR = lefts[-1], rights[-1]
        # close with the other cap
        if 1 <= s - used <= 4:
            result = _close(sides, fixed, count, lefts, rights, cap)
            if result is not None and result[2] not in seen:
                mark = admit(_piece(sides, span(iL, iR), 1))
                if mark is not None:
                    seen.add(result[2])
                    seen.add(tuple(sorted((y, x) for x, y in result[2])))
                    yield result[0], list(result[1])
                    signs.rollback(mark)
        for dL, dR in ((0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (0, 2)):
            if used + dL + dR > s - 1:
                continue
            jL, jR = (iL + dL) % s, (iR - dR) % s
            okL, okR = place(jL), place(jR)
            if okL and okR and _within(_free_points(sides, fixed, count), cap):
                mark = admit(_piece(sides, span(iL, jL) + span(jR, iR), 2))
                if mark is not None:
                    lefts.append(jL)
                    rights.append(jR)
                    yield from walk(used + dL + dR)
                    lefts.pop()
                    rights.pop()
                    signs.rollback(mark)
            count[jL] -= 1
            count[jR] -= 1

    for iR in range(s):
        for t in range(1, 5):
            if t > s - 1:
                break
            iL = (iR + t) % s
            okL, okR = place(iL), place(iR)
            if okL and okR:
                mark = admit(_piece(sides, span(iR, iL), 1))
                if mark is not None:
                    lefts.append(iL)
                    rights.append(iR)
                    yield from walk(t)
                    lefts.pop()
                    rights.pop()
                    signs.rollback(mark)
            count[iL] -= 1
            count[iR] -= 1


def _free_points(sides: list[_Side], fixed: list[int | None], count: list[int]) -> tuple[int, int]:
    """The points placed so far on edges not yet numbered, on each axis of ``B`` (an edge on
    two sides counts once)."""
    most: dict[int, tuple[int, int]] = {}
    for i, side in enumerate(sides):
        if fixed[i] is None:
            most[side.edge] = (side.axis, max(most.get(side.edge, (0, 0))[1], count[i]))
    out = [0, 0]
    for axis, m in most.values():
        out[axis] += m
    return out[0], out[1]


def _within(placed: tuple[int, int], cap: tuple[int, int]) -> bool:
    return placed[0] <= cap[0] and placed[1] <= cap[1]


def _close(sides: list[_Side], fixed: list[int | None], count: list[int], lefts: list[int],
           rights: list[int], cap: tuple[int, int]
           ) -> tuple[dict[int, int], tuple[_Chord, ...], tuple] | None:
    """The points and chords of a closed walk, or ``None`` when its counts miss the edges
    already numbered, the cap, or an edge the region has on two sides."""
    if any(m is not None and m != c for m, c in zip(fixed, count, strict=True)):
        return None
    counts: dict[int, int] = {}
    for i, side in enumerate(sides):
        if fixed[i] is None and counts.setdefault(side.edge, count[i]) != count[i]:
            return None
    if not _within(_free_points(sides, fixed, count), cap):
        return None
    # ranks along each side, in the boundary's forward order: the left ends, then the right ones
    seq = lefts + rights[::-1]
    rank = [0] * len(seq)
    on = [0] * len(sides)
    for q, i in enumerate(seq):
        rank[q] = on[i]
        on[i] += 1
    ends = []
    for q, i in enumerate(seq):
        side = sides[i]
        j = count[i] - 1 - rank[q] if side.reverse else rank[q]
        ends.append((side.edge, j, side.reverse))
    k = len(lefts)
    chords = tuple((ends[q], ends[len(seq) - 1 - q]) for q in range(k))
    return counts, chords, tuple(sorted(chords))


def _piece(sides: list[_Side], subsides: list[int], chords: int) -> list[tuple[int, int, int]] | None:
    """The parity constraints of one piece (a corner), or ``None`` when it cannot be one:
    ``subsides`` indexes the region's sides it has pieces of, ``chords`` its third-axis sides."""
    total = len(subsides) + chords
    if not 3 <= total <= 6:
        return None
    of_axis: list[list[_Side]] = [[], []]
    for i in subsides:
        of_axis[sides[i].axis].append(sides[i])
    if len(of_axis[0]) > 2 or len(of_axis[1]) > 2:
        return None
    if len({sides[i].loop for i in subsides}) < len(subsides):
        return None
    return [(p.loop, q.loop, -p.forward * q.forward) for p, q in (pair for pair in of_axis if len(pair) == 2)]


def _build(base: TorusArrangement, points: dict[int, int], chords: list[list[_Chord]]
           ) -> tuple[tuple[int, ...], tuple[int, ...]] | None:
    """The whole arrangement (``twin``, ``layer``) from the points and chords, or ``None`` when
    a third-axis loop crosses one region twice."""
    n0 = len(base.twin)
    index: dict[tuple[int, int], int] = {}
    for e in sorted(points):
        for j in range(points[e]):
            index[(e, j)] = len(index)
    twin = list(base.twin) + [0] * (4 * len(index))
    layer = [0] * n0 + [0] * (4 * len(index))
    for e, m in points.items():
        if not m:
            continue
        darts = [e] + [x for j in range(m) for x in (n0 + 4 * index[(e, j)] + 2, n0 + 4 * index[(e, j)])] \
            + [base.twin[e]]
        for x, y in zip(darts[0::2], darts[1::2], strict=True):  # along the edge, point by point
            twin[x], twin[y] = y, x
    for region_chords in chords:
        for chord in region_chords:
            # the dart into the region: left of the edge's numbering direction, or right
            dx, dy = (n0 + 4 * index[(e, j)] + (3 if reverse else 1) for e, j, reverse in chord)
            twin[dx], twin[dy] = dy, dx
            layer[dx] = layer[dy] = 1
    # each third-axis loop crosses each region once: no two chords of a region on one loop
    seen = DisjointSets(range(len(index)))
    for region_chords in chords:
        for one, other in region_chords:
            seen.union(index[one[:2]], index[other[:2]])
    for region_chords in chords:
        roots = [seen.find(index[one[:2]]) for one, _ in region_chords]
        if len(set(roots)) < len(roots):
            return None
    return tuple(twin), tuple(layer)

