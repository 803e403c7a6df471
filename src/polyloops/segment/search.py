"""The search of ``polyloops segment``: states of loops on the surface, a start, greedy moves.

Two kinds of loop are drawn on the surface.  *Section curves* are closed curves of
axis-aligned plane sections (:mod:`~polyloops.segment.refine`): a loop of axis X runs round the
X axis, across triangles whose normals are perpendicular to it, which is what the paper's
Section 5 asks of a loop's path; the surface is cut once by a set of candidate planes per axis.
*Drawn additions* are the kernel's valid additions of the current structure drawn as cheapest
paths (:mod:`~polyloops.segment.paths`), valid by construction.  A *state* is a set of loops.

1. **Start**: at genus 0 the cube, three curves of the planes through the centroid (or nearest
   it) that cross pairwise twice, checked as a polycube loop structure; at any genus (and at
   genus 0 when no cube is found) a grid of section curves mended into a polycube loop
   structure (:mod:`~polyloops.segment.grid`; finer grids, and grids of a polycube-like
   deformation, are tried in turn); or a given start (:mod:`~polyloops.segment.start`).
2. **Search**: greedy, under a time budget: every move from the current state (add a section
   curve, add one of the first :data:`PATH_MOVES` valid additions of each axis drawn as a path,
   remove a loop the kernel's removal test allows, or replace one by a curve of its axis) is
   tried in an order the seed fixes; a state counts when its structure passes ``verify`` and
   primalizes and no region is a sliver (under :data:`MIN_REGION_SHARE` of the area); its
   score is the fidelity its labels could reach (each triangle labelled by the best direction
   among its region's faces, see :class:`_Scorer`), less a price per loop; the best move is
   made while it improves the score.
3. **Layout and certificate** (:mod:`~polyloops.segment.run`): the last states are laid out
   (:mod:`~polyloops.segment.layout`) and checked twice (:mod:`~polyloops.segment.certify`),
   and the certified one whose labels score best is kept; when none passes, the states before
   them are tried in turn.
"""

from __future__ import annotations

import itertools
import random
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from polyloops.core.directions import Axis
from polyloops.core.errors import PolyloopsError
from polyloops.core.moves import removals, valid_additions
from polyloops.segment import PRICE
from polyloops.segment.embedded import Embedded, Loop, NotAStructure, SurfaceLoop, read_structure
from polyloops.segment.labellings import DIRECTION_VECTORS, face_directions
from polyloops.segment.paths import addition_path
from polyloops.segment.refine import Plane, Refined, cut
from polyloops.segment.surface import Surface
from polyloops.verify import check_polycube_loop_structure

__all__ = [
    "SearchPath",
    "SearchSettings",
    "StartError",
    "State",
    "candidate_loops",
    "greedy_search",
    "section_loops",
    "start_state",
]


class StartError(PolyloopsError, ValueError):
    """No start was found on the surface (no three central curves cross pairwise twice)."""


MIN_REGION_SHARE = 0.002  # a move leaving a region smaller than this share of the area is not made


@dataclass(frozen=True)
class SearchSettings:
    """The search's knobs: the time ``budget`` in seconds, the ``seed`` of its move order, the
    candidate ``planes`` per axis, the ``price`` of a loop in fidelity, and a ``guide`` (per
    input triangle the unit vector of a label to keep) that the score follows instead of the
    normals."""

    budget: float = 20.0
    seed: int = 0
    planes: int = 9
    price: float = PRICE
    guide: np.ndarray | None = field(default=None, compare=False)  # per input triangle, a unit vector


@dataclass(frozen=True)
class State:
    """A set of section curves (indices into the candidates) and what they give."""

    loops: frozenset[int]
    score: float
    fidelity: float
    embedded: Embedded = field(compare=False, repr=False)


def candidate_loops(surface: Surface, planes_per_axis: int, heights: np.ndarray | None = None
                    ) -> tuple[Refined, list[SurfaceLoop], list[int]]:
    """The surface cut by the candidate planes (per axis, one through the area centroid, then
    ``planes_per_axis`` evenly spread, all in the ``heights``: the points by default, see
    :mod:`~polyloops.segment.refine`), their section curves, and the indices of the three
    central planes' first curves."""
    hv = surface.points if heights is None else heights
    centroid = surface.area_centroid(heights)
    lo, hi = hv.min(axis=0), hv.max(axis=0)
    planes = [Plane(a, float(centroid[a])) for a in range(3)]
    for a in range(3):
        step = (hi[a] - lo[a]) / (planes_per_axis + 1)
        planes += [Plane(a, float(lo[a] + step * (k + 1))) for k in range(planes_per_axis)
                   if abs(lo[a] + step * (k + 1) - centroid[a]) > step / 4]
    r = cut(Refined.of(surface, heights), planes)
    loops = section_loops(r)
    return r, loops, [i for i, lp in enumerate(loops) if lp.plane < 3]


