"""The three level graphs side by side: zones as nodes placed by level, loops as arcs."""

from __future__ import annotations

import os
from collections import defaultdict
from typing import Any

import networkx as nx
from matplotlib.patches import FancyArrowPatch

from polyloops.core.directions import Axis
from polyloops.core.duality import DualityError, zone_levels
from polyloops.core.structure import LoopStructure
from polyloops.core.words import plural
from polyloops.render.colours import AXIS_COLOUR, LIGHT_COLOUR
from polyloops.render.figure import new_figure, save_figure


def _positions(ls: LoopStructure, axis: Axis, g: nx.MultiDiGraph) -> dict[int, tuple[float, float]]:
    """Level (longest path from a source, as primalize places zones) upwards; nodes of one
    level spread evenly.  A graph with a cycle has no levels: its nodes go on a circle."""
    try:
        level = zone_levels(ls, axis)
    except DualityError:
        return {k: (float(x), float(y)) for k, (x, y) in nx.circular_layout(g).items()}
    rows: dict[int, list[int]] = defaultdict(list)
    for z in sorted(g.nodes):
        rows[level[z]].append(z)
    pos = {}
    for lev, zs in rows.items():
        for i, z in enumerate(zs):
            pos[z] = (i - (len(zs) - 1) / 2, float(lev))
    return pos


def draw_level_graph(ax, ls: LoopStructure, axis: Axis, shades: list[str] | None = None) -> None:
    """Draw one level graph on matplotlib axes: zones by level, arcs by loop id; with
    ``shades``, each zone's node filled with its shade in the picture of the zones."""
    g = ls.level_graph(axis)
    pos = _positions(ls, axis, g)
    seen: dict[tuple[int, int], int] = defaultdict(int)
    for u, v, loop in sorted(g.edges(keys=True)):
        pair = (min(u, v), max(u, v))
        k = seen[pair]
        seen[pair] += 1
        style: dict[str, Any] = dict(arrowstyle="-|>", mutation_scale=14, color=AXIS_COLOUR[axis], lw=1.6)
        if u == v:  # a self-loop (an invalid structure): a small arc above the node, stacked
            (x, y), lift = pos[u], 0.25 * k
            arrow = FancyArrowPatch((x + 0.12, y + 0.1 + lift), (x - 0.12, y + 0.1 + lift),
                                    connectionstyle="arc3,rad=2.2", shrinkA=0, shrinkB=0, **style)
            ax.add_patch(arrow)
            ax.text(x + 0.3, y + 0.35 + lift, str(loop), fontsize=7, color=AXIS_COLOUR[axis])
            continue
        rad = 0.0 if k == 0 else (0.35 * ((k + 1) // 2)) * (1 if k % 2 else -1)
        arrow = FancyArrowPatch(pos[u], pos[v], connectionstyle=f"arc3,rad={rad}", shrinkA=11, shrinkB=11,
                                **style)
        ax.add_patch(arrow)
        mx, my = (pos[u][0] + pos[v][0]) / 2, (pos[u][1] + pos[v][1]) / 2
        ax.text(mx + 0.12 + rad * 0.4, my, str(loop), fontsize=7, color=AXIS_COLOUR[axis])
    for z, (x, y) in pos.items():
        fill = LIGHT_COLOUR[axis] if shades is None else shades[z]
        ax.plot([x], [y], "o", ms=16, color=fill, markeredgecolor=AXIS_COLOUR[axis])
        ax.text(x, y, str(z), ha="center", va="center", fontsize=8)
    xs = [p[0] for p in pos.values()] or [0.0]
    ys = [p[1] for p in pos.values()] or [0.0]
    ax.set_xlim(min(xs) - 1, max(xs) + 1)
    ax.set_ylim(min(ys) - 0.7, max(ys) + 0.7)
    acyclic = nx.is_directed_acyclic_graph(g)
    ax.set_title(f"{axis}-graph: {plural(g.number_of_nodes(), 'zone')}, {plural(g.number_of_edges(), 'loop')}"
                 + ("" if acyclic else " (cycle!)"), fontsize=9, color="black" if acyclic else "red")
    ax.axis("off")


def render_level_graphs(ls: LoopStructure, path: str | os.PathLike[str] | None = None):
    """The X-, Y- and Z-graphs side by side (zones numbered as in ``zones(axis)``, arcs by loop id)."""
    if not ls.oriented:
        raise ValueError("a labelled loop structure has no level graphs; orient it first")
    fig = new_figure(11, 4)
    for i, axis in enumerate(Axis):
        draw_level_graph(fig.add_subplot(1, 3, i + 1), ls, axis)
    fig.subplots_adjust(left=0.02, right=0.98, bottom=0.03, top=0.9, wspace=0.1)
    if path is None:
        return fig
    save_figure(fig, path)
    return None
