"""An interactive 3D viewer: one self-contained HTML page per polycube (plotly).

The page shows the polycube's quads, its loops in the paper's colours (two strokes each, the
``+`` side dark and the ``-`` side light), and its corners.  It can be turned and zoomed with
the mouse; clicking an entry of the legend (``X-loops``, ``Y-loops``, ``Z-loops``, ``corners``)
hides or shows it; hovering names a face and its zones, a loop, or a corner and its
configuration.  plotly.js is written into the page (or, for a site of many pages, once beside
them), so it opens without a network.

>>> from polyloops.io.examples import load_example
>>> fig = viewer_figure(load_example("l-shape"))
>>> sorted({t.legendgroup for t in fig.data})
['X-loops', 'Y-loops', 'Z-loops', 'corners', 'faces']
"""

from __future__ import annotations

import math
import os
from typing import Any

from polyloops.core.corners import classify
from polyloops.core.directions import Axis
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.io.files import write_atomic
from polyloops.render.colours import AXIS_COLOUR, LIGHT_COLOUR
from polyloops.render.polycube import FACE_SHADE, OFFSET, as_polycube

LIFT = 0.02  # loops float this far above the surface, so that faces do not hide them


def _face_text(q: Polycube, ls: LoopStructure | None, f: int) -> str:
    n = q.face_normal(f)
    text = f"face {f}, normal {n if n is not None else '?'}"
    if ls is not None:
        parts = []
        for a in Axis:
            zones = sorted({ls.zones(a).zone_of[c] for c in q.faces[f]})
            parts.append(f"{a.name}: {'|'.join(map(str, zones))}")
        text += "<br>zones " + ", ".join(parts)
    return text


def _loop_paths(q: Polycube, ls: LoopStructure, loop: int) -> tuple[list[Any], list[Any]]:
    """The ``+`` and ``-`` strokes of a loop: through the midpoints of the edges it crosses,
    lifted off the surface, shifted along its axis (``None`` breaks a line)."""
    axis = ls.axes[loop]
    m = q.map
    lp = ls.loops[loop]
    plus: list[Any] = []
    minus: list[Any] = []
    for i, d in enumerate(lp.darts):
        f = lp.faces[i]
        n = q.face_normal(f)
        normal = n.vector if n is not None else (0, 0, 0)
        for dart in (d, m.next[m.next[d]]):  # the entry and exit edges of this face
            a, b = q.positions[m.origin(dart)], q.positions[m.target(dart)]
            mid = [(a[k] + b[k]) / 2 + LIFT * normal[k] for k in range(3)]
            for stroke, side in ((plus, 1), (minus, -1)):
                point = list(mid)
                point[axis] += side * OFFSET
                stroke.append(point)
    return plus, minus


def viewer_figure(obj: Polycube | LoopStructure, title: str | None = None):
    """The plotly figure of :func:`write_viewer`.

    Parameters
    ----------
    obj:
        A polycube, or an oriented loop structure (primalized first).
    title:
        A line above the view (default: corners, faces, loops and genus).

    Returns
    -------
    plotly.graph_objects.Figure

    Raises
    ------
    DualityError, PictureError
        As :func:`viewer_spec`.
    """
    import plotly.graph_objects as go

    return go.Figure(viewer_spec(obj, title))


