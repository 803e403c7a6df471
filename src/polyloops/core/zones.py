"""Zones, level graphs and zone genera.

The ``Delta``-zones partition the corners: two corners are in one zone when a
path of edges not crossed by ``Delta``-loops joins them.  The ``Delta``-graph
(level graph) has a node per zone and an arc per ``Delta``-loop, from the zone
on its ``-`` side to the zone on its ``+`` side.

A zone, as a piece of the surface cut along the ``Delta``-loops, retracts onto
its corners, its non-``Delta`` edges and the faces that no ``Delta``-loop
crosses.  With ``chi = V - E + F`` of that complex and ``b`` the number of
``Delta``-loop sides on its boundary, its genus is ``(2 - b - chi) / 2``.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass
from typing import TYPE_CHECKING

from polyloops.core.directions import Axis
from polyloops.core.disjoint_sets import DisjointSets

if TYPE_CHECKING:
    import networkx as nx

    from polyloops.core.structure import LoopStructure


@dataclass(frozen=True)
class Zones:
    """The zones of one axis: ``zone_of[corner]``, zones numbered by their lowest corner."""

    axis: Axis
    zone_of: tuple[int, ...]
    count: int
    # For each loop of this axis: (zone of its left side, zone of its right side)
    # with respect to the loop's stored walk.
    sides: dict[int, tuple[int, int]]
    genera: tuple[int, ...]

    def members(self) -> list[list[int]]:
        """The corners of each zone."""
        out: list[list[int]] = [[] for _ in range(self.count)]
        for c, z in enumerate(self.zone_of):
            out[z].append(c)
        return out

    @property
    def total_genus(self) -> int:
        """Gamma of Theorem 3: the sum of the genera of the zones."""
        return sum(self.genera)


def compute_zones(ls: LoopStructure, axis: Axis) -> Zones:
    """The ``axis``-zones of a structure (array kernels from :data:`~polyloops.core.arrays.LARGE` darts
    on)."""
    from polyloops.core.arrays import use_arrays

    if use_arrays(ls.map.num_darts):
        return _compute_zones_arrays(ls, axis)
    return _compute_zones_tuples(ls, axis)


def dart_axes(ls: LoopStructure):
    """The axis of every dart's loop, as an array."""
    codes = ls.direction_codes
    return codes // 2 if ls.oriented else codes


