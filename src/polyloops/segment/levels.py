"""The level start of ``polyloops segment``: loops between the levels of a polycube-like surface.

On a polycube every face normal to X lies at one of a few levels ``x = c_1 < ... < c_k``, and a
plane strictly between two consecutive levels crosses only faces normal to Y or Z: its section
is a union of X-loops of the polycube's dual loop structure, and the sections of one plane in
each gap between consecutive levels, over the three axes, are all its loops.  On a surface near
a polycube (a CAD part in its own coordinates, or any surface in its polycube-like deformation,
:mod:`~polyloops.segment.deform`) the area whose normal is nearest ``±X`` gathers near such
levels.  So the level start

1. groups, per axis, the triangles whose normal is nearest that axis by their centroid's
   coordinate along it (a gap wider than ``gap`` of the extent begins a new level, and so
   does a gap a tenth as wide between area facing opposite ways: the two sides of a thin
   plate, or of a thin slot, are two levels with a plane between; a level with less than
   :data:`LEAST` of the area is noise; past :data:`MOST_LEVELS` an axis, the lightest level
   joins its nearer neighbour),
2. cuts a plane through the middle of each gap between consecutive levels,
3. builds a loop structure of their sections: the cube of the curves nearest the centre (as the
   cube start does), then every other curve, longest first, kept when the curves still make a
   loop structure (a curve that crosses nothing, or leaves a region that is no disc, waits for
   the next pass; passes repeat until one keeps nothing),

and the grid's mending (:mod:`~polyloops.segment.grid`) repairs what breaks Definition 4.  On a
surface that is a polycube, the start is its own dual loop structure.

>>> from polyloops.io.examples import load_example
>>> from polyloops.segment.surface import surface_of
>>> from polyloops.surface.construct import labelled_mesh_from_polycube
>>> m = labelled_mesh_from_polycube(load_example("l-shape"))
>>> s = surface_of(np.array(m.points, dtype=float), np.array(m.triangles))
>>> sorted((p.axis, p.value) for p in level_planes(s, s.points))
[(0, 0.5), (0, 1.5), (1, 0.5), (1, 1.5), (2, 0.5)]
>>> g = level_grid(s)
>>> len(g.chosen), g.violations
(5, 0)
"""

from __future__ import annotations

import itertools
import time

import numpy as np

from polyloops.segment.embedded import NotAStructure, read_structure
from polyloops.segment.grid import CutGrid, every_crossing
from polyloops.segment.labellings import chart_indices
from polyloops.segment.refine import Plane, Refined, cut
from polyloops.segment.search import StartError, crossing_only, section_loops, start_state
from polyloops.segment.surface import Surface
from polyloops.verify import check_polycube_loop_structure

__all__ = ["GAPS", "LEAST", "MOST_LEVELS", "level_grid", "level_planes", "levels"]

GAPS = (0.01, 0.02)  # of an axis's extent: a wider gap between facing triangles begins a new level
# (each is tried: the finer splits a gentle step off, the coarser keeps a curved wall in one level)
OPPOSITE = 0.1  # of the gap: a wider gap between area facing opposite ways begins a new level
LEAST = 0.002  # of the area: a lighter level is noise (a bump's tip, a sliver)
MOST_LEVELS = 13  # levels an axis at most (each gap is a plane, so a loop or more)


def levels(surface: Surface, heights: np.ndarray, gap: float = GAPS[0], labels: np.ndarray | None = None
           ) -> list[list[tuple[float, float, float]]]:
    """Per axis, its levels in order: ``(low, high, area)`` of the triangles (normals in the
    ``heights``, areas on the surface) whose normal is nearest that axis and whose centroids
    lie in one level (see the module docstring).  With ``labels`` (per triangle a direction's
    index, :class:`~polyloops.core.directions.Direction`), the charts of those labels instead
    of triangles: each chart (triangles of one label joined across edges) at the area-weighted
    mean of its centroids, so that a protrusion's face whose span overlaps the body's is a
    level of its own."""
    areas = surface.areas
    out = []
    for a, (values, weights, signs) in enumerate(_facing(surface, heights, labels)):
        order = np.argsort(values, kind="stable")
        values, weights, signs = values[order], weights[order], signs[order]
        found: list[list[float]] = []
        wide = gap * float(np.ptp(heights[:, a]))
        last = 0
        for v, w, sign in zip(values.tolist(), weights.tolist(), signs.tolist(), strict=True):
            if found and v - found[-1][1] <= (wide if sign == last else OPPOSITE * wide):
                found[-1][1] = v
                found[-1][2] += w
            else:
                found.append([v, v, w])
            last = sign
        kept = [f for f in found if f[2] >= LEAST * float(areas.sum())]
        while len(kept) > MOST_LEVELS:
            k = min(range(len(kept)), key=lambda i: kept[i][2])
            j = _nearer(kept, k)
            lo, hi = min(kept[k][0], kept[j][0]), max(kept[k][1], kept[j][1])
            kept[min(j, k)] = [lo, hi, kept[k][2] + kept[j][2]]
            del kept[max(j, k)]
        out.append([(lo, hi, w) for lo, hi, w in kept])
    return out