def viewer_spec(obj: Polycube | LoopStructure, title: str | None = None) -> dict[str, Any]:
    """The viewer's figure as plotly's JSON form (``{"data": [...], "layout": {...}}``):
    what :func:`viewer_figure` wraps, and what :func:`viewer_html` writes without building
    plotly's validated objects (most of a page's cost in a gallery of thousands).

    Raises
    ------
    DualityError
        When a loop structure has no polycube.
    PictureError
        When the polycube is too large to draw.
    """
    q, ls = as_polycube(obj)
    xs: list[float] = []
    ys: list[float] = []
    zs: list[float] = []
    tri: list[tuple[int, int, int]] = []
    colours: list[str] = []
    texts: list[str] = []
    for f, face in enumerate(q.faces):
        base = len(xs)
        for c in face:  # each face its own corners, so that hover names the face
            x, y, z = q.positions[c]
            xs.append(x)
            ys.append(y)
            zs.append(z)
            texts.append(_face_text(q, ls, f))
        n = q.face_normal(f)
        shade = FACE_SHADE[n.axis] if n is not None else "#ff8080"
        tri += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
        colours += [shade, shade]
    i, j, k = zip(*tri, strict=True)
    traces: list[dict[str, Any]] = [dict(
        type="mesh3d", x=xs, y=ys, z=zs, i=list(i), j=list(j), k=list(k), facecolor=colours,
        flatshading=True, hovertext=texts, hoverinfo="text", name="faces", legendgroup="faces",
        showlegend=True, lighting=dict(ambient=0.75, diffuse=0.35, specular=0.05), opacity=1.0)]
    # Edges of the quads, as one line trace (None separates segments).
    ex: list[Any] = []
    ey: list[Any] = []
    ez: list[Any] = []
    for u, v in (q.map.edge_corners(e) for e in range(q.map.num_edges)):
        for point in (q.positions[u], q.positions[v], (None, None, None)):
            ex.append(point[0])
            ey.append(point[1])
            ez.append(point[2])
    traces.append(dict(type="scatter3d", x=ex, y=ey, z=ez, mode="lines", line=dict(color="#4d4d4d", width=2),
                       hoverinfo="skip", name="faces", legendgroup="faces", showlegend=False))
    if ls is not None:
        for axis in Axis:
            first = True
            for loop in (lp.id for lp in ls.loops if ls.axes[lp.id] == axis):
                plus, minus = _loop_paths(q, ls, loop)
                text = f"{axis.name}-loop {loop}, {len(ls.loops[loop])} segments"
                for stroke, colour in ((plus, AXIS_COLOUR[axis]), (minus, LIGHT_COLOUR[axis])):
                    closed = [*stroke, stroke[0]]
                    traces.append(dict(
                        type="scatter3d", x=[p[0] for p in closed], y=[p[1] for p in closed],
                        z=[p[2] for p in closed], mode="lines", line=dict(color=colour, width=6),
                        hoverinfo="text", hovertext=text, name=f"{axis.name}-loops",
                        legendgroup=f"{axis.name}-loops", showlegend=first))
                    first = False
    corner_text = []
    for c in range(q.map.num_corners):
        config = classify(q.corner_directions(c))
        about = (f"configuration {config.id} ({config.category}): {config.label}" if config is not None
                 else "no polycube corner")
        corner_text.append(f"corner {c} at {tuple(q.positions[c])}<br>degree {q.map.degree(c)}, {about}")
    traces.append(dict(
        type="scatter3d", x=[p[0] for p in q.positions], y=[p[1] for p in q.positions],
        z=[p[2] for p in q.positions], mode="markers", marker=dict(size=3, color="#202020"),
        hoverinfo="text", hovertext=corner_text, name="corners", legendgroup="corners",
        visible="legendonly" if q.map.num_corners > 400 else True))
    heading = title or (f"{q.map.num_corners} corners, {q.map.num_faces} faces, genus {q.genus}"
                        + ("" if ls is None else ", loops " + " ".join(
                            f"{a.name}:{ls.axes.count(a)}" for a in Axis)))
    aspect, eye = fitted_camera(q)
    layout = dict(
        title=dict(text=heading, font=dict(size=14)), margin=dict(l=0, r=0, t=40, b=0),
        scene=dict(aspectmode="manual", aspectratio=aspect, xaxis=dict(title=dict(text="X")),
                   yaxis=dict(title=dict(text="Y")), zaxis=dict(title=dict(text="Z")),
                   camera=dict(eye=eye, center=dict(x=0, y=0, z=0))),
        legend=dict(itemclick="toggle", groupclick="togglegroup"), paper_bgcolor="white")
    return {"data": traces, "layout": layout}


VIEW_DIRECTION = (1.4, 1.1, 0.9)  # from the front right, a little above
FIELD_OF_VIEW = math.radians(45)  # plotly's perspective camera (vertical)
FIT_MARGIN = 1.15  # room for the axes' ticks and titles around the box


