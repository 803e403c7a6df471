"""Checkers for the paper's definitions; each returns a :class:`Report` of every violation.

What lives here: Definition 1 (:mod:`~polyloops.verify.definition1`), the surface checks
(:mod:`~polyloops.verify.surface`), Definitions 3 and 4
(:mod:`~polyloops.verify.loop_structure`), homology and Theorem 3
(:mod:`~polyloops.verify.homology`), reports with witnesses (:mod:`~polyloops.verify.report`)
and summaries (:mod:`~polyloops.verify.describe`).  It imports the kernel and ``io`` only.

>>> from polyloops.io.examples import load_example
>>> verify(load_example("ring")).valid
True
>>> [str(v.condition) for v in verify(load_example("degree-two")).violations][:1]
['2']
"""

from __future__ import annotations

from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import FaceListError, MapError
from polyloops.core.loops import OddFaceError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.io.formats import Document, Structure
from polyloops.verify.definition1 import POLYGONS, check_polycube, check_polycube_faces
from polyloops.verify.loop_structure import (
    GenusBalance,
    check_polycube_loop_structure,
    check_quad_loop_structure,
    check_theorem3,
    genus_balance,
)
from polyloops.verify.report import Check, Condition, Kind, Report, ReportBuilder, Source, Status, Violation
from polyloops.verify.surface import add_surface_checks

__all__ = [
    "Check", "Condition", "GenusBalance", "Kind", "NeedsSidesError", "NotAPolycubeError", "Report",
    "Source", "Status", "Violation", "as_loop_structure", "check_polycube", "check_polycube_faces",
    "check_polycube_loop_structure", "check_quad_loop_structure", "check_theorem3",
    "genus_balance", "verify", "verify_document",
]


def verify(obj: Structure) -> Report:
    """Check a structure against the paper: Definition 1 for a polycube; Definitions 3 and 4 for a
    loop structure, and Theorem 3 when Definition 4 holds.

    Parameters
    ----------
    obj:
        A polycube or a loop structure (a labelled one is checked as far as labels allow:
        Conditions 3 and 5 need sides).

    Returns
    -------
    Report
        Every condition with its status, every violation with a witness; ``valid`` when there
        is none.

    Notes
    -----
    Nothing is raised: a polycube whose faces are not axis-aligned rectangles is reported.

    >>> from polyloops.io.examples import load_example
    >>> verify(load_example("ring")).valid
    True
    >>> [str(v.condition) for v in verify(load_example("torus-cycle")).violations]
    ['5', '5']
    """
    if isinstance(obj, Polycube):
        return check_polycube(obj)
    report = check_quad_loop_structure(obj) + check_polycube_loop_structure(obj)
    if report.valid and obj.oriented:
        report = report + check_theorem3(obj)
    return report


def verify_document(doc: Document) -> Report:
    """Like :func:`verify`, for a parsed file: a face list that is not a closed oriented surface
    gives a report of its surface violations instead of an exception.

    Parameters
    ----------
    doc:
        A parsed document (:func:`polyloops.io.formats.parse_document`).

    Returns
    -------
    Report

    Raises
    ------
    LabelError
        When the edge labels do not fit the faces (a file error, not a finding).

    >>> from polyloops.io.formats import parse_document
    >>> doc = parse_document('{"polyloops": 1, "kind": "loop-structure", '
    ...                      '"faces": [[0, 1, 2, 3]], "edges": []}')
    >>> report = verify_document(doc)
    >>> report.valid, sorted({str(v.condition) for v in report.violations})
    (False, ['closed'])
    """
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


class NotAPolycubeError(PolyloopsError, ValueError):
    """A structure that fails its definition where a valid one is needed; ``report`` has
    every violation."""

    def __init__(self, message: str, report: Report):
        super().__init__(message)
        self.report = report


class NeedsSidesError(PolyloopsError, ValueError):
    """A labelled loop structure (no sides) where an oriented one is needed."""


def as_loop_structure(obj: Structure, *, oriented: bool = False, valid: bool = False) -> LoopStructure:
    """``obj`` as a loop structure: a polycube must satisfy Definition 1 and is dualized.

    Parameters
    ----------
    obj:
        A :class:`~polyloops.core.polycube.Polycube` or a
        :class:`~polyloops.core.structure.LoopStructure`.
    oriented:
        Refuse a labelled structure without sides.
    valid:
        Require a polycube loop structure (Definition 4); implies ``oriented``.

    Returns
    -------
    LoopStructure

    Raises
    ------
    NotAPolycubeError
        When Definition 1 (for a polycube) or, with ``valid``, Definition 4 fails; the message
        names the first violation.
    NeedsSidesError
        When sides are needed and ``obj`` has none.

    >>> from polyloops.io.examples import load_example
    >>> as_loop_structure(load_example("l-shape"), valid=True).map.num_corners
    16
    >>> as_loop_structure(load_example("torus-cycle"), valid=True)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    polyloops.verify.NotAPolycubeError: not a polycube loop structure: Definition 4 condition 5: ...
    """
    if isinstance(obj, Polycube):
        report = check_polycube(obj)
        if not report.valid:
            raise NotAPolycubeError(f"not a polycube: {report.first_violation()}", report)
        from polyloops.core.duality import dualize

        obj = dualize(obj)
    if (oriented or valid) and not obj.oriented:
        raise NeedsSidesError("is a labelled loop structure without sides; orient it first")
    if valid:
        report = verify(obj)
        if not report.valid:
            raise NotAPolycubeError(f"not a polycube loop structure: {report.first_violation()}", report)
    return obj
