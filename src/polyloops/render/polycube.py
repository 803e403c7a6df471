"""Pictures of polycubes with their loops.

Hidden surfaces are resolved per pixel by a depth buffer (:mod:`polyloops.render.raster`), so
that concave, self-intersecting and high-genus polycubes are drawn right: the face drawn at
each point is the nearest one.  The polycube's own quads are drawn with their edges (the unit
grid on request); each loop is drawn on the surface as two thin strokes on either side of its
path, the stroke on the ``+`` side (towards higher coordinates of the loop's axis) dark, the
one on the ``-`` side light, in the paper's colours.  With ``zones``, the zones of one axis are
shaded in alternating greys, as in the paper's figure of zones and level graphs.
"""

from __future__ import annotations

import io
import math
import os
from collections.abc import Iterable

import numpy as np

from polyloops.core.directions import Axis, Direction
from polyloops.core.duality import DualityError, dualize, primalize
from polyloops.core.errors import PolyloopsError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.render.colours import AXIS_COLOUR, LIGHT_COLOUR
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.projection import View
from polyloops.render.raster import DepthBuffer, rasterize

FACE_SHADE = {Axis.X: "#cfcfcf", Axis.Y: "#e8e8e8", Axis.Z: "#b4b4b4"}

Vec = tuple[float, float, float]


def _vec(xs: Iterable[float]) -> Vec:
    """Three numbers as a point (the type checker cannot count a generator's items)."""
    x, y, z = xs
    return (x, y, z)


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def _add(a, b, s=1.0):
    return (a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2])


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def face_normal(q: Polycube, f: int) -> Direction | None:
    """The outward normal of a face (faces are counter-clockwise seen from outside)."""
    return q.face_normal(f)


def candidate_views() -> list[tuple[float, float]]:
    """Azimuth/elevation pairs looking from each of the eight octants, slightly off-diagonal;
    views from above first, so that they win ties."""
    return [(az, el) for el in (28.0, -28.0) for az in (35.0, 125.0, 215.0, 305.0)]


def choose_views(q: Polycube, count: int) -> list[View]:
    """Greedy: each view shows the most faces (facing the camera) not shown by earlier ones."""
    normals = {f: n for f in range(q.map.num_faces) if (n := face_normal(q, f)) is not None}
    remaining = set(normals)
    chosen: list[View] = []
    pool = [View(az, el) for az, el in candidate_views()]
    for _ in range(count):
        best = max(pool, key=lambda v: (sum(v.facing(normals[f].vector) > 0 for f in remaining),
                                        -pool.index(v)))
        chosen.append(best)
        pool.remove(best)
        remaining -= {f for f in remaining if best.facing(normals[f].vector) > 0}
        if not pool:
            break
    return chosen


def _face_frame(q: Polycube, f: int) -> tuple[int, int, list[int], list[int]] | None:
    """The two in-plane axes and the bounds of an axis-aligned rectangular face, else ``None``."""
    p = [q.positions[c] for c in q.faces[f]]
    lo = [min(x[i] for x in p) for i in range(3)]
    hi = [max(x[i] for x in p) for i in range(3)]
    flat = [i for i in range(3) if lo[i] == hi[i]]
    if len(flat) != 1:
        return None
    a, b = [i for i in range(3) if i != flat[0]]
    return a, b, lo, hi


EDGE_COLOUR = "#4d4d4d"
BACK_COLOUR = "#ff8080"  # the inside of the surface, seen where it passes through itself
ZONE_SHADES = ("#e6e6e6", "#a8a8a8", "#c8c8c8")  # alternating zones (a third if two do not do)
LIGHT = {Axis.X: 0.93, Axis.Y: 1.0, Axis.Z: 0.84}  # zones keep some sense of shape
SUPERSAMPLE = 3
STROKE = 0.035  # half the width of a loop stroke, in unit cells
OFFSET = 0.08   # the two strokes of a loop lie this far on either side of its path
GRID = 0.015


def _rgb(colour: str) -> np.ndarray:
    return np.array([int(colour[k:k + 2], 16) / 255 for k in (1, 3, 5)])


