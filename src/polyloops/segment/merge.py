"""Coarser certified labellings: whole charts relabelled as a neighbour, so that they merge.

A labelling's charts can often be fewer for a little fidelity: a small chart between two of
one label (a step the normals barely ask for) relabelled as they are merges the three.  Which
merges keep a labelling valid is the checker's to say, so each is checked
(:func:`~polyloops.segmentation.check_segmentation`), and only certified ones are returned.

The merges are greedy: at each step, of the charts relabelled as a chart beside them, the most
faithful labellings come first, and the first one the checker finds valid is the step; the next
step starts from it.  Relabelling chart ``c`` as ``L`` merges it with the ``k`` charts of label
``L`` beside it, leaving ``k`` fewer charts, and changes the fidelity by the area-weighted
``n . L - n . label`` over ``c`` alone, so both are known before any check.  A step may be
more faithful than the labelling before it (a chart whose neighbour's label suits its triangles
better: a search's result is not always at its most faithful), as faithful (a face at 45
degrees between two axes) or less; ``least`` stops the merges where no fewer loops could pay
for the fidelity lost (:func:`polyloops.segment.run.segment_surface` passes the fidelity less
the loops' price times the loops, or less a loss it allows, and the floor).

>>> from polyloops.shapes.meshes import ellipsoid
>>> from polyloops.segment.surface import surface_of
>>> from polyloops.segment.labellings import naive_label_indices
>>> s = surface_of(*ellipsoid(2, 1, 0.7, level=3))
>>> merges(s, naive_label_indices(s), least=0.0)   # the box's six charts merge into nothing valid
()
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from polyloops.core.directions import Direction
from polyloops.segment.labellings import DIRECTION_VECTORS, chart_indices
from polyloops.segment.surface import Surface
from polyloops.segmentation import SegmentationReport, check_segmentation

__all__ = ["Merge", "merge_options", "merges"]

CHECKS = 24  # of the merges of one step, the most faithful ones checked before giving up


@dataclass(frozen=True, eq=False)
class Merge:
    """One certified step: the labels (direction indices per triangle), their charts and
    fidelity, and the checker's report (valid, with the realising polycube)."""

    labels: np.ndarray
    charts: int
    fidelity: float
    report: SegmentationReport


def merge_options(surface: Surface, labels: np.ndarray, target: np.ndarray | None = None,
                  chart: np.ndarray | None = None) -> list[tuple[float, int, int, int]]:
    """Every chart relabelled as a chart beside it: ``(fidelity, charts, chart, label)`` after
    the merge, the most faithful first (then the fewest charts), unchecked; with ``target`` (a
    unit vector per triangle, such as a guide's labels) the agreement with it instead of the
    fidelity (as :func:`~polyloops.segment.labellings.fidelity`).  ``chart``: the labels'
    :func:`~polyloops.segment.labellings.chart_indices`, when the caller has them.

    >>> import numpy as np
    >>> from polyloops.shapes.meshes import ellipsoid
    >>> from polyloops.segment.surface import surface_of
    >>> from polyloops.segment.labellings import naive_label_indices, fidelity
    >>> s = surface_of(*ellipsoid(2, 1, 0.7, level=3))
    >>> options = merge_options(s, naive_label_indices(s))
    >>> len(options), {charts for _, charts, _, _ in options}   # 6 charts, 4 neighbours each
    (24, {5})
    """
    labels = np.asarray(labels, dtype=np.int64)
    chart = chart_indices(surface, labels) if chart is None else chart
    n = int(chart.max()) + 1
    wanted = surface.normals if target is None else target
    weighted = surface.areas[:, None] * (wanted @ DIRECTION_VECTORS.T)  # per triangle and label
    total = float(surface.areas.sum())
    rows = np.arange(len(labels))
    now = float(weighted[rows, labels].sum()) / total
    own = np.bincount(chart, weights=weighted[rows, labels], minlength=n)
    as_label = np.zeros((n, 6))
    np.add.at(as_label, chart, weighted)
    # the charts beside each chart, and their labels
    pairs, _ = surface.adjacency
    a, b = chart[pairs[:, 0]], chart[pairs[:, 1]]
    apart = a != b
    touching = np.unique(np.concatenate([np.stack([a[apart], b[apart]], axis=1),
                                         np.stack([b[apart], a[apart]], axis=1)]), axis=0)
    label_of = np.zeros(n, dtype=np.int64)
    label_of[chart] = labels
    out = []
    for c in range(n):
        beside = touching[touching[:, 0] == c, 1]
        for label in sorted(set(label_of[beside].tolist()) - {int(label_of[c])}):
            k = int((label_of[beside] == label).sum())
            after = now + float(as_label[c, label] - own[c]) / total
            out.append((after, n - k, c, label))
    out.sort(key=lambda o: (-o[0], o[1], o[2], o[3]))
    return out


def merges(surface: Surface, labels: np.ndarray, least: float, steps: int = 6,
           deadline: float | None = None, target: np.ndarray | None = None) -> tuple[Merge, ...]:
    """The certified merges from ``labels``, step by step (each from the one before, at most
    ``steps``), none less faithful than ``least`` (with ``target``: agreeing less with it, see
    :func:`merge_options`; ``fidelity`` is then that agreement); checking stops at
    ``deadline`` (``time.monotonic()``) and after :data:`CHECKS` invalid merges in one step."""
    found: list[Merge] = []
    current = np.asarray(labels, dtype=np.int64)
    for _ in range(steps):
        chart = chart_indices(surface, current)
        step = None
        for checked, (after, charts, c, label) in enumerate(merge_options(surface, current, target, chart)):
            if after < least or checked >= CHECKS or (deadline is not None and time.monotonic() > deadline):
                break
            trial = current.copy()
            trial[chart == c] = label
            report = check_segmentation(surface.labelled(tuple(Direction(int(k)) for k in trial)))
            if report.valid is True and report.polycube is not None:
                step = Merge(trial, charts, after, report)
                break
        if step is None:
            break
        found.append(step)
        current = step.labels
    return tuple(found)
