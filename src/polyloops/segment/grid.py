"""The grid start of ``polyloops segment``: section curves, refined where they break Definition 4.

Every candidate curve of a grid of planes that crosses another is a loop structure on most
surfaces, but seldom a polycube one: where two curves cross twice with nothing between them a
region has two sides (condition 2), and where a curve bends round a thin part a region meets it
twice (condition 3).  Both are local, and both are mended by one more curve through the region,
of an axis that cuts it apart: the axis neither curve has for a region with two sides, and for a
region meeting one side twice the other axis along which the region is longest.  So each round
cuts one plane through the middle of each violating region (in the heights the planes cut, see
:mod:`~polyloops.segment.refine`) and adds the curve of its section that passes there.  A round's
additions are made when they leave fewer violations; otherwise they are weighed against
removing one of the curves that bound most violating regions (a sliver, a crossing too close
to another are mended so), and the step to the fewest violations is made, never back to a grid
met before.  What comes out is checked like any start; the search then removes the loops it
does not need.

>>> from polyloops.shapes.meshes import torus
>>> from polyloops.segment.surface import surface_of
>>> r, loops, chosen = grid_start(surface_of(*torus(2.0, 0.7, 32, 16)), 9)
>>> read_structure(r, [loops[i] for i in chosen]).structure.genus
1
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass

import numpy as np

from polyloops.core.directions import Direction
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.segment.embedded import Embedded, NotAStructure, SurfaceLoop, read_structure
from polyloops.segment.refine import Plane, Refined, cut
from polyloops.segment.search import StartError, candidate_loops, crossing_only, section_loops
from polyloops.segment.surface import Surface
from polyloops.verify import check_polycube_loop_structure
from polyloops.verify.report import Condition, Report

__all__ = ["ROUNDS", "CutGrid", "cut_grid", "every_crossing", "grid_start", "mend"]

ROUNDS = 24  # rounds of additions or removals before a grid is given up
REMOVALS = 3  # the most blamed curves whose removal is weighed against the additions each round
SAME_PLANE = 0.01  # planes closer than this share of the extent are one plane in a round

Grid = tuple[Refined, list[SurfaceLoop], list[int]]


@dataclass(frozen=True, eq=False)
class CutGrid:
    """A grid as cut, before mending: the cut surface, its candidate curves, the chosen ones
    (every curve that crosses another), the structure they make and its report."""

    refined: Refined
    loops: list[SurfaceLoop]
    chosen: list[int]
    embedded: Embedded
    report: Report

    @property
    def violations(self) -> int:
        """How many violations of Definition 4 the grid has as cut."""
        return len(self.report.violations)


def cut_grid(surface: Surface, planes_per_axis: int, heights: np.ndarray | None = None) -> CutGrid:
    """The grid of ``planes_per_axis`` planes an axis (in ``heights``; the points by default),
    every curve that crosses another chosen, read off the surface and checked.

    Raises
    ------
    StartError
        When those curves make no loop structure at all.
    """
    r, loops, _ = candidate_loops(surface, planes_per_axis, heights)
    return every_crossing(r, loops, "the grid")


def every_crossing(r: Refined, loops: list[SurfaceLoop], what: str) -> CutGrid:
    """Every curve of ``loops`` that crosses another, read off ``r`` and checked.

    Raises
    ------
    StartError
        When those curves make no loop structure at all (``what`` names them).
    """
    chosen = crossing_only(loops, list(range(len(loops))))
    try:
        e = read_structure(r, [loops[i] for i in chosen])
    except NotAStructure as err:
        why = f"{what} of {len(chosen)} section curves is no loop structure: {err}"
        # on a sphere the faces of a connected union of curves are discs: the largest set of
        # curves joined by crossings, of all three axes, is a loop structure there (the aeroplane:
        # the curves round a wing cross none of those round the fuselage)
        for part in _crossing_parts(r, loops, chosen) if r.surface.genus == 0 else []:
            try:
                e = read_structure(r, [loops[i] for i in part])
            except NotAStructure:
                continue
            return CutGrid(r, loops, part, e, check_polycube_loop_structure(e.structure))
        raise StartError(why) from None
    return CutGrid(r, loops, chosen, e, check_polycube_loop_structure(e.structure))


def _crossing_parts(r: Refined, loops: list[SurfaceLoop], chosen: list[int]) -> list[list[int]]:
    """The connected parts of the graph of ``chosen`` curves joined where they cross, those with
    curves of all three axes, most curves first."""
    vsets = {i: set(loops[i].vertices) for i in chosen}
    joined: DisjointSets[int] = DisjointSets(chosen)
    for i, j in itertools.combinations(chosen, 2):
        if vsets[i] & vsets[j]:
            joined.union(i, j)
    parts = [sorted(p) for p in joined.to_sets()]
    full = [p for p in parts if len({r.planes[loops[i].plane].axis for i in p}) == 3]
    return sorted(full, key=lambda p: (-len(p), p))


def grid_start(surface: Surface, planes_per_axis: int, heights: np.ndarray | None = None,
               rounds: int = ROUNDS, deadline: float = float("inf")) -> Grid:
    """The cut surface, its candidate curves, and the chosen ones: a polycube loop structure
    grown from the grid of ``planes_per_axis`` planes an axis (in ``heights``; the points by
    default), as the module docstring says; no round is begun after ``deadline`` (a
    :func:`time.monotonic` time).

    Raises
    ------
    StartError
        When no polycube loop structure came of it (the message says what the last one broke).
    """
    return mend(cut_grid(surface, planes_per_axis, heights), rounds, deadline)


def mend(grid: CutGrid, rounds: int = ROUNDS, deadline: float = float("inf")) -> Grid:
    """``grid`` mended into a polycube loop structure (see the module docstring).

    Raises
    ------
    StartError
        When no polycube loop structure came of it (the message says what the last one broke).
    """
    r, loops, chosen, e, report = grid.refined, grid.loops, grid.chosen, grid.embedded, grid.report
    seen = {_key(loops, chosen)}
    for done in itertools.count():
        if report.valid:
            return r, loops, chosen
        v = report.violations[0]
        why = f"the grid of {len(chosen)} section curves breaks condition {v.condition}: {v.message}"
        if done == rounds or time.monotonic() > deadline:
            why += f" (after {done} rounds of mending" + (
                ")" if done == rounds else ", when the time budget was spent)")
            break
        # the additions when they leave fewer violations; else the step to the fewest among
        # them and a few removals, never back to a grid already met (so the mending cannot go
        # round in a circle)
        checked = []
        added = _add_curves(r, loops, chosen, e, report)
        if added is not None and _key(added[1], added[2]) not in seen:
            checked.append((check_polycube_loop_structure(added[3].structure), added))
        if not checked or len(checked[0][0].violations) >= len(report.violations):
            checked += [(check_polycube_loop_structure(s[3].structure), s)
                        for s in _removals(loops, chosen, e, report) if _key(s[1], s[2]) not in seen]
        if not checked:
            break
        report, (r, loops, chosen, e) = min(checked, key=lambda c: len(c[0].violations))
        seen.add(_key(loops, chosen))
    raise StartError(why)


def _region_of(v: object) -> int | None:
    witness = getattr(v, "witness", {})
    return int(witness["region"]) if "region" in witness else None


def _splitting_planes(e: Embedded, report: Report) -> list[tuple[Plane, np.ndarray]]:
    """Per violating region, a plane through its middle that cuts it apart, with a point of the
    region (in the heights) to find the curve by; planes of one axis closer than
    :data:`SAME_PLANE` of the extent are one."""
    r = e.refined
    triangles = e.region_triangles
    span = np.ptp(r.heights, axis=0)
    out: list[tuple[Plane, np.ndarray]] = []
    for v in report.violations:
        g = _region_of(v)
        if g is None:
            continue
        pts = r.heights[r.triangles[triangles[g]]].reshape(-1, 3)
        extent = np.ptp(pts, axis=0) / np.maximum(span, 1e-300)
        if v.condition == Condition.TWO:
            bounding = {e.loops[k].axis_in(r) for k in _bounding_curves(e, {g})}
            axes = [a for a in range(3) if a not in bounding] or [0, 1, 2]
        elif v.condition == Condition.THREE:
            twice = int(Direction.parse(v.witness["direction"]).axis)
            axes = [a for a in range(3) if a != twice]
        else:
            axes = [0, 1, 2]
        a = max(axes, key=lambda ax: extent[ax])
        value = float((pts[:, a].max() + pts[:, a].min()) / 2)
        if not any(p.axis == a and abs(p.value - value) < SAME_PLANE * span[a] for p, _ in out):
            out.append((Plane(a, value), pts.mean(axis=0)))
    return out


def _add_curves(r: Refined, loops: list[SurfaceLoop], chosen: list[int], e: Embedded, report: Report
                ) -> tuple[Refined, list[SurfaceLoop], list[int], Embedded] | None:
    """The grid with a curve through each violating region added (None when that is no loop
    structure)."""
    wanted = _splitting_planes(e, report)
    if not wanted:
        return None
    kept = [(loops[i].plane, loops[i].vertices[0]) for i in chosen]
    first = len(r.planes)
    r2 = cut(r, [p for p, _ in wanted])
    loops2 = section_loops(r2)
    # the chosen curves, found again by a vertex (vertices keep their numbers when cut)
    where = {(lp.plane, v): i for i, lp in enumerate(loops2) for v in lp.vertices}
    if any(key not in where for key in kept):
        return None  # a chosen section is no longer a union of closed curves
    chosen2 = {where[key] for key in kept}
    for j, (_, point) in enumerate(wanted):
        on = [i for i, lp in enumerate(loops2) if lp.plane == first + j]
        if on:
            chosen2.add(min(on, key=lambda i: float(np.min(np.linalg.norm(
                r2.heights[list(loops2[i].vertices)] - point, axis=1)))))
    chosen3 = crossing_only(loops2, sorted(chosen2))
    try:
        return r2, loops2, chosen3, read_structure(r2, [loops2[i] for i in chosen3])
    except NotAStructure:
        return None


def _removals(loops: list[SurfaceLoop], chosen: list[int], e: Embedded, report: Report
              ) -> list[tuple[Refined, list[SurfaceLoop], list[int], Embedded]]:
    """The grid without one of the :data:`REMOVALS` curves that bound most violating regions,
    each that leaves a loop structure."""
    r = e.refined
    named = {g for g in map(_region_of, report.violations) if g is not None}
    blamed = _bounding_curves(e, named)
    out = []
    for worst in sorted(blamed, key=lambda k: (-blamed[k], k))[:REMOVALS]:
        fewer = crossing_only(loops, [i for j, i in enumerate(chosen) if j != worst])
        try:
            out.append((r, loops, fewer, read_structure(r, [loops[i] for i in fewer])))
        except NotAStructure:
            continue
    return out


def _key(loops: list[SurfaceLoop], chosen: list[int]) -> frozenset[tuple[int, int]]:
    """A grid's chosen curves by plane and least vertex (both kept when more planes cut)."""
    return frozenset((loops[i].plane, min(loops[i].vertices)) for i in chosen)


def _bounding_curves(e: Embedded, regions: set[int]) -> dict[int, int]:
    """Per curve of ``e`` (its index in ``e.loops``), how many of ``regions`` it bounds."""
    r = e.refined
    key_of = {}
    for k, lp in enumerate(e.loops):
        for u, v in lp.edges():
            key_of[int(r.edge_key(u, v))] = k
    pairs, keys = r.adjacency
    count: dict[int, set[int]] = {}
    for (a, b), key in zip(pairs.tolist(), keys.tolist(), strict=True):
        curve = key_of.get(key)
        if curve is None:
            continue
        for g in (int(e.region[a]), int(e.region[b])):
            if g in regions:
                count.setdefault(curve, set()).add(g)
    return {k: len(gs) for k, gs in count.items()}