def zone_shades(ls: LoopStructure, axis: Axis) -> list[str]:
    """A grey per ``axis``-zone such that zones joined by a loop differ: two alternating
    hues when the level graph (as an undirected graph) is bipartite, as at genus 0, else a
    greedy colouring."""
    import networkx as nx

    g = nx.Graph()
    g.add_nodes_from(range(ls.zones(axis).count))
    g.add_edges_from((u, v) for u, v, _ in ls.level_graph(axis).edges(keys=True) if u != v)
    bipartite = nx.is_bipartite(g)
    colour = nx.bipartite.color(g) if bipartite else nx.greedy_color(g, strategy="largest_first")
    return [ZONE_SHADES[colour[z] % len(ZONE_SHADES)] for z in range(g.number_of_nodes())]


def shade(q: Polycube, buf: DepthBuffer, view: View, loops: LoopStructure | None,
          zones: Axis | None = None, grid: bool = False) -> np.ndarray:
    """The colours of a depth buffer's pixels (``(H, W, 3)`` in 0..1): each visible face in
    its shade (by its normal, or by its zone along ``zones``), the quads' edges, the unit grid
    on request, and each loop as two strokes, dark on its ``+`` side and light on its ``-``
    side, all decided from what each pixel actually sees.  Each pixel holds an index into a
    palette (the faces' colours, then the zones', the strokes', the grid's and the edges'),
    and the colours are looked up once at the end."""
    nf = q.map.num_faces
    palette = [np.ones(3)] * (nf + 1)  # a row per face; the last: background
    light = np.ones(nf + 1)
    frames = [_face_frame(q, f) for f in range(nf)]
    mid = np.zeros((nf + 1, 3))
    in_plane = np.zeros((nf + 1, 3), dtype=bool)
    inside = np.zeros(nf + 1, dtype=bool)  # faces that show the viewer their inside
    axis_of = np.zeros(nf + 1, dtype=np.int64)
    for f in range(nf):
        n = face_normal(q, f)
        inside[f] = n is None or view.facing(n.vector) <= 0
        palette[f] = _rgb(FACE_SHADE[n.axis] if n is not None and not inside[f] else BACK_COLOUR)
        light[f] = LIGHT[n.axis] if n is not None else 1.0
        axis_of[f] = n.axis if n is not None else 1  # LIGHT[Y] is 1.0, as for faces without normal
        frame = frames[f]
        if frame is not None:
            a, b, lo, hi = frame
            for k in (a, b):
                in_plane[f, k] = True
                mid[f, k] = (lo[k] + hi[k]) / 2
    fid = np.where(buf.face >= 0, buf.face, nf)
    index = fid.copy()
    seen = buf.face >= 0

    def colour(rgb: np.ndarray) -> int:
        palette.append(rgb)
        return len(palette) - 1

    if zones is not None and loops is not None:
        base = len(palette)
        for shade_rgb in map(_rgb, zone_shades(loops, zones)):  # a row per (zone, face axis)
            for a in Axis:
                colour(shade_rgb * LIGHT[a])
        zone_of = loops.zones(zones).zone_of
        low_zone, high_zone = np.zeros(nf + 1, dtype=np.int64), np.zeros(nf + 1, dtype=np.int64)
        for f, face in enumerate(q.faces):
            coords = [q.positions[c][zones] for c in face]
            low_zone[f] = zone_of[face[coords.index(min(coords))]]
            high_zone[f] = zone_of[face[coords.index(max(coords))]]
        # A face crossed by a loop of this axis is split at its midline between two zones.
        above = buf.point[..., zones] > np.take(mid[:, zones], fid)
        zone = np.where(np.take(in_plane[:, zones], fid) & above, np.take(high_zone, fid),
                        np.take(low_zone, fid))
        index = np.where(seen & ~np.take(inside, fid), base + zone * 3 + np.take(axis_of, fid), index)
    # Every override below is in place, in drawing order (later marks cover earlier ones).
    # Gathers are per axis with np.take: several times faster than indexing rows by ``fid``.
    plane = [np.take(in_plane[:, k], fid) & seen for k in range(3)]  # seen faces along axis k
    if grid:
        grey = colour(_rgb("#8c8c8c"))
        for k in range(3):
            frac = np.abs(buf.point[..., k] - np.round(buf.point[..., k]))
            index[plane[k] & (frac < GRID)] = grey
    if loops is not None:
        for k in Axis:
            on, dk = plane[k], buf.point[..., k] - np.take(mid[:, k], fid)
            index[on & (np.abs(dk + OFFSET) < STROKE)] = colour(_rgb(LIGHT_COLOUR[k]))
            index[on & (np.abs(dk - OFFSET) < STROKE)] = colour(_rgb(AXIS_COLOUR[k]))
    # The quads' edges: where the visible face changes between neighbouring pixels.
    edge = np.zeros_like(seen)
    across, down = fid[:, :-1] != fid[:, 1:], fid[:-1, :] != fid[1:, :]
    edge[:, :-1] |= across
    edge[:, 1:] |= across
    edge[:-1, :] |= down
    edge[1:, :] |= down
    index[edge] = colour(_rgb(EDGE_COLOUR))
    return np.take(np.asarray(palette), index, axis=0)


