"""A sheet of small renders with captions: for a list of structures or a catalog directory.

A PNG sheet is composed directly: each cell's picture (the gallery's thumbnail, drawn by
:func:`polyloops.render.polycube.thumbnail_pixels`, in worker processes on request) is pasted
into one canvas under its caption.  An SVG sheet is a matplotlib figure, so that its captions
stay text.

>>> import tempfile, pathlib
>>> from polyloops.io.examples import load_example
>>> with tempfile.TemporaryDirectory() as tmp:
...     render_sheet([("cube", load_example("cube")), ("L", load_example("l-shape"))],
...                  pathlib.Path(tmp) / "sheet.png")
...     from PIL import Image
...     Image.open(pathlib.Path(tmp) / "sheet.png").size
(440, 255)
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from polyloops.io.files import writing
from polyloops.io.formats import Structure

if TYPE_CHECKING:
    import numpy as np

CAPTION = 35  # pixels of caption band above each picture (0.35 inch at 100 dpi)
FONT_SIZE = 11


def render_sheet(items: Sequence[tuple[str, Structure]], path: str | os.PathLike[str],
                 columns: int = 6, cell: float = 2.2, workers: int = 1,
                 progress: Callable[[], None] | None = None) -> None:
    """Draw each structure (one view, with loops) captioned with its label, ``columns`` to a
    row, each picture ``cell`` inches (100 pixels an inch) square; PNG or SVG by the ending.

    Raises
    ------
    ValueError
        When there is nothing to draw or the ending is neither .png nor .svg.
    DualityError, PictureError
        As :func:`polyloops.render.polycube.render_polycube`.
    OSError
        When the file cannot be written.
    """
    from polyloops.render.figure import picture_format

    if not items:
        raise ValueError("nothing to draw")
    fmt = picture_format(path)
    columns = max(1, min(columns, len(items)))
    pixels = int(cell * 100)
    if fmt == "svg":
        _figure_sheet(items, path, columns, cell, progress)
        return
    from PIL import Image

    from polyloops.parallel import run_jobs

    rows = math.ceil(len(items) / columns)
    canvas = Image.new("RGB", (columns * pixels, rows * (pixels + CAPTION)), (255, 255, 255))
    jobs = [(obj, pixels) for _, obj in items]
    batch = max(1, min(16, len(jobs) // (4 * workers)))
    for i, picture in enumerate(run_jobs(_cell, jobs, workers, batch=batch)):
        r, c = divmod(i, columns)
        canvas.paste(Image.fromarray(picture), (c * pixels, r * (pixels + CAPTION) + CAPTION))
        if progress is not None:
            progress()
    _caption(canvas, [caption for caption, _ in items], columns, pixels)
    with writing(path, suffix=".png") as out:
        canvas.save(out.path, format="png")  # no metadata: a fixed input gives the same bytes


def _cell(job: tuple[Structure, int]) -> np.ndarray:
    """One picture as 8-bit RGB (a job for a worker)."""
    from polyloops.render.polycube import thumbnail_pixels

    obj, pixels = job
    return thumbnail_pixels(obj, pixels)


def _caption(canvas, captions: list[str], columns: int, pixels: int) -> None:
    """Each caption centred in the band above its picture."""
    from matplotlib import font_manager
    from PIL import ImageDraw, ImageFont

    draw = ImageDraw.Draw(canvas)
    font = ImageFont.truetype(font_manager.findfont("DejaVu Sans Mono"), FONT_SIZE)
    for i, caption in enumerate(captions):
        r, c = divmod(i, columns)
        draw.text((c * pixels + pixels / 2, r * (pixels + CAPTION) + CAPTION - 6), caption,
                  fill=(0, 0, 0), font=font, anchor="ms")


def _figure_sheet(items: Sequence[tuple[str, Structure]], path: str | os.PathLike[str], columns: int,
                  cell: float, progress: Callable[[], None] | None) -> None:
    """The SVG sheet: a matplotlib figure, one axes a picture, captions as text."""
    from polyloops.render.figure import new_figure, save_figure
    from polyloops.render.polycube import THUMBNAIL_SUPERSAMPLE, as_polycube, choose_views, draw_polycube

    rows = math.ceil(len(items) / columns)
    fig = new_figure(columns * cell, rows * (cell + 0.35))
    for i, (caption, obj) in enumerate(items):
        ax = fig.add_subplot(rows, columns, i + 1)
        q, ls = as_polycube(obj)
        draw_polycube(ax, q, choose_views(q, 1)[0], ls, pixels=int(cell * 100),
                      supersample=THUMBNAIL_SUPERSAMPLE)
        ax.set_title(caption, fontsize=7, family="monospace")
        if progress is not None:
            progress()
    fig.subplots_adjust(left=0.01, right=0.99, bottom=0.01, top=1 - 0.35 / (rows * (cell + 0.35)) * 1.2,
                        wspace=0.05, hspace=0.25)
    save_figure(fig, path)
