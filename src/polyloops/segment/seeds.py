"""Seeds: the loops of a valid labelling of the surface, as a start of the search.

Where the checker finds a labelling of the mesh valid (often the graph-cut one on a CAD part),
it builds a polycube that realises it (:mod:`polyloops.segmentation.realise`): each chart is a
face of that polycube, at an integer level along its label's axis, and each corner of the
charts a corner of it.  The polycube's X-loops are its sections by the planes
``x = k + 1/2`` between consecutive levels.  To draw them on the surface, the surface is mapped
onto the polycube: per axis, the vertices of the charts labelled along it take their chart's
level, and every other vertex the harmonic interpolation of those levels (a sparse Laplace
problem with positive weights, so no value leaves the range of its neighbours' and no level
set closes up inside a chart).  On the polycube's own faces the coordinate is linear between the
faces across it; here it is harmonic, so each section ``x = k + 1/2`` of these *heights* (see
:mod:`~polyloops.segment.refine`) runs, chart by chart, where the polycube's loop runs.  The
sections cut from them are a start like any other (:func:`seed_start`): read off the surface,
checked, mended where a section came out otherwise, and searched on.

>>> import numpy as np
>>> from polyloops.io.examples import load_example
>>> from polyloops.segment.surface import surface_of
>>> from polyloops.surface.construct import labelled_mesh_from_polycube
>>> m = labelled_mesh_from_polycube(load_example("l-shape"))
>>> s = surface_of(np.array(m.points, dtype=float), np.array(m.triangles))
>>> r, loops, chosen, how = seed_start(s, m.labels)
>>> len(chosen), how
(5, 'the loops of the valid per-triangle labelling')
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix, diags
from scipy.sparse.linalg import spsolve

from polyloops.core.directions import Direction
from polyloops.segment.embedded import SurfaceLoop
from polyloops.segment.grid import every_crossing, mend
from polyloops.segment.refine import Plane, Refined, cut
from polyloops.segment.search import StartError, section_loops
from polyloops.segment.surface import Surface
from polyloops.segmentation import SegmentationReport, check_segmentation

__all__ = ["polycube_map", "seed_grid", "seed_start"]

MIN_WEIGHT = 1e-3  # of the mean cotangent weight: every edge keeps a positive weight


def _weights(surface: Surface) -> csr_matrix:
    """The symmetric edge weights of the Laplacian: cotangent weights clamped from below, so
    that the discrete maximum principle holds (a harmonic value lies between its neighbours')."""
    p, t = surface.points, surface.triangles
    rows, cols, vals = [], [], []
    for k in range(3):
        i, j, o = t[:, (k + 1) % 3], t[:, (k + 2) % 3], t[:, k]  # edge ij, opposite corner o
        u, v = p[i] - p[o], p[j] - p[o]
        cross = np.linalg.norm(np.cross(u, v), axis=1)
        cot = (u * v).sum(axis=1) / np.maximum(cross, 1e-300)
        rows += [i, j]
        cols += [j, i]
        vals += [cot / 2, cot / 2]
    w = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                   shape=(len(p),) * 2).tocsr()  # duplicates (the two triangles of an edge) summed
    w.data = np.maximum(w.data, MIN_WEIGHT * max(float(np.abs(w.data).mean()), 1e-300))
    return w


def polycube_map(surface: Surface, report: SegmentationReport) -> np.ndarray:
    """Per vertex of ``surface``, its place on the polycube that realises the valid labelling
    ``report`` checked (on ``surface``'s own triangles): per axis, a chart's level on its
    vertices where the chart is labelled along that axis, harmonic elsewhere (see the module
    docstring).

    Raises
    ------
    ValueError
        When the report is not valid with a polycube, is not of this surface, or a chart has
        no corner to read its level from.
    """
    seg, cube = report.segmentation, report.polycube
    if report.valid is not True or cube is None:
        raise ValueError("the labelling is not valid with a realising polycube")
    if len(seg.chart_of_triangle) != len(surface.triangles):
        raise ValueError("the report is of another mesh")
    n = len(surface.points)
    chart_of = np.asarray(seg.chart_of_triangle)
    axis_of = np.array([int(ch.label.axis) for ch in seg.charts])
    # a chart's level: that of any corner on it (the realisation's first points are the
    # charts' corners, in order)
    corner_at = np.full(n, -1)
    corner_at[[c.vertex for c in seg.corners]] = [c.id for c in seg.corners]
    level = np.full(len(seg.charts), np.nan)
    positions = np.array(cube.positions[:len(seg.corners)], dtype=float).reshape(-1, 3)
    for k in range(3):
        at = corner_at[surface.triangles[:, k]]
        on = np.flatnonzero(at >= 0)
        level[chart_of[on]] = positions[at[on], axis_of[chart_of[on]]]
    if np.isnan(level).any():
        raise ValueError(f"chart {int(np.flatnonzero(np.isnan(level))[0])} has no corner")
    lap = _weights(surface)
    heights = np.zeros((n, 3))
    for a in range(3):
        fixed = np.zeros(n, dtype=bool)
        value = np.zeros(n)
        mine = np.flatnonzero(axis_of[chart_of] == a)
        for k in range(3):
            fixed[surface.triangles[mine, k]] = True
            value[surface.triangles[mine, k]] = level[chart_of[mine]]
        free = np.flatnonzero(~fixed)
        if len(free):  # the Dirichlet problem: (D - W) x = W x_fixed on the free vertices
            rows = lap[free]
            degree = np.asarray(rows.sum(axis=1)).ravel()
            system = (diags(degree) - rows[:, free]).tocsc()
            value[free] = spsolve(system, np.asarray(rows[:, fixed] @ value[fixed]).ravel())
        heights[:, a] = value
    return heights


def _planes(heights: np.ndarray) -> list[Plane]:
    """The planes between consecutive integer levels of each axis: the polycube's loops."""
    out = []
    for a in range(3):
        lo, hi = int(np.floor(heights[:, a].min())), int(np.ceil(heights[:, a].max()))
        out += [Plane(a, k + 0.5) for k in range(lo, hi)]
    return out


def seed_grid(surface: Surface, heights: np.ndarray, what: str = "the seed",
              deadline: float = float("inf")) -> tuple[Refined, list[SurfaceLoop], list[int]]:
    """The surface cut along the polycube's loops drawn through ``heights``
    (:func:`polycube_map`): the cut surface, its section curves, and those chosen, every one
    that crosses another, mended (within ``deadline``, a :func:`time.monotonic` time) where
    they break Definition 4 (``what`` names them in an error).

    Raises
    ------
    StartError
        When the curves make no loop structure, and mending finds none.
    """
    r = cut(Refined.of(surface, heights), _planes(heights))
    return mend(every_crossing(r, section_loops(r), what), deadline=deadline)


def seed_start(surface: Surface, labels: Sequence[Direction], what: str = "per-triangle",
               report: SegmentationReport | None = None) -> tuple[Refined, list[SurfaceLoop], list[int], str]:
    """The start of the loops of ``labels``, a valid labelling of ``surface`` (``what`` names
    it; ``report``: the checker's report on it, made when not given): :func:`seed_grid` of
    :func:`polycube_map`, and how it is named.

    Raises
    ------
    StartError
        When the labelling is not valid, or its loops drawn so make no loop structure.
    """
    how = f"the loops of the valid {what} labelling"
    if report is None:
        report = check_segmentation(surface.labelled(labels))
    try:
        heights = polycube_map(surface, report)
    except ValueError as err:
        raise StartError(f"{how}: {err}") from None
    return (*seed_grid(surface, heights, how), how)
