"""A given loop structure embedded on a surface: ``polyloops segment --start``.

A start is a polycube loop structure (a catalog class such as ``T32.1``, a signature, a file)
of the surface's genus.  It is embedded by plane sections: its polycube
(:meth:`~polyloops.core.structure.LoopStructure.primalize`) is turned by one of the 48 signed
permutations of the axes; each loop lies between the levels of the corners its segments join,
so it is drawn at the middle of the levels all its segments span (its *level*); the levels of
an axis, in order, are matched with planes of the surface's candidate grid, in the same order,
whose sections hold at least as many curves as the level holds loops, the planes nearest the
levels' places in the bounding box first.  A choice of curves is the start when the structure
read off the surface (:func:`~polyloops.segment.embedded.read_structure`) is the turned start
itself, labels and sides included (:func:`~polyloops.core.canonical.is_isomorphic`, labelled):
an orientation-preserving homeomorphism of the surfaces then carries each loop of the start to
its curve, so every loop is embedded in its homology class, and the search begins from there.

When no choice in the surface's coordinates reproduces the start, the planes cut a
polycube-like deformation of the surface instead (:mod:`~polyloops.segment.deform`), whose
sections follow a thin handle or a tilted arm where planes of the coordinates fall apart.

A loop whose segments span no common level (it is no plane section of its polycube) cannot be
drawn this way; such a start is refused with its reason, as is a surface on which no choice
within the tries reproduces the start.

>>> from polyloops.io.examples import load_example
>>> [len(levels) for levels in start_levels(load_example("cube").dualize())]
[1, 1, 1]
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass

from polyloops.core.canonical import is_isomorphic, signature, transformed
from polyloops.core.errors import PolyloopsError
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import SIGNED_PERMUTATIONS, SignedPermutation, Symmetry
from polyloops.segment.deform import polycube_heights
from polyloops.segment.embedded import NotAStructure, SurfaceLoop, read_structure
from polyloops.segment.refine import Refined
from polyloops.segment.search import StartError, candidate_loops, crossing_only
from polyloops.segment.surface import Surface
from polyloops.verify import check_polycube_loop_structure

__all__ = ["Level", "StartMismatch", "StartPlacement", "check_start", "embed_start", "start_levels"]


class StartMismatch(PolyloopsError, ValueError):
    """A start that cannot be one for this surface: another genus, or no polycube loop
    structure (bad input, not a failed search)."""


@dataclass(frozen=True)
class Level:
    """A plane of a start's polycube: its ``axis``, its ``value`` (the middle of the levels its
    loops' segments all span) and how many ``loops`` of the start lie on it."""

    axis: int
    value: float
    loops: int


@dataclass(frozen=True)
class StartPlacement:
    """Where a start was embedded: the signed permutation that turned it, the curves (indices
    into the candidates), the tries it took and whether the planes cut the deformation."""

    symmetry: SignedPermutation
    curves: tuple[int, ...]
    tries: int
    deformed: bool = False  # the planes cut the polycube-like deformation, not the coordinates


def start_levels(start: LoopStructure) -> tuple[tuple[Level, ...], ...]:
    """Per axis, the levels of ``start``'s loops on its primalized polycube, in order.

    Raises
    ------
    StartError
        When a loop is no plane section of the polycube (its segments span no common level).
    """
    q = start.primalize()
    ls = q.dualize()
    spans: dict[int, list[tuple[int, int]]] = {}
    for e in ls.segments:
        u, v = ls.map.edge_corners(e)
        a = int(ls.axes[ls.loop_of_segment(e)])
        lo, hi = sorted((q.positions[u][a], q.positions[v][a]))
        spans.setdefault(ls.loop_of_segment(e), []).append((lo, hi))
    levels: list[dict[float, int]] = [{}, {}, {}]
    for loop, sp in sorted(spans.items()):
        lo, hi = max(s[0] for s in sp), min(s[1] for s in sp)
        if lo >= hi:
            raise StartError(f"loop {loop} of the start is no plane section of its polycube (its "
                             "segments span no common level), so it cannot be drawn by a plane")
        a = int(ls.axes[loop])
        value = (lo + hi) / 2
        levels[a][value] = levels[a].get(value, 0) + 1
    lo_box = [min(p[a] for p in q.positions) for a in range(3)]
    hi_box = [max(p[a] for p in q.positions) for a in range(3)]
    return tuple(tuple(Level(a, (v - lo_box[a]) / (hi_box[a] - lo_box[a]), n)
                       for v, n in sorted(levels[a].items())) for a in range(3))


def check_start(surface: Surface, start: LoopStructure) -> None:
    """Refuse a start of another genus than the surface's, or no polycube loop structure.

    Raises
    ------
    StartMismatch
        Naming both genera, or the condition the start breaks.
    """
    if start.genus != surface.genus:
        raise StartMismatch(f"the start has genus {start.genus} and the mesh genus {surface.genus}")
    report = check_polycube_loop_structure(start)
    if not report.valid:
        v = report.violations[0]
        raise StartMismatch(f"the start is no polycube loop structure (condition {v.condition}: {v.message})")


TRIES_PER_AXIS = 8  # plane choices kept per axis, nearest the levels' places first
SUBSETS = 4  # choices of curves tried on a plane with more curves than the level's loops
MAX_TRIES = 300  # structures read off one grid before the next grid is cut


