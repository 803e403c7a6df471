"""Labelled segmentations: does a polycube realise these charts with these labels?

The paper's introduction: local criteria accept labelled segmentations that no polycube
realises (Sokolov's ramp).  :func:`check_segmentation` reports both:

- the local criteria (:mod:`polyloops.segmentation.local`), each necessary;
- the global test (:mod:`polyloops.segmentation.levels`): directions for the boundaries that
  satisfy every corner and keep the level graphs acyclic, or a witness that none exist;
- when the global test passes, a polycube built from those directions
  (:mod:`polyloops.segmentation.realise`), checked with Definition 1.

The verdict is ``True`` when a polycube was built and checked, ``False`` when a necessary
condition fails, and ``None`` (undecided) when the conditions pass but the construction
does not succeed.

>>> from polyloops.io.examples import load_example
>>> from polyloops.surface.construct import labelled_mesh_from_polycube
>>> report = check_segmentation(labelled_mesh_from_polycube(load_example("l-shape")))
>>> report.valid, len(report.segmentation.charts), report.polycube.map.num_corners > 0
(True, 8, True)
"""

from __future__ import annotations

from dataclasses import dataclass

from polyloops.core.polycube import Polycube
from polyloops.segmentation.charts import Boundary, Chart, Corner, Segmentation, segment
from polyloops.segmentation.levels import GlobalResult, Witness, check_global
from polyloops.segmentation.local import LocalResult, LocalViolation, check_local
from polyloops.segmentation.realise import Realisation, realise
from polyloops.surface.mesh import LabelledMesh

__all__ = ["Boundary", "Chart", "Corner", "GlobalResult", "LocalResult", "LocalViolation", "Realisation",
           "Segmentation", "SegmentationReport", "Witness", "check_global", "check_local",
           "check_segmentation", "realise", "segment"]


@dataclass(frozen=True)
class SegmentationReport:
    """The verdict on a labelled mesh: its segmentation, the local and global results, and a realising
    polycube."""

    segmentation: Segmentation
    local: LocalResult
    global_: GlobalResult
    realisation: Realisation | None

    @property
    def polycube(self) -> Polycube | None:
        """The polycube that realises the labels, when one was built."""
        return None if self.realisation is None else self.realisation.polycube

    @property
    def valid(self) -> bool | None:
        """``True`` valid, ``False`` invalid (with a witness), ``None`` undecided."""
        if not self.local.valid or self.global_.valid is False:
            return False
        if self.polycube is not None:
            return True
        return None

    @property
    def reason(self) -> str:
        """Why the verdict is undecided (empty otherwise)."""
        if self.valid is not None:
            return ""
        if self.global_.valid is None:
            return self.global_.reason
        assert self.realisation is not None
        return self.realisation.reason

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict of the verdict (the segmentation command's --json)."""
        seg = self.segmentation
        out: dict[str, object] = {
            "valid": self.valid, "local": self.local.to_json(), "global": self.global_.to_json(seg),
            "charts": len(seg.charts), "boundaries": len(seg.boundaries), "corners": len(seg.corners)}
        if self.valid is None:
            out["undecided"] = self.reason
        if self.polycube is not None:
            out["polycube"] = {"corners": self.polycube.map.num_corners, "faces": self.polycube.map.num_faces}
        return out


def check_segmentation(mesh: LabelledMesh) -> SegmentationReport:
    """Local criteria, global test and, when it passes, a checked polycube; raises
    ``MapError`` when the triangles are not a closed, connected, oriented surface."""
    seg = segment(mesh)
    local = check_local(seg)
    result = check_global(seg)
    realisation = realise(seg, result) if result.valid else None
    return SegmentationReport(seg, local, result, realisation)
