"""Pictures of polycubes with their loops, and of level graphs.

Faces are drawn with the painter's algorithm after cutting them into unit cells, so that
depth sorting stays right for concave and self-intersecting polycubes.  Each loop is drawn
on the surface through the face centres it visits, as two thin strokes on either side of
its path: the stroke on the ``+`` side (towards higher coordinates of the loop's axis) dark,
the one on the ``-`` side light, in the paper's colours.
"""

from __future__ import annotations

import io
import math
import os
from collections.abc import Iterable
from itertools import product

from matplotlib.patches import Polygon

from polyloops.core.directions import Axis, Direction
from polyloops.core.duality import DualityError, dualize, primalize
from polyloops.core.errors import PolyloopsError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.render.colors import AXIS_COLOR, LIGHT_COLOR
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.projection import View

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


def _cells(q: Polycube, f: int) -> list[tuple[tuple[int, int], list[Vec]]]:
    """The face cut into unit cells, each with its grid position (faces are axis-aligned
    rectangles with integer corners; any other face stays whole, at position (0, 0))."""
    p = [q.positions[c] for c in q.faces[f]]
    frame = _face_frame(q, f)
    if frame is None:
        return [((0, 0), [_vec(map(float, x)) for x in p])]
    a, b, lo, hi = frame
    out = []
    for u, v in product(range(lo[a], hi[a]), range(lo[b], hi[b])):
        cell = []
        for corner in p:  # keep the face's orientation
            x = list(map(float, corner))
            x[a] = u + (1.0 if corner[a] == hi[a] else 0.0)
            x[b] = v + (1.0 if corner[b] == hi[b] else 0.0)
            cell.append((x[0], x[1], x[2]))
        out.append(((u, v), cell))
    return out


def _pieces(a: Vec, b: Vec, longest: float = 0.5) -> list[tuple[Vec, Vec]]:
    """A segment cut into pieces no longer than ``longest``."""
    length = math.dist(a, b)
    k = max(1, math.ceil(length / longest))
    pts = [_vec(a[i] + (b[i] - a[i]) * j / k for i in range(3)) for j in range(k + 1)]
    return [(pts[j], pts[j + 1]) for j in range(k)]


def _loop_strokes(q: Polycube, ls: LoopStructure, lift: float,
                  faces: set[int]) -> list[tuple[int, tuple[Vec, Vec], str, float]]:
    """Pieces of every loop on the given faces: (face, segment, colour, width), one stroke on
    each side of the loop's path."""
    m = q.map
    out = []
    for lp in ls.loops:
        axis = ls.axes[lp.id]
        e = [0.0, 0.0, 0.0]
        e[axis] = 1.0
        for i, d in enumerate(lp.darts):
            f = lp.faces[i]
            n = face_normal(q, f)
            if n is None or f not in faces:
                continue
            ends = []
            for dart in (d, m.next[m.next[d]]):  # entry and exit edges of this face
                a, b = q.positions[m.origin(dart)], q.positions[m.target(dart)]
                ends.append(tuple((a[k] + b[k]) / 2 for k in range(3)))
            centre = tuple(sum(q.positions[c][k] for c in q.faces[f]) / 4 for k in range(3))
            for side, colour in ((1.0, AXIS_COLOR[axis]), (-1.0, LIGHT_COLOR[axis])):
                path = (ends[0], centre, ends[1])
                pts = [_add(_add(p, n.vector, lift), tuple(e), side * 0.08) for p in path]
                for j in range(2):
                    for piece in _pieces(pts[j], pts[j + 1]):
                        out.append((f, piece, colour, 2.2))
    return out


EDGE_COLOUR = "#4d4d4d"