def draw_polycube(ax, q: Polycube, view: View, loops: LoopStructure | None, pixels: int = 400,
                  zones: Axis | None = None, grid: bool = False,
                  supersample: int = SUPERSAMPLE) -> DepthBuffer:
    """Draw ``q`` from ``view`` on matplotlib axes, hidden surfaces by a depth buffer
    (:mod:`polyloops.render.raster`) supersampled for smooth edges; returns the buffer."""
    buf, small = _picture(q, view, loops, pixels, zones, grid, supersample)
    ax.imshow(small, extent=buf.extent, interpolation="antialiased", origin="upper")
    ax.set_aspect("equal")
    ax.axis("off")
    return buf


def _picture(q: Polycube, view: View, loops: LoopStructure | None, pixels: int, zones: Axis | None,
             grid: bool, supersample: int) -> tuple[DepthBuffer, np.ndarray]:
    """The depth buffer at ``pixels * supersample`` and the shaded picture averaged down to
    ``pixels`` square."""
    buf = rasterize(q, view, pixels * supersample)
    rgb = shade(q, buf, view, loops, zones, grid)
    # The mean of each s x s block, as a sum of s * s strided views (several times faster
    # than a reduction over the block's axes).
    small = sum(rgb[a::supersample, b::supersample] for a in range(supersample) for b in range(supersample))
    return buf, np.asarray(small) / supersample ** 2


THUMBNAIL_SUPERSAMPLE = 2  # small pictures: 2 x 2 samples a pixel look the same as 3 x 3 there


def thumbnail_pixels(obj: Polycube | LoopStructure, pixels: int = 240) -> np.ndarray:
    """One view with the loops as a ``pixels`` x ``pixels`` x 3 array of 8-bit RGB: what a
    gallery or a sheet shows for each class.

    Raises
    ------
    DualityError, PictureError
        As :func:`render_polycube`.
    """
    q, ls = as_polycube(obj)
    _, small = _picture(q, choose_views(q, 1)[0], ls, pixels, None, False, THUMBNAIL_SUPERSAMPLE)
    # Truncated, as matplotlib does when it saves floats (so the gallery's files keep their bytes).
    return (np.clip(small, 0.0, 1.0) * 255).astype(np.uint8)


def write_thumbnail(obj: Polycube | LoopStructure, path: str | os.PathLike[str], pixels: int = 240) -> None:
    """A small PNG of :func:`thumbnail_pixels`, the picture alone (no figure around it), at a
    third of :func:`render_polycube`'s cost.

    Raises
    ------
    DualityError, PictureError
        As :func:`render_polycube`.
    OSError
        When the file cannot be written.
    """
    import matplotlib.image

    from polyloops.io.files import writing

    rgb = thumbnail_pixels(obj, pixels)
    with writing(path, suffix=".png") as out:
        # None drops matplotlib's version from the file, so a fixed input gives the same bytes
        matplotlib.image.imsave(out.path, rgb, format="png",
                                metadata={"Software": None})  # type: ignore[dict-item]


MAX_EXTENT = 256  # unit cells per axis that a picture draws; beyond, the compact form is drawn


class PictureError(PolyloopsError, ValueError):
    """A structure that cannot be drawn."""


def _extent(q: Polycube) -> int:
    lo, hi = q.bounding_box()
    return max(h - low for h, low in zip(hi, lo, strict=True))