def section_loops(r: Refined) -> list[SurfaceLoop]:
    """Every closed curve of every plane's section of ``r``, plane by plane."""
    loops: list[SurfaceLoop] = []
    for p in range(len(r.planes)):
        try:
            loops += [SurfaceLoop(p, c) for c in r.sections(p)]
        except ValueError:
            continue  # a degenerate section: its curves are not candidates
    return loops


def _valid(r: Refined, loops: Sequence[Loop]) -> Embedded | None:
    try:
        e = read_structure(r, loops)
    except NotAStructure:
        return None
    if not check_polycube_loop_structure(e.structure).valid:
        return None
    return e


def start_state(r: Refined, loops: list[SurfaceLoop]) -> list[int]:
    """Three curves, one per axis, crossing pairwise twice and making the cube: from the
    central planes first, then from planes ever farther from the centre.

    Raises
    ------
    StartError
        When no three candidate curves make the cube.
    """
    centre = [r.planes[a].value for a in range(3)]
    by_axis: list[list[int]] = [[], [], []]
    for i, lp in enumerate(loops):
        by_axis[r.planes[lp.plane].axis].append(i)
    def nearness(i: int) -> tuple[float, int]:  # central planes first, longer curves first
        plane = r.planes[loops[i].plane]
        return abs(plane.value - centre[plane.axis]), -len(loops[i].vertices)

    for axis in range(3):
        by_axis[axis].sort(key=nearness)
    vsets = [set(lp.vertices) for lp in loops]
    tried = 0
    for i in by_axis[0][:6]:
        for j in by_axis[1][:6]:
            if len(vsets[i] & vsets[j]) != 2:
                continue
            for k in by_axis[2][:6]:
                if len(vsets[i] & vsets[k]) != 2 or len(vsets[j] & vsets[k]) != 2:
                    continue
                tried += 1
                if _valid(r, [loops[i], loops[j], loops[k]]) is not None:
                    return [i, j, k]
    raise StartError(f"no three section curves make a cube ({tried} triples crossing pairwise twice tried)")


def crossing_only(loops: list[SurfaceLoop], chosen: list[int]) -> list[int]:
    """``chosen`` without the curves that cross none of the others (repeatedly)."""
    while True:
        vsets = {i: set(loops[i].vertices) for i in chosen}
        crossing = [i for i in chosen if any(vsets[i] & vsets[j] for j in chosen if j != i)]
        if crossing == chosen:
            return chosen
        chosen = crossing


class _Scorer:
    """The fidelity a state's labels could reach: each triangle labelled by the direction,
    among those of its region's faces (the polycube corner's), nearest its normal; with a
    ``guide`` (per input triangle a unit vector), their agreement with it instead.  A layout
    gives each region's faces sectors of it, and polishing (:mod:`~polyloops.segment.polish`)
    moves each triangle towards that best direction where the patches allow, so this tracks
    the certified labels' fidelity (on two smooth benchmark meshes, seven starts each: within
    0.035 of the polished layout's, where labelling each triangle by its nearest crossing fell
    0.05 to 0.29 short).  It is optimistic where regions are large (a cube's octant may take
    any of its three labels anywhere), so the starts are ranked otherwise (see ``run``)."""

    def __init__(self, r: Refined, guide: np.ndarray | None = None):
        surface = r.surface
        self.areas = surface.areas
        wanted = surface.normals if guide is None else guide[r.parent]
        self.worth = wanted @ DIRECTION_VECTORS.T  # per triangle and direction

    def fidelity(self, e: Embedded) -> float:
        polycube = e.polycube
        allowed = np.full((int(e.region.max()) + 1, 6), -np.inf)
        for face, d in zip(polycube.faces, face_directions(polycube).tolist(), strict=True):
            allowed[list(face), d] = 0.0
        best = (self.worth + allowed[e.region]).max(axis=1)
        return float((self.areas * best).sum() / self.areas.sum())