def embed_start(surface: Surface, start: LoopStructure, grids: tuple[int, ...] = (9, 13, 19),
                budget: float = float("inf")) -> tuple[Refined, list[SurfaceLoop], StartPlacement]:
    """The surface cut by a grid of candidate planes (the first of ``grids`` that works), its
    candidate curves, and where ``start`` lies on it (see the module docstring).

    Raises
    ------
    StartMismatch
        When the start has another genus than the surface, or is no polycube loop structure.
    StartError
        When no choice of curves within the tries (or ``budget`` seconds) reproduces it.
    """
    check_start(surface, start)
    began = time.monotonic()
    turned = _turned(start)
    if not turned:
        start_levels(start)  # raises, naming a loop that is no plane section
        raise StartError("no turn of the start has all its loops plane sections")
    reasons: list[str] = []
    tries = 0
    deformed = None
    for k in grids:
        for kind in ("coordinates", "deformation"):
            if reasons and time.monotonic() - began > budget:
                reasons.append("nothing more tried: the time budget is spent")
                raise StartError("the start was not found among plane sections: " + "; ".join(reasons))
            if kind == "deformation" and deformed is None:
                deformed = polycube_heights(surface)
            r, loops, _ = candidate_loops(surface, k, deformed if kind == "deformation" else None)
            found = _place(r, loops, turned, began + budget)
            if isinstance(found, StartPlacement):
                return r, loops, StartPlacement(found.symmetry, found.curves, tries + found.tries,
                                                kind == "deformation")
            tries += found
            reasons.append(f"{k} planes an axis in the {kind}: no choice of {found} reproduced it")
    raise StartError("the start was not found among plane sections: " + "; ".join(reasons))


Turn = tuple[SignedPermutation, LoopStructure, tuple[tuple[Level, ...], ...]]


def _turned(start: LoopStructure) -> list[Turn]:
    """The start under each signed permutation (one per distinct image) with its levels."""
    out: list[Turn] = []
    seen = set()
    for g in SIGNED_PERMUTATIONS:
        image = transformed(start, g)
        key = signature(image, Symmetry.LABELLED)
        if key in seen:
            continue
        seen.add(key)
        try:
            out.append((g, image, start_levels(image)))
        except StartError:
            continue
    return out


def _place(r: Refined, loops: list[SurfaceLoop], turned: list[Turn], deadline: float) -> StartPlacement | int:
    """The first choice of curves reproducing a turn of the start, or the number tried."""
    planes_of: list[list[int]] = [[], [], []]
    for p, plane in enumerate(r.planes):
        planes_of[plane.axis].append(p)
    curves_on: dict[int, list[int]] = {}
    for i, lp in enumerate(loops):
        curves_on.setdefault(lp.plane, []).append(i)
    lo = r.heights.min(axis=0)
    span = r.heights.max(axis=0) - lo
    place = {p: (pl.value - lo[pl.axis]) / span[pl.axis] for p, pl in enumerate(r.planes)}
    count = {p: len(curves_on.get(p, ())) for p in place}
    for a in range(3):
        planes_of[a].sort(key=lambda p: place[p])
    plans = []  # (cost, turn, planes per level)
    for t, (_, _, levels) in enumerate(turned):
        per_axis = []
        for a in range(3):
            options = []
            for chosen in itertools.combinations(planes_of[a], len(levels[a])):
                pairs = list(zip(chosen, levels[a], strict=True))
                if all(count[p] >= lv.loops for p, lv in pairs):
                    # planes whose sections hold just the level's loops first, then the nearest
                    excess = sum(count[p] - lv.loops for p, lv in pairs)
                    options.append(((excess, sum((place[p] - lv.value) ** 2 for p, lv in pairs)), chosen))
            options.sort()
            per_axis.append(options[:TRIES_PER_AXIS])
        for combo in itertools.product(*per_axis):
            cost = (sum(c[0] for c, _ in combo), sum(c[1] for c, _ in combo))
            plans.append((cost, t, tuple(p for _, chosen in combo for p in chosen)))
    plans.sort()
    tries = 0
    for _, t, chosen_planes in plans:
        g, image, levels = turned[t]
        wanted = [lv.loops for axis_levels in levels for lv in axis_levels]
        for curves in itertools.islice(_curve_choices(loops, curves_on, chosen_planes, wanted), SUBSETS):
            if time.monotonic() > deadline or tries >= MAX_TRIES:
                return tries
            tries += 1
            try:
                e = read_structure(r, [loops[i] for i in curves])
            except NotAStructure:
                continue
            if is_isomorphic(e.structure, image, Symmetry.LABELLED):
                return StartPlacement(g, tuple(curves), tries)
    return tries


def _curve_choices(loops: list[SurfaceLoop], curves_on: dict[int, list[int]], planes: tuple[int, ...],
                   wanted: list[int]):
    """Choices of ``wanted[k]`` curves on ``planes[k]``: the longest curves first."""
    per_plane = []
    for p, n in zip(planes, wanted, strict=True):
        ranked = sorted(curves_on[p], key=lambda i: -len(loops[i].vertices))
        per_plane.append(list(itertools.combinations(ranked, n)))
    for pick in itertools.product(*per_plane):
        curves = sorted(i for group in pick for i in group)
        if crossing_only(loops, curves) == curves:
            yield curves
