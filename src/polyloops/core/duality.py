"""Theorems 1 and 2: from a polycube to its loop structure and back.

Both directions keep the map, so corner ids survive a round trip:

>>> from polyloops.io.examples import load_example
>>> q = load_example("l-shape")
>>> ls = dualize(q)
>>> dualize(primalize(ls)) == ls
True
>>> is_order_equivalent(primalize(ls), q) is not None
True
"""

from __future__ import annotations

from collections import deque

from polyloops.core.arrays import use_arrays
from polyloops.core.directions import Axis
from polyloops.core.errors import PolyloopsError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.core.zones import find_directed_cycle, level_arcs, topological_order


class DualityError(PolyloopsError, ValueError):
    """The input is not valid enough for the requested construction."""


def dualize(q: Polycube) -> LoopStructure:
    """The oriented loop structure of a polycube (Theorem 1).

    Each loop is labelled with the axis of the edges it crosses, and its ``+`` side holds their
    ends with the higher coordinate.

    Parameters
    ----------
    q:
        A polycube; Definition 1 is not checked here (use :func:`polyloops.verify.verify`).

    Returns
    -------
    LoopStructure
        Oriented, on the same quad map (corner and face ids kept).

    Raises
    ------
    DualityError
        When the edges of one loop are not parallel or not consistently signed, which happens
        exactly when some face is not an axis-aligned rectangle.

    >>> from polyloops.io.examples import load_example
    >>> ls = dualize(load_example("l-shape"))
    >>> ls.oriented, [ls.axes.count(a) for a in Axis]
    (True, [2, 2, 1])
    """
    m = q.map
    if use_arrays(m.num_darts):
        found = _dualize_arrays(q)
        if found is not None:
            return found
    axes: list[Axis] = []
    signs: list[int] = []
    for lp in m.loop_system.loops:
        seen = {q.direction(d) for d in lp.darts}
        if len(seen) != 1 or None in seen:
            u, v = m.edge_corners(lp.edges[0])
            raise DualityError(f"the loop through edge ({u}, {v}) crosses edges that are "
                               "not parallel and equally directed; some face is not a rectangle")
        (d,) = seen
        assert d is not None
        axes.append(d.axis)
        signs.append(d.sign)
    return LoopStructure(m, tuple(axes), tuple(signs))


