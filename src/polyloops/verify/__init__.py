"""Checkers for the paper's definitions; each returns a :class:`Report` of every violation.

>>> from polyloops.core.examples import load_example
>>> verify(load_example("ring")).valid
True
>>> [v.condition for v in verify(load_example("degree-two")).violations][:1]
['2']
"""

from __future__ import annotations

from polyloops.core.formats import Document, Structure
from polyloops.core.halfedge import FaceListError, MapError
from polyloops.core.loops import OddFaceError
from polyloops.core.polycube import Polycube
from polyloops.verify.definition1 import POLYGONS, check_polycube, check_polycube_faces
from polyloops.verify.loop_structure import (
    GenusBalance,
    check_polycube_loop_structure,
    check_quad_loop_structure,
    check_theorem3,
    genus_balance,
)
from polyloops.verify.report import Check, Report, ReportBuilder, Violation
from polyloops.verify.surface import add_surface_checks

__all__ = [
    "Check", "GenusBalance", "Report", "Violation", "check_polycube", "check_polycube_faces",
    "check_polycube_loop_structure", "check_quad_loop_structure", "check_theorem3",
    "genus_balance", "verify", "verify_document",
]


def verify(obj: Structure) -> Report:
    """Definition 1 for a polycube; Definitions 3 and 4 for a loop structure, and
    Theorem 3 when Definition 4 holds."""
    if isinstance(obj, Polycube):
        return check_polycube(obj)
    report = check_quad_loop_structure(obj) + check_polycube_loop_structure(obj)
    if report.valid and obj.oriented:
        report = report + check_theorem3(obj)
    return report


def verify_document(doc: Document) -> Report:
    """Like :func:`verify`, but a face list that is not a closed oriented surface gives a
    report of its surface violations instead of an exception.  Label errors still raise."""
    if doc.kind == "polycube":
        assert doc.positions is not None
        return check_polycube_faces(doc.faces, doc.positions)
    try:
        obj = doc.build()
    except MapError as err:
        rb = ReportBuilder("loop-structure", "surface")
        add_surface_checks(rb, err.problems)
        return rb.build()
    except (FaceListError, OddFaceError) as err:
        rb = ReportBuilder("loop-structure", "surface")
        rb.condition("polygons", POLYGONS if isinstance(err, FaceListError) else
                     "every face has an even number of sides, so loops can cross it", [
                         rb.violation("polygons", str(err))])
        return rb.build()
    return verify(obj)
