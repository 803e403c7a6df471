"""Pictures of labelled segmentations: triangles coloured by label, chart boundaries in black,
and, for an invalid one, the witness in red."""

from __future__ import annotations

import os
from itertools import pairwise

from matplotlib.collections import PolyCollection
from matplotlib.patches import Patch

from polyloops.core.directions import Direction
from polyloops.render.colours import direction_colour
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.projection import View

WITNESS_COLOUR = "#d7191c"
VIEWS = (View(35.0, 28.0), View(215.0, -28.0))


def _normal(points, tri) -> tuple[float, float, float]:
    a, b, c = (points[i] for i in tri)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


SUBDIVISIONS = 6  # each triangle drawn as 36 small ones, so that far-to-near order holds


def _tint(colour: str) -> tuple[float, float, float]:
    """The colour mixed half with the witness red."""
    from matplotlib.colors import to_rgb

    a, b = to_rgb(colour), to_rgb(WITNESS_COLOUR)
    return (0.5 * a[0] + 0.5 * b[0], 0.5 * a[1] + 0.5 * b[1], 0.5 * a[2] + 0.5 * b[2])


def draw_segmentation(ax, report, view: View) -> None:
    """Draw one view.  Front-facing triangles are cut into small ones and drawn far to near,
    chart boundaries with them (red where they belong to the witness or a violation); charts
    that break a local rule of their own are tinted red, and witness corners marked."""
    seg = report.segmentation
    mesh, m = seg.mesh, seg.map
    witness = report.global_.witness
    hot_charts: set[int] = set()
    hot_edges: set[frozenset[int]] = set()
    hot_boundaries = set(witness.all_boundaries()) if witness is not None else set()
    for v in report.local.violations:
        hot_boundaries |= set(v.boundaries)
        hot_charts |= set(v.charts) if v.rule in ("few-boundaries", "chart-handle") else set()
    for b in hot_boundaries:
        vs = seg.boundaries[b].vertices
        hot_edges |= {frozenset(e) for e in pairwise(vs)}
    chart_of = seg.chart_of_triangle
    items: list[tuple[float, list[tuple[float, float]], object, object, float]] = []
    n = SUBDIVISIONS
    front = [f for f, tri in enumerate(mesh.triangles) if view.facing(_normal(mesh.points, tri)) > 0]
    for f in front:
        a, b, c = (mesh.points[i] for i in mesh.triangles[f])
        colour = direction_colour(mesh.labels[f])
        fill = _tint(colour) if chart_of[f] in hot_charts else colour

        def at(i: int, j: int, a=a, b=b, c=c) -> tuple[float, float, float]:
            x, y, z = (a[k] + i / n * (b[k] - a[k]) + j / n * (c[k] - a[k]) for k in range(3))
            return (x, y, z)

        edge_kind: list[tuple[str, float] | None] = []
        for k in range(3):
            d = m.face_start[f] + k
            if chart_of[m.face_of[m.twin[d]]] == chart_of[f]:
                edge_kind.append(None)
            else:
                hot = frozenset((m.origin(d), m.target(d))) in hot_edges
                edge_kind.append((WITNESS_COLOUR, 3.0) if hot else ("black", 1.0))
        for i in range(n):
            for j in range(n - i):
                pieces = [((i, j), (i + 1, j), (i, j + 1))]
                if i + j <= n - 2:
                    pieces.append(((i + 1, j), (i + 1, j + 1), (i, j + 1)))
                for piece in pieces:
                    pts = [at(*ij) for ij in piece]
                    depth = sum(view.depth(p) for p in pts) / 3
                    # An edge in the fill colour hides the seams between the small pieces.
                    items.append((depth, [view.project(p) for p in pts], fill, fill, 0.6))
                # The upright piece next to an edge of the triangle carries that edge's piece.
                sides = []
                if j == 0:
                    sides.append((0, (i, 0), (i + 1, 0)))
                if i + j == n - 1:
                    sides.append((1, (i + 1, j), (i, j + 1)))
                if i == 0:
                    sides.append((2, (0, j + 1), (0, j)))
                for k, p, q in sides:
                    kind = edge_kind[k]
                    if kind is not None:
                        pts = [at(*p), at(*q)]
                        depth = sum(view.depth(x) for x in pts) / 2 + 1e-6
                        colour_k, width = kind
                        items.append((depth, [view.project(x) for x in pts], "none", colour_k, width))
    items.sort(key=lambda item: item[0])
    ax.add_collection(PolyCollection([it[1] for it in items], facecolors=[it[2] for it in items],
                                     edgecolors=[it[3] for it in items], linewidths=[it[4] for it in items],
                                     closed=False))
    if witness is not None and witness.corners:
        visible = {i for f in front for i in mesh.triangles[f]}
        xy = [view.project(mesh.points[seg.corners[c].vertex]) for c in witness.corners
              if seg.corners[c].vertex in visible]
        if xy:
            ax.scatter([p[0] for p in xy], [p[1] for p in xy], s=40, color=WITNESS_COLOUR, zorder=5,
                       edgecolors="white", linewidths=0.8)
    ax.autoscale_view()
    ax.set_aspect("equal")
    ax.axis("off")


def _wrap(text: str, width: int = 110) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width))


def render_segmentation(report, path: str | os.PathLike[str]) -> None:
    """Two opposite views side by side, a legend of the six labels, and the verdict."""
    fig = new_figure(9.0, 4.6)
    axes = fig.subplots(1, 2)
    for ax, view in zip(axes, VIEWS, strict=True):
        draw_segmentation(ax, report, view)
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
