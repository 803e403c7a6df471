"""Pictures of labelled segmentations: triangles coloured by label, chart boundaries in black,
for an invalid one the witness in red, and loops drawn on the surface where they are known."""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

import numpy as np
from matplotlib.colors import to_rgb
from matplotlib.patches import Patch

from polyloops.core.directions import Axis, Direction
from polyloops.render.colours import AXIS_COLOUR, direction_colour
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.projection import View
from polyloops.render.raster import triangle_buffer

WITNESS_COLOUR = "#d7191c"
VIEWS = (View(35.0, 28.0), View(215.0, -28.0))


PIXELS = 480  # the depth buffer of one view is PIXELS on its longer side (a little over the axes')


def _tint(colour: str) -> tuple[float, float, float]:
    """The colour mixed half with the witness red."""
    from matplotlib.colors import to_rgb

    a, b = to_rgb(colour), to_rgb(WITNESS_COLOUR)
    return (0.5 * a[0] + 0.5 * b[0], 0.5 * a[1] + 0.5 * b[1], 0.5 * a[2] + 0.5 * b[2])


def _neighbours(ids: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Every pair of neighbouring pixels (a pixel and the one right of it or below it), as
    flat indices, for chart boundaries, outlines and witness edges to compare."""
    h, w = ids.shape
    flat = np.arange(h * w).reshape(h, w)
    return (np.concatenate([flat[:, :-1].ravel(), flat[:-1, :].ravel()]),
            np.concatenate([flat[:, 1:].ravel(), flat[1:, :].ravel()]))


def loop_pixels(ids: np.ndarray, region: np.ndarray, axis_of: np.ndarray, width: int = 1) -> np.ndarray:
    """Per pixel of a depth buffer's triangle ``ids``, the axis of a loop drawn there (-1 for
    none): a pixel is on a loop where its neighbour shows a triangle of another ``region`` and
    it takes ``axis_of`` its triangle (the axis of a loop edge of it, -1 if none); lines are
    widened by ``width`` pixels each way, on the surface only."""
    return np.where(ids >= 0, _widened(_loop_line(ids, region, axis_of), width), -1)


def _loop_line(ids: np.ndarray, region: np.ndarray, axis_of: np.ndarray) -> np.ndarray:
    """:func:`loop_pixels` one pixel wide, before it is kept to the surface."""
    a, b = _neighbours(ids)
    ta, tb = ids.ravel()[a], ids.ravel()[b]
    edge = (ta >= 0) & (tb >= 0) & (region[np.maximum(ta, 0)] != region[np.maximum(tb, 0)])
    line = np.full(ids.size, -1, dtype=np.int64)
    for side in (a, b):
        tri = ids.ravel()[side[edge]]
        axis = axis_of[tri]
        known = axis >= 0
        line[side[edge][known]] = axis[known]
    return line.reshape(ids.shape)


def _widened(line: np.ndarray, width: int) -> np.ndarray:
    """``line`` grown by ``width`` pixels each way, each pixel taking a neighbour's axis."""
    for _ in range(width):
        for k in (0, 1):
            for shift in (1, -1):
                moved = np.roll(line, shift, k)
                line = np.where((line < 0) & (moved >= 0), moved, line)
    return line


def loop_axes(triangles: np.ndarray, loop_edges: dict[tuple[int, int], Axis]) -> np.ndarray:
    """Per triangle, the axis of a loop edge of it (``loop_edges``: ``(u, v)`` with ``u < v``),
    -1 when it has none."""
    axis_of = np.full(len(triangles), -1, dtype=np.int64)
    for t, (a, b, c) in enumerate(np.asarray(triangles).tolist()):
        for u, v in ((a, b), (b, c), (c, a)):
            axis = loop_edges.get((min(u, v), max(u, v)))
            if axis is not None:
                axis_of[t] = int(axis)
    return axis_of


LOOP_RGBA = np.array([(*to_rgb(AXIS_COLOUR[axis]), 1.0) for axis in Axis])


def hot_parts(report: Any) -> tuple[set[int], set[int]]:
    """The charts and boundaries drawn in red: those the global witness names (the charts whose
    turning numbers it uses, the boundaries of its cycles and arcs) and those of local
    violations (a chart only where the rule is about the chart itself)."""
    witness = report.global_.witness
    charts: set[int] = set(witness.turning) if witness is not None else set()
    boundaries = set(witness.all_boundaries()) if witness is not None else set()
    for v in report.local.violations:
        boundaries |= set(v.boundaries)
        charts |= set(v.charts) if v.rule in ("few-boundaries", "chart-handle") else set()
    return charts, boundaries


