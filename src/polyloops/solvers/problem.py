"""The orientation problem of a labelled loop structure (the paper's "Orienting a labeled
loop structure").

Each loop ``l`` gets a sign ``s_l``: ``+1`` when its ``+`` side is on the right of its stored
walk.  Condition 3 of Definition 4 only involves loops of one axis: for two darts ``d1, d2``
leaving one corner across loops ``l1, l2`` of the same axis, the directions differ exactly
when ``s_l1 * s_l2 = -e1 * e2``, where ``e = +1`` if the corner lies on the left of the loop.
These constraints are the edges of the paper's **side graph**: a node per loop side, the two
sides of a loop joined, and two sides joined when they bound the same region.  Condition 3
can be met exactly when the side graph is bipartite; each of its ``k`` components is then a
free binary choice, ``2^k`` in all.  Condition 5 (acyclic level graphs) restricts the choices;
at genus 0 the level graphs are trees and every choice is acyclic.

>>> from polyloops.io.examples import load_example
>>> p = OrientationProblem(load_example("l-shape").dualize())
>>> p.k, [len(p.components_of(a)) for a in Axis]
(3, [1, 1, 1])
"""

from __future__ import annotations

import copy
from collections import defaultdict, deque
from dataclasses import dataclass
from functools import cached_property

from polyloops.core.directions import Axis
from polyloops.core.labellings import sign_system
from polyloops.core.loops import same_axis_meetings
from polyloops.core.structure import LoopStructure
from polyloops.core.zones import find_directed_cycle
from polyloops.verify.loop_structure import check_polycube_loop_structure

Side = tuple[int, str]  # (loop, "L" or "R")
Arc = tuple[int, int, int]  # (minus zone, plus zone, loop)


@dataclass(frozen=True)
class Component:
    """A component of one axis' side graph: its loops and each loop's sign relative to the first.

    Choosing ``c`` in ``{+1, -1}`` gives every member loop ``l`` the sign ``c * relative[l]``.
    """

    axis: Axis
    loops: tuple[int, ...]
    relative: tuple[int, ...]


@dataclass(frozen=True)
class OddCycle:
    """Sides that must alternate in colour around a cycle of odd length: Condition 3 fails."""

    axis: Axis
    sides: tuple[Side, ...]

    def describe(self) -> str:
        """The odd cycle in one sentence."""
        path = " - ".join(f"{loop}{side}" for loop, side in self.sides)
        return f"the {self.axis}-side graph has an odd cycle {path} (loop id + L/R side)"


