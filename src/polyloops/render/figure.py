"""Saving matplotlib figures: headless, deterministic, atomic."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from matplotlib.figure import Figure

from polyloops.io.files import STDIO, writing

FORMATS = {".png": "png", ".svg": "svg"}


def new_figure(width: float, height: float) -> Figure:
    """A figure not registered with pyplot, so nothing leaks between calls."""
    return Figure(figsize=(width, height), dpi=100)


def picture_format(path: str | os.PathLike[str]) -> str:
    """``png`` or ``svg``, by the file's ending; PNG on standard output and on a device or FIFO
    (``-o /dev/null``).  Raises :class:`ValueError` for another ending.

    >>> picture_format("a.SVG"), picture_format("-"), picture_format("/dev/null")
    ('svg', 'png', 'png')
    """
    from polyloops.io.files import OutputError, Sink, resolve_output

    try:
        if os.fspath(path) == STDIO or resolve_output(path).sink is Sink.STREAM:
            return "png"
    except OutputError:
        pass  # the writer says what is wrong with it
    fmt = FORMATS.get(Path(path).suffix.lower())
    if fmt is None:
        raise ValueError(f"{path}: pictures are written as .png or .svg")
    return fmt


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> None:
    """Write PNG or SVG by the file's ending, through :func:`polyloops.io.files.writing`.

    Metadata that would change from run to run (dates, software versions) is
    left out, so a fixed input gives a byte-identical file.
    """
    fmt = picture_format(path)
    metadata = {"Software": None} if fmt == "png" else {"Date": None, "Creator": None}
    with writing(path, suffix=f".{fmt}") as out:
        if fmt == "svg":
            import matplotlib as mpl

            with mpl.rc_context({"svg.hashsalt": "polyloops"}):
                fig.savefig(out.path, format=fmt, metadata=metadata)
        else:
            fig.savefig(out.path, format=fmt, metadata=metadata)