def as_polycube(obj: Polycube | LoopStructure) -> tuple[Polycube, LoopStructure | None]:
    """The polycube to draw and its loop structure (``None`` if it has none); raises
    :class:`DualityError` when a loop structure has no polycube (a cyclic level graph).

    A polycube wider than ``MAX_EXTENT`` unit cells is drawn in its compact order-equivalent
    form (Theorem 2's coordinates), which shows the same polycube; one that has no loop
    structure and is that wide raises :class:`PictureError`."""
    if isinstance(obj, Polycube):
        q = obj.outward()
        try:
            ls = dualize(q)
        except DualityError:
            ls = None
        if _extent(q) <= MAX_EXTENT:
            return q, ls
        try:
            compact = primalize(ls).outward() if ls is not None else None
        except DualityError:
            compact = None
        if compact is None or _extent(compact) > MAX_EXTENT:
            raise PictureError(f"too large to draw: {_extent(q)} unit cells across "
                               f"(pictures draw at most {MAX_EXTENT})")
        return compact, dualize(compact)
    if not obj.oriented:
        raise DualityError("a labelled loop structure has no polycube; orient it first")
    q = primalize(obj).outward()
    if _extent(q) > MAX_EXTENT:
        raise PictureError(f"too large to draw: {_extent(q)} unit cells across "
                           f"(pictures draw at most {MAX_EXTENT})")
    return q, dualize(q) if q.map is not obj.map else obj


def render_polycube(obj: Polycube | LoopStructure, path: str | os.PathLike[str] | None = None,
                    views: int = 1, loops: bool = True, title: str | None = None, size: float = 4.0,
                    zones: Axis | None = None, level_graph: bool = False, grid: bool = False):
    """Draw a polycube (a loop structure is primalized first) from ``views`` directions.

    Parameters
    ----------
    obj:
        A polycube or an oriented loop structure.
    path:
        Write PNG or SVG here (by its ending); ``None`` returns the matplotlib figure.
    views:
        How many views, each from another octant, chosen to show the most faces.
    loops:
        Draw the loops on the surface.
    title:
        A line above the picture.
    size:
        Inches per view.
    zones:
        Shade the zones of this axis in alternating greys (the paper's figure of zones).
    level_graph:
        With ``zones``, draw that axis' level graph beside, its nodes in the same shades.
    grid:
        Draw the unit grid on the faces too.

    Returns
    -------
    matplotlib.figure.Figure or None

    Raises
    ------
    DualityError
        When a loop structure has no polycube (a level graph has a cycle).
    PictureError
        When the polycube is too large to draw, or zones are asked of a shape without loops.

    >>> from polyloops.io.examples import load_example
    >>> fig = render_polycube(load_example("l-shape"), zones=Axis.X, level_graph=True)
    >>> len(fig.axes)
    2
    """
    q, ls = as_polycube(obj)
    if zones is not None and ls is None:
        raise PictureError("no loop structure, so no zones to shade")
    chosen = choose_views(q, max(1, views))
    beside = 1 if zones is not None and level_graph else 0
    panels = len(chosen) + beside
    cols = min(panels, 2 if panels == 4 else panels)
    rows = math.ceil(panels / cols)
    fig = new_figure(size * cols, size * rows + (0.4 if title else 0))
    for i, view in enumerate(chosen):
        ax = fig.add_subplot(rows, cols, i + 1)
        draw_polycube(ax, q, view, ls if loops else None, pixels=int(size * 100), zones=zones, grid=grid)
    if beside:
        from polyloops.render.level_graphs import draw_level_graph

        assert ls is not None and zones is not None
        draw_level_graph(fig.add_subplot(rows, cols, panels), ls, zones, zone_shades(ls, zones))
    if title:
        fig.suptitle(title, fontsize=10)
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=0.93 if title else 0.99,
                        wspace=0.02, hspace=0.02)
    if path is None:
        return fig
    save_figure(fig, path)
    return None


def png_bytes(obj: Polycube | LoopStructure, size: float = 3.5) -> bytes:
    """PNG of a single view (for Jupyter's ``_repr_png_``)."""
    fig = render_polycube(obj, None, views=1, size=size)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", metadata={"Software": None})
    return buf.getvalue()
