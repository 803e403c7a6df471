"""The catalog of genus-0 polycubes, up to order-equivalence, by number of corners.

For each quadrangulation from plantri that survives the batch filter (no self-crossing
loop), :func:`polycube_structures` finds every labelling and orientation that makes it a
polycube loop structure: crossing loops get different axes (a proper 3-colouring of the
crossing graph), and Condition 3 holds at every corner (a 2-colouring of the side graph of
each axis; each component is a free choice).  Condition 5 holds at genus 0 and Conditions 1,
2 and 4 hold for every simple quadrangulation with minimum degree 3.

Structures are then identified by signature in each symmetry mode.  plantri lists each map
once, mirror images identified, and signatures identify mirror images too, so structures on
different maps never coincide: classes are counted map by map.

>>> from polyloops.io.examples import load_example
>>> cube = load_example("cube").map
>>> classes = map_classes(cube)
>>> {str(mode): len(v) for mode, v in classes.items()}
{'labelled': 1, 'rotation': 1, 'full': 1}
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterator
from dataclasses import dataclass
from itertools import product
from typing import Any

from polyloops.core.canonical import CanonicalForm, canonical_form
from polyloops.core.corners import CATEGORIES, corner_histogram
from polyloops.core.directions import Axis
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.loops import same_axis_meetings
from polyloops.core.moves import removals
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import Symmetry

MODES = tuple(Symmetry)  # labelled, rotation, full


def _colourings(adjacency: list[set[int]]) -> Iterator[list[int]]:
    """Every proper colouring with colours 0, 1, 2 (backtracking, most constrained first)."""
    n = len(adjacency)
    order = sorted(range(n), key=lambda v: -len(adjacency[v]))
    colour = [-1] * n

    def extend(i: int) -> Iterator[list[int]]:
        if i == n:
            yield list(colour)
            return
        v = order[i]
        used = {colour[w] for w in adjacency[v]}
        for c in (0, 1, 2):
            if c not in used:
                colour[v] = c
                yield from extend(i + 1)
        colour[v] = -1

    yield from extend(0)


def _sign_choices(m: HalfEdgeMap, axes: list[int]) -> list[list[tuple[int, int]]] | None:
    """Condition 3 as parity constraints ``s_a * s_b = p``; the components of the constraint
    graph with each loop's sign relative to its component's root, or ``None`` if some
    constraint cycle is odd."""
    system = m.loop_system
    n = len(system.loops)
    parent = list(range(n))
    parity = [1] * n  # sign relative to parent

    def find(a: int) -> tuple[int, int]:
        p = 1
        while parent[a] != a:
            p *= parity[a]
            a = parent[a]
        return a, p

    for l1, e1, l2, e2 in same_axis_meetings(m, axes):
        want = -e1 * e2  # s_l1 * s_l2
        (r1, p1), (r2, p2) = find(l1), find(l2)
        if r1 == r2:
            if p1 * p2 != want:
                return None
        else:
            parent[r1], parity[r1] = r2, p1 * p2 * want
    groups: dict[int, list[tuple[int, int]]] = defaultdict(list)
    for loop in range(n):
        root, p = find(loop)
        groups[root].append((loop, p))
    return list(groups.values())


def polycube_structures(m: HalfEdgeMap) -> Iterator[LoopStructure]:
    """Every polycube loop structure on a genus-0 quad map (labelled and oriented)."""
    system = m.loop_system
    if any(lp.self_crossings for lp in system.loops):
        return
    adjacency: list[set[int]] = [set() for _ in system.loops]
    for f in range(m.num_faces):
        a, b = system.loops_of_face(m, f)
        adjacency[a].add(b)
        adjacency[b].add(a)
    for colouring in _colourings(adjacency):
        comps = _sign_choices(m, colouring)
        if comps is None:
            continue
        axes = tuple(Axis(c) for c in colouring)
        for choice in product((1, -1), repeat=len(comps)):
            signs = [0] * len(system.loops)
            for comp, c in zip(comps, choice, strict=True):
                for loop, rel in comp:
                    signs[loop] = c * rel
            yield LoopStructure(m, axes, tuple(signs))


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


@dataclass(frozen=True)
class CatalogRecord:
    """One polycube class in one symmetry mode."""

    signature: str
    corners: int
    faces: int
    loops: dict[str, int]
    categories: dict[str, int]
    automorphisms: int
    chiral: bool
    removable_loops: int  # loops whose removal leaves a polycube loop structure

    @property
    def irreducible(self) -> bool:
        """No loop can be removed: additions alone cannot build it (the cube is one too)."""
        return self.removable_loops == 0

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict: the record's fields and whether it is irreducible."""
        return {"signature": self.signature, "corners": self.corners, "faces": self.faces,
                "loops": self.loops, "corner_categories": self.categories,
                "automorphisms": self.automorphisms, "chiral": self.chiral,
                "removable_loops": self.removable_loops, "irreducible": self.irreducible}


def map_classes(m: HalfEdgeMap) -> dict[str, list[CatalogRecord]]:
    """The polycube classes on one map, in every symmetry mode."""
    labelled: dict[str, tuple[LoopStructure, CanonicalForm]] = {}
    for ls in polycube_structures(m):
        form = canonical_form(ls, "labelled")
        labelled.setdefault(form.signature, (ls, form))
    out: dict[str, dict[str, CatalogRecord]] = {mode: {} for mode in MODES}
    for ls, form in labelled.values():
        full = canonical_form(ls, "full")
        chiral = not full.achiral
        forms = {"labelled": form, "rotation": canonical_form(ls, "rotation"), "full": full}
        _, categories, _ = corner_histogram(ls)
        removable = len(removals(ls))  # the same for every image under a symmetry
        for mode, form in forms.items():
            key = form.signature
            if key not in out[mode]:
                # Symmetries permute the axes: count loops on the class's own representative,
                # the structure its signature names, not on the one met first.
                rep = ls if mode == "labelled" else form.structure
                out[mode][key] = CatalogRecord(
                    key, m.num_corners, m.num_faces, {a.name: rep.axes.count(a) for a in Axis},
                    {c: categories[c] for c in CATEGORIES}, form.automorphisms, chiral, removable)
    return {mode: list(v.values()) for mode, v in out.items()}