def _facing(surface: Surface, heights: np.ndarray, labels: np.ndarray | None
            ) -> list[tuple[np.ndarray, np.ndarray, np.ndarray]]:
    """Per axis, the values along it, the areas and the signs (which way they face) that make
    its levels: the triangles whose normal in the ``heights`` is nearest it, or with
    ``labels`` the charts labelled on it."""
    tri = heights[surface.triangles]
    centroids = tri.mean(axis=1)
    areas = surface.areas
    if labels is None:
        cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        nearest = np.argmax(np.abs(cross), axis=1)
        sign = np.sign(cross[np.arange(len(cross)), nearest]).astype(np.int64)
        return [(centroids[nearest == a, a], areas[nearest == a], sign[nearest == a]) for a in range(3)]
    chart = chart_indices(surface, labels)
    weight = np.bincount(chart, weights=areas)
    direction = np.zeros(len(weight), dtype=np.int64)
    direction[chart] = labels
    axis, sign = direction // 2, 1 - 2 * (direction % 2)
    out = []
    for a in range(3):
        mean = np.bincount(chart, weights=areas * centroids[:, a]) / np.maximum(weight, 1e-300)
        out.append((mean[axis == a], weight[axis == a], sign[axis == a]))
    return out


def _nearer(kept: list[list[float]], k: int) -> int:
    """The neighbour of level ``k`` across the narrower gap."""
    if k == 0:
        return 1
    if k == len(kept) - 1:
        return k - 1
    return k - 1 if kept[k][0] - kept[k - 1][1] <= kept[k + 1][0] - kept[k][1] else k + 1


def level_planes(surface: Surface, heights: np.ndarray, gap: float = GAPS[0],
                 labels: np.ndarray | None = None) -> list[Plane]:
    """The planes through the middles of the gaps between consecutive levels of each axis,
    the one nearest the area centroid of each axis first (the cube is sought among them)."""
    centroid = surface.area_centroid(heights)
    planes = [Plane(a, (lower[1] + upper[0]) / 2)
              for a, found in enumerate(levels(surface, heights, gap, labels))
              for lower, upper in itertools.pairwise(found)]
    central = []
    for a in range(3):
        mine = [p for p in planes if p.axis == a]
        central.append(min(mine, key=lambda p: abs(p.value - centroid[a])) if mine
                       else Plane(a, float(centroid[a])))
    return central + [p for p in planes if p not in central]


def level_grid(surface: Surface, heights: np.ndarray | None = None, gap: float = GAPS[0],
               labels: np.ndarray | None = None, deadline: float = float("inf")) -> CutGrid:
    """The level start as cut, before mending (see the module docstring): in ``heights``, the
    points by default, of the charts of ``labels`` when given (:func:`levels`).  At positive
    genus there is no cube to begin with, nor at genus 0 when
    the curves nearest the centre make none: every curve that crosses another is taken at
    once, and must make a loop structure (at genus 0, where they leave a region that is not a
    disc, the largest set of them joined by crossings, of all three axes:
    :func:`~polyloops.segment.grid.every_crossing`).  No curve is added after ``deadline`` (a
    :func:`time.monotonic` time): the curves kept by then are the start.

    Raises
    ------
    StartError
        When neither way gives a loop structure.
    """
    hv = surface.points if heights is None else heights
    r = cut(Refined.of(surface, heights), level_planes(surface, hv, gap, labels))
    loops = section_loops(r)
    if surface.genus > 0:
        return every_crossing(r, loops, "the levels")
    try:
        chosen = start_state(r, loops)
    except StartError as err:  # no cube near the centre (an aeroplane's wings): every curve at once
        try:
            return every_crossing(r, loops, "the levels")
        except StartError as again:
            raise StartError(f"{err}; {again}") from None
    e = read_structure(r, [loops[i] for i in chosen])
    # longest first; a curve refused may fit once another is in (two curves that only make
    # discs together), so passes repeat until one adds nothing
    waiting = sorted(set(range(len(loops))) - set(chosen), key=lambda i: (-len(loops[i].vertices), i))
    while True:
        before = len(chosen)
        for i in list(waiting):
            if time.monotonic() > deadline:
                break
            more = crossing_only(loops, [*chosen, i])
            if len(more) <= len(chosen):
                continue  # it crosses nothing
            try:
                e = read_structure(r, [loops[j] for j in more])
            except NotAStructure:
                continue
            chosen = more
            waiting.remove(i)
        if len(chosen) == before or time.monotonic() > deadline:
            return CutGrid(r, loops, chosen, e, check_polycube_loop_structure(e.structure))