def _compute_zones_arrays(ls: LoopStructure, axis: Axis) -> Zones:
    """:func:`compute_zones` with components and counts on arrays."""
    import numpy as np

    from polyloops.core.arrays import components

    m = ls.map
    a = m.arrays
    axis_of = dart_axes(ls)
    lower = a.edge_darts
    keep = lower[axis_of[lower] != axis]
    count, zone_of = components(m.num_corners, a.origin[keep], a.target[keep])
    mine = [lp.id for lp in m.loop_system.loops if ls.axes[lp.id] == axis]
    first = np.fromiter((m.loop_system.loops[k].darts[0] for k in mine), dtype=np.int64, count=len(mine))
    left, right = zone_of[a.origin[first]], zone_of[a.target[first]]
    sides = dict(zip(mine, zip(left.tolist(), right.tolist(), strict=True), strict=True))
    boundary = np.bincount(left, minlength=count) + np.bincount(right, minlength=count)
    zone_list = zone_of.tolist()
    crossed = np.zeros(m.num_faces, dtype=bool)
    crossed[a.face_of[axis_of == axis]] = True
    first_corner = a.origin[a.face_start]
    chi = (np.bincount(zone_of, minlength=count)
           - np.bincount(zone_of[a.origin[keep]], minlength=count)
           + np.bincount(zone_of[first_corner[~crossed]], minlength=count))
    genera = tuple(((2 - boundary - chi) // 2).tolist())
    return Zones(axis, tuple(zone_list), count, sides, genera)


def _compute_zones_tuples(ls: LoopStructure, axis: Axis) -> Zones:
    m = ls.map
    system = m.loop_system
    parts = DisjointSets(range(m.num_corners))
    for d in m.edge_darts:
        if ls.axes[system.loop_of_dart[d]] != axis:
            parts.union(m.origin(d), m.target(d))
    # Number zones by their lowest corner.
    label: dict[int, int] = {}
    zone_of = [label.setdefault(parts[c], len(label)) for c in range(m.num_corners)]
    count = len(label)

    sides: dict[int, tuple[int, int]] = {}
    boundary = [0] * count
    for lp in system.loops:
        if ls.axes[lp.id] == axis:
            d = lp.darts[0]
            left, right = zone_of[m.origin(d)], zone_of[m.target(d)]
            sides[lp.id] = (left, right)
            boundary[left] += 1
            boundary[right] += 1

    chi = [0] * count
    for c in range(m.num_corners):
        chi[zone_of[c]] += 1
    for d in m.edge_darts:
        if ls.axes[system.loop_of_dart[d]] != axis:
            chi[zone_of[m.origin(d)]] -= 1
    for f in range(m.num_faces):
        if all(ls.axes[i] != axis for i in system.loops_of_face(m, f)):
            chi[zone_of[m.faces[f][0]]] += 1
    genera = tuple((2 - boundary[z] - chi[z]) // 2 for z in range(count))
    return Zones(axis, tuple(zone_of), count, sides, genera)


def topological_order(successors: list[list[int]]) -> list[int] | None:
    """Nodes ``0..n-1`` in an order where every arc goes forward (Kahn), or ``None`` when
    the graph has a cycle; ``successors[z]`` lists the heads of the arcs leaving ``z``.

    >>> topological_order([[1], [2], []]), topological_order([[1], [0]])
    ([0, 1, 2], None)
    """
    indegree = [0] * len(successors)
    for heads in successors:
        for w in heads:
            indegree[w] += 1
    ready = [z for z in range(len(successors)) if indegree[z] == 0]
    order = []
    while ready:
        z = ready.pop()
        order.append(z)
        for w in successors[z]:
            indegree[w] -= 1
            if indegree[w] == 0:
                ready.append(w)
    return order if len(order) == len(successors) else None


def find_directed_cycle(n: int, arcs: list[tuple[int, int, int]]) -> list[tuple[int, int, int]] | None:
    """A directed cycle among ``arcs`` on nodes ``0..n-1`` (iterative DFS), or ``None``.

    The kernel's one cycle finder: level graphs, orientation solvers and segmentations all
    ask it.  An arc is ``(tail, head, key)``; the cycle comes back as its arcs, in order.

    >>> find_directed_cycle(3, [(0, 1, 7), (1, 2, 8), (2, 1, 9)])
    [(1, 2, 8), (2, 1, 9)]
    >>> find_directed_cycle(3, [(0, 1, 7), (1, 2, 8)]) is None
    True
    """
    out: list[list[tuple[int, int, int]]] = [[] for _ in range(n)]
    for arc in arcs:
        out[arc[0]].append(arc)
    state = [0] * n  # 0 new, 1 on stack, 2 done
    for start in range(n):
        if state[start]:
            continue
        stack: list[tuple[int, int]] = [(start, 0)]
        via: list[tuple[int, int, int]] = []
        state[start] = 1
        while stack:
            u, i = stack[-1]
            if i < len(out[u]):
                stack[-1] = (u, i + 1)
                arc = out[u][i]
                w = arc[1]
                if state[w] == 1:
                    # The cycle: arcs on the stack from w, then this arc.
                    nodes = [x for x, _ in stack]
                    j = nodes.index(w)
                    return [*via[j:], arc]
                if state[w] == 0:
                    state[w] = 1
                    stack.append((w, 0))
                    via.append(arc)
            else:
                state[u] = 2
                stack.pop()
                if via:
                    via.pop()
    return None


def level_arcs(ls: LoopStructure, axis: Axis) -> list[tuple[int, int, int]]:
    """The arcs of the ``axis``-graph as ``(minus zone, plus zone, loop)``."""
    if ls.signs is None:
        raise ValueError("a labelled loop structure has no level graphs; orient it first")
    signs = ls.signs
    return [(left, right, loop) if signs[loop] > 0 else (right, left, loop)
            for loop, (left, right) in ls.zones(axis).sides.items()]


def level_graph(ls: LoopStructure, axis: Axis) -> nx.MultiDiGraph:
    """The ``axis``-graph: arcs keyed by loop id, from the ``-`` zone to the ``+`` zone."""
    if ls.signs is None:
        raise ValueError("a labelled loop structure has no level graphs; orient it first")
    import networkx as nx

    g = nx.MultiDiGraph(axis=str(axis))
    g.add_nodes_from(range(ls.zones(axis).count))
    g.add_edges_from(level_arcs(ls, axis))
    return g


# -- level arcs, shared by the removal tests (core.moves and its array twin core.removal_arrays) --

class LevelArcs:
    """Each axis's level graph as successor lists, built once for many removal tests, and
    which arcs have another path between their ends (contracting those closes a cycle)."""

    def __init__(self, ls: LoopStructure):
        self.ls = ls
        self._succ: dict[Axis, dict[int, list[tuple[int, int]]]] = {}
        self._bypassed: dict[Axis, set[int] | None] = {}

    def bypassed(self, axis: Axis) -> set[int] | None:
        """The loops whose arc ``u -> v`` is not the only path from ``u`` to ``v`` (a parallel
        arc, or a path through another successor of ``u``); ``None`` when the graph has a
        cycle already.  Reachability as bit sets, in reverse topological order: one pass."""
        if axis not in self._bypassed:
            succ = self.successors(axis)
            count = self.ls.zones(axis).count
            order = topological_order([[w for w, _ in succ.get(z, ())] for z in range(count)])
            if order is None:
                self._bypassed[axis] = None
                return None
            reach = [0] * self.ls.zones(axis).count  # zones reachable by a path of one arc or more
            for z in reversed(order):
                r = 0
                for w, _ in succ.get(z, ()):
                    r |= reach[w] | (1 << w)
                reach[z] = r
            out = set()
            for arcs in succ.values():
                heads = [w for w, _ in arcs]
                for i, (v, loop) in enumerate(arcs):
                    others = heads[:i] + heads[i + 1:]
                    if v in others or any(reach[w] >> v & 1 for w in others):
                        out.add(loop)
            self._bypassed[axis] = out
        return self._bypassed[axis]

    def successors(self, axis: Axis) -> dict[int, list[tuple[int, int]]]:
        """zone -> [(next zone, loop)] along the arcs of ``axis``."""
        if axis not in self._succ:
            succ: dict[int, list[tuple[int, int]]] = defaultdict(list)
            for loop, (a, b) in self.ls.zones(axis).sides.items():
                tail, head = (a, b) if self.ls.signs[loop] > 0 else (b, a)  # type: ignore[index]
                succ[tail].append((head, loop))
            self._succ[axis] = succ
        return self._succ[axis]


def level_arcs_of(ls: LoopStructure) -> LevelArcs:
    """The level arcs of ``ls``, kept with it (as its cached zones are), so that callers
    testing loop after loop share them."""
    found = ls.__dict__.get("_level_arcs")
    if found is None:
        found = ls.__dict__["_level_arcs"] = LevelArcs(ls)
    return found


def closes_cycle(ls: LoopStructure, loop: int, arcs: LevelArcs) -> bool:
    """Whether contracting ``loop``'s arc closes a cycle of its level graph: another path
    joins the arc's ends (from the bit sets, when the graph is acyclic), or else a search from
    the merged zone returns to it."""
    axis = ls.axes[loop]
    bypassed = arcs.bypassed(axis)
    if bypassed is not None:
        return loop in bypassed
    left, right = ls.zones(axis).sides[loop]
    merged = {left, right}
    succ = arcs.successors(axis)
    stack = [z for start in merged for z, other in succ.get(start, ()) if other != loop]
    seen_zones: set[int] = set()
    while stack:
        z = stack.pop()
        if z in merged:
            return True
        if z not in seen_zones:
            seen_zones.add(z)
            stack.extend(head for head, _ in succ.get(z, ()))
    return False