def nearest_faces(r: Refined, e: Embedded) -> np.ndarray:
    """Per triangle, the face of the crossing nearest it in its region (along the triangles'
    adjacency, from the triangles round each crossing): the patches of a rough layout."""
    centroid = r.points[r.triangles].mean(axis=1)
    pairs, edge_keys = r.adjacency
    on_loops = np.array(sorted(x for lp in e.loops for x in lp.edges()), dtype=np.int64)
    keep = ~np.isin(edge_keys, r.edge_key(on_loops[:, 0], on_loops[:, 1]))
    a, b = pairs[keep, 0], pairs[keep, 1]
    w = np.linalg.norm(centroid[a] - centroid[b], axis=1) + 1e-12
    m = len(r.triangles)
    graph = coo_matrix((np.concatenate([w, w]), (np.concatenate([a, b]), np.concatenate([b, a]))),
                       shape=(m, m)).tocsr()
    sources, face_of_source = [], {}
    for f, v in enumerate(e.crossings):
        for t in r.incident[v]:
            sources.append(t)
            face_of_source[t] = f
    _, _, nearest = dijkstra(graph, indices=sources, min_only=True, return_predecessors=True)
    return np.array([face_of_source.get(int(t), 0) for t in nearest.tolist()], dtype=np.int64)


PATH_MOVES = 2  # valid additions per axis drawn as paths at each step of the search


def _drawn_additions(e: Embedded, loops: list[Loop]) -> list[int]:
    """The first :data:`PATH_MOVES` valid additions of each axis of ``e``'s structure, drawn
    as paths (:mod:`~polyloops.segment.paths`) and appended to ``loops``: their indices."""
    out = []
    for axis in Axis:
        for move in itertools.islice(valid_additions(e.structure, axis), PATH_MOVES):
            path = addition_path(e, move)
            if path is not None:
                loops.append(path)
                out.append(len(loops) - 1)
    return out


@dataclass(frozen=True)
class SearchPath:
    """The states a search went through, the start first and the best last; ``converged`` when
    its last step tried every move and none improved the score (then the same seed gives the
    same states on any machine; a search the budget stopped depends on the machine's speed)."""

    states: tuple[State, ...]
    converged: bool
    loops: tuple[Loop, ...]  # the candidates and the paths drawn: what the states' indices name


def greedy_search(r: Refined, loops: Sequence[Loop], start: list[int], settings: SearchSettings,
                  on_step: Callable[[State], None] | None = None) -> SearchPath:
    """The greedy search from ``start`` (see the module docstring)."""
    deadline = time.monotonic() + settings.budget
    loops = list(loops)  # the paths drawn are added to a copy, returned with the states
    rng = random.Random(settings.seed)
    scorer = _Scorer(r, settings.guide)

    def state(chosen: frozenset[int]) -> State | None:
        e = _valid(r, [loops[i] for i in sorted(chosen)])
        if e is None:
            return None
        if chosen != frozenset(start) and np.bincount(e.region, weights=scorer.areas).min() < tiny:
            return None  # a loop that cuts off a sliver of the surface: a corner no face can fit
        try:
            fid = scorer.fidelity(e)
        except (PolyloopsError, ValueError):
            return None
        return State(chosen, fid - settings.price * len(chosen), fid, e)

    tiny = MIN_REGION_SHARE * float(scorer.areas.sum())
    first = state(frozenset(start))
    assert first is not None  # start_state checked it
    path = [first]
    if on_step:
        on_step(first)
    converged = False
    while time.monotonic() < deadline:
        here = path[-1]
        moves = [here.loops | {i} for i in range(len(loops)) if i not in here.loops]
        # the kernel's valid additions, drawn as cheapest paths (valid by construction)
        moves += [here.loops | {i} for i in _drawn_additions(here.embedded, loops)]
        axis_of = [lp.axis_in(r) for lp in loops]
        # removals the kernel's removal test allows (the structure left is valid by the theorem)
        removable = set(removals(here.embedded.structure))
        moves += [here.loops - {i} for k, i in enumerate(sorted(here.loops))
                  if len(here.loops) > 3 and here.embedded.structure_loop(k) in removable]
        # a loop replaced by a curve of its axis on another plane (often the same crossings)
        moves += [(here.loops - {i}) | {j} for i in sorted(here.loops) for j in range(len(loops))
                  if j not in here.loops and axis_of[j] == axis_of[i]]
        rng.shuffle(moves)
        best, complete = None, True
        for chosen in moves:
            if time.monotonic() >= deadline:
                complete = False
                break
            s = state(chosen)
            if s is not None and s.score > here.score + 1e-9 and (best is None or s.score > best.score):
                best = s
        if best is None:
            converged = complete
            break
        path.append(best)
        if on_step:
            on_step(best)
    return SearchPath(tuple(path), converged, tuple(loops))
