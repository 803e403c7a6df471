"""The sheet of all corner configurations, grouped by category (the paper's figure of all
unique corners)."""

from __future__ import annotations

import os
from typing import Any

from matplotlib.patches import Polygon

from polyloops.core.corners import CATEGORIES, CornerConfig, corner_configurations
from polyloops.render.colours import direction_colour
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.projection import View

FRONT, BACK = "#dcdcdc", "#8c8c8c"


def _cross(a: tuple[int, int, int], b: tuple[int, int, int]) -> tuple[int, int, int]:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def draw_corner(ax, config: CornerConfig, view: View) -> None:
    """The corner's edges as coloured rays and the quarter faces between consecutive edges,
    light where their outside faces the viewer and dark where their inside does."""
    dirs = config.directions
    items: list[tuple[float, str, Any, Any]] = []
    for i, d in enumerate(dirs):
        e = dirs[(i + 1) % len(dirs)]
        a, b = d.vector, e.vector
        quad = [(0, 0, 0), a, tuple(x + y for x, y in zip(a, b, strict=True)), b]
        normal = _cross(a, b)  # outward: the directions turn counter-clockwise seen from outside
        centre = [sum(p[k] for p in quad) / 4 for k in range(3)]
        items.append((view.depth(centre), "face", quad, normal))
    for d in dirs:
        items.append((view.depth([0.5 * x for x in d.vector]) + 0.01, "edge", d, None))
    for _, kind, obj, normal in sorted(items, key=lambda t: t[0]):
        if kind == "face":
            pts = [view.project(p) for p in obj]
            colour = FRONT if view.facing(normal) > 0 else BACK
            ax.add_patch(Polygon(pts, closed=True, facecolor=colour, edgecolor="white", lw=0.5, alpha=0.9))
        else:
            x, y = view.project(obj.vector)
            ax.plot([0, x], [0, y], color=direction_colour(obj), lw=2.5, solid_capstyle="round")
    ax.plot([0], [0], "o", color="black", ms=2.5)
    ax.set_xlim(-1.25, 1.25)
    ax.set_ylim(-1.25, 1.25)
    ax.set_aspect("equal")
    ax.axis("off")


def corner_sheet(path: str | os.PathLike[str], columns: int = 16) -> None:
    """Draw every configuration, one row block per category, captioned with its id."""
    configs = corner_configurations()
    rows_per = {cat: -(-sum(c.category == cat for c in configs) // columns) for cat in CATEGORIES}
    total_rows = sum(rows_per.values())
    cell = 1.3
    fig = new_figure(columns * cell, (total_rows + 0.45 * len(CATEGORIES)) * cell + 0.5)
    heights = []
    for cat in CATEGORIES:
        heights += [0.45] + [1.0] * rows_per[cat]
    gs = fig.add_gridspec(len(heights), columns, height_ratios=heights, hspace=0.25, wspace=0.0,
                          left=0.005, right=0.995, bottom=0.005, top=1 - 0.5 / fig.get_figheight())
    fig.text(0.005, 1 - 0.2 / fig.get_figheight(),
             "All 126 polycube corners.  Edges: X purple, Y orange, Z green (+ dark, - light).  "
             "Faces: light where the outside faces you, dark where the inside does.",
             fontsize=11, va="center")
    view = View()
    row = 0
    for cat in CATEGORIES:
        members = [c for c in configs if c.category == cat]
        title = fig.add_subplot(gs[row, :])
        title.axis("off")
        title.text(0.0, 0.1, f"{cat} ({len(members)})", fontsize=12, weight="bold",
                   transform=title.transAxes)
        row += 1
        for i, c in enumerate(members):
            ax = fig.add_subplot(gs[row + i // columns, i % columns])
            draw_corner(ax, c, view)
            ax.set_title(f"#{c.id}", fontsize=8, pad=0)
        row += rows_per[cat]
    save_figure(fig, path)
