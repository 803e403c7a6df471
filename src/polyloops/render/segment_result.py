"""Pictures of a segmentation that ``segment`` made: the mesh coloured by label (the paper's
colours) with its loops drawn on it, beside the loops' polycube.

:func:`render_segment` writes the still picture (two views of the mesh, one of the polycube);
:func:`polyloops.render.segmentation_viewer.write_segmentation_viewer` the interactive page.

>>> import tempfile, pathlib
>>> from polyloops.shapes.meshes import ellipsoid
>>> from polyloops.segment.run import segment_mesh
>>> done = segment_mesh(*ellipsoid(2.0, 1.0, 0.7, level=3), budget=1.0, direct=False)
>>> [axis.name for axis, _ in loop_curves(done)].count("X") >= 1
True
>>> with tempfile.TemporaryDirectory() as tmp:
...     render_segment(done, pathlib.Path(tmp) / "seg.png")
...     (pathlib.Path(tmp) / "seg.png").stat().st_size > 10_000
True
"""

from __future__ import annotations

import os
from collections.abc import Callable
from typing import Any

import numpy as np
from matplotlib.patches import Patch

from polyloops.core.directions import Axis, Direction
from polyloops.render.colours import AXIS_COLOUR, direction_colour
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.polycube import as_polycube, choose_views, draw_polycube
from polyloops.render.segmentation import VIEWS, draw_segmentation, loop_axes

__all__ = ["loop_curves", "render_segment"]


def loop_curves(result: Any) -> list[tuple[Axis, tuple[int, ...]]]:
    """The loops of a :class:`~polyloops.segment.run.SegmentResult` as closed paths of its
    labelled mesh's vertices (the mesh is refined along them), each with its axis; none for a
    valid guide kept as it was (no loops were drawn)."""
    if result.layout is None:
        return []
    embedded = result.layout.embedded
    return [(Axis(lp.axis_in(embedded.refined)), tuple(lp.vertices)) for lp in embedded.loops]


def loop_overlay(result: Any) -> tuple[np.ndarray, np.ndarray] | None:
    """What :func:`~polyloops.render.segmentation.draw_segmentation` needs to draw the loops:
    per triangle of the labelled mesh its region (a corner of the loops' structure) and the
    axis of a loop edge of it (-1 for none); ``None`` without loops."""
    if result.layout is None:
        return None
    edges: dict[tuple[int, int], Axis] = {}
    for axis, vs in loop_curves(result):
        for u, v in zip(vs, vs[1:] + vs[:1], strict=True):
            edges[min(u, v), max(u, v)] = axis
    triangles = np.asarray(result.mesh.triangles, dtype=np.int64).reshape(-1, 3)
    return np.asarray(result.layout.embedded.region), loop_axes(triangles, edges)


def render_segment(result: Any, path: str | os.PathLike[str],
                   progress: Callable[[str], None] | None = None) -> None:
    """Two opposite views of the labelled mesh, its charts outlined and its loops drawn in
    their axes' colours, beside the loops' polycube with the same loops; ``progress`` is told
    of each panel drawn and of the file written."""
    fig = new_figure(13.5, 4.8)
    axes = fig.subplots(1, 3, gridspec_kw={"width_ratios": [1, 1, 0.9]})
    overlay = loop_overlay(result)
    for ax, view in zip(axes[:2], VIEWS, strict=True):
        draw_segmentation(ax, result.report, view, loops=overlay)
        if progress is not None:
            progress("view")
    kept = result.layout is None  # a valid guide: the checker's polycube, its own loops
    q, ls = as_polycube(result.polycube if kept else result.layout.embedded.structure)
    draw_polycube(axes[2], q, choose_views(q, 1)[0], ls, pixels=360)
    which = "the realising polycube" if kept else "the loops' polycube"
    axes[2].set_title(f"{which}: {q.map.num_corners} corners", fontsize=9)
    if progress is not None:
        progress("polycube")
    fig.suptitle(f"certified polycube segmentation: {result.charts} charts, {result.corners} corners, "
                 f"{result.loops} loops; fidelity {result.fidelity:.4f} (per-triangle bound "
                 f"{result.naive_fidelity:.4f})", fontsize=10)
    handles = [Patch(color=direction_colour(d), label=str(d)) for d in Direction]
    handles += [Patch(color=AXIS_COLOUR[a], label=f"{a.name} loops", hatch="//") for a in Axis]
    fig.legend(handles=handles, loc="lower center", ncol=9, fontsize=8, frameon=False)
    save_figure(fig, path)
    if progress is not None:
        progress("written")
