"""Hidden surfaces by a depth buffer: every pixel shows the nearest face.

A painter's algorithm (sorting faces or unit cells by depth) misorders faces near concave
corners and cannot draw a surface that passes through itself.  Here each face is cut into
two triangles, and every triangle is rasterised in screen space: at each pixel centre it
covers, its depth comes from barycentric interpolation, and the pixel keeps the nearest face
(a depth buffer: compiled, ``_raster.c``, or numpy-vectorised per triangle, the same
buffers bit for bit).  The buffer keeps, per pixel, the face and
the 3D point seen there, so everything drawn on the surface (the quads' edges, the loops,
zones, the unit grid) is decided per pixel from what is actually visible: nothing can show
through a nearer face.

:func:`triangle_buffer` is the same depth test for large triangle meshes (labelled
segmentations of scanned models): all triangles at once, pixel candidates generated from each
triangle's bounding box in chunks, the nearest kept by one sort.  A test compares it with the
triangle-at-a-time loop on random triangles.

``tests/test_render.py`` checks the buffer against an independent oracle: rays cast through
sampled pixels, intersected exactly (rational arithmetic) with every face.

>>> from polyloops.io.examples import load_example
>>> from polyloops.render.projection import View
>>> buf = rasterize(load_example("l-shape"), View(35, 28), 64)
>>> buf.face.shape, int((buf.face >= 0).sum()) > 1000
((64, 64), True)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from polyloops.core import compiled
from polyloops.core.polycube import Polycube
from polyloops.render.projection import View


@dataclass(frozen=True)
class DepthBuffer:
    """What a view sees, pixel by pixel (row 0 at the top).

    ``face`` is the visible face's id (-1 for background), ``depth`` its distance towards the
    viewer (larger is nearer), ``point`` the 3D point seen.  Pixel ``(i, j)`` has its centre at
    view coordinates ``(u[j], v[i])``.
    """

    face: np.ndarray
    depth: np.ndarray
    point: np.ndarray
    u: np.ndarray
    v: np.ndarray

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """``(left, right, bottom, top)`` of the pixel area, for matplotlib's ``imshow``."""
        du, dv = self.u[1] - self.u[0], self.v[0] - self.v[1]
        return (self.u[0] - du / 2, self.u[-1] + du / 2, self.v[-1] - dv / 2, self.v[0] + dv / 2)


def view_bounds(q: Polycube, view: View, pad: float = 0.3) -> tuple[float, float, float]:
    """The centre and half-width of a square around the projected polycube."""
    flat = np.array([view.project(p) for p in q.positions], dtype=float)
    lo, hi = flat.min(axis=0), flat.max(axis=0)
    centre = (lo + hi) / 2
    return float(centre[0]), float(centre[1]), float((hi - lo).max() / 2 + pad)


def rasterize(q: Polycube, view: View, pixels: int,
              bounds: tuple[float, float, float] | None = None) -> DepthBuffer:
    """The depth buffer of ``q`` seen from ``view`` on a square of ``pixels`` by ``pixels``
    (``bounds``: centre and half-width in view coordinates; default around the polycube)."""
    cu, cv, half = bounds if bounds is not None else view_bounds(q, view)
    step = 2 * half / pixels
    u = cu - half + step * (np.arange(pixels) + 0.5)
    v = cv + half - step * (np.arange(pixels) + 0.5)
    face = np.full((pixels, pixels), -1, dtype=np.int64)
    depth = np.full((pixels, pixels), -np.inf)
    point = np.zeros((pixels, pixels, 3))
    pos = np.asarray(q.positions, dtype=float)
    right, up, toward = (np.asarray(a) for a in (view.right, view.up, view.toward))
    flat_u, flat_v, flat_d = pos @ right, pos @ up, pos @ toward
    # Faces that face the viewer first: where two faces coincide (a surface touching itself),
    # a later face must be nearer by more than a rounding error to win, so the outside shows.
    tie = 1e-7 * max(1.0, float(np.abs(flat_d).max(initial=0.0)))
    quads = np.asarray(q.faces, dtype=np.int64).reshape(-1, 4)
    order = np.argsort(~_facing(pos, quads, toward), kind="stable")
    # Each face as two triangles (corners 0 1 2 and 0 2 3), in drawing order.
    tris = quads[order][:, [0, 1, 2, 0, 2, 3]].reshape(-1, 3)
    faces = np.repeat(order, 2)
    part = compiled.load("raster")  # the compiled depth buffer: the same buffers bit for bit
    if part is not None:
        a, b, c = tris.T
        rows = np.column_stack([flat_u[a], flat_v[a], flat_u[b], flat_v[b], flat_u[c], flat_v[c],
                                flat_d[tris], faces.astype(float), pos[tris].reshape(-1, 9)])
        part.fill(np.ascontiguousarray(rows).tobytes(), u.tobytes(), v.tobytes(), cu - half, cv + half,
                     step, tie, face, depth, point)
    else:
        for f, tri in zip(faces.tolist(), tris.tolist(), strict=True):
            _triangle(f, tri, flat_u, flat_v, flat_d, pos, u, v, step, cu - half, cv + half,
                      face, depth, point, tie)
    return DepthBuffer(face, depth, point, u, v)


