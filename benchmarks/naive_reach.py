"""A naive breadth-first search of the move graph, the reference that benchmarks/reach.py
measures polyloops' search against.

It uses none of polyloops' move tests.  Each state is rebuilt from its signature; every simple
cycle of its corner graph short enough for the corner bound is tried as a new loop of each axis
in both directions, every loop is tried for removal, and each result that is a loop structure at
all is checked from scratch against Definition 4 (``check_polycube_loop_structure``) and named
by its signature.  So it finds the same states (``tests/test_reach.py`` compares the two), at
the price of trying every cycle and re-checking every child.
"""

from __future__ import annotations

import networkx as nx

from polyloops.core.canonical import from_signature, signature
from polyloops.core.directions import Axis
from polyloops.core.errors import PolyloopsError
from polyloops.core.moves import Addition, add_loop, remove_loop
from polyloops.core.structure import LoopStructure
from polyloops.verify import check_polycube_loop_structure


def children(ls: LoopStructure, max_corners: int) -> set[str]:
    """The signatures (mode ``labelled``) of every polycube loop structure one move away."""
    out: set[str] = set()
    room = max_corners - ls.map.num_corners
    tried: list[LoopStructure] = []
    if room >= 3:
        m = ls.map
        graph = nx.Graph((m.origin(d), m.target(d)) for d in m.edge_darts)
        for cycle in nx.simple_cycles(graph, length_bound=room):
            for walk in (cycle, cycle[::-1]):
                for axis in Axis:
                    try:
                        tried.append(add_loop(ls, Addition(axis, tuple(walk))))
                    except (PolyloopsError, KeyError):
                        continue
    for lp in ls.loops:
        try:
            tried.append(remove_loop(ls, lp.id))
        except PolyloopsError:
            continue
    for child in tried:
        if child.map.num_corners <= max_corners and check_polycube_loop_structure(child).valid:
            out.add(signature(child, "labelled"))
    return out


def naive_explore(start: LoopStructure, max_corners: int) -> dict[int, int]:
    """States (up to renumbering) reachable from ``start`` within ``max_corners``, by corners."""
    first = signature(start, "labelled")
    seen = {first}
    frontier = [first]
    while frontier:
        nxt = []
        for sig in frontier:
            for child in children(from_signature(sig), max_corners):
                if child not in seen:
                    seen.add(child)
                    nxt.append(child)
        frontier = nxt
    counts: dict[int, int] = {}
    for sig in seen:
        n = from_signature(sig).map.num_corners
        counts[n] = counts.get(n, 0) + 1
    return dict(sorted(counts.items()))
