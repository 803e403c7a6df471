"""A polycube's own segmentation: each quad cut into two triangles labelled by its normal,
certified by the checker (the polycube realising it is found again, not assumed).

>>> from polyloops.shapes.builders import box
>>> done = certified_from_polycube(box(2, 1, 1))
>>> done.report.valid, len(done.mesh.triangles), len(done.report.segmentation.charts)
(True, 20, 6)
"""

from __future__ import annotations

from dataclasses import dataclass

from polyloops.core.errors import PolyloopsError
from polyloops.core.polycube import Polycube
from polyloops.segmentation import SegmentationReport, check_segmentation
from polyloops.surface.construct import labelled_mesh_from_polycube
from polyloops.surface.mesh import LabelledMesh

__all__ = ["CertifiedSegmentation", "UncertifiedError", "certified_from_polycube"]


class UncertifiedError(PolyloopsError, ValueError):
    """The checker did not pass what a constructor built: nothing is handed out."""


@dataclass(frozen=True)
class CertifiedSegmentation:
    """A labelled mesh and the checker's report on it (valid, with a realising polycube)."""

    mesh: LabelledMesh
    report: SegmentationReport


def certified_from_polycube(q: Polycube) -> CertifiedSegmentation:
    """The labelling of ``q``'s triangulated quads by their normals, with the checker's report.

    Raises
    ------
    UncertifiedError
        When the checker does not find the labelling valid (an inside-out or self-touching
        polycube can give such a labelling); the message says what it found.
    """
    mesh = labelled_mesh_from_polycube(q)
    report = check_segmentation(mesh)
    if report.valid is not True:
        verdict = "invalid" if report.valid is False else "undecided"
        raise UncertifiedError(f"the checker finds this labelling {verdict}: {report.reason}")
    return CertifiedSegmentation(mesh, report)
