"""Repair of a labelling by local moves, until the checker finds it valid.

The graph-cut labelling of a smooth mesh is often invalid for a few local reasons the checker
names (:mod:`polyloops.segmentation.local`), and each has a local remedy:

- *a boundary between opposite labels* (a thin part's two sides meeting, such as a fin's
  ``+X`` and ``-X``): the triangles of the smaller chart along it take, each, the direction
  perpendicular to both that it faces most, so a strip of the third and fourth directions
  comes between, as a polycube has round a thin plate;
- *a chart with fewer than four boundaries, a closed boundary, a handle, or a corner no
  polycube has*: the smaller chart concerned joins a chart beside it, the one whose label its
  triangles face best (a speck, an island, a bump's top).

Each round makes every remedy the checker's report asks for, at most one per chart, the smallest
charts first; rounds repeat while the report names local violations, at most :data:`ROUNDS`.
Where that fails, the repair starts again from the labelling given with strips that take, where
they can, the labels of the charts that meet the boundary at its ends (a thin part's rim
continued rather than a new chart made beside it).
What comes out is returned only when the checker finds it valid (so a global violation, such as
a level graph with a cycle, ends the repair with nothing): the repair is a heuristic, and the
checker its judge.

>>> from polyloops.shapes.meshes import ellipsoid
>>> from polyloops.segment.labellings import graphcut_labels
>>> from polyloops.segment.surface import surface_of
>>> s = surface_of(*ellipsoid(1.0, 0.6, 0.05, level=3))  # a thin plate: +Z meets -Z at the rim
>>> done = repair_labels(s, graphcut_labels(s))
>>> done is not None and done.report.valid, done.rounds
(True, 1)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from polyloops.core.directions import Direction
from polyloops.segment.labellings import DIRECTION_VECTORS
from polyloops.segment.polish import Fans
from polyloops.segment.surface import Surface
from polyloops.segmentation import SegmentationReport, check_segmentation
from polyloops.segmentation.charts import Boundary, Segmentation
from polyloops.segmentation.local import LocalViolation

__all__ = ["ROUNDS", "Repaired", "repair_labels"]

ROUNDS = 8  # rounds of remedies before giving up (the successes on the shared meshes took 1 to 4)
JOINS = frozenset({"few-boundaries", "closed-boundary", "chart-handle", "corner"})


@dataclass(frozen=True)
class Repaired:
    """A valid labelling made from another: its ``labels``, the checker's ``report`` on them,
    the ``rounds`` of remedies it took, and the ``charts`` changed (joined or cut a strip)."""

    labels: tuple[Direction, ...]
    report: SegmentationReport
    rounds: int
    charts: int


def repair_labels(surface: Surface, labels: Sequence[Direction], rounds: int = ROUNDS) -> Repaired | None:
    """``labels`` (one per triangle of ``surface``) repaired by the local remedies of the module
    docstring until the checker finds them valid, or ``None`` when it does not within
    ``rounds`` rounds, or a round has nothing to remedy (a valid labelling is returned as it
    is, after 0 rounds).  Strips between opposite labels take the directions their triangles
    face best; where that fails, the repair starts again with strips that take, where they
    can, the labels of the charts at the boundary's ends (:func:`_ends`)."""
    lab = np.array([int(d) for d in labels], dtype=np.int64)
    given = check_segmentation(surface.labelled(list(labels)))  # where both strategies start
    worth = (surface.normals @ DIRECTION_VECTORS.T) * surface.areas[:, None]
    fans = Fans(surface.triangles)
    for ends in (False, True):
        done = _rounds(surface, lab.copy(), given, rounds, worth, fans, ends)
        if done is not None or given.valid is True or not given.local.violations:
            return done
    return None


def _rounds(surface: Surface, lab: np.ndarray, given: SegmentationReport, rounds: int, worth: np.ndarray,
            fans: Fans, ends: bool) -> Repaired | None:
    """Rounds of remedies from ``lab``, whose report is ``given``."""
    changed = 0
    for k in range(rounds + 1):
        report = given if k == 0 else check_segmentation(surface.labelled([Direction(int(d)) for d in lab]))
        if report.valid is True:
            return Repaired(tuple(Direction(int(d)) for d in lab), report, k, changed)
        if k == rounds or not report.local.violations:
            return None
        done = _remedy(surface, report.segmentation, report.local.violations, lab, worth, fans, ends)
        if not done:
            return None
        changed += done
    return None


def _remedy(surface: Surface, seg: Segmentation, violations: Sequence[LocalViolation], lab: np.ndarray,
            worth: np.ndarray, fans: Fans, ends: bool = False) -> int:
    """One round's remedies made on ``lab`` (in place); how many charts they changed.  With
    ``ends``, a strip between opposite labels takes the labels of the charts at the boundary's
    ends where there are such (:func:`_ends`)."""
    chart_of = np.asarray(seg.chart_of_triangle)
    area = np.bincount(chart_of, weights=surface.areas, minlength=len(seg.charts))
    touched: set[int] = set()
    count = 0
    for v in sorted(violations, key=lambda v: min((area[c] for c in v.charts), default=0.0)):
        if not v.charts or touched & set(v.charts):
            continue
        if v.rule == "opposite-labels":
            b = seg.boundaries[v.boundaries[0]]
            small = min((b.left, b.right), key=lambda c: area[c])
            along = np.unique(np.concatenate([fans.fan(u) for u in b.vertices]))
            strip = along[chart_of[along] == small]
            axis = int(seg.charts[small].label) // 2
            across = (_ends(seg, b, axis) if ends else []) or [d for d in range(6) if d // 2 != axis]
            lab[strip] = np.array(across)[np.argmax(worth[strip][:, across], axis=1)]
            touched |= {b.left, b.right}
        elif v.rule in JOINS:
            small = min(v.charts, key=lambda c: area[c])
            mine = np.asarray(seg.charts[small].triangles)
            near = np.unique(np.concatenate([fans.fan(int(u)) for u in np.unique(surface.triangles[mine])]))
            beside = sorted({int(c) for c in chart_of[near]} - {small})
            if not beside:
                continue
            best = max(beside, key=lambda c: (worth[mine, int(seg.charts[c].label)].sum(), -c))
            lab[mine] = int(seg.charts[best].label)
            touched |= {small, best}
        else:
            continue
        count += 1
    return count


def _ends(seg: Segmentation, b: Boundary, axis: int) -> list[int]:
    """The labels across ``axis`` of the charts that meet the boundary ``b`` at its ends: a
    strip of them joins those charts (a thin part's rim, continued) instead of making a new
    chart."""
    charts = {c for k in (b.start, b.end) if k is not None for _, _, c in seg.corners[k].sides}
    return sorted({int(seg.charts[c].label) for c in charts} - {2 * axis, 2 * axis + 1})
