"""Pictures of loops on a surface: the mesh shaded in grey, each loop drawn in its axis's colour
(the colours of every other picture: X purple, Y orange, Z green), from two opposite views.

A pixel is on a loop where its neighbour shows a triangle of another region (the loops are the
regions' boundaries); it takes the axis of a loop edge of its triangle.  Decided per pixel from
a depth buffer, like :mod:`polyloops.render.segmentation`, so nothing hidden shows through.
"""

from __future__ import annotations

import os

import numpy as np
from matplotlib.patches import Patch

from polyloops.core.directions import Axis
from polyloops.render.colours import AXIS_COLOUR
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.projection import View
from polyloops.render.segmentation import LOOP_RGBA, VIEWS, loop_axes, loop_pixels, mesh_view

__all__ = ["render_loops_on_surface"]


def _draw(ax, points: np.ndarray, tris: np.ndarray, region: np.ndarray, axis_of: np.ndarray,
          view: View) -> None:
    seen_from = mesh_view(points, tris, view)
    ids, shape = seen_from.ids, seen_from.ids.shape
    length = np.linalg.norm(seen_from.normals, axis=1)
    toward = np.asarray(view.toward)
    shade = np.where(length > 0, (seen_from.normals @ toward) / np.maximum(length, 1e-300), 0.0)
    image = np.ones((*shape, 4))
    image[..., 3] = 0.0
    shown = ids >= 0
    grey = 0.55 + 0.4 * shade[ids[shown]]
    image[shown, :3] = grey[:, None]
    image[shown, 3] = 1.0
    line = loop_pixels(ids, region, axis_of)
    drawn = line >= 0
    image[drawn] = LOOP_RGBA[line[drawn]]
    ax.imshow(image, extent=seen_from.extent, interpolation="nearest")
    ax.set_aspect("equal")
    ax.axis("off")


def render_loops_on_surface(points: np.ndarray, triangles: np.ndarray, region: np.ndarray,
                            loop_edges: dict[tuple[int, int], Axis], path: str | os.PathLike[str],
                            title: str = "") -> None:
    """Two opposite views of the surface with its loops: ``region`` per triangle (the loops are
    the boundaries between regions), ``loop_edges`` each loop edge ``(u, v)`` (``u < v``) with
    its loop's axis."""
    axis_of = loop_axes(triangles, loop_edges)
    fig = new_figure(9.0, 4.6)
    for ax, view in zip(fig.subplots(1, 2), VIEWS, strict=True):
        _draw(ax, np.asarray(points, dtype=float), np.asarray(triangles), np.asarray(region), axis_of, view)
    if title:
        fig.suptitle(title, fontsize=10)
    fig.legend(handles=[Patch(color=AXIS_COLOUR[a], label=f"{a} loops") for a in Axis],
               loc="lower center", ncol=3, fontsize=8, frameon=False)
    save_figure(fig, path)
