"""Arrangements of loops on the torus as marked maps, and their canonical codes.

The dual of a genus-1 quad mesh is a *cellular* arrangement of simple closed curves on the
torus: a 4-regular map whose crossings are the quads and whose regions (all discs) are the
corners; on the torus there are as many corners as crossings.  A connected union of curves on
the torus carries its first homology (rank 2: the faces are discs), or a rank-1 part of it (one
face is an annulus, the others discs), or nothing (one face is a torus with a hole).  Its
rotation system describes a torus in the first case and a sphere in the others, and a *state*
of the search (:mod:`~polyloops.generate.torus.stages`) is the rotation system with its non-disc
faces *marked*: no mark, the two ends of the annulus (:data:`ANNULUS`), or the holed torus
(:data:`HANDLE`).  Two states are one graph on the torus up to homeomorphism exactly when their
marked maps are isomorphic, which :func:`canonical` decides.

In the second stage an arrangement also carries a ``layer``: the darts of its third axis's
loops, the two-axis arrangement ``B`` being the rest (:func:`axis_classes`).

>>> a = TorusArrangement((2, 3, 0, 1))  # one crossing: two loops, one region
>>> a.crossings, a.num_loops, a.cellular, len(a.faces)
(1, 2, True, 1)
"""

from __future__ import annotations

import array
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property

from polyloops.core import compiled
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.halfedge import HalfEdgeMap, permutation_orbits

__all__ = [
    "ANNULUS",
    "HANDLE",
    "MARK_NEED",
    "THIRD",
    "TorusArrangement",
    "arrangement_of_twin",
    "axis_classes",
    "canonical",
    "irot4",
    "labelled_mesh",
    "layered_code",
    "piece_mark",
    "piece_of_mark",
    "pieces_need",
    "regions_of_base",
    "rot4",
    "twin_bytes",
    "walk_forward",
    "with_layer",
]

ANNULUS, HANDLE = "A", "H"  # an end of the annulus face; the face with the handle
MARK_NEED = {HANDLE: 2, ANNULUS: 1}  # a holed torus is crossed twice at least, an annulus end once
THIRD = 2  # the class of the third axis's loops in the second stage


def piece_mark(genus: int, piece: int) -> str:
    """The kind of a mark on a surface of genus 2 or more: the face is a boundary of the non-disc
    piece ``piece`` (an id within the state) of genus ``genus``; each boundary of a piece carries
    one mark.  The torus keeps :data:`ANNULUS` and :data:`HANDLE`.

    >>> piece_mark(1, 0), piece_of_mark(piece_mark(1, 0)), piece_of_mark(ANNULUS), piece_of_mark(HANDLE)
    ('g1.0', (1, '0'), (0, 'A'), (1, 'H'))
    """
    return f"g{genus}.{piece}"


def piece_of_mark(kind: str) -> tuple[int, str]:
    """The genus of the piece a mark's face bounds, and the piece's key (the two ends of the
    torus's annulus are one piece)."""
    if kind in (ANNULUS, HANDLE):
        return (0 if kind == ANNULUS else 1), kind
    genus, piece = kind[1:].split(".")
    return int(genus), piece


def pieces_need(kinds: Sequence[str]) -> int:
    """Twice a lower bound on the later crossings that the pieces of these marks take (all of
    each piece's marks given).  A piece of genus ``h`` with ``b`` boundaries cut into discs by
    ``p`` points of its boundary and ``c`` crossings inside has ``2 - 2h - b + p/2 + c`` faces
    (Euler's formula: each point adds an edge to the boundary and an end of an arc, each
    crossing four ends), at least one, so ``p + 2c >= 2 (2h + b - 1)``; the torus's marks keep
    :data:`MARK_NEED`.

    >>> pieces_need(["A", "A"]), pieces_need(["H"]), pieces_need(["g1.0"]), pieces_need(["g0.3"] * 3)
    (2, 2, 4, 4)
    """
    total = 0
    pieces: dict[str, list[int]] = {}
    for kind in kinds:
        if kind in MARK_NEED:
            total += MARK_NEED[kind]
        else:
            genus, piece = piece_of_mark(kind)
            pieces.setdefault(piece, [genus, 0])[1] += 1
    return total + sum(2 * (2 * genus + b - 1) for genus, b in pieces.values())


