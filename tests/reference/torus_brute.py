"""The slow twin of the torus search: every 4-regular map, by brute force.

An independent and plainly complete enumeration for small sizes, sharing no code with
:mod:`polyloops.generate.torus.search`.  A connected 4-regular map with ``n`` vertices is a pairing of
its ``4 n`` darts (each vertex's four darts in counter-clockwise order).  Numbered breadth first
from a root dart (a vertex's darts in rotation order from the dart by which it is first
reached), every rooted map has exactly one numbering, and the numberings are exactly the
pairings made by taking the least unpaired dart and pairing it with an unpaired dart of a
vertex reached already, or with the first dart of the next vertex.  Each map is then kept once
by the least code over all roots and both orientations.  The maps of genus 1 whose
straight-ahead walks are simple closed curves are the cellular arrangements of simple loops on
the torus.

>>> [len(torus_maps_by_brute_force(n)) for n in (1, 2, 3)]
[1, 2, 5]
"""

from __future__ import annotations

from collections.abc import Iterator

__all__ = ["rooted_maps", "surface_maps_by_brute_force", "torus_maps_by_brute_force"]


def rooted_maps(n: int) -> Iterator[list[int]]:
    """Every connected rooted 4-regular map with ``n`` vertices, as its pairing of darts in the
    breadth-first numbering from the root (dart 0)."""
    pair = [-1] * (4 * n)

    def extend(reached: int) -> Iterator[list[int]]:
        d = next((e for e in range(4 * n) if pair[e] < 0), None)
        if d is None:
            yield list(pair)
            return
        if d // 4 >= reached:
            return  # a vertex not reached when its darts are read: not breadth first
        for e in range(d + 1, 4 * reached):
            if pair[e] < 0:
                pair[d], pair[e] = e, d
                yield from extend(reached)
                pair[d] = pair[e] = -1
        if reached < n:
            e = 4 * reached
            pair[d], pair[e] = e, d
            yield from extend(reached + 1)
            pair[d] = pair[e] = -1

    yield from extend(1)


def _turn(d: int, k: int) -> int:
    return 4 * (d // 4) + (d + k) % 4


def _genus(pair: list[int]) -> int:
    darts = len(pair)
    seen = [False] * darts
    faces = 0
    for d in range(darts):
        if not seen[d]:
            faces += 1
            e = d
            while not seen[e]:
                seen[e] = True
                e = _turn(pair[e], 3)
    vertices, edges = darts // 4, darts // 2
    return (2 - (vertices - edges + faces)) // 2


def _simple_loops(pair: list[int]) -> bool:
    """Whether the two straight lines through every vertex belong to different walks."""
    walk = [-1] * len(pair)
    count = 0
    for d in range(len(pair)):
        if walk[d] < 0:
            e = d
            while walk[e] < 0:
                walk[e] = walk[pair[e]] = count
                e = _turn(pair[e], 2)
            count += 1
    return all(walk[4 * v] != walk[4 * v + 1] for v in range(len(pair) // 4))


def _code_from(pair: list[int], root: int, step: int) -> tuple[int, ...]:
    """The breadth-first code from ``root``, turning ``step`` (1: counter-clockwise, 3: the
    mirror image) around each vertex."""
    num: dict[int, int] = {}
    order: list[int] = []

    def reach(t: int) -> None:
        for k in range(4):
            u = 4 * (t // 4) + (t % 4 + k * step) % 4
            num[u] = len(order)
            order.append(u)

    reach(root)
    code = []
    i = 0
    while i < len(order):
        t = pair[order[i]]
        if t not in num:
            reach(t)
        code.append(num[t])
        i += 1
    return tuple(code)


def _least_code(pair: list[int]) -> tuple[int, ...]:
    """The least code over every root and both orientations."""
    return min(_code_from(pair, root, step) for step in (1, 3) for root in range(len(pair)))


def surface_maps_by_brute_force(n: int, genus: int) -> set[tuple[int, ...]]:
    """The cellular arrangements of simple loops on the surface of ``genus`` with ``n``
    crossings, each as its least code (a set: one element an arrangement up to homeomorphism)."""
    return {_least_code(p) for p in rooted_maps(n) if _genus(p) == genus and _simple_loops(p)}


def torus_maps_by_brute_force(n: int) -> set[tuple[int, ...]]:
    """:func:`surface_maps_by_brute_force` on the torus."""
    return surface_maps_by_brute_force(n, 1)