def fitted_camera(q: Polycube) -> tuple[dict[str, float], dict[str, float]]:
    """The scene's aspect ratio (the bounding box's sides over its longest, as plotly's
    ``aspectmode="data"``) and an eye far enough along :data:`VIEW_DIRECTION` that the whole
    box fits in the first view: the sphere around the box (radius half its diagonal, in the
    scene's units, where the box spans the aspect ratio about the centre) seen within the
    field of view, with a margin.

    >>> from polyloops.shapes.builders import box
    >>> aspect, eye = fitted_camera(box(1, 1, 6))
    >>> aspect == {"x": 1 / 6, "y": 1 / 6, "z": 1.0}, round(math.dist((0, 0, 0), eye.values()), 2)
    (True, 1.54)
    """
    lo, hi = q.bounding_box()
    sides = [max(h - low, 1e-9) for low, h in zip(lo, hi, strict=True)]
    longest = max(sides)
    aspect = {k: side / longest for k, side in zip("xyz", sides, strict=True)}
    radius = math.dist((0, 0, 0), aspect.values()) / 2
    distance = FIT_MARGIN * radius / math.sin(FIELD_OF_VIEW / 2)
    norm = math.dist((0, 0, 0), VIEW_DIRECTION)
    return aspect, {k: distance * c / norm for k, c in zip("xyz", VIEW_DIRECTION, strict=True)}


def viewer_html(obj: Polycube | LoopStructure, title: str | None = None,
                plotly_js: bool | str = True, full_html: bool = True) -> str:
    """The viewer as HTML text; ``plotly_js``: ``True`` writes plotly.js into the page,
    ``"directory"`` refers to a ``plotly.min.js`` beside it.  A whole page (one viewer) names
    its plot ``polyloops-viewer``, so that a fixed input gives the same bytes; a fragment (a
    notebook shows many) keeps plotly's random name."""
    import plotly.io as pio

    return pio.to_html(viewer_spec(obj, title), include_plotlyjs=plotly_js, full_html=full_html,
                       default_height="92vh", default_width="100%", validate=False,
                       div_id="polyloops-viewer" if full_html else None,
                       config={"displaylogo": False, "responsive": True},
                       post_script=HIGHLIGHT if full_html else None)


# A page opened as ``NAME.html#loop-N`` shows loop N thick and the other loops faded (the
# gallery links a removable loop this way); the hash can change without reloading.
HIGHLIGHT = """
(function () {
  var gd = document.getElementById('{plot_id}');
  function highlight() {
    var m = /^#loop-(\\d+)$/.exec(window.location.hash);
    gd.data.forEach(function (t, i) {
      if (t.type !== 'scatter3d' || t.mode !== 'lines' || typeof t.hovertext !== 'string') return;
      var loop = /-loop (\\d+),/.exec(t.hovertext);
      if (!loop) return;
      var on = !m || loop[1] === m[1];
      Plotly.restyle(gd, {'line.width': m && on ? 14 : 6, 'opacity': on ? 1 : 0.25}, [i]);
    });
  }
  highlight();
  window.addEventListener('hashchange', highlight);
})();
"""


def write_viewer(obj: Polycube | LoopStructure, path: str | os.PathLike[str], title: str | None = None,
                 plotly_js: bool | str = True) -> None:
    """Write the viewer of a polycube or loop structure as one HTML page.

    Parameters
    ----------
    obj:
        A polycube, or an oriented loop structure (primalized first).
    path:
        The HTML file to write (atomically).
    title:
        A line above the view.
    plotly_js:
        ``True`` (default): plotly.js inside the page, which then needs nothing else;
        ``"directory"``: the page loads ``plotly.min.js`` from its own directory (write it
        once with :func:`write_plotly_js`), for a site of many pages.

    Returns
    -------
    None

    Raises
    ------
    DualityError, PictureError
        As :func:`viewer_spec`.
    OSError
        When the file cannot be written.

    >>> import tempfile, pathlib
    >>> from polyloops.io.examples import load_example
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write_viewer(load_example("cube"), pathlib.Path(tmp) / "cube.html")
    ...     size = (pathlib.Path(tmp) / "cube.html").stat().st_size
    >>> size > 1_000_000  # plotly.js is inside: no network needed
    True
    """
    write_atomic(path, viewer_html(obj, title, plotly_js))


def write_plotly_js(directory: str | os.PathLike[str]) -> None:
    """Write ``plotly.min.js`` into a directory, for viewer pages written with
    ``plotly_js="directory"``."""
    from pathlib import Path

    from plotly.offline import get_plotlyjs

    write_atomic(Path(directory) / "plotly.min.js", get_plotlyjs())
