"""Arrangements of loops on the torus, built one loop at a time: the genus-1 candidate maps.

The dual of a genus-1 quad mesh is a *cellular* arrangement of simple closed curves on the
torus: a 4-regular map whose crossings are the quads and whose regions (all discs) are the
corners; on the torus there are as many corners as crossings.

**Any connected arrangement.**  As on the sphere (:mod:`polyloops.generate.loops.arrangements`),
every connected arrangement with at least two loops has a loop whose deletion leaves it
connected, so it is reached from a single loop by adding curves, and McKay's canonical
construction path makes the search a tree.  What is new on the torus is that the arrangements
met on the way need not be cellular.  A connected union of curves on the torus carries its
first homology (rank 2: the faces are discs), or a rank-1 part of it (one face is an annulus,
the others discs), or nothing (one face is a torus with a hole).  Its rotation system describes
a torus in the first case and a sphere in the others, and a *state* is the rotation system with
its non-disc faces *marked*: no mark, the two ends of the annulus (``A``), or the holed torus
(``H``).  Two states are one graph on the torus up to homeomorphism exactly when their marked
maps are isomorphic.  A new curve is drawn arc by arc through the faces.  An arc through a disc
face is fixed by its ends; through a marked face it is one of a few kinds, each fixed up to a
homeomorphism of the face that keeps its boundary (so the arrangements are the same):

- in ``H``, an arc between two points of its boundary cuts off a disc on either side (the
  handle stays in the other piece), or does not separate (the face becomes an annulus: both
  pieces of the rotation system become its ends);
- in an annulus end, an arc back to the same end cuts off a disc on either side; an arc to the
  other end crosses the annulus, which becomes a disc (the rotation system becomes a torus).

A child is kept when its new loop is the canonical loop to delete (among loops whose deletion
leaves the arrangement connected, those with fewest crossings, and of these the first in the
canonical numbering of the marked map).  :func:`torus_arrangements` lists every cellular
arrangement so (``colours`` keeps those whose crossing graph that many colours colour).

**Polycubes, in two stages** (``docs/searches.md`` proves it).  Deleting every loop of one axis
from a polycube loop structure of positive genus merges its corners along paths of edges of
that axis, so the two other axes' loops form a cellular arrangement ``B`` (its crossing graph
is bipartite), and the deleted loops are pairwise disjoint, each crossing every region of ``B``
at most once.  Taking the axis whose deletion leaves fewest crossings, ``B`` has at most a third
of the crossings.  :func:`candidate_torus_arrangements` lists every such ``B`` with the search
above, and then its third axis: region by region
(:func:`polyloops.generate.torus.regions.third_axis_systems`, where the level graphs of ``B``
cut early), or, as the twin kept for the tests, one loop at a time, each child kept when its new
loop is the canonical third-axis loop to delete (every state of this stage is cellular).

>>> from collections import Counter
>>> sorted(Counter(a.crossings for a in torus_arrangements(3)).items())
[(1, 1), (2, 2), (3, 5)]
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field, fields
from functools import cached_property, lru_cache

from polyloops.core import compiled
from polyloops.core.disjoint_sets import DisjointSets, ParitySets
from polyloops.core.halfedge import HalfEdgeMap, permutation_orbits
from polyloops.core.labellings import proper_colourings

__all__ = ["ANNULUS", "HANDLE", "SECOND_STAGE", "THIRD", "TorusArrangement",
           "TorusSearchStats", "axis_runs", "candidate_torus_arrangements", "carries_polycube",
           "compiled_search_available", "decomposes", "face_need", "first_stage", "labelled_mesh",
           "layered_code", "layered_need", "orientable", "polycube_decompositions", "third_sides_consistent",
           "torus_arrangements", "torus_children", "two_axis_bases", "two_stage_decompositions"]

ANNULUS, HANDLE = "A", "H"  # an end of the annulus face; the face with the handle
MARK_NEED = {HANDLE: 2, ANNULUS: 1}  # a holed torus is crossed twice at least, an annulus end once


def _rot4(d: int) -> int:
    return 4 * (d // 4) + (d + 1) % 4


def _irot4(d: int) -> int:
    return 4 * (d // 4) + (d + 3) % 4


@dataclass(frozen=True)
class TorusArrangement:
    """A connected arrangement of simple loops on the torus, as a marked map: darts numbered
    four a crossing counter-clockwise (``rot(d) = 4 (d // 4) + (d + 1) % 4``), ``twin`` pairing
    the darts of each edge; ``marks``, the non-disc faces as ``(kind, dart)`` with the face on
    the left of ``dart`` (none when every face is a disc, two ``A`` for the ends of an annulus,
    one ``H`` for a face with the handle); ``layer``, per dart, 1 on a loop of the third axis
    (in the second stage; empty otherwise).  ``code`` identifies it up to homeomorphism,
    mirror images identified."""

    twin: tuple[int, ...]
    marks: tuple[tuple[str, int], ...] = ()
    layer: tuple[int, ...] = ()
    code: tuple = field(default=(), compare=False, repr=False)

    @property
    def crossings(self) -> int:
        """The number of crossings (on the torus also the number of regions)."""
        return len(self.twin) // 4

    @property
    def cellular(self) -> bool:
        """Whether every face is a disc (the loops carry the torus's homology)."""
        return not self.marks

    @cached_property
    def faces(self) -> list[list[int]]:
        """The faces of the rotation system, each as the darts with it on their left."""
        return permutation_orbits([_irot4(t) for t in self.twin])

    @cached_property
    def face_of(self) -> tuple[int, ...]:
        """Per dart, the face on its left (an index into :attr:`faces`)."""
        out = [0] * len(self.twin)
        for i, face in enumerate(self.faces):
            for d in face:
                out[d] = i
        return tuple(out)

    @cached_property
    def loop_of(self) -> tuple[int, ...]:
        """Per dart, its loop (loops numbered by their lowest dart)."""
        out = [-1] * len(self.twin)
        n = 0
        for d in range(len(self.twin)):
            if out[d] < 0:
                e = d
                while out[e] < 0:
                    out[e] = out[self.twin[e]] = n
                    e = _rot4(_rot4(self.twin[e]))
                n += 1
        return tuple(out)

    @property
    def num_loops(self) -> int:
        """The number of loops."""
        return max(self.loop_of, default=-1) + 1

    def loop_crossings(self) -> list[int]:
        """Per loop, its number of crossings."""
        out = [0] * self.num_loops
        for d in range(len(self.twin)):
            out[self.loop_of[d]] += 1
        return [c // 2 for c in out]  # a loop has two darts at each of its crossings

    def crossing_graph(self) -> list[set[int]]:
        """Per loop, the loops it crosses."""
        adj: list[set[int]] = [set() for _ in range(self.num_loops)]
        for v in range(self.crossings):
            a, b = self.loop_of[4 * v], self.loop_of[4 * v + 1]
            adj[a].add(b)
            adj[b].add(a)
        return adj

    def third_loops(self) -> set[int]:
        """The loops of the third axis (second stage)."""
        return {self.loop_of[d] for d, flag in enumerate(self.layer) if flag}

    @classmethod
    def of_quad_mesh(cls, m: HalfEdgeMap) -> TorusArrangement:
        """The arrangement dual to a genus-1 quad mesh (the same darts: a quad's darts turn
        around its crossing, ``twin`` crosses an edge)."""
        if m.genus != 1 or any(len(f) != 4 for f in m.faces):
            raise ValueError("not a quad mesh of genus 1")
        return cls(tuple(m.twin))

    def without_loops(self, loops: set[int]) -> TorusArrangement:
        """The cellular arrangement left when ``loops`` are deleted (the others run straight on
        through their crossings).  Raises ``ValueError`` when a face of what is left is not a
        disc, or a loop has no crossing left."""
        gone = [self.loop_of[4 * v] in loops or self.loop_of[4 * v + 1] in loops
                for v in range(self.crossings)]
        keep = [v for v in range(self.crossings) if not gone[v]]
        if not keep:
            raise ValueError("no crossing is left")
        index = {4 * v + i: 4 * k + i for k, v in enumerate(keep) for i in range(4)}

        def through(t: int) -> int:
            while gone[t // 4]:
                t = self.twin[_rot4(_rot4(t))]
            return t

        out = TorusArrangement(tuple(index[through(self.twin[d])] for d in sorted(index)))
        if len(out.faces) != out.crossings:  # V - E + F = 0 on the torus exactly when cellular
            raise ValueError("what is left is not cellular")
        if out.num_loops != self.num_loops - len(loops):
            raise ValueError("a loop is left without crossings")
        return out

    def quad_mesh(self) -> HalfEdgeMap:
        """The dual quad mesh: a quad a crossing, a corner a region (cellular, no two regions
        sharing two edges, none on both sides of one)."""
        if self.marks:
            raise ValueError("a non-cellular arrangement has no dual quad mesh")
        return HalfEdgeMap.from_faces([[self.face_of[_irot4(d)] for d in range(4 * v, 4 * v + 4)]
                                       for v in range(self.crossings)])


# -- the canonical form of a marked map -----------------------------------------------------------

def _mark_sets(a: TorusArrangement, mirrored: bool) -> list[tuple[str, frozenset[int]]]:
    # A face is a cyclic list of angles; the angle between d and rot(d) lies in the face on the
    # left of d, and in the mirror image in the face on the left of rot(d).
    out = []
    for kind, dart in a.marks:
        face = a.faces[a.face_of[dart]]
        out.append((kind, frozenset(_rot4(d) for d in face) if mirrored else frozenset(face)))
    return out


def _code(a: TorusArrangement, mirrored: bool, root: int, mark_sets: list[tuple[str, frozenset[int]]]
          ) -> tuple[tuple, list[int]]:
    """The breadth-first code of ``a`` from dart ``root`` (twins in the numbering, the layer,
    then the marked faces by their least dart number), and the darts in numbering order."""
    step = _irot4 if mirrored else _rot4
    num = [-1] * len(a.twin)
    order: list[int] = []

    def visit(t: int) -> None:
        for _ in range(4):
            num[t] = len(order)
            order.append(t)
            t = step(t)

    visit(root)
    twins = []
    for d in order:  # grows while read
        t = a.twin[d]
        if num[t] < 0:
            visit(t)
        twins.append(num[t])
    layer = tuple(a.layer[d] for d in order) if a.layer else ()
    marks = tuple(sorted((min(num[e] for e in face), kind) for kind, face in mark_sets))
    return (tuple(twins), layer, marks), order


def canonical(a: TorusArrangement, wanted: int | None = None,
              candidates: frozenset[int] = frozenset()) -> tuple[tuple, bool]:
    """The canonical code of ``a`` (the least over roots and both orientations), and whether
    some numbering reaching it meets a dart of loop ``wanted`` before any other loop of
    ``candidates`` (McKay's test that ``wanted`` is in the orbit of the canonical loop)."""
    crossings = a.loop_crossings()
    sizes = [len(f) for f in a.faces]
    marked = {a.face_of[d] for _, d in a.marks}
    layer = a.layer or (0,) * len(a.twin)
    keys = {}
    for mirrored in (False, True):
        for d in range(len(a.twin)):
            face = a.face_of[a.twin[d]] if mirrored else a.face_of[d]
            keys[mirrored, d] = (crossings[a.loop_of[d]], layer[d], sizes[face], face in marked)
    low = min(keys.values())
    best: tuple | None = None
    accepted = False
    for mirrored in (False, True):
        sets = _mark_sets(a, mirrored)
        for d in range(len(a.twin)):
            if keys[mirrored, d] != low:
                continue
            code, order = _code(a, mirrored, d, sets)
            first = next((a.loop_of[e] for e in order if a.loop_of[e] in candidates), None)
            if best is None or code < best:
                best, accepted = code, first == wanted
            elif code == best and first == wanted:
                accepted = True
    assert best is not None
    return best, accepted


# -- what a state still needs ---------------------------------------------------------------------

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


THIRD = 2  # the class of the third axis's loops in the second stage


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


def _bad(face: Sequence[int], loop: Sequence[int], twin: Sequence[int]) -> bool:
    """Whether a face has two sides on one loop or lies on both sides of an edge: no corner of
    a polycube does (a loop with a corner on both sides is a loop of its level graph, and two
    sides on one side of a loop repeat a direction), so such a face must still be cut."""
    loops = [loop[d] for d in face]
    darts = set(face)
    return len(set(loops)) < len(loops) or any(twin[d] in darts for d in face)


@dataclass(frozen=True)
class _Facts:
    bound: int  # a lower bound on the crossings of any target that grows from it
    target: bool  # a cellular arrangement (stage 1) or a candidate map (stage 2)
    colourable: bool


def _classes(a: TorusArrangement) -> list[int]:
    """Per loop of a second-stage state: :data:`THIRD` for the third axis, else its class in
    the bipartition of ``B``'s crossing graph (connected, as ``B`` is cellular)."""
    third = a.third_loops()
    out = [THIRD if lp in third else -1 for lp in range(a.num_loops)]
    adj = a.crossing_graph()
    start = next(lp for lp in range(a.num_loops) if lp not in third)
    out[start] = 0
    stack = [start]
    while stack:
        v = stack.pop()
        for u in adj[v]:
            if out[u] < 0:
                out[u] = 1 - out[v]
                stack.append(u)
    return out


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
    (:func:`_classes`, or ``klass``) along ``loop``, cyclically (1 when every crossing is with
    one class).

    In a polycube the loop's strip of faces, cut at its level, is a closed rectilinear curve
    that goes straight through faces of one normal (consecutive faces of the same normal are
    coplanar, and a fold back would overlap edges) and turns at each change: so it has at least
    four runs, alternately of the two other axes (``docs/searches.md``, "Two stages")."""
    klass = klass if klass is not None else _classes(a)
    start = next(d for d in range(len(a.twin)) if a.loop_of[d] == loop)
    seq, e = [], start
    while True:
        seq.append(klass[a.loop_of[_rot4(e)]])
        e = _rot4(_rot4(a.twin[e]))
        if e == start:
            break
    changes = sum(seq[i] != seq[i - 1] for i in range(len(seq)))
    return max(changes, 1)


def _deficit(a: TorusArrangement, klass: Sequence[int]) -> int:
    """The crossings with the third axis that the loops of ``B`` still lack: each ends with its
    crossings in four runs at least (:func:`axis_runs`, with the third axis against the other
    class of ``B``), a later crossing adds at most two runs to the loop it crosses and crosses
    one loop of ``B``, so a loop with ``r`` runs needs ``ceil((4 - r) / 2)`` more."""
    side = [1 if k == THIRD else 0 for k in klass]
    return sum(max(0, 5 - axis_runs(a, lp, side)) // 2 for lp in range(a.num_loops) if klass[lp] != THIRD)


def _facts(a: TorusArrangement, regions: bool, colours: int | None) -> _Facts:
    needs = 0
    klass = _classes(a) if a.layer else None
    for i, face in enumerate(a.faces):
        kind = next((k for k, d in a.marks if a.face_of[d] == i), None)
        if kind is not None:
            needs += MARK_NEED[kind]
        elif regions and klass is not None:
            classes = [klass[a.loop_of[d]] for d in face]
            needs += layered_need(len(face), classes, _bad(face, a.loop_of, a.twin))
        elif regions:
            needs += face_need(len(face), _bad(face, a.loop_of, a.twin))
    later = (needs + 1) // 2
    if regions and klass is not None:
        later = max(later, _deficit(a, klass))
    bound = a.crossings + later
    target = a.cellular and (not regions or (needs == 0 and _simple_quad_mesh(a)))
    colourable = colours is None or _colourable(a.crossing_graph(), colours)
    return _Facts(bound, target, colourable)


# -- drawing a curve ------------------------------------------------------------------------------

class _Drawing:
    """A parent's rotation system while a curve is drawn on it: darts of any degree, points
    where the curve crosses the parent's edges, chords; per dart its parent loop (-1 on the
    curve), its layer, and (second stage) the region of ``B`` it lies in."""

    def __init__(self, rot: Sequence[int], twin: Sequence[int], marks: Sequence[tuple[str, int]],
                 loop: Sequence[int], layer: Sequence[int], region: Sequence[int], curve_layer: int):
        self.rot, self.twin, self.marks = list(rot), list(twin), list(marks)
        self.loop, self.layer, self.region = list(loop), list(layer), list(region)
        self.irot = [0] * len(self.rot)
        for d, r in enumerate(self.rot):
            self.irot[r] = d
        self.curve_layer = curve_layer

    def face(self, d: int) -> list[int]:
        out, e = [], d
        while True:
            out.append(e)
            e = self.irot[self.twin[e]]
            if e == d:
                return out

    def _add(self, loop: int, layer: int, region: int) -> int:
        for lst, v in ((self.rot, -1), (self.irot, -1), (self.twin, -1), (self.loop, loop),
                       (self.layer, layer), (self.region, region)):
            lst.append(v)
        return len(self.rot) - 1

    def subdivide(self, y: int) -> tuple[int, int]:
        """A point on the edge of ``y``: darts ``q1`` (on, as ``y`` runs; beside ``y``'s face)
        and ``q2`` (back; beside the other face)."""
        t = self.twin[y]
        q1 = self._add(self.loop[y], self.layer[y], self.region[y])
        q2 = self._add(self.loop[y], self.layer[y], self.region[t])
        self.rot[q1], self.rot[q2], self.irot[q1], self.irot[q2] = q2, q1, q2, q1
        self.twin[y], self.twin[q2], self.twin[q1], self.twin[t] = q2, y, t, q1
        return q1, q2

    def chord(self, x: int, y: int) -> tuple[int, int]:
        """An edge of the curve from the origin of ``x`` (right after it, counter-clockwise)
        to that of ``y``."""
        a = self._add(-1, self.curve_layer, self.region[x])
        b = self._add(-1, self.curve_layer, self.region[y])
        for new, at in ((a, x), (b, y)):
            nxt = self.rot[at]
            self.rot[at], self.rot[new], self.irot[new], self.irot[nxt] = new, nxt, at, new
        self.twin[a], self.twin[b] = b, a
        return a, b

    def mark_index(self, face: list[int]) -> int | None:
        darts = set(face)
        return next((i for i, (_, d) in enumerate(self.marks) if d in darts), None)

    def needs(self, open_darts: set[int], regions: bool, klass: Sequence[int] | None = None) -> int:
        """Twice a lower bound on the crossings still to come from the faces that are not open
        (no dart of ``open_darts``): marked faces, and with ``regions`` faces that are not yet
        regions of a candidate map."""
        marked = {d: kind for kind, d in self.marks}
        total = 0
        for face in permutation_orbits([self.irot[t] for t in self.twin]):
            if open_darts.intersection(face):
                continue
            kind = next((marked[e] for e in face if e in marked), None)
            if kind is not None:
                total += MARK_NEED[kind]
            elif regions:
                sides = [e for e in face if self.rot[self.rot[e]] != e]  # not from a point of degree 2
                bad = _bad(sides, self.loop, self.twin)
                if klass is None:
                    total += face_need(len(sides), bad)
                else:
                    total += layered_need(len(sides), [klass[self.loop[e]] if self.loop[e] >= 0 else THIRD
                                                       for e in sides], bad)
        return total

    def snapshot(self) -> tuple:
        return len(self.rot), list(self.rot), list(self.irot), list(self.twin), list(self.marks)

    def restore(self, snap: tuple) -> None:
        n, rot, irot, twin, marks = snap
        self.rot, self.irot, self.twin, self.marks = list(rot), list(irot), list(twin), marks
        for lst in (self.loop, self.layer, self.region):
            del lst[n:]


def _finish(w: _Drawing, layered: bool) -> tuple[TorusArrangement, int]:
    """The child a closed curve makes: points of degree 2 smoothed away, darts renumbered four
    a crossing; and a dart of the new loop."""
    index: dict[int, int] = {}
    for orbit in permutation_orbits(w.rot):  # the vertices
        if len(orbit) == 4:
            base = len(index)
            for i, e in enumerate(orbit):
                index[e] = base + i

    def through(t: int) -> int:  # straight on through a point of degree 2
        while t not in index:
            t = w.twin[w.rot[t]]
        return t

    twin = [0] * len(index)
    layer = [0] * len(index)
    for d, i in index.items():
        twin[i] = index[through(w.twin[d])]
        layer[i] = w.layer[d]
    marks = []
    for kind, d in w.marks:
        e = d
        while e not in index:  # a dart of the same face that stays
            e = w.irot[w.twin[e]]
        marks.append((kind, index[e]))
    curve = next(i for d, i in index.items() if w.loop[d] < 0)
    return TorusArrangement(tuple(twin), tuple(marks), tuple(layer) if layered else ()), curve


def _connected_without(adj: list[set[int]], skip: int) -> bool:
    rest = [v for v in range(len(adj)) if v != skip]
    if len(rest) <= 1:
        return True
    seen, stack = {rest[0]}, [rest[0]]
    while stack:
        for u in adj[stack.pop()]:
            if u != skip and u not in seen:
                seen.add(u)
                stack.append(u)
    return len(seen) == len(rest)


@dataclass
class TorusSearchStats:
    """What a search did: curves closed, children over the bound, not canonical, or with a
    crossing graph the colours cannot colour; states kept, and targets among them."""

    closed: int = 0
    over_bound: int = 0
    not_canonical: int = 0
    not_colourable: int = 0
    inconsistent_sides: int = 0  # second stage: third-axis loops that no orientation fits
    not_rectilinear: int = 0  # second stage: a new loop whose crossings run in fewer than 4 runs
    states: int = 0
    targets: int = 0
    region_choices: int = 0  # region search: regions cut (a region's chords chosen)
    one_way: int = 0  # region search: pieces that force a level graph's cycle one way round
    third_axes: int = 0  # region search: third axes built (each region crossed once a loop)

    def add(self, other: TorusSearchStats) -> None:
        """Add another search's counts to these."""
        for f in fields(self):
            setattr(self, f.name, getattr(self, f.name) + getattr(other, f.name))


_ROOTS = (  # a single loop, as a point of degree 2 on it: essential, or bounding a disc
    ((1, 0), (1, 0), ((ANNULUS, 0), (ANNULUS, 1))),
    ((1, 0), (1, 0), ((HANDLE, 1),)),
)


def _regions_of_base(a: TorusArrangement) -> list[int]:
    """Per dart, the region of ``B`` (the arrangement without the third axis's loops) that the
    face on its left lies in: faces joined across third-axis edges."""
    joined = DisjointSets(range(len(a.faces)))
    for d, flag in enumerate(a.layer):
        if flag:
            joined.union(a.face_of[d], a.face_of[a.twin[d]])
    return [joined.find(a.face_of[d]) for d in range(len(a.twin))]


def torus_children(parent: TorusArrangement | int, max_crossings: int, colours: int | None = None,
                   regions: bool = False, stats: TorusSearchStats | None = None,
                   ) -> list[tuple[TorusArrangement, _Facts]]:
    """The canonical children of ``parent`` that can still grow into a target with at most
    ``max_crossings`` crossings, each once, in a fixed order.

    ``parent`` is a state, or an int: the single loop, essential (0) or not (1).  A parent
    with a ``layer`` is in the second stage: the new loop is of the third axis, crosses no loop
    of it and each region of ``B`` at most once.  ``colours`` keeps children whose crossing
    graph is that colourable; ``regions`` counts the crossings the faces need to become corners
    of a candidate map (3 to 6 sides, no two on one loop) in the bound."""
    stats = stats if stats is not None else TorusSearchStats()
    layered = not isinstance(parent, int) and bool(parent.layer)
    if _compiled():
        if layered and regions and colours is None:
            assert not isinstance(parent, int)
            return _compiled_children(parent, max_crossings, stats)
        if not layered and not regions and colours in (None, 2):
            return _compiled_first_children(parent, max_crossings, colours or 0, stats)
    base_crossings, third_with = 0, [0, 0]
    rot: Sequence[int]
    twin: Sequence[int]
    marks: Sequence[tuple[str, int]]
    loop: Sequence[int]
    layer: Sequence[int]
    region: Sequence[int]
    if isinstance(parent, int):
        rot, twin, marks = _ROOTS[parent]
        loop, layer, region = [0, 0], [0, 0], [0, 0]
        parent_crossings = 0
        deletable: list[tuple[int, int]] = []
        klass = None
    else:
        rot = [_rot4(d) for d in range(len(parent.twin))]
        twin, marks, loop = parent.twin, parent.marks, parent.loop_of
        layer = parent.layer or [0] * len(twin)
        region = _regions_of_base(parent) if layered else [0] * len(twin)
        klass = _classes(parent) if layered else None
        if klass is not None:  # crossings of B, and of the third axis with each class of B
            for v in range(parent.crossings):
                k1, k2 = sorted((klass[parent.loop_of[4 * v]], klass[parent.loop_of[4 * v + 1]]))
                if k2 == THIRD:
                    third_with[k1] += 1
                else:
                    base_crossings += 1
        parent_crossings = parent.crossings
        lc = parent.loop_crossings()
        if layered:
            deletable = [(lp, lc[lp]) for lp in parent.third_loops()]
        else:
            adj = parent.crossing_graph()
            deletable = [(lp, lc[lp]) for lp in range(parent.num_loops) if _connected_without(adj, lp)]
    w = _Drawing(rot, twin, marks, loop, layer, region, 1 if layered else 0)
    budget = max_crossings - parent_crossings
    found: dict[tuple, tuple[TorusArrangement, _Facts]] = {}
    met: dict[int, int] = {}  # the curve's crossings with each parent loop
    visited: set[int] = set()  # second stage: the regions of B the curve has passed
    # Second stage: crossing the start edge again would leave a face of two sides, a piece of
    # an edge of B and the new loop, which later third-axis loops (they cross only B, each
    # region once) can only cut into more such faces, so nothing grows from it.
    start_edge: set[int] = set()

    def unbalanced() -> bool:
        # B is the two-axis arrangement with fewest crossings: the third axis ends crossing
        # each class of B at least as often as B crosses itself.
        assert klass is not None
        with_class = list(third_with)
        for lp, k in met.items():
            with_class[klass[lp]] += k
        return base_crossings + sum(max(c, base_crossings) for c in with_class) > max_crossings

    def hopeless(cr: int) -> bool:
        if layered and unbalanced():
            return True
        # A parent loop that stays deletable with fewer crossings than the curve makes the curve
        # not canonical, and the curve only grows.  In the first stage a loop stays deletable
        # when the curve meets another loop too; in the second every third-axis loop does.
        crossed = len(met)
        return any((layered or crossed > (met.get(lp, 0) > 0)) and cr > c + met.get(lp, 0)
                   for lp, c in deletable)

    def chords(x: int, y: int) -> Iterator[None]:
        """Draw the chord from x to y in each way the faces allow, yielding after each and
        restoring the drawing after each."""
        face = w.face(x)
        i = w.mark_index(face)
        kind = w.marks[i][0] if i is not None else None
        snap = w.snapshot()
        if y not in set(face):  # across the annulus, from one end to the other
            assert kind == ANNULUS
            w.chord(x, y)
            w.marks = []
            yield
            w.restore(snap)
            return
        for option in {None: (None,), HANDLE: ("a", "b", "both"), ANNULUS: ("a", "b")}[kind]:
            a, b = w.chord(x, y)
            if option == "both":
                w.marks = [(ANNULUS, a), (ANNULUS, b)]
            elif option is not None:
                assert i is not None and kind is not None
                w.marks = list(w.marks)
                w.marks[i] = (kind, a if option == "a" else b)
            yield
            w.restore(snap)

    def keep(child: TorusArrangement, curve: int) -> None:
        facts = _facts(child, regions, colours)
        if facts.bound > max_crossings:
            stats.over_bound += 1
            return
        if not facts.colourable:
            stats.not_colourable += 1
            return
        if layered and not orientable(child):
            stats.inconsistent_sides += 1
            return
        if layered and axis_runs(child, child.loop_of[curve]) < 4:
            stats.not_rectilinear += 1
            return
        lc = child.loop_crossings()
        if layered:
            may = sorted(child.third_loops())
        else:
            adj = child.crossing_graph()
            may = [lp for lp in range(child.num_loops) if _connected_without(adj, lp)]
        least = min(lc[lp] for lp in may)
        wanted = child.loop_of[curve]
        if lc[wanted] != least:
            stats.not_canonical += 1
            return
        code, accepted = canonical(child, wanted, frozenset(lp for lp in may if lc[lp] == least))
        if not accepted:
            stats.not_canonical += 1
            return
        found.setdefault(code, (TorusArrangement(child.twin, child.marks, child.layer, code), facts))

    def dfs(x: int, end: int, cr: int) -> None:
        """Continue the curve from the point of dart ``x`` into the face on its left; ``end`` is
        the starting point's dart on the other side, ``cr`` the crossings so far."""
        if hopeless(cr):
            return
        if parent_crossings + cr + (w.needs({x, end}, regions, klass) + 1) // 2 > max_crossings:
            stats.over_bound += 1
            return
        face = w.face(x)
        i = w.mark_index(face)
        targets = list(face)
        if i is not None and w.marks[i][0] == ANNULUS:
            other = next(d for k, (_, d) in enumerate(w.marks) if k != i)
            targets += w.face(other)
        if end in targets:
            for _ in chords(x, end):
                stats.closed += 1
                keep(*_finish(w, layered))
        if cr >= budget or (layered and w.region[x] == w.region[end]):
            return  # (second stage: in the last region of B the curve only closes)
        for y in targets:
            lp = w.loop[y]
            if lp < 0 or w.layer[y] or y in start_edge:
                continue  # the curve does not cross itself, nor (second stage) the third axis
            if layered:
                there = w.region[w.twin[y]]
                if there in visited or (there == w.region[end] and end not in w.face(w.twin[y])):
                    continue  # B's regions once each, the last one entered only to close
            snap = w.snapshot()
            q1, q2 = w.subdivide(y)
            met[lp] = met.get(lp, 0) + 1
            if layered:
                visited.add(w.region[q2])
            for _ in chords(x, q1):
                dfs(q2, end, cr + 1)
            if layered:
                visited.discard(w.region[q2])
            met[lp] -= 1
            if not met[lp]:
                del met[lp]
            w.restore(snap)

    # The curve starts at a point on a parent edge and enters the face on the left of that edge.
    for y0 in range(len(w.rot)):
        if w.layer[y0]:
            continue
        snap = w.snapshot()
        t0 = w.twin[y0]
        p1, p2 = w.subdivide(y0)
        if layered:  # the start edge's two pieces, which the curve does not cross again
            start_edge.update((y0, t0, p1, p2))
        met[w.loop[y0]] = 1
        if layered:
            visited.add(w.region[p1])
        dfs(p1, p2, 1)
        visited.clear()
        start_edge.clear()
        met.clear()
        w.restore(snap)
    kids = [found[k] for k in sorted(found)]
    stats.states += len(kids)
    stats.targets += sum(f.target for _, f in kids)
    return kids


# Both stages run in C when the compiled part ``torus`` is in use (``_torus.c``: the same
# children as the Python search, tested), the first for the marked search without a regions'
# bound and with two colours or none; its twin is the Python search below.
def compiled_search_available() -> bool:
    """Whether the compiled torus search runs: built (it needs a C compiler) and not switched to
    its Python twin (:mod:`polyloops.core.compiled`)."""
    return compiled.in_use("torus")


def _compiled() -> bool:
    return compiled.in_use("torus")


def _compiled_children(parent: TorusArrangement, max_crossings: int, stats: TorusSearchStats
                       ) -> list[tuple[TorusArrangement, _Facts]]:
    """:func:`torus_children` of a second-stage state, by the compiled search (one of each
    child, ordered by its code)."""
    import array

    out = []
    start = array.array("H", parent.twin).tobytes()
    for (twin, layer), flags in _layered_children(start, bytes(parent.layer), max_crossings, stats):
        child = TorusArrangement(tuple(array.array("H", twin)), (), tuple(layer), (twin + layer,))
        out.append((child, _Facts(0, bool(flags & 1), True)))
    return out


def _layered_children(twin: bytes, layer: bytes, max_crossings: int, stats: TorusSearchStats
                      ) -> list[tuple[tuple[bytes, bytes], int]]:
    """The compiled second stage's children of one state, one of each, ordered by code, as
    ``((twin, layer), flags)``; its counts added to ``stats``."""
    _torus = compiled.require("torus")

    found, counts = _torus.children(twin, layer, max_crossings)
    _, closed, over, inconsistent, rejected, straight = counts
    stats.closed += closed
    stats.over_bound += over
    stats.inconsistent_sides += inconsistent
    stats.not_canonical += rejected
    stats.not_rectilinear += straight
    kids = sorted({(t, y): flags for t, y, flags in found}.items())
    stats.states += len(kids)
    stats.targets += sum(flags & 1 for _, flags in kids)
    return kids


def _compiled_first_children(parent: TorusArrangement | int, max_crossings: int, colours: int,
                             stats: TorusSearchStats) -> list[tuple[TorusArrangement, _Facts]]:
    """:func:`torus_children` of a state of the marked search (no layer, no regions' bound), by
    the compiled search (one of each child, ordered by its code)."""
    import array

    _torus = compiled.require("torus")

    if isinstance(parent, int):
        found, counts = _torus.first_children(b"", parent, max_crossings, colours)
    else:
        found, counts = _torus.first_children(array.array("H", parent.twin).tobytes(), list(parent.marks),
                                              max_crossings, colours)
    _, closed, over, rejected, uncolourable = counts
    stats.closed += closed
    stats.over_bound += over
    stats.not_canonical += rejected
    stats.not_colourable += uncolourable
    kids: dict[tuple, tuple[TorusArrangement, _Facts]] = {}
    for twin, marks, cellular in found:
        key = (twin, tuple(marks))
        if key not in kids:
            child = TorusArrangement(tuple(array.array("H", twin)), tuple(marks), (), key)
            kids[key] = (child, _Facts(0, bool(cellular), True))
    out = [kids[k] for k in sorted(kids)]
    stats.states += len(out)
    stats.targets += sum(f.target for _, f in out)
    return out


def torus_arrangements(max_crossings: int, colours: int | None = None, regions: bool = False,
                       on_stats: Callable[[TorusSearchStats], None] | None = None
                       ) -> Iterator[TorusArrangement]:
    """Every cellular arrangement of simple loops on the torus with at most ``max_crossings``
    crossings and a crossing graph that ``colours`` colours colour, once up to homeomorphism,
    mirror images identified; with ``regions``, only the candidate maps (regions of 3 to 6
    sides, none with two sides on one loop or on both sides of an edge, a simple quad mesh)."""
    stats = TorusSearchStats()
    stack: list[tuple[TorusArrangement, _Facts] | int] = [1, 0]
    while stack:
        node = stack.pop()
        parent = node if isinstance(node, int) else node[0]
        if not isinstance(node, int) and node[1].target:
            yield node[0]
        stack.extend(reversed(torus_children(parent, max_crossings, colours, regions, stats)))
    if on_stats:
        on_stats(stats)


def _zones_split_every_loop(a: TorusArrangement) -> bool:
    """Whether, for each class of the bipartition of the crossing graph, every loop of it has
    two different zones on its sides (zones: the components left when that class's loops are
    cut away).  A loop with one zone on both sides is a loop of its level graph, so no ``B``
    of a polycube has one."""
    side = _classes(a)
    for cls in (0, 1):
        zones = DisjointSets(range(len(a.faces)))
        for d in range(len(a.twin)):
            if side[a.loop_of[d]] != cls:
                zones.union(a.face_of[d], a.face_of[a.twin[d]])
        if any(side[a.loop_of[d]] == cls and zones.find(a.face_of[d]) == zones.find(a.face_of[a.twin[d]])
               for d in range(len(a.twin))):
            return False
    return True


def two_axis_bases(max_crossings: int, on_stats: Callable[[TorusSearchStats], None] | None = None
                   ) -> Iterator[TorusArrangement]:
    """Every cellular arrangement with a bipartite crossing graph and at most ``max_crossings``
    crossings whose loops each have two different zones on their sides: the arrangements ``B``
    of the second stage."""
    for a in torus_arrangements(max_crossings, colours=2, on_stats=on_stats):
        if _zones_split_every_loop(a):
            yield a


SECOND_STAGE = "regions"  # or "loops": third-axis loops one at a time (the twin, kept for the tests)


def candidate_torus_arrangements(max_crossings: int, res: int = 0, mod: int = 1,
                                 on_stats: Callable[[TorusSearchStats], None] | None = None,
                                 polycubes: bool = True,
                                 bases: tuple[Sequence[bytes], TorusSearchStats] | None = None
                                 ) -> Iterator[TorusArrangement]:
    """Every map of genus 1 with at most ``max_crossings`` crossings that carries a polycube
    loop structure, once up to homeomorphism, through the two stages: each ``B`` with at most
    a third of the crossings, then its third axis (:data:`SECOND_STAGE`: region by region,
    :func:`polyloops.generate.torus.regions.third_axis_systems`, or loop by loop); a map is
    listed from its canonical decomposition (:func:`polycube_decompositions`).  ``res``/``mod``
    keeps the ``B`` whose rank is ``res`` modulo ``mod`` (independent shares).  With
    ``polycubes`` false (the loop-by-loop stage only) every map with a decomposition is listed,
    from its canonical one among :func:`two_stage_decompositions`.  ``bases`` gives the first
    stage's arrangements (:func:`first_stage`) when they were listed already.  The maps come
    without a ``code`` (:func:`canonical` gives it)."""
    if not polycubes and SECOND_STAGE != "loops":
        raise ValueError("only the loop-by-loop second stage lists maps that carry no polycube")
    stats = TorusSearchStats()
    listed, first_stats = bases if bases is not None else first_stage(max_crossings // 3)
    if res == 0:
        stats.add(first_stats)
    for rank, raw in enumerate(listed):
        if rank % mod != res:
            continue
        for kid in _third_axes(_base(raw), max_crossings, stats):
            if (not polycubes or carries_polycube(kid)) and _canonical_decomposition(kid, polycubes):
                yield TorusArrangement(kid.twin)
    if on_stats:
        on_stats(stats)


def _third_axes(base: TorusArrangement, max_crossings: int, stats: TorusSearchStats
                ) -> Iterator[TorusArrangement]:
    """The decompositions with ``B = base`` (:func:`decomposes`), each once up to homeomorphism,
    that the chosen second stage reaches (the region search leaves out those whose loops of
    ``B`` no orientation fits)."""
    if SECOND_STAGE == "loops":
        yield from (_second_stage_compiled if _compiled() else _second_stage)(base, max_crossings, stats)
        return
    from polyloops.generate.torus.regions import third_axis_systems

    seen: set[bytes | tuple] = set()
    code = layered_code
    for twin, layer in third_axis_systems(base, max_crossings, stats):
        kid = TorusArrangement(twin, (), layer)
        key = code(kid)
        if key in seen:
            continue
        seen.add(key)
        if decomposes(TorusArrangement(twin), frozenset(kid.third_loops()), max_crossings):
            yield kid


@lru_cache(maxsize=4)
def _bases(max_crossings: int, compiled: bool) -> tuple[tuple[bytes, ...], TorusSearchStats]:
    """:func:`two_axis_bases` (each as its ``twin`` array of uint16, compactly: 150,791 through
    14 crossings) and the first stage's statistics, kept for the process's later shares (a
    catalog's worker runs several)."""
    import array

    stats = TorusSearchStats()
    listed = two_axis_bases(max_crossings, on_stats=stats.add)
    return tuple(array.array("H", a.twin).tobytes() for a in listed), stats


def first_stage(max_crossings: int) -> tuple[tuple[bytes, ...], TorusSearchStats]:
    """The arrangements ``B`` of :func:`two_axis_bases` with at most ``max_crossings``
    crossings, each as its ``twin`` array of uint16 (bytes), and the search's statistics; kept
    for the process's later calls."""
    return _bases(max_crossings, _compiled())


def _base(raw: bytes) -> TorusArrangement:
    import array

    return TorusArrangement(tuple(array.array("H", raw)))


def _second_stage(base: TorusArrangement, max_crossings: int, stats: TorusSearchStats
                  ) -> Iterator[TorusArrangement]:
    """The second stage from ``base``: every target state in which ``B`` has the fewest
    crossings of the three two-axis arrangements and no loop of ``B`` lacks third-axis
    crossings (the others are no decomposition of their map)."""
    stack = [TorusArrangement(base.twin, (), (0,) * len(base.twin))]
    while stack:
        kids = torus_children(stack.pop(), max_crossings, None, True, stats)
        for kid, facts in kids:
            if facts.target and _balanced(kid, base.crossings) and _deficit(kid, _classes(kid)) == 0:
                yield kid
        stack.extend(kid for kid, _ in reversed(kids))


def _second_stage_compiled(base: TorusArrangement, max_crossings: int, stats: TorusSearchStats
                           ) -> Iterator[TorusArrangement]:
    """:func:`_second_stage` by the compiled search, the states kept as the bytes it works on
    (the same targets, in another order)."""
    import array

    stack = [(array.array("H", base.twin).tobytes(), bytes(len(base.twin)))]
    while stack:
        kids = _layered_children(*stack.pop(), max_crossings, stats)
        for (twin, layer), flags in kids:
            if flags == 7:  # a target, balanced, no loop of B lacking (else not a decomposition)
                yield TorusArrangement(tuple(array.array("H", twin)), (), tuple(layer))
        stack.extend(key for key, _ in reversed(kids))


def _canonical_decomposition(kid: TorusArrangement, polycubes: bool = True) -> bool:
    """Whether a second-stage state is its map's canonical decomposition: the least code of
    the map with the loops of a decomposition marked, over all its decompositions that carry a
    polycube (:func:`polycube_decompositions`; all of them with ``polycubes`` false)."""
    plain = TorusArrangement(kid.twin)
    code = layered_code
    own = code(TorusArrangement(kid.twin, (), kid.layer))
    listed = polycube_decompositions if polycubes else two_stage_decompositions
    codes = [code(_with_layer(plain, chosen)) for chosen in listed(plain, plain.crossings)]
    return own == min(codes, default=None)


def _with_layer(a: TorusArrangement, chosen: frozenset[int]) -> TorusArrangement:
    return TorusArrangement(a.twin, (), tuple(int(a.loop_of[d] in chosen) for d in range(len(a.twin))))


def polycube_decompositions(a: TorusArrangement, max_crossings: int) -> list[frozenset[int]]:
    """The decompositions (:func:`two_stage_decompositions`) whose labelling, the loops ``D``
    one axis and the two classes of ``B`` the others, carries a polycube loop structure: the
    ones a polycube on the map has, by the two-stage theorem, when ``D`` is its axis whose
    deletion leaves fewest crossings."""
    return [chosen for chosen in two_stage_decompositions(a, max_crossings)
            if carries_polycube(_with_layer(a, chosen))]


def carries_polycube(a: TorusArrangement) -> bool:
    """Whether a second-stage arrangement (with its ``layer``) carries a polycube loop
    structure labelled by its decomposition: the third axis one axis, the two classes of ``B``
    the others."""
    from polyloops.core.labellings import admits_polycube

    return admits_polycube(*labelled_mesh(a))


def labelled_mesh(a: TorusArrangement) -> tuple[HalfEdgeMap, list[int]]:
    """The dual quad mesh of a second-stage arrangement and the label of each of its loops (in
    the mesh's numbering): :data:`THIRD` for the third axis, the class in ``B`` otherwise."""
    m = a.quad_mesh()  # quad v is crossing v
    system = m.loop_system
    klass = _classes(a)
    crossings: dict[int, set[int]] = {}
    for v in range(a.crossings):
        for d in (4 * v, 4 * v + 1):
            crossings.setdefault(a.loop_of[d], set()).add(v)
    mine = {frozenset(vs): lp for lp, vs in crossings.items()}
    faces: dict[int, set[int]] = {}
    for v in range(m.num_faces):
        for lp in system.loops_of_face(m, v):
            faces.setdefault(lp, set()).add(v)
    return m, [klass[mine[frozenset(faces[lp])]] for lp in range(len(system.loops))]


def layered_code(a: TorusArrangement) -> bytes | tuple[int, ...]:
    """A canonical code of a layered arrangement: the compiled one when the part ``torus`` runs,
    the Python one otherwise (within one run, equal classes get equal codes)."""
    return _layered_code(a) if _compiled() else canonical(a)[0]


def _layered_code(a: TorusArrangement) -> bytes:
    """The compiled search's canonical code of a layered arrangement (its own order)."""
    import array

    _torus = compiled.require("torus")

    return _torus.layered_code(array.array("H", a.twin).tobytes(), bytes(a.layer))


def third_sides_consistent(a: TorusArrangement) -> bool:
    """Whether the third axis's loops of a second-stage state can be oriented so that every
    face between two of them lies on the ``+`` side of one and the ``-`` side of the other.

    In a polycube each region of ``B`` is a path of corners along the third axis, and a corner
    between two edges of that axis has one ``+`` and one ``-`` edge.  A later third-axis loop
    through such a face cuts it into two faces whose two constraints imply the old one, so an
    inconsistency is never repaired: no polycube grows from the state."""
    return _third_faces(a, _walk_forward(a)) is not None


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


def _walk_forward(a: TorusArrangement) -> list[int]:
    """Per dart, +1 when it leaves its crossing along its loop's reference walk (from the
    loop's least dart), -1 when against it."""
    forward = [0] * len(a.twin)
    for d in range(len(a.twin)):
        if forward[d] == 0:
            e = d
            while forward[e] == 0:
                forward[e], forward[a.twin[e]] = 1, -1
                e = _rot4(_rot4(a.twin[e]))
    return forward


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
    klass = _classes(a)
    forward = _walk_forward(a)
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
            other = _rot4(e)
            crossed.append((a.loop_of[other], 1 if forward[other] == 1 else -1))
            e = _rot4(_rot4(a.twin[e]))
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


def _balanced(a: TorusArrangement, base_crossings: int) -> bool:
    """Whether ``B`` has the fewest crossings of the three two-axis arrangements: the third
    axis crosses each class of ``B``'s bipartition at least as often as ``B`` crosses itself."""
    third = a.third_loops()
    side = _classes(a)
    with_class = [0, 0]
    for v in range(a.crossings):
        l1, l2 = a.loop_of[4 * v], a.loop_of[4 * v + 1]
        if (l1 in third) != (l2 in third):
            other = l2 if l1 in third else l1
            with_class[side[other]] += 1
    return min(with_class) >= base_crossings


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
    return [chosen for chosen in _independent_with_bipartite_rest(a.crossing_graph())
            if decomposes(a, chosen, max_crossings)]


def decomposes(a: TorusArrangement, chosen: frozenset[int], max_crossings: int) -> bool:
    """Whether the loops ``chosen`` of a cellular arrangement are a decomposition in the sense
    of :func:`two_stage_decompositions` (the final test of the second stage)."""
    try:
        base = a.without_loops(set(chosen))
    except ValueError:
        return False
    if base.crossings > max_crossings // 3 or not _zones_split_every_loop(base):
        return False
    crossings = a.loop_crossings()
    layer = tuple(int(a.loop_of[d] in chosen) for d in range(len(a.twin)))
    layered = TorusArrangement(a.twin, (), layer)
    region = _regions_of_base(layered)
    once = all(len({region[d] for d in range(len(a.twin)) if a.loop_of[d] == lp}) == crossings[lp]
               for lp in chosen)
    return (once and _balanced(layered, base.crossings) and orientable(layered)
            and _facts(layered, True, None).target and _deficit(layered, _classes(layered)) == 0
            and all(axis_runs(layered, lp) >= 4 for lp in chosen))


def _independent_with_bipartite_rest(adj: list[set[int]]) -> list[frozenset[int]]:
    """Every nonempty set of loops, not all of them, no two of which cross, whose complement's
    crossing graph is bipartite: the colour classes of proper 3-colourings (such a set and the
    two sides of its complement are one), sorted."""
    every = frozenset(range(len(adj)))
    found = {frozenset(v for v, c in enumerate(colouring) if c == k)
             for colouring in proper_colourings(adj, 3) for k in range(3)}
    return sorted((d for d in found if d and d != every), key=sorted)