@dataclass(frozen=True)
class MeshView:
    """A triangle mesh seen from a view: per pixel the nearest front-facing triangle (``ids``,
    -1 for none), the vertices' screen coordinates ``pu``, ``pv``, the triangles' normals (not
    normalised), and the pixel grid's origin ``lo_u``, ``hi_v`` and ``step``."""

    ids: np.ndarray
    pu: np.ndarray
    pv: np.ndarray
    normals: np.ndarray
    lo_u: float
    hi_v: float
    step: float

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """The image's extent for ``imshow``."""
        h, w = self.ids.shape
        return (self.lo_u, self.lo_u + w * self.step, self.hi_v - h * self.step, self.hi_v)


def mesh_view(points: np.ndarray, tris: np.ndarray, view: View, pixels: int = PIXELS) -> MeshView:
    """The depth buffer of a triangle mesh's front-facing triangles from ``view``
    (:func:`~polyloops.render.raster.triangle_buffer`), ``pixels`` on its longer side."""
    right, up, toward = (np.asarray(a) for a in (view.right, view.up, view.toward))
    pu, pv, pd = points @ right, points @ up, points @ toward
    p = points[tris]
    normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    front = np.flatnonzero(normals @ toward > 0)
    lo_u, hi_u, lo_v, hi_v = pu.min(initial=0), pu.max(initial=1), pv.min(initial=0), pv.max(initial=1)
    pad = 0.02 * max(hi_u - lo_u, hi_v - lo_v, 1e-12)
    lo_u, hi_u, lo_v, hi_v = lo_u - pad, hi_u + pad, lo_v - pad, hi_v + pad
    step = max(hi_u - lo_u, hi_v - lo_v) / pixels
    shape = (max(1, int(np.ceil((hi_v - lo_v) / step))), max(1, int(np.ceil((hi_u - lo_u) / step))))
    seen, _ = triangle_buffer((pu - lo_u) / step, (hi_v - pv) / step, pd, tris[front], shape)
    ids = np.where(seen >= 0, front[np.maximum(seen, 0)], -1)
    return MeshView(ids, pu, pv, normals, float(lo_u), float(hi_v), float(step))


