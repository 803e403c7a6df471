"""The polycube loop structures a quad map carries: labellings of its loops by axes and
choices of sides that satisfy Definition 4 (step 3 of the catalog, and how a file without axis
labels, such as plantri's planar code, is read).

Crossing loops get different axes (a proper 3-colouring of the crossing graph), and Condition 3
holds at every corner (a 2-colouring of the side graph of each axis, solved as parity
constraints; each component is a free choice).  Condition 5 holds at genus 0 and is checked at
positive genus; Conditions 1, 2 and 4 hold for every simple quadrangulation with minimum
degree 3.

>>> from polyloops.io.examples import load_example
>>> len(polycube_classes_on(load_example("cube").map))
1
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from itertools import product

from polyloops.core.canonical import canonical_form
from polyloops.core.directions import Axis
from polyloops.core.disjoint_sets import ParitySets
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.loops import same_axis_meetings
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import Symmetry

__all__ = ["MapStructureError", "SignSystem", "admits_polycube", "only_structure_on", "polycube_classes_on",
           "polycube_structures", "proper_colourings", "sign_components", "sign_system"]


def proper_colourings(adjacency: Sequence[set[int]], colours: int = 3) -> Iterator[list[int]]:
    """Every proper colouring with colours ``0 .. colours - 1`` (backtracking, most constrained
    first).

    >>> len(list(proper_colourings([{1}, {0, 2}, {1}], 2)))
    2
    """
    n = len(adjacency)
    order = sorted(range(n), key=lambda v: -len(adjacency[v]))
    colour = [-1] * n

    def extend(i: int) -> Iterator[list[int]]:
        if i == n:
            yield list(colour)
            return
        v = order[i]
        used = {colour[w] for w in adjacency[v]}
        for c in range(colours):
            if c not in used:
                colour[v] = c
                yield from extend(i + 1)
        colour[v] = -1

    yield from extend(0)


@dataclass(frozen=True)
class SignSystem:
    """Condition 3 of Definition 4 as parity constraints ``s_a * s_b = p`` between the signs of
    loops of one axis that meet at a corner: the components of the constraint graph (each a
    list of ``(loop, sign relative to its lowest loop)``, loops ascending, components by lowest
    loop), and the constraints that contradict those before them (``(a, b, p)``; none exactly
    when some choice of sides meets Condition 3).  The one home of this parity system: the
    catalog's labelling search and the orientation solvers both read it."""

    components: tuple[tuple[tuple[int, int], ...], ...]
    conflicts: tuple[tuple[int, int, int], ...]


def sign_system(m: HalfEdgeMap, axes: Sequence[int]) -> SignSystem:
    """The parity system of Condition 3 for loops labelled ``axes`` (see :class:`SignSystem`).

    >>> from polyloops.io.examples import load_example
    >>> cube = load_example("cube").dualize()
    >>> system = sign_system(cube.map, [int(a) for a in cube.axes])
    >>> [len(c) for c in system.components], system.conflicts
    ([1, 1, 1], ())
    """
    signs = ParitySets(range(len(m.loop_system.loops)))
    conflicts = []
    for l1, e1, l2, e2 in same_axis_meetings(m, axes):
        if not signs.relate(l1, l2, -e1 * e2):  # s_l1 * s_l2 = -e1 * e2
            conflicts.append((l1, l2, -e1 * e2))
    components = []
    for comp in signs.components():
        comp.sort()
        first = comp[0][1]
        components.append(tuple((loop, sign * first) for loop, sign in comp))
    return SignSystem(tuple(sorted(components)), tuple(conflicts))


def sign_components(m: HalfEdgeMap, axes: Sequence[int]) -> tuple[tuple[tuple[int, int], ...], ...] | None:
    """The components of :func:`sign_system`, or ``None`` when some constraint cycle is odd (no
    choice of sides meets Condition 3)."""
    system = sign_system(m, axes)
    return None if system.conflicts else system.components