def _facing(pos: np.ndarray, quads: np.ndarray, toward: np.ndarray) -> np.ndarray:
    """Which faces (counter-clockwise seen from outside) show their outside to the viewer."""
    p = pos[quads]
    normal = (np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
              + np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))
    return normal @ toward > 0


def _triangle(f: int, tri: list[int], fu: np.ndarray, fv: np.ndarray, fd: np.ndarray,
              pos: np.ndarray, u: np.ndarray, v: np.ndarray, step: float, left: float, top: float,
              face: np.ndarray, depth: np.ndarray, point: np.ndarray, tie: float) -> None:
    a, b, c = tri
    xa, ya, xb, yb, xc, yc = fu[a], fv[a], fu[b], fv[b], fu[c], fv[c]
    area = (xb - xa) * (yc - ya) - (xc - xa) * (yb - ya)
    if abs(area) < 1e-12:  # seen edge-on: covers no pixel centre
        return
    n = len(u)
    j0 = max(0, int(np.floor((min(xa, xb, xc) - left) / step)))
    j1 = min(n, int(np.ceil((max(xa, xb, xc) - left) / step)) + 1)
    i0 = max(0, int(np.floor((top - max(ya, yb, yc)) / step)))
    i1 = min(n, int(np.ceil((top - min(ya, yb, yc)) / step)) + 1)
    if j0 >= j1 or i0 >= i1:
        return
    px, py = np.meshgrid(u[j0:j1], v[i0:i1])
    # Barycentric coordinates from edge functions; a centre on an edge counts as inside.
    wa = ((xb - px) * (yc - py) - (xc - px) * (yb - py)) / area
    wb = ((xc - px) * (ya - py) - (xa - px) * (yc - py)) / area
    wc = 1.0 - wa - wb
    eps = -1e-9
    inside = (wa >= eps) & (wb >= eps) & (wc >= eps)
    if not inside.any():
        return
    d = wa * fd[a] + wb * fd[b] + wc * fd[c]
    window = depth[i0:i1, j0:j1]
    nearer = inside & (d > window + tie)
    window[nearer] = d[nearer]
    face[i0:i1, j0:j1][nearer] = f
    p = wa[..., None] * pos[a] + wb[..., None] * pos[b] + wc[..., None] * pos[c]
    point[i0:i1, j0:j1][nearer] = p[nearer]