def _dualize_arrays(q: Polycube) -> LoopStructure | None:
    """:func:`dualize` on arrays; ``None`` when some loop's edges disagree (the tuple code
    then raises with the loop named)."""
    import numpy as np

    from polyloops.core.arrays import per_loop, points_array

    m = q.map
    a = m.arrays
    system = m.loop_system
    walked = np.flatnonzero(system.side_array > 0)
    p = points_array(q.positions)
    step = p[a.target[walked]] - p[a.origin[walked]]
    moved = step != 0
    if np.any(moved.sum(axis=1) != 1):
        return None
    axis = moved.argmax(axis=1)
    code = 2 * axis + (step[np.arange(len(step)), axis] < 0)
    low = per_loop(system.loop_array[walked], code, len(system.loops))
    if low is None:
        return None
    return LoopStructure(m, tuple(Axis(x) for x in (low // 2).tolist()), tuple((1 - 2 * (low % 2)).tolist()))


def zone_levels(ls: LoopStructure, axis: Axis) -> list[int]:
    """Each zone's level: the length of the longest path into it in the level graph.

    Raises :class:`DualityError` naming a cycle if the level graph has one.
    """
    if ls.signs is None:
        raise ValueError("a labelled loop structure has no level graphs; orient it first")
    zones = ls.zones(axis)
    arcs = level_arcs(ls, axis)
    succ: list[list[int]] = [[] for _ in range(zones.count)]
    for minus, plus, _ in arcs:
        succ[minus].append(plus)
    order = topological_order(succ)
    if order is None:
        cycle = find_directed_cycle(zones.count, arcs) or []
        raise DualityError(f"the {axis}-graph has a cycle through zones {[u for u, *_ in cycle]}")
    level = [0] * zones.count  # each zone one above the highest zone with an arc into it
    for z in order:
        for w in succ[z]:
            level[w] = max(level[w], level[z] + 1)
    return level


def primalize(ls: LoopStructure) -> Polycube:
    """The polycube of Theorem 2, compact: each zone at its longest-path level.

    Corner ``c`` gets position ``(x, y, z)`` from the levels of its X-, Y- and Z-zones, so
    coordinates start at 0 without gaps.

    Parameters
    ----------
    ls:
        An oriented loop structure with quad faces and acyclic level graphs.  The other
        conditions of Definition 4 are not checked, so an invalid structure can give a mesh that
        is not a polycube (the Definition-1 checker will say so).

    Returns
    -------
    Polycube
        On the same quad map as ``ls``.

    Raises
    ------
    DualityError
        When ``ls`` has no sides, or a level graph has a cycle (named in the message).

    >>> from polyloops.io.examples import load_example
    >>> q = load_example("l-shape")
    >>> is_order_equivalent(primalize(dualize(q)), q) is not None
    True
    """
    if not ls.oriented:
        raise DualityError("a labelled loop structure has no polycube; orient it first")
    levels = [zone_levels(ls, a) for a in Axis]
    zone_of = [ls.zones(a).zone_of for a in Axis]
    if use_arrays(ls.map.num_darts):
        import numpy as np

        from polyloops.core.arrays import as_array

        columns = [np.asarray(levels[a], dtype=np.int64)[as_array(zone_of[a])].tolist() for a in Axis]
        return Polycube(ls.map, tuple(zip(*columns, strict=True)))
    positions = tuple(
        (levels[0][zone_of[0][c]], levels[1][zone_of[1][c]], levels[2][zone_of[2][c]])
        for c in range(ls.map.num_corners)
    )
    return Polycube(ls.map, positions)


Relation = tuple[int, int, int]


def _dart_relations(q: Polycube) -> list[Relation]:
    """Per dart, the sign of the coordinate change along each axis: the three orders."""
    m, pos = q.map, q.positions

    def sgn(a: int) -> int:
        return (a > 0) - (a < 0)

    out = []
    for d in range(m.num_darts):
        a, b = pos[m.origin(d)], pos[m.target(d)]
        out.append((sgn(b[0] - a[0]), sgn(b[1] - a[1]), sgn(b[2] - a[2])))
    return out


def _extend(p: Polycube, q: Polycube, dp: list[Relation], dq: list[Relation],
            root_p: int, root_q: int) -> list[int] | None:
    """Extend ``root_p -> root_q`` to a direction-preserving map isomorphism."""
    mp, mq = p.map, q.map
    phi = [-1] * mp.num_darts
    used = [False] * mq.num_darts
    phi[root_p], used[root_q] = root_q, True
    todo = deque([root_p])
    while todo:
        a = todo.popleft()
        b = phi[a]
        for a2, b2 in ((mp.next[a], mq.next[b]), (mp.twin[a], mq.twin[b])):
            if phi[a2] < 0:
                if used[b2] or dp[a2] != dq[b2]:
                    return None
                phi[a2], used[b2] = b2, True
                todo.append(a2)
            elif phi[a2] != b2:
                return None
    corner = [-1] * mp.num_corners
    for a, b in enumerate(phi):
        if b < 0:
            return None
        u, v = mp.origin(a), mq.origin(b)
        if corner[u] not in (-1, v):
            return None
        corner[u] = v
    return corner


def is_order_equivalent(p: Polycube, q: Polycube) -> list[int] | None:
    """Definition 2: a mesh isomorphism preserving the order of every edge's ends on each axis.

    The isomorphism may reverse orientation, so a polycube is order-equivalent to its inverse.
    The cost is ``O(E)`` per candidate image of one dart, ``O(E^2)`` at worst.

    Parameters
    ----------
    p, q:
        Two polycubes.

    Returns
    -------
    list[int] or None
        The corner map ``f`` (``f[v]`` is the corner of ``q`` matched with corner ``v`` of
        ``p``), or ``None`` when they are not order-equivalent.

    Raises
    ------
    AttributeError
        When ``p`` or ``q`` is a loop structure (it has no positions to order).

    >>> from polyloops.io.examples import load_example
    >>> q = load_example("box-2x1x1")
    >>> is_order_equivalent(q, q.inverse()) is not None, is_order_equivalent(q, load_example("cube"))
    (True, None)
    """
    mp, mq = p.map, q.map
    if (mp.num_corners, mp.num_edges, mp.num_faces) != (mq.num_corners, mq.num_edges, mq.num_faces):
        return None
    dp = _dart_relations(p)
    for target in (q, q.inverse()):
        dq = _dart_relations(target)
        # Try the identity first: the common case after a round trip.
        candidates = [0] + [b for b in range(mq.num_darts) if b != 0 and dq[b] == dp[0]]
        for b in candidates:
            if dq[b] == dp[0]:
                found = _extend(p, target, dp, dq, 0, b)
                if found is not None:
                    return found
    return None
