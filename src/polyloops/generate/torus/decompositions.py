"""Decompositions of a map of genus 1 into a two-axis arrangement and a third axis.

A map is listed by the torus search from its *canonical* decomposition
(:func:`canonical_decomposition`), so each comes once however many decompositions it has.  The
sets tried are the colour classes of the proper 3-colourings of the crossing graph (the third
axis ``D`` and the two classes of ``B``), and a set is a decomposition when it passes the second
stage's final test (:func:`decomposes`).
"""

from __future__ import annotations

from polyloops.core.labellings import admits_polycube, proper_colourings
from polyloops.generate.torus.arrangement import (
    TorusArrangement,
    axis_classes,
    labelled_mesh,
    layered_code,
    regions_of_base,
    with_layer,
)
from polyloops.generate.torus.cuts import (
    axis_runs,
    balanced,
    base_bound,
    deficit,
    facts_of,
    orientable,
    zones_split_every_loop,
)

__all__ = ["canonical_decomposition", "carries_polycube", "decomposes", "independent_with_bipartite_rest",
           "polycube_decompositions", "two_stage_decompositions"]


def canonical_decomposition(kid: TorusArrangement, polycubes: bool = True) -> bool:
    """Whether a second-stage state is its map's canonical decomposition: the least code of
    the map with the loops of a decomposition marked, over all its decompositions that carry a
    polycube (:func:`polycube_decompositions`; all of them with ``polycubes`` false)."""
    plain = TorusArrangement(kid.twin)
    own = layered_code(TorusArrangement(kid.twin, (), kid.layer))
    listed = polycube_decompositions if polycubes else two_stage_decompositions
    codes = [layered_code(with_layer(plain, chosen)) for chosen in listed(plain, plain.crossings)]
    return own == min(codes, default=None)



def polycube_decompositions(a: TorusArrangement, max_crossings: int) -> list[frozenset[int]]:
    """The decompositions (:func:`two_stage_decompositions`) whose labelling, the loops ``D``
    one axis and the two classes of ``B`` the others, carries a polycube loop structure: the
    ones a polycube on the map has, by the two-stage theorem, when ``D`` is its axis whose
    deletion leaves fewest crossings."""
    return [chosen for chosen in two_stage_decompositions(a, max_crossings)
            if carries_polycube(with_layer(a, chosen))]


def carries_polycube(a: TorusArrangement) -> bool:
    """Whether a second-stage arrangement (with its ``layer``) carries a polycube loop
    structure labelled by its decomposition: the third axis one axis, the two classes of ``B``
    the others."""
    return admits_polycube(*labelled_mesh(a))



def two_stage_decompositions(a: TorusArrangement, max_crossings: int) -> list[frozenset[int]]:
    """The sets of loops ``D`` of a cellular arrangement through which the second stage builds
    it within ``max_crossings`` crossings (the object of the two-stage theorem): no two loops
    of ``D`` cross, what is left (``B``) is cellular with a bipartite crossing graph, at most a
    third of ``max_crossings`` crossings and loops with two zones on their sides, each loop of
    ``D`` passes each region of ``B`` at most once, ``D`` crosses each class of ``B`` at least
    as often as ``B`` crosses itself, the loops can be oriented as :func:`orientable`
    asks, no region has more than two sides of one class
    (:func:`layered_need`), every loop of ``B`` crosses ``D`` twice at least and every loop of
    ``D`` crosses the two classes of ``B`` in four runs at least (:func:`axis_runs`): exactly
    the final states the second stage keeps, so a map's canonical decomposition is one the
    search reaches.  The sets tried are the colour classes
    of the proper 3-colourings of the crossing graph (``D`` and the two classes of ``B``),
    sorted (a test compares them with every set of loops)."""
    return [chosen for chosen in independent_with_bipartite_rest(a.crossing_graph())
            if decomposes(a, chosen, max_crossings)]


def decomposes(a: TorusArrangement, chosen: frozenset[int], max_crossings: int) -> bool:
    """Whether the loops ``chosen`` of a cellular arrangement are a decomposition in the sense
    of :func:`two_stage_decompositions` (the final test of the second stage)."""
    try:
        base = a.without_loops(set(chosen))
    except ValueError:
        return False
    if base.crossings > base_bound(max_crossings) or not zones_split_every_loop(base):
        return False
    crossings = a.loop_crossings()
    layer = tuple(int(a.loop_of[d] in chosen) for d in range(len(a.twin)))
    layered = TorusArrangement(a.twin, (), layer)
    region = regions_of_base(layered)
    once = all(len({region[d] for d in range(len(a.twin)) if a.loop_of[d] == lp}) == crossings[lp]
               for lp in chosen)
    return (once and balanced(layered, base.crossings) and orientable(layered)
            and facts_of(layered, True, None).target and deficit(layered, axis_classes(layered)) == 0
            and all(axis_runs(layered, lp) >= 4 for lp in chosen))


def independent_with_bipartite_rest(adj: list[set[int]]) -> list[frozenset[int]]:
    """Every nonempty set of loops, not all of them, no two of which cross, whose complement's
    crossing graph is bipartite: the colour classes of proper 3-colourings (such a set and the
    two sides of its complement are one), sorted."""
    every = frozenset(range(len(adj)))
    found = {frozenset(v for v, c in enumerate(colouring) if c == k)
             for colouring in proper_colourings(adj, 3) for k in range(3)}
    return sorted((d for d in found if d and d != every), key=sorted)
