"""An interactive page of a labelled segmentation (plotly): the mesh coloured by label (the
paper's colours), its chart boundaries, the loops on the surface when they are known, and,
beside it, the polycube that realises the labels with its loops.

Clicking an entry of the legend hides or shows it; an axis's loops are one entry on both sides.
Like :mod:`polyloops.render.viewer`, plotly.js is written into the page, which then opens
without a network.

>>> from polyloops.io.examples import labelled_mesh_example
>>> from polyloops.segmentation import check_segmentation
>>> spec = segmentation_viewer_spec(check_segmentation(labelled_mesh_example("l-shape")))
>>> sorted({t["legendgroup"] for t in spec["data"]})[:4]
['+X', '+Y', '+Z', '-X']
>>> "scene2" in spec["layout"]  # the polycube beside the mesh
True
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from polyloops.core.directions import Axis, Direction
from polyloops.io.files import write_atomic
from polyloops.render.colours import AXIS_COLOUR, direction_colour
from polyloops.render.segmentation import WITNESS_COLOUR

__all__ = ["segmentation_viewer_html", "segmentation_viewer_spec", "write_segmentation_viewer"]

LIFT = 0.002  # loops and boundaries float this fraction of the mesh's size above it


def _lines(points: np.ndarray, paths: Sequence[Sequence[int]], closed: bool) -> dict[str, list[Any]]:
    """One line trace's coordinates for many vertex paths (``None`` separates them)."""
    xs: list[Any] = []
    ys: list[Any] = []
    zs: list[Any] = []
    for path in paths:
        for v in [*path, path[0]] if closed else path:
            x, y, z = points[v]
            xs.append(float(x))
            ys.append(float(y))
            zs.append(float(z))
        xs.append(None)
        ys.append(None)
        zs.append(None)
    return {"x": xs, "y": ys, "z": zs}


def _lifted(points: np.ndarray, tris: np.ndarray) -> np.ndarray:
    """The points moved a little along their normals (area-weighted), so that lines drawn
    through them are not hidden by the triangles beside them."""
    p = points[tris]
    face = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    normal = np.zeros_like(points)
    for k in range(3):
        np.add.at(normal, tris[:, k], face)
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    size = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0))) or 1.0
    return points + LIFT * size * normal / np.maximum(length, 1e-300)


def segmentation_viewer_spec(report: Any, loops: Sequence[tuple[Axis, Sequence[int]]] = (),
                             title: str | None = None) -> dict[str, Any]:
    """The page's figure as plotly's JSON form: the checker's ``report`` on a labelled mesh
    (:func:`polyloops.segmentation.check_segmentation`), and ``loops`` drawn on its surface
    (closed vertex paths with their axes, as
    :func:`~polyloops.render.segment_result.loop_curves` gives them).  The right-hand scene
    shows the realising polycube and its loops when the report has one; the boundaries that a
    witness of invalidity names are red, and the charts it names tinted red (as in
    :func:`~polyloops.render.segmentation.render_segmentation`)."""
    from matplotlib.colors import to_hex

    from polyloops.render.segmentation import _tint, hot_parts
    from polyloops.render.viewer import viewer_spec

    seg = report.segmentation
    mesh = seg.mesh
    points = np.asarray(mesh.points, dtype=float).reshape(-1, 3)
    tris = np.asarray(mesh.triangles, dtype=np.int64).reshape(-1, 3)
    labels = list(mesh.labels)
    hot_charts, hot = hot_parts(report)
    chart_of = seg.chart_of_triangle
    traces: list[dict[str, Any]] = []
    for d in Direction:  # one trace a label, so that the legend shows and hides each
        mine = [t for t, label in enumerate(labels) if label == d]
        if not mine:
            continue
        plain, tinted = direction_colour(d), to_hex(_tint(direction_colour(d)))
        fills = [tinted if chart_of[t] in hot_charts else plain for t in mine]
        used, sub = np.unique(tris[mine], return_inverse=True)  # only this label's vertices
        sub = sub.reshape(-1, 3)
        xyz = points[used]
        traces.append(dict(
            type="mesh3d", x=xyz[:, 0].tolist(), y=xyz[:, 1].tolist(), z=xyz[:, 2].tolist(),
            i=sub[:, 0].tolist(), j=sub[:, 1].tolist(), k=sub[:, 2].tolist(), facecolor=fills,
            flatshading=True, name=str(d), legendgroup=str(d), showlegend=True, hoverinfo="name",
            lighting=dict(ambient=0.85, diffuse=0.25, specular=0.0), scene="scene"))
    lifted = _lifted(points, tris)
    for name, which, colour in (("chart boundaries", [b for b in range(len(seg.boundaries)) if b not in hot],
                                 "#000000"),
                                ("witness", sorted(hot), WITNESS_COLOUR)):
        if which:
            traces.append(dict(type="scatter3d", mode="lines", line=dict(color=colour, width=3),
                               **_lines(lifted, [seg.boundaries[b].vertices for b in which], False),
                               name=name, legendgroup=name, hoverinfo="skip", scene="scene"))
    for axis in Axis:
        paths = [vs for a, vs in loops if a == axis]
        if paths:
            traces.append(dict(type="scatter3d", mode="lines", line=dict(color=AXIS_COLOUR[axis], width=5),
                               **_lines(lifted, paths, True), name=f"{axis.name}-loops",
                               legendgroup=f"{axis.name}-loops", hoverinfo="name", scene="scene"))
    layout: dict[str, Any] = dict(
        title=dict(text=title or _heading(report), font=dict(size=14)), margin=dict(l=0, r=0, t=40, b=0),
        legend=dict(itemclick="toggle", groupclick="togglegroup"), paper_bgcolor="white",
        scene=dict(aspectmode="data", domain=dict(x=[0.0, 0.6], y=[0.0, 1.0])))
    if report.polycube is not None:
        polycube = viewer_spec(report.polycube)
        have = {t["legendgroup"] for t in traces}
        for t in polycube["data"]:
            t["scene"] = "scene2"
            t["showlegend"] = t.get("showlegend", True) and t["legendgroup"] not in have
            have.add(t["legendgroup"])
            traces.append(t)
        layout["scene2"] = {**polycube["layout"]["scene"], "domain": dict(x=[0.6, 1.0], y=[0.0, 1.0])}
    return {"data": traces, "layout": layout}


def _heading(report: Any) -> str:
    seg = report.segmentation
    verdict = {True: "valid", False: "invalid", None: "undecided"}[report.valid]
    text = f"labelled segmentation: {verdict}, {len(seg.charts)} charts, {len(seg.corners)} corners"
    if report.polycube is not None:
        text += f"; realised by a polycube of {report.polycube.map.num_corners} corners (right)"
    return text


def segmentation_viewer_html(report: Any, loops: Sequence[tuple[Axis, Sequence[int]]] = (),
                             title: str | None = None) -> str:
    """The page as HTML text, plotly.js inside (the same bytes for the same input)."""
    import plotly.io as pio

    return pio.to_html(segmentation_viewer_spec(report, loops, title), include_plotlyjs=True, full_html=True,
                       default_height="92vh", default_width="100%", validate=False,
                       div_id="polyloops-segmentation", config={"displaylogo": False, "responsive": True})


def write_segmentation_viewer(report: Any, path: str | os.PathLike[str],
                              loops: Sequence[tuple[Axis, Sequence[int]]] = (),
                              title: str | None = None) -> None:
    """Write :func:`segmentation_viewer_html` to ``path`` (atomically).

    Raises
    ------
    OSError
        When the file cannot be written.
    """
    write_atomic(path, segmentation_viewer_html(report, loops, title))