def polycube_structures(m: HalfEdgeMap) -> Iterator[LoopStructure]:
    """Every polycube loop structure on a quad map (labelled and oriented).

    At genus 0 Condition 5 holds for every choice of sides (the paper's Corollary); at positive
    genus a choice is kept when every level graph is acyclic, and the map needs corners of
    degree 3 at least (Condition 2), which the catalog's generators of genus 0 guarantee.

    >>> from polyloops.io.examples import load_example
    >>> ring = load_example("ring").map
    >>> all(ls.map.genus == 1 for ls in polycube_structures(ring))
    True
    """
    system = m.loop_system
    if any(lp.self_crossings for lp in system.loops):
        return
    positive_genus = m.genus > 0
    if positive_genus and any(m.degree(c) < 3 for c in range(m.num_corners)):
        return
    adjacency: list[set[int]] = [set() for _ in system.loops]
    for f in range(m.num_faces):
        a, b = system.loops_of_face(m, f)
        adjacency[a].add(b)
        adjacency[b].add(a)
    for colouring in proper_colourings(adjacency):
        comps = sign_components(m, colouring)
        if comps is None:
            continue
        axes = tuple(Axis(c) for c in colouring)
        sides = [LoopStructure(m, axes).zones(axis).sides for axis in Axis] if positive_genus else []
        for choice in product((1, -1), repeat=len(comps)):
            signs = [0] * len(system.loops)
            for comp, c in zip(comps, choice, strict=True):
                for loop, rel in comp:
                    signs[loop] = c * rel
            if positive_genus and not all(_acyclic(by_loop, signs) for by_loop in sides):
                continue
            yield LoopStructure(m, axes, tuple(signs))


def admits_polycube(m: HalfEdgeMap, axes: Sequence[int]) -> bool:
    """Whether some choice of sides makes the loops labelled ``axes`` a polycube loop structure
    on ``m`` (Condition 3, and at positive genus acyclic level graphs: each axis's level graph
    depends only on its own loops' signs, so the axes are decided one at a time).

    >>> from polyloops.io.examples import load_example
    >>> ring = load_example("ring").dualize()
    >>> admits_polycube(ring.map, [int(a) for a in ring.axes])
    True
    """
    comps = sign_components(m, axes)
    if comps is None:
        return False
    if m.genus == 0:
        return True
    ls = LoopStructure(m, tuple(Axis(c) for c in axes))
    for axis in Axis:
        sides = ls.zones(axis).sides
        mine = [comp for comp in comps if axes[comp[0][0]] == int(axis)]
        signs = [0] * len(axes)
        for choice in product((1, -1), repeat=len(mine)):
            for comp, c in zip(mine, choice, strict=True):
                for loop, rel in comp:
                    signs[loop] = c * rel
            if _acyclic(sides, signs):
                break
        else:
            return False
    return True


def _acyclic(sides: dict[int, tuple[int, int]], signs: Sequence[int]) -> bool:
    """Whether the level graph with arcs ``sides[loop] = (left zone, right zone)`` oriented by
    ``signs`` (``+`` on the right) has no directed cycle (Condition 5); a loop with one zone on
    both sides is a cycle."""
    import networkx as nx

    g = nx.DiGraph()
    for loop, (left, right) in sides.items():
        if left == right:
            return False
        g.add_edge(*((left, right) if signs[loop] > 0 else (right, left)))
    return nx.is_directed_acyclic_graph(g)


def polycube_classes_on(m: HalfEdgeMap, mode: Symmetry | str = Symmetry.FULL) -> list[LoopStructure]:
    """One polycube loop structure on ``m`` (in ``m``'s own numbering) per class in a
    symmetry mode, in the order :func:`polycube_structures` meets them.

    >>> from polyloops.io.examples import load_example
    >>> len(polycube_classes_on(load_example("cube").map))
    1
    """
    found: dict[str, LoopStructure] = {}
    for ls in polycube_structures(m):
        found.setdefault(canonical_form(ls, mode).signature, ls)
    return list(found.values())


class MapStructureError(PolyloopsError, ValueError):
    """A map that carries no polycube loop structure, or several (``count`` says how many
    classes, up to all 48 symmetries)."""

    def __init__(self, message: str, count: int):
        super().__init__(message)
        self.count = count


def only_structure_on(m: HalfEdgeMap) -> LoopStructure:
    """The polycube loop structure a map carries, when it carries exactly one up to symmetry
    (how a file without axis labels, such as plantri's planar code, is read).

    Raises :class:`MapStructureError` when it carries none or several.

    >>> from polyloops.io.examples import load_example
    >>> only_structure_on(load_example("cube").map).map.num_corners
    8
    """
    odd = next((f for f, face in enumerate(m.faces) if len(face) != 4), None)
    if odd is not None:
        raise MapStructureError(f"not a quadrangulation (face {odd} has {len(m.faces[odd])} sides), so it "
                                "carries no polycube loop structure", 0)
    classes = polycube_classes_on(m)
    if len(classes) == 1:
        return classes[0]
    if not classes:
        raise MapStructureError("the map carries no polycube loop structure", 0)
    raise MapStructureError(f"planar code has no axis labels, and the map carries {len(classes)} "
                            "different polycube loop structures; give the one you mean as JSON or .graph",
                            len(classes))
