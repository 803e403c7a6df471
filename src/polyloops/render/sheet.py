"""A sheet of small renders with captions: for a list of structures or a catalog directory."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence

from polyloops.io.formats import Structure
from polyloops.render.figure import new_figure, save_figure
from polyloops.render.polycube import THUMBNAIL_SUPERSAMPLE, as_polycube, choose_views, draw_polycube


def render_sheet(items: Sequence[tuple[str, Structure]], path: str | os.PathLike[str],
                 columns: int = 6, cell: float = 2.2) -> None:
    """Draw each structure (one view, with loops) captioned with its label."""
    if not items:
        raise ValueError("nothing to draw")
    columns = max(1, min(columns, len(items)))
    rows = math.ceil(len(items) / columns)
    fig = new_figure(columns * cell, rows * (cell + 0.35))
    for i, (caption, obj) in enumerate(items):
        ax = fig.add_subplot(rows, columns, i + 1)
        q, ls = as_polycube(obj)
        draw_polycube(ax, q, choose_views(q, 1)[0], ls, pixels=int(cell * 100),
                      supersample=THUMBNAIL_SUPERSAMPLE)
        ax.set_title(caption, fontsize=7, family="monospace")
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=1 - 0.35 / (rows * (cell + 0.35)) * 1.2,
                        wspace=0.05, hspace=0.25)
    save_figure(fig, path)