def draw_polycube(ax, q: Polycube, view: View, loops: LoopStructure | None) -> None:
    """Faces turned away from the camera are left out (the surface is closed, so they are hidden
    unless it meets itself).  The rest are cut into unit cells sorted by depth; each cell is
    drawn with the pieces of face edges and loops that lie on it, so they are hidden with it."""
    cells: dict[tuple[int, int, int], list] = {}
    frames: dict[int, tuple[int, int, list[int], list[int]] | None] = {}
    for f in range(q.map.num_faces):
        n = face_normal(q, f)
        if n is not None and view.facing(n.vector) <= 0:
            continue
        frames[f] = _face_frame(q, f)
        colour = FACE_SHADE[n.axis] if n is not None else "#ff8080"
        for (u, v), cell in _cells(q, f):
            centre = tuple(sum(p[k] for p in cell) / 4 for k in range(3))
            cells[(f, u, v)] = [view.depth(centre), cell, colour, [], []]

    def cell_of(f: int, point: Vec) -> list:
        frame = frames[f]
        if frame is None:
            return cells[(f, 0, 0)]
        a, b, lo, hi = frame
        u = min(max(math.floor(point[a]), lo[a]), hi[a] - 1)
        v = min(max(math.floor(point[b]), lo[b]), hi[b] - 1)
        return cells[(f, u, v)]

    for f in frames:
        corners = [_vec(map(float, q.positions[c])) for c in q.faces[f]]
        inward = _vec(sum(c[k] for c in corners) / 4 for k in range(3))
        for i in range(4):
            for piece in _pieces(corners[i], corners[(i + 1) % 4], 1.0):
                mid = _vec((piece[0][k] + piece[1][k]) / 2 for k in range(3))
                # Nudge towards the face centre to find the cell the piece borders.
                probe = _vec(mid[k] + 0.25 * math.copysign(1, inward[k] - mid[k]) * (inward[k] != mid[k])
                              for k in range(3))
                cell_of(f, probe)[3].append(piece)
    if loops is not None:
        for f, piece, colour, width in _loop_strokes(q, loops, 0.02, set(frames)):
            mid = _vec((piece[0][k] + piece[1][k]) / 2 for k in range(3))
            cell_of(f, mid)[4].append((piece, colour, width))
    xs, ys = [], []
    for _, poly, colour, edges, strokes in sorted(cells.values(), key=lambda c: c[0]):
        flat = [view.project(p) for p in poly]
        xs += [x for x, _ in flat]
        ys += [y for _, y in flat]
        ax.add_patch(Polygon(flat, closed=True, facecolor=colour, edgecolor=colour, lw=0.3))
        for a, b in edges:
            (x0, y0), (x1, y1) = view.project(a), view.project(b)
            ax.plot([x0, x1], [y0, y1], color=EDGE_COLOUR, lw=0.7, solid_capstyle="round")
        for (a, b), c, width in strokes:
            (x0, y0), (x1, y1) = view.project(a), view.project(b)
            ax.plot([x0, x1], [y0, y1], color=c, lw=width, solid_capstyle="round")
    if xs:
        pad = 0.3
        cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
        r = max(max(xs) - min(xs), max(ys) - min(ys)) / 2 + pad
        ax.set_xlim(cx - r, cx + r)
        ax.set_ylim(cy - r, cy + r)
    ax.set_aspect("equal")
    ax.axis("off")


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
                    views: int = 1, loops: bool = True, title: str | None = None, size: float = 4.0):
    """Draw a polycube (a loop structure is primalized first) from ``views`` directions.

    Writes PNG or SVG to ``path``; with ``path=None`` returns the figure."""
    q, ls = as_polycube(obj)
    chosen = choose_views(q, max(1, views))
    cols = min(len(chosen), 2 if len(chosen) == 4 else len(chosen))
    rows = math.ceil(len(chosen) / cols)
    fig = new_figure(size * cols, size * rows + (0.4 if title else 0))
    for i, view in enumerate(chosen):
        ax = fig.add_subplot(rows, cols, i + 1)
        draw_polycube(ax, q, view, ls if loops else None)
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
