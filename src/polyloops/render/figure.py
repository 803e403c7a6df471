"""Saving matplotlib figures: headless, deterministic, atomic."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from matplotlib.figure import Figure

from polyloops.core.files import replace_atomic

FORMATS = {".png": "png", ".svg": "svg"}


def new_figure(width: float, height: float) -> Figure:
    """A figure not registered with pyplot, so nothing leaks between calls."""
    return Figure(figsize=(width, height), dpi=100)


def save_figure(fig: Figure, path: str | os.PathLike[str]) -> None:
    """Write PNG or SVG by the file's ending, through a temporary file and a rename.

    Metadata that would change from run to run (dates, software versions) is
    left out, so a fixed input gives a byte-identical file.
    """
    target = Path(path)
    fmt = FORMATS.get(target.suffix.lower())
    if fmt is None:
        raise ValueError(f"{target}: pictures are written as .png or .svg")
    metadata = {"Software": None} if fmt == "png" else {"Date": None, "Creator": None}
    fd, tmp = tempfile.mkstemp(dir=target.parent or ".", prefix=f".{target.name}.", suffix=".tmp")
    os.close(fd)
    try:
        if fmt == "svg":
            import matplotlib as mpl

            with mpl.rc_context({"svg.hashsalt": "polyloops"}):
                fig.savefig(tmp, format=fmt, metadata=metadata)
        else:
            fig.savefig(tmp, format=fmt, metadata=metadata)
        replace_atomic(tmp, target)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