def draw_segmentation(ax, report, view: View, pixels: int = PIXELS,
                      loops: tuple[np.ndarray, np.ndarray] | None = None) -> None:
    """Draw one view from a depth buffer of the mesh's front-facing triangles
    (:func:`~polyloops.render.raster.triangle_buffer`): each pixel shows the nearest triangle
    in its label's colour (charts that break a local rule of their own, or whose turning number
    the witness uses, tinted red), a pixel
    is a chart boundary where its neighbour shows another chart (red, and thicker, where
    either triangle lies on the witness or a violation), and the witness corners that are
    visible are marked.  Everything is decided per pixel, so nothing hidden shows through,
    and the cost grows with the triangles plus the pixels, not their product.  With ``loops``
    (per triangle its region and the axis of a loop edge of it, as
    :func:`~polyloops.render.loops_on_surface.loop_pixels` takes them) the loops are drawn
    over the labels in their axes' colours."""
    seg = report.segmentation
    mesh = seg.mesh
    witness = report.global_.witness
    hot_charts, hot_boundaries = hot_parts(report)
    hot_edges = {frozenset(e) for b in hot_boundaries for e in pairwise(seg.boundaries[b].vertices)}
    points = np.asarray(mesh.points, dtype=float).reshape(-1, 3)
    tris = np.asarray(mesh.triangles, dtype=np.int64).reshape(-1, 3)
    seen_from = mesh_view(points, tris, view, pixels)
    ids, pu, pv = seen_from.ids, seen_from.pu, seen_from.pv
    lo_u, hi_v, step = seen_from.lo_u, seen_from.hi_v, seen_from.step
    shape = ids.shape
    chart_of = np.asarray(seg.chart_of_triangle, dtype=np.int64)
    fills = {d: to_rgb(direction_colour(d)) for d in Direction}
    fill = np.array([fills[label] for label in mesh.labels]).reshape(-1, 3)
    for f in (np.flatnonzero(np.isin(chart_of, list(hot_charts))) if hot_charts else ()):
        fill[f] = _tint(direction_colour(mesh.labels[f]))
    image = np.ones((*shape, 4))
    image[..., 3] = 0.0
    shown = ids >= 0
    image[shown, :3] = fill[ids[shown]]
    image[shown, 3] = 1.0
    a, b = _neighbours(ids)
    ta, tb = ids.ravel()[a], ids.ravel()[b]
    both = (ta >= 0) & (tb >= 0)
    # Lines two pixels wide: both pixels of a pair that differs are drawn.
    edge = both & (chart_of[np.maximum(ta, 0)] != chart_of[np.maximum(tb, 0)])
    outline = (ta >= 0) != (tb >= 0)
    hot_tri = np.zeros(len(tris), dtype=bool)
    if hot_edges:
        hot_tri = np.array([any(frozenset((t[k], t[(k + 1) % 3])) in hot_edges for k in range(3))
                            for t in mesh.triangles], dtype=bool)
    hot_pair = edge & (hot_tri[np.maximum(ta, 0)] | hot_tri[np.maximum(tb, 0)])
    flat = image.reshape(-1, 4)
    for mask in (edge, outline):
        flat[np.concatenate([a[mask], b[mask]])] = (0.0, 0.0, 0.0, 1.0)
    hot = np.zeros(shape[0] * shape[1], dtype=bool)
    hot[np.concatenate([a[hot_pair], b[hot_pair]])] = True
    hot = hot.reshape(shape)
    for axis in (0, 1):  # the witness's lines a little wider than the others
        hot = hot | np.roll(hot, 1, axis)
    image[hot & shown] = (*to_rgb(WITNESS_COLOUR), 1.0)
    if loops is not None:
        # outlined in black: a loop runs over charts of its own colour family
        line = _widened(_loop_line(ids, *loops), 1)
        image[(_widened(line, 1) >= 0) & shown] = (0.0, 0.0, 0.0, 1.0)
        line = np.where(shown, line, -1)
        image[line >= 0] = LOOP_RGBA[line[line >= 0]]
    ax.imshow(image, extent=(lo_u, lo_u + shape[1] * step, hi_v - shape[0] * step, hi_v),
              interpolation="nearest")
    if witness is not None and witness.corners:
        xy = []
        for c in witness.corners:
            vertex = seg.corners[c].vertex
            j, i = int((pu[vertex] - lo_u) / step), int((hi_v - pv[vertex]) / step)
            near = ids[max(0, i - 1):i + 2, max(0, j - 1):j + 2].ravel()
            if any(vertex in mesh.triangles[t] for t in near[near >= 0]):  # visible: drawn there
                xy.append((pu[vertex], pv[vertex]))
        if xy:
            ax.scatter([q[0] for q in xy], [q[1] for q in xy], s=40, color=WITNESS_COLOUR, zorder=5,
                       edgecolors="white", linewidths=0.8)
    ax.set_aspect("equal")
    ax.axis("off")


def _wrap(text: str, width: int = 110) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width))


def render_segmentation(report, path: str | os.PathLike[str],
                        progress: Callable[[str], None] | None = None) -> None:
    """Two opposite views side by side, a legend of the six labels, and the verdict;
    ``progress`` is told of each view drawn and of the file written."""
    fig = new_figure(9.0, 4.6)
    axes = fig.subplots(1, 2)
    for ax, view in zip(axes, VIEWS, strict=True):
        draw_segmentation(ax, report, view)
        if progress is not None:
            progress("view")
    verdict = {True: "valid", False: "invalid", None: "undecided"}[report.valid]
    seg = report.segmentation
    title = f"labelled segmentation: {verdict} ({len(seg.charts)} charts)"
    if report.global_.witness is not None:
        title += "\n" + _wrap(f"witness (red): {report.global_.witness.describe(seg)}")
    elif report.local.violations:
        title += "\n" + _wrap(f"{report.local.violations[0].rule}: {report.local.violations[0].message}")
    fig.suptitle(title, fontsize=10)
    fig.legend(handles=[Patch(color=direction_colour(d), label=str(d)) for d in Direction],
               loc="lower center", ncol=6, fontsize=8, frameon=False)
    save_figure(fig, path)
    if progress is not None:
        progress("written")