class OrientationProblem:
    """Components, constraints and zones of one labelled loop structure."""

    def __init__(self, ls: LoopStructure):
        self.structure = ls.forget_orientation()
        self.num_loops = len(ls.loops)
        self.loops_of_axis = {a: [i for i, x in enumerate(ls.axes) if x == a] for a in Axis}
        self._side_edges = self._build_side_edges()
        self.components, self.odd_cycles = self._colour()
        # Zones on the left and right of each loop, in the zones of its own axis.
        self.loop_zones: dict[int, tuple[int, int]] = {}
        for a in Axis:
            self.loop_zones.update(self.structure.zones(a).sides)
        self.zone_counts = {a: self.structure.zones(a).count for a in Axis}
        self.checked_axes: tuple[Axis, ...] = tuple(Axis)
        self._base_signs = self._signs_with_all_plus()

    def _signs_with_all_plus(self) -> list[int]:
        signs = [1] * self.num_loops
        for comp in self.components:
            for loop, rel in zip(comp.loops, comp.relative, strict=True):
                signs[loop] = rel
        return signs

    # -- the side graph ---------------------------------------------------------------------
    def _build_side_edges(self) -> dict[Axis, list[tuple[Side, Side]]]:
        ls = self.structure
        edges: dict[Axis, list[tuple[Side, Side]]] = {a: [] for a in Axis}
        for i in range(self.num_loops):
            edges[ls.axes[i]].append(((i, "L"), (i, "R")))
        seen = set()
        for l1, e1, l2, e2 in same_axis_meetings(ls.map, ls.axes):
            a, b = (l1, "L" if e1 > 0 else "R"), (l2, "L" if e2 > 0 else "R")
            key = (min(a, b), max(a, b))
            if key not in seen:
                seen.add(key)
                edges[ls.axes[l1]].append(key)
        return edges

    def side_graph(self, axis: Axis):
        """The paper's graph on the sides of the ``axis``-loops, as a networkx Graph."""
        import networkx as nx

        g = nx.Graph()
        g.add_nodes_from((i, s) for i in self.loops_of_axis[axis] for s in "LR")
        g.add_edges_from(self._side_edges[axis])
        return g

    def _colour(self) -> tuple[list[Component], list[OddCycle]]:
        """The components of the kernel's parity system (:func:`~polyloops.core.labellings.sign_system`:
        a loop's sign relative to the lowest loop of its component), and for each axis whose
        constraints conflict, an odd cycle of its side graph as a witness."""
        ls = self.structure
        system = sign_system(ls.map, ls.axes)
        components = [Component(ls.axes[comp[0][0]], tuple(loop for loop, _ in comp),
                                tuple(sign for _, sign in comp)) for comp in system.components]
        odd_axes = sorted({ls.axes[a] for a, _, _ in system.conflicts})
        return components, [self._odd_cycle(axis) for axis in odd_axes]

    def _odd_cycle(self, axis: Axis) -> OddCycle:
        """An odd cycle of the side graph of ``axis`` (breadth-first 2-colouring)."""
        adjacency: dict[Side, list[Side]] = defaultdict(list)
        for u, v in self._side_edges[axis]:
            adjacency[u].append(v)
            adjacency[v].append(u)
        colour: dict[Side, int] = {}
        parent: dict[Side, Side | None] = {}
        for root_loop in self.loops_of_axis[axis]:
            root = (root_loop, "R")
            if root in colour:
                continue
            colour[root], parent[root] = 1, None
            queue = deque([root])
            while queue:
                u = queue.popleft()
                for v in adjacency[u]:
                    if v not in colour:
                        colour[v], parent[v] = -colour[u], u
                        queue.append(v)
                    elif colour[v] == colour[u]:
                        return OddCycle(axis, self._cycle(parent, u, v))
        raise AssertionError(f"the {axis}-constraints conflict, so their side graph has an odd cycle")

    @staticmethod
    def _cycle(parent: dict[Side, Side | None], u: Side, v: Side) -> tuple[Side, ...]:
        def path(x: Side) -> list[Side]:
            out = [x]
            while parent[out[-1]] is not None:
                out.append(parent[out[-1]])  # type: ignore[arg-type]
            return out

        pu, pv = path(u), path(v)
        on_pv = set(pv)
        lca = next(x for x in pu if x in on_pv)
        return tuple(pu[: pu.index(lca) + 1] + list(reversed(pv[: pv.index(lca)])))

    # -- views --------------------------------------------------------------------------------
    @property
    def k(self) -> int:
        """The number of free binary choices (side-graph components), over all axes."""
        return len(self.components)

    def components_of(self, axis: Axis) -> list[Component]:
        """The side-graph components of one axis."""
        return [c for c in self.components if c.axis == axis]

    @property
    def colourable(self) -> bool:
        """Whether Condition 3 can be met: the side graph is bipartite."""
        return not self.odd_cycles

    @cached_property
    def local_violations(self) -> list[str]:
        """Conditions no choice of sides can mend: 1, 2, and crossings (Condition 3)."""
        report = check_polycube_loop_structure(self.structure)
        return [f"condition {v.condition}: {v.message}" for v in report.violations]

    def signs_from_choices(self, choices: list[int] | tuple[int, ...]) -> tuple[int, ...]:
        """Loop signs from one ``+1/-1`` choice per component (in component order); loops of
        components outside a restricted problem take choice ``+1``."""
        signs = list(self._base_signs)
        for comp, c in zip(self.components, choices, strict=True):
            for loop, rel in zip(comp.loops, comp.relative, strict=True):
                signs[loop] = c * rel
        return tuple(signs)

    def arcs(self, signs: tuple[int, ...] | list[int], axis: Axis) -> list[tuple[int, int, int]]:
        """The ``axis``-graph under these signs: ``(minus zone, plus zone, loop)``."""
        out = []
        for loop in self.loops_of_axis[axis]:
            left, right = self.loop_zones[loop]
            out.append((left, right, loop) if signs[loop] > 0 else (right, left, loop))
        return out

    def find_cycle(self, signs: tuple[int, ...] | list[int]) -> tuple[Axis, list[Arc]] | None:
        """A directed cycle in some level graph under these signs, as arcs, or ``None``."""
        for axis in self.checked_axes:
            cycle = find_directed_cycle(self.zone_counts[axis], self.arcs(signs, axis))
            if cycle is not None:
                return axis, cycle
        return None

    def is_solution(self, signs: tuple[int, ...] | list[int]) -> bool:
        """Whether these signs leave every level graph acyclic."""
        return self.find_cycle(signs) is None

    # -- decomposition --------------------------------------------------------------------------
    def bridge_components(self, axis: Axis) -> list[Component]:
        """Components of ``axis`` all of whose loops are bridges of the undirected level graph.

        A bridge lies on no cycle, so flipping such a component never makes or breaks a
        directed cycle: each one doubles the number of solutions.  At genus 0 every loop is
        a bridge (the level graphs are trees).
        """
        import networkx as nx

        multiplicity: dict[tuple[int, int], int] = defaultdict(int)
        for loop in self.loops_of_axis[axis]:
            u, v = self.loop_zones[loop]
            multiplicity[(min(u, v), max(u, v))] += 1
        simple = nx.Graph(u_v for u_v in multiplicity if u_v[0] != u_v[1])
        bridges = {(min(u, v), max(u, v)) for u, v in nx.bridges(simple)}
        on_cycle = set()
        for loop in self.loops_of_axis[axis]:
            u, v = self.loop_zones[loop]
            key = (min(u, v), max(u, v))
            if u == v or multiplicity[key] > 1 or key not in bridges:
                on_cycle.add(loop)
        return [c for c in self.components_of(axis) if not on_cycle.intersection(c.loops)]

    def restricted(self, axis: Axis, components: list[Component]) -> OrientationProblem:
        """The same problem with only ``components`` free and only the ``axis``-graph checked."""
        sub = copy.copy(self)
        sub.components = list(components)
        sub.checked_axes = (axis,)
        return sub
