"""The plain breadth-first detour search: every neighbour of every state of a level, in the
order :func:`polyloops.reach.search.neighbours` gives them, the goal tested on each child as it
comes. The twin of :func:`polyloops.reach.conjecture.find_detour`, which tries a level's
removals before building its additions."""

from __future__ import annotations

from collections import deque

from polyloops.core.canonical import canonical_form
from polyloops.core.moves import check_removal, remove_loop
from polyloops.core.structure import LoopStructure
from polyloops.reach.search import Move, MoveKind, neighbours


def plain_neighbours(ls: LoopStructure, max_corners: int):
    """Additions as :func:`neighbours` gives them, then removals tested loop by loop with
    :func:`check_removal` (not the array test :func:`removals` uses)."""
    yield from neighbours(ls, max_corners, (MoveKind.ADD,))
    for lp in ls.loops:
        if check_removal(ls, lp.id).valid:
            yield Move.remove(lp.id), remove_loop(ls, lp.id, checked=False)


def plain_detour(ls: LoopStructure, max_corners: int, target: str | None = None) -> list[Move] | None:
    """Breadth first with one FIFO queue; a child is the goal when it has fewer corners than
    ``ls`` or is the ``target`` class, tested as it is generated."""
    n = ls.map.num_corners
    queue = deque([(ls, ())])
    seen = {canonical_form(ls, "full").signature}
    while queue:
        current, path = queue.popleft()
        for move, child in plain_neighbours(current, max_corners):
            key = canonical_form(child, "full").signature
            if child.map.num_corners < n or key == target:
                return [*path, move]
            if key not in seen:
                seen.add(key)
                queue.append((child, (*path, move)))
    return None