def rot4(d: int) -> int:
    """The next dart counter-clockwise round its crossing (four darts a crossing)."""
    return 4 * (d // 4) + (d + 1) % 4


def irot4(d: int) -> int:
    """The next dart clockwise round its crossing."""
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
        return permutation_orbits([irot4(t) for t in self.twin])

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
                    e = rot4(rot4(self.twin[e]))
                n += 1
        return tuple(out)

    @property
    def num_loops(self) -> int:
        """The number of loops."""
        return max(self.loop_of, default=-1) + 1

    @property
    def genus(self) -> int:
        """The genus of the surface a cellular arrangement lies on (``V - E + F = 2 - 2g``, with
        ``E = 2V``), without building its quad mesh."""
        return (2 + self.crossings - len(self.faces)) // 2

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
                t = self.twin[rot4(rot4(t))]
            return t

        out = TorusArrangement(tuple(index[through(self.twin[d])] for d in sorted(index)))
        if len(out.faces) - out.crossings != len(self.faces) - self.crossings:
            raise ValueError("what is left is not cellular")  # V - E + F = F - V falls unless cellular
        if out.num_loops != self.num_loops - len(loops):
            raise ValueError("a loop is left without crossings")
        return out

    def quad_mesh(self) -> HalfEdgeMap:
        """The dual quad mesh: a quad a crossing, a corner a region (cellular, no two regions
        sharing two edges, none on both sides of one)."""
        if self.marks:
            raise ValueError("a non-cellular arrangement has no dual quad mesh")
        return HalfEdgeMap.from_faces([[self.face_of[irot4(d)] for d in range(4 * v, 4 * v + 4)]
                                       for v in range(self.crossings)])


# -- the canonical form of a marked map -----------------------------------------------------------

def twin_bytes(a: TorusArrangement) -> bytes:
    """``a.twin`` as an array of uint16, the form the compiled searches and the first stage use."""
    return array.array("H", a.twin).tobytes()


def arrangement_of_twin(raw: bytes, layer: Sequence[int] = ()) -> TorusArrangement:
    """The arrangement :func:`twin_bytes` wrote (with ``layer`` when given)."""
    return TorusArrangement(tuple(array.array("H", raw)), (), tuple(layer))


def _mark_sets(a: TorusArrangement, mirrored: bool) -> list[tuple[str, frozenset[int]]]:
    # A face is a cyclic list of angles; the angle between d and rot(d) lies in the face on the
    # left of d, and in the mirror image in the face on the left of rot(d).
    out = []
    for kind, dart in a.marks:
        face = a.faces[a.face_of[dart]]
        out.append((kind, frozenset(rot4(d) for d in face) if mirrored else frozenset(face)))
    return out


def _code(a: TorusArrangement, mirrored: bool, root: int, mark_sets: list[tuple[str, frozenset[int]]]
          ) -> tuple[tuple, list[int]]:
    """The breadth-first code of ``a`` from dart ``root`` (twins in the numbering, the layer,
    then the marked faces by their least dart number), and the darts in numbering order."""
    step = irot4 if mirrored else rot4
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
    least = [min(num[e] for e in face) for _, face in mark_sets]
    if all(kind in MARK_NEED for kind, _ in mark_sets):
        marks: tuple = tuple(sorted(zip(least, (kind for kind, _ in mark_sets), strict=True)))
    else:  # a piece is named by the least number of its boundaries
        pieces: dict[str, int] = {}
        for (kind, _), low in zip(mark_sets, least, strict=True):
            key = piece_of_mark(kind)[1]
            pieces[key] = min(pieces.get(key, low), low)
        marks = tuple(sorted((low, piece_of_mark(kind)[0], pieces[piece_of_mark(kind)[1]])
                             for (kind, _), low in zip(mark_sets, least, strict=True)))
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


# -- the second stage's layer ---------------------------------------------------------------------

def axis_classes(a: TorusArrangement) -> list[int]:
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


def walk_forward(a: TorusArrangement) -> list[int]:
    """Per dart, +1 when it leaves its crossing along its loop's reference walk (from the
    loop's least dart), -1 when against it."""
    forward = [0] * len(a.twin)
    for d in range(len(a.twin)):
        if forward[d] == 0:
            e = d
            while forward[e] == 0:
                forward[e], forward[a.twin[e]] = 1, -1
                e = rot4(rot4(a.twin[e]))
    return forward


def regions_of_base(a: TorusArrangement) -> list[int]:
    """Per dart, the region of ``B`` (the arrangement without the third axis's loops) that the
    face on its left lies in: faces joined across third-axis edges."""
    joined = DisjointSets(range(len(a.faces)))
    for d, flag in enumerate(a.layer):
        if flag:
            joined.union(a.face_of[d], a.face_of[a.twin[d]])
    return [joined.find(a.face_of[d]) for d in range(len(a.twin))]


def with_layer(a: TorusArrangement, chosen: frozenset[int]) -> TorusArrangement:
    """``a`` with the loops ``chosen`` as its third axis."""
    return TorusArrangement(a.twin, (), tuple(int(a.loop_of[d] in chosen) for d in range(len(a.twin))))


def labelled_mesh(a: TorusArrangement) -> tuple[HalfEdgeMap, list[int]]:
    """The dual quad mesh of a second-stage arrangement and the label of each of its loops (in
    the mesh's numbering): :data:`THIRD` for the third axis, the class in ``B`` otherwise."""
    m = a.quad_mesh()  # quad v is crossing v
    system = m.loop_system
    klass = axis_classes(a)
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
    return _layered_code(a) if compiled.in_use("torus") else canonical(a)[0]


def _layered_code(a: TorusArrangement) -> bytes:
    """The compiled search's canonical code of a layered arrangement (its own order)."""
    return compiled.require("torus").layered_code(twin_bytes(a), bytes(a.layer))
