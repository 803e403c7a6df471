"""The plain breadth-first detour search: every neighbour of every state of a level, in the
order :func:`polyloops.reach.search.neighbours` gives them, the goal tested on each child as it
comes. The twin of :func:`polyloops.reach.conjecture.find_detour`, which tries a level's
removals before building its additions."""

from __future__ import annotations

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
    n = ls.map.num_corners
    seen = {canonical_form(ls, "full").signature}
    level: list[tuple[LoopStructure, list[Move]]] = [(ls, [])]
    while level:
        nxt = []
        for current, moves in level:
            for move, child in plain_neighbours(current, max_corners):
                if child.map.num_corners < n:
                    return [*moves, move]
                s = canonical_form(child, "full").signature
                if s == target:
                    return [*moves, move]
                if s not in seen:
                    seen.add(s)
                    nxt.append((child, [*moves, move]))
        level = nxt
    return None