def triangle_buffer(x: np.ndarray, y: np.ndarray, d: np.ndarray, triangles: np.ndarray,
                    shape: tuple[int, int], chunk: int = 1 << 21) -> tuple[np.ndarray, np.ndarray]:
    """The nearest triangle at every pixel centre, for many triangles at once.

    ``x`` and ``y`` are the points' pixel coordinates (column and row, continuous: pixel
    ``(i, j)`` has its centre at ``(j + 0.5, i + 0.5)``), ``d`` their depths (larger is nearer),
    ``triangles`` a ``(T, 3)`` array of point ids.  Returns the triangle seen at each pixel
    (-1 for background) and its depth there.  A centre on an edge counts as inside; of two
    triangles equally near, the lower id wins.  Memory: about 100 bytes a candidate pixel,
    ``chunk`` candidates at a time.

    >>> x, y, d = np.array([0., 4, 0]), np.array([0., 0, 4]), np.zeros(3)
    >>> seen, _ = triangle_buffer(x, y, d, np.array([[0, 1, 2]]), (4, 4))
    >>> (seen == 0).astype(int).tolist()[0], int((seen == 0).sum())
    ([1, 1, 1, 1], 10)
    """
    h, w = shape
    seen = np.full(h * w, -1, dtype=np.int64)
    depth = np.full(h * w, -np.inf)
    tri = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    xs, ys, ds = x[tri], y[tri], d[tri]
    area = ((xs[:, 1] - xs[:, 0]) * (ys[:, 2] - ys[:, 0]) - (xs[:, 2] - xs[:, 0]) * (ys[:, 1] - ys[:, 0]))
    # Pixel centres j + 0.5 inside each bounding box, clipped to the picture.
    j0 = np.clip(np.ceil(xs.min(axis=1) - 0.5), 0, w).astype(np.int64)
    j1 = np.clip(np.floor(xs.max(axis=1) - 0.5) + 1, 0, w).astype(np.int64)
    i0 = np.clip(np.ceil(ys.min(axis=1) - 0.5), 0, h).astype(np.int64)
    i1 = np.clip(np.floor(ys.max(axis=1) - 0.5) + 1, 0, h).astype(np.int64)
    cols, rows = np.maximum(j1 - j0, 0), np.maximum(i1 - i0, 0)
    counts = np.where(np.abs(area) < 1e-12, 0, cols * rows)  # edge-on: covers no centre
    ends = np.cumsum(counts)
    start = 0
    while start < len(tri):
        stop = max(start + 1, int(np.searchsorted(ends, ends[start] - counts[start] + chunk, side="right")))
        _resolve(np.arange(start, min(stop, len(tri))), counts, j0, i0, cols, xs, ys, ds, area, w,
                 seen, depth)
        start = stop
    return seen.reshape(h, w), depth.reshape(h, w)


def _resolve(ids: np.ndarray, counts: np.ndarray, j0: np.ndarray, i0: np.ndarray, cols: np.ndarray,
             xs: np.ndarray, ys: np.ndarray, ds: np.ndarray, area: np.ndarray, w: int,
             seen: np.ndarray, depth: np.ndarray) -> None:
    """Rasterise the triangles ``ids`` and keep, per pixel, the nearest of them and the buffer."""
    n = counts[ids]
    t = np.repeat(ids, n)
    if not len(t):
        return
    local = np.arange(len(t)) - np.repeat(np.cumsum(n) - n, n)
    j = j0[t] + local % cols[t]
    i = i0[t] + local // cols[t]
    px, py = j + 0.5, i + 0.5
    xa, xb, xc = xs[t, 0], xs[t, 1], xs[t, 2]
    ya, yb, yc = ys[t, 0], ys[t, 1], ys[t, 2]
    wa = ((xb - px) * (yc - py) - (xc - px) * (yb - py)) / area[t]
    wb = ((xc - px) * (ya - py) - (xa - px) * (yc - py)) / area[t]
    wc = 1.0 - wa - wb
    inside = (wa >= -1e-9) & (wb >= -1e-9) & (wc >= -1e-9)
    t, pix = t[inside], (i * w + j)[inside]
    dd = wa[inside] * ds[t, 0] + wb[inside] * ds[t, 1] + wc[inside] * ds[t, 2]
    order = np.lexsort((t, -dd, pix))  # per pixel: nearest first, then the lower id
    pix, dd, t = pix[order], dd[order], t[order]
    first = np.ones(len(pix), dtype=bool)
    first[1:] = pix[1:] != pix[:-1]
    pix, dd, t = pix[first], dd[first], t[first]
    better = (dd > depth[pix]) | ((dd == depth[pix]) & (t < seen[pix]))
    depth[pix[better]] = dd[better]
    seen[pix[better]] = t[better]
