"""Jupyter pictures for the kernel's values, registered from above the kernel.

:mod:`polyloops.core` imports nothing above it, so it cannot draw; importing :mod:`polyloops`
calls :func:`register`, which gives :class:`~polyloops.core.polycube.Polycube` and
:class:`~polyloops.core.structure.LoopStructure` a ``_repr_html_`` (the interactive viewer of
:mod:`polyloops.render.viewer`) and a ``_repr_png_`` (the static picture, which front ends
without HTML show instead).  Each imports plotly or matplotlib only when Jupyter asks (so
``import polyloops`` stays light).
"""

from __future__ import annotations

from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure


def _polycube_png(self: Polycube) -> bytes | None:
    """Jupyter shows a polycube as its picture."""
    from polyloops.render.polycube import png_bytes

    return png_bytes(self)


def _structure_png(self: LoopStructure) -> bytes | None:
    """Jupyter shows an oriented structure as its polycube with loops; ``None`` (text
    instead) when it has none."""
    from polyloops.core.duality import DualityError
    from polyloops.render.polycube import png_bytes

    try:
        return png_bytes(self)
    except DualityError:
        return None


_plotly_sent = False  # whether this process has put plotly.js into a notebook's page yet


def _viewer_html(self: Polycube | LoopStructure) -> str | None:
    """Jupyter shows the interactive viewer; ``None`` (the picture instead) when there is no
    polycube to show or plotly is missing.

    plotly.js (4.8 MB) goes into the first viewer this process shows and defines ``Plotly`` for
    the whole page; later viewers are a few kB each and use it, so a notebook of twenty
    polycubes stays small.  (A notebook reopened with saved outputs has that first output
    too; a kernel restarted sends plotly.js again with its first viewer.)"""
    global _plotly_sent
    from polyloops.core.duality import DualityError
    from polyloops.render.polycube import PictureError

    try:
        from polyloops.render.viewer import viewer_html
    except ImportError:
        return None
    try:
        html = viewer_html(self, full_html=False, plotly_js=not _plotly_sent)
    except (DualityError, PictureError):
        return None
    _plotly_sent = True
    return html


def register() -> None:
    """Give polycubes and loop structures a ``_repr_html_`` and a ``_repr_png_``, so Jupyter
    shows them."""
    Polycube._repr_png_ = _polycube_png  # type: ignore[attr-defined]
    LoopStructure._repr_png_ = _structure_png  # type: ignore[attr-defined]
    Polycube._repr_html_ = _viewer_html  # type: ignore[attr-defined]
    LoopStructure._repr_html_ = _viewer_html  # type: ignore[attr-defined]
