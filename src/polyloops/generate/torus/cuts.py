"""What a state of the torus search still needs, and the tests every polycube passes.

The search (:mod:`~polyloops.generate.torus.stages`) cuts a branch when a lower bound on the
crossings of anything that grows from it exceeds the budget (:func:`facts_of`), and the second
stage when a state breaks a property that every polycube loop structure with its decomposition
has and that later loops cannot repair (:func:`orientable`, :func:`axis_runs`,
:func:`balanced`).  The proofs are in ``docs/searches.md`` ("Two stages").

>>> base_bound(44), face_need(4, False), face_need(9, False)
(14, 0, 3)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from polyloops.core.disjoint_sets import DisjointSets, ParitySets
from polyloops.core.labellings import proper_colourings
from polyloops.generate.torus.arrangement import (
    THIRD,
    TorusArrangement,
    axis_classes,
    pieces_need,
    rot4,
    walk_forward,
)

__all__ = ["Facts", "axis_runs", "bad_face", "balanced", "base_bound", "deficit", "face_need", "facts_of",
           "layered_need", "orientable", "third_sides_consistent", "zones_split_every_loop"]


def base_bound(max_crossings: int) -> int:
    """The most crossings the two-axis arrangement ``B`` of a polycube's map with at most
    ``max_crossings`` crossings needs: the axis whose deletion leaves fewest crossings leaves at
    most a third of them (the three two-axis arrangements share out the crossings).

    >>> [base_bound(n) for n in (8, 36, 44, 48)]
    [2, 12, 14, 16]
    """
    return max_crossings // 3


def face_need(sides: int, bad: bool) -> int:
    """Twice a lower bound on the later crossings that a disc face of ``sides`` sides takes,
    when every region must end with 3 to 6 sides and a ``bad`` face must be cut.  Cut by ``p``
    points on its boundary and ``c`` crossings inside, a face has ``1 + p/2 + c`` regions with
    ``sides + 2p + 4c`` sides in all, so ``p + 2c >= sides - 6`` and ``p + 2c >= 6 - 2 sides``;
    a point on an edge serves the two faces beside it and a crossing one, so later crossings
    are at least half the sum of ``p + 2c`` over the faces.

    >>> face_need(4, False), face_need(9, False), face_need(2, False), face_need(5, True)
    (0, 3, 2, 2)
    """
    return max(sides - 6, 6 - 2 * sides, 2 if bad else 0, 0)


def layered_need(sides: int, classes: Sequence[int], bad: bool) -> int:
    """:func:`face_need` in the second stage, where every later crossing is a third-axis loop
    crossing an edge of ``B`` and third-axis loops never cross: ``classes`` holds the class of
    each side (0 or 1 for the two axes of ``B``, :data:`THIRD` for the third).  Cut by ``p``
    chords' ends, ``p_0`` of them on sides of class 0, a face has ``1 + p/2`` pieces and
    ``a + p_0`` sides of class 0 (``a`` now), at most two a piece, so ``p - p_0 >= a - 2``;
    likewise for class 1.  A face with three sides of the third axis can never be a corner.

    >>> layered_need(8, [0, 1] * 4, False), layered_need(4, [0, 1, 2, 2, 2], False) > 100
    (4, True)
    """
    count = [classes.count(k) for k in (0, 1, THIRD)]
    if count[2] > 2:
        return 1 << 20
    return max(face_need(sides, bad), max(count[0] - 2, 0) + max(count[1] - 2, 0))


def bad_face(face: Sequence[int], loop: Sequence[int], twin: Sequence[int]) -> bool:
    """Whether a face has two sides on one loop or lies on both sides of an edge: no corner of
    a polycube does (a loop with a corner on both sides is a loop of its level graph, and two
    sides on one side of a loop repeat a direction), so such a face must still be cut."""
    loops = [loop[d] for d in face]
    darts = set(face)
    return len(set(loops)) < len(loops) or any(twin[d] in darts for d in face)


@dataclass(frozen=True)
class Facts:
    """What the search knows of a state."""

    bound: int  # a lower bound on the crossings of any target that grows from it
    target: bool  # a cellular arrangement (stage 1) or a candidate map (stage 2)
    colourable: bool
    split: bool | None = None  # a two-colour target: zones_split_every_loop, when known


def _colourable(adj: list[set[int]], colours: int) -> bool:
    return next(proper_colourings(adj, colours), None) is not None


def _simple_quad_mesh(a: TorusArrangement) -> bool:
    """No region on both sides of an edge, no two regions sharing two edges."""
    pairs: set[tuple[int, int]] = set()
    for d in range(len(a.twin)):
        f, g = a.face_of[d], a.face_of[a.twin[d]]
        if f == g or (f, g) in pairs:
            return False
        pairs.add((f, g))
    return True


def axis_runs(a: TorusArrangement, loop: int, klass: Sequence[int] | None = None) -> int:
    """The number of maximal runs of crossings with loops of one class of a second-stage state
    (:func:`axis_classes`, or ``klass``) along ``loop``, cyclically (1 when every crossing is with
    one class).

    In a polycube the loop's strip of faces, cut at its level, is a closed rectilinear curve
    that goes straight through faces of one normal (consecutive faces of the same normal are
    coplanar, and a fold back would overlap edges) and turns at each change: so it has at least
    four runs, alternately of the two other axes (``docs/searches.md``, "Two stages")."""
    klass = klass if klass is not None else axis_classes(a)
    start = next(d for d in range(len(a.twin)) if a.loop_of[d] == loop)
    seq, e = [], start
    while True:
        seq.append(klass[a.loop_of[rot4(e)]])
        e = rot4(rot4(a.twin[e]))
        if e == start:
            break
    changes = sum(seq[i] != seq[i - 1] for i in range(len(seq)))
    return max(changes, 1)


def deficit(a: TorusArrangement, klass: Sequence[int]) -> int:
    """The crossings with the third axis that the loops of ``B`` still lack: each ends with its
    crossings in four runs at least (:func:`axis_runs`, with the third axis against the other
    class of ``B``), a later crossing adds at most two runs to the loop it crosses and crosses
    one loop of ``B``, so a loop with ``r`` runs needs ``ceil((4 - r) / 2)`` more."""
    side = [1 if k == THIRD else 0 for k in klass]
    return sum(max(0, 5 - axis_runs(a, lp, side)) // 2 for lp in range(a.num_loops) if klass[lp] != THIRD)


def facts_of(a: TorusArrangement, regions: bool, colours: int | None) -> Facts:
    """What the search knows of state ``a``: the crossings its marked faces need (and, with
    ``regions``, those its faces need to become corners of a candidate map), whether it is a
    target, and whether ``colours`` colours colour its crossing graph."""
    needs = pieces_need([kind for kind, _ in a.marks])
    klass = axis_classes(a) if a.layer else None
    marked = {a.face_of[d] for _, d in a.marks}
    for i, face in enumerate(a.faces):
        if i in marked:
            continue
        if regions and klass is not None:
            classes = [klass[a.loop_of[d]] for d in face]
            needs += layered_need(len(face), classes, bad_face(face, a.loop_of, a.twin))
        elif regions:
            needs += face_need(len(face), bad_face(face, a.loop_of, a.twin))
    later = (needs + 1) // 2
    if regions and klass is not None:
        later = max(later, deficit(a, klass))
    bound = a.crossings + later
    target = a.cellular and (not regions or (needs == 0 and _simple_quad_mesh(a)))
    colourable = colours is None or _colourable(a.crossing_graph(), colours)
    return Facts(bound, target, colourable)


def zones_split_every_loop(a: TorusArrangement) -> bool:
    """Whether, for each class of the bipartition of the crossing graph, every loop of it has
    two different zones on its sides (zones: the components left when that class's loops are
    cut away).  A loop with one zone on both sides is a loop of its level graph, so no ``B``
    of a polycube has one."""
    side = axis_classes(a)
    for cls in (0, 1):
        zones = DisjointSets(range(len(a.faces)))
        for d in range(len(a.twin)):
            if side[a.loop_of[d]] != cls:
                zones.union(a.face_of[d], a.face_of[a.twin[d]])
        if any(side[a.loop_of[d]] == cls and zones.find(a.face_of[d]) == zones.find(a.face_of[a.twin[d]])
               for d in range(len(a.twin))):
            return False
    return True


def third_sides_consistent(a: TorusArrangement) -> bool:
    """Whether the third axis's loops of a second-stage state can be oriented so that every
    face between two of them lies on the ``+`` side of one and the ``-`` side of the other.

    In a polycube each region of ``B`` is a path of corners along the third axis, and a corner
    between two edges of that axis has one ``+`` and one ``-`` edge.  A later third-axis loop
    through such a face cuts it into two faces whose two constraints imply the old one, so an
    inconsistency is never repaired: no polycube grows from the state."""
    return _third_faces(a, walk_forward(a)) is not None


def _third_faces(a: TorusArrangement, forward: list[int]) -> ParitySets[int] | None:
    """The parity system of :func:`third_sides_consistent` (``None`` when inconsistent)."""
    sides: ParitySets[int] = ParitySets()
    for face in a.faces:
        third = [d for d in face if a.layer[d]]
        if len(third) == 2 and a.loop_of[third[0]] != a.loop_of[third[1]]:
            d1, d2 = third
            if not sides.relate(a.loop_of[d1], a.loop_of[d2], -forward[d1] * forward[d2]):
                return None
    return sides


def orientable(a: TorusArrangement) -> bool:
    """Whether a second-stage state's loops can be oriented as every polycube that grows from
    it orients them, as far as its third-axis loops already decide: a parity system over all
    loops (``s_l = +1`` when the ``+`` side of loop ``l`` is on the right of its reference walk)
    with

    - the constraints of :func:`third_sides_consistent` (a face between two third-axis loops);
    - along each third-axis loop, two consecutive crossings with loops of one class of ``B``
      cross them in the same sense (``-`` to ``+`` both, or ``+`` to ``-`` both): they lie on
      one straight run of its cross-section (:func:`axis_runs`), which moves one way along
      the axis;
    - along each loop of ``B``, two consecutive crossings with the third axis likewise (later
      third-axis crossings between them only lengthen that run).

    Each constraint is Condition 3 at a corner every polycube from the state keeps, and later
    loops only add constraints, so an inconsistent state grows no polycube."""
    klass = axis_classes(a)
    forward = walk_forward(a)
    sides = _third_faces(a, forward)
    if sides is None:
        return False
    seen: set[int] = set()
    for d in range(len(a.twin)):
        lp = a.loop_of[d]
        if lp in seen or forward[d] != 1:
            continue
        seen.add(lp)
        crossed = []  # (the loop crossed, +1 when this walk crosses it from its left to its right)
        e = d
        while True:
            other = rot4(e)
            crossed.append((a.loop_of[other], 1 if forward[other] == 1 else -1))
            e = rot4(rot4(a.twin[e]))
            if e == d:
                break
        mine = klass[lp] == THIRD
        for (m1, r1), (m2, r2) in zip(crossed, crossed[1:] + crossed[:1], strict=True):
            k1, k2 = klass[m1], klass[m2]
            if k1 != k2 or (k1 == THIRD) == mine:
                continue  # a turn, or (along B) two crossings with B, which a later loop may part
            if not sides.relate(m1, m2, r1 * r2):
                return False
    return True


def balanced(a: TorusArrangement, base_crossings: int) -> bool:
    """Whether ``B`` has the fewest crossings of the three two-axis arrangements: the third
    axis crosses each class of ``B``'s bipartition at least as often as ``B`` crosses itself."""
    third = a.third_loops()
    side = axis_classes(a)
    with_class = [0, 0]
    for v in range(a.crossings):
        l1, l2 = a.loop_of[4 * v], a.loop_of[4 * v + 1]
        if (l1 in third) != (l2 in third):
            other = l2 if l1 in third else l1
            with_class[side[other]] += 1
    return min(with_class) >= base_crossings
