"""Jupyter pictures for the kernel's values, registered from above the kernel.

:mod:`polyloops.core` imports nothing above it, so it cannot draw; importing :mod:`polyloops`
calls :func:`register`, which gives :class:`~polyloops.core.polycube.Polycube` and
:class:`~polyloops.core.structure.LoopStructure` a ``_repr_png_`` that imports matplotlib only
when Jupyter asks for a picture (so ``import polyloops`` stays light).
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


def register() -> None:
    """Give polycubes and loop structures a ``_repr_png_``, so Jupyter draws them."""
    Polycube._repr_png_ = _polycube_png  # type: ignore[attr-defined]
    LoopStructure._repr_png_ = _structure_png  # type: ignore[attr-defined]
