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
from enum import Enum

import numpy as np

from polyloops.core.directions import Direction
from polyloops.segment.labellings import label_indices
from polyloops.segment.polish import Fans
from polyloops.segment.polish import worth as facing
from polyloops.segment.surface import Surface
from polyloops.segmentation import SegmentationReport, check_segmentation
from polyloops.segmentation.charts import Boundary, Segmentation
from polyloops.segmentation.local import LocalViolation

__all__ = ["ROUNDS", "Repaired", "Way", "repair_labels"]

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
    lab = label_indices(labels)
    given = check_segmentation(surface.labelled(list(labels)))  # where both strategies start
    worth = facing(surface)  # per triangle and direction, its area times n . d
    fans = Fans(surface.triangles)
    for way in Way:
        done = _rounds(surface, lab.copy(), given, rounds, worth, fans, way)
        if done is not None or given.valid is True or not given.local.violations:
            return done
    return None


class Way(Enum):
    """The strategies of the repair, tried in turn until one makes the labelling valid."""

    PLAIN = "strips that face best, joins into the chart faced best"
    ENDS = "strips that continue the charts at the boundary's ends"
    CAREFUL = "strips smoothed along the boundary, joins that make no opposite pair, missing sides filled"


def _rounds(surface: Surface, lab: np.ndarray, given: SegmentationReport, rounds: int, worth: np.ndarray,
            fans: Fans, way: Way) -> Repaired | None:
    """Rounds of remedies from ``lab``, whose report is ``given``."""
    changed = 0
    for k in range(rounds + 1):
        report = given if k == 0 else check_segmentation(surface.labelled([Direction(int(d)) for d in lab]))
        if report.valid is True:
            return Repaired(tuple(Direction(int(d)) for d in lab), report, k, changed)
        if k == rounds or not report.local.violations:
            return None
        if way is Way.CAREFUL:
            done = _careful(surface, report.segmentation, report.local.violations, lab, worth, fans)
        else:
            done = _remedy(surface, report.segmentation, report.local.violations, lab, worth, fans,
                           way is Way.ENDS)
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
            b, strip, axis = _strip(seg, v, area, chart_of, fans)
            across = (_ends(seg, b, axis) if ends else []) or [d for d in range(6) if d // 2 != axis]
            lab[strip] = np.array(across)[np.argmax(worth[strip][:, across], axis=1)]
            touched |= {b.left, b.right}
        elif v.rule in JOINS:
            small = min(v.charts, key=lambda c: area[c])
            mine, beside = _beside(surface, seg, chart_of, small, fans)
            if not beside:
                continue
            best = max(beside, key=lambda c: (worth[mine, int(seg.charts[c].label)].sum(), -c))
            lab[mine] = int(seg.charts[best].label)
            touched |= {small, best}
        else:
            continue
        count += 1
    return count


def _strip(seg: Segmentation, v: LocalViolation, area: np.ndarray, chart_of: np.ndarray, fans: Fans
           ) -> tuple[Boundary, np.ndarray, int]:
    """For a boundary between opposite labels (``v``): the boundary, the triangles of its
    smaller chart that touch it (the strip that takes other labels), and that chart's axis."""
    b = seg.boundaries[v.boundaries[0]]
    small = min((b.left, b.right), key=lambda c: area[c])
    along = np.unique(np.concatenate([fans.fan(u) for u in b.vertices]))
    return b, along[chart_of[along] == small], int(seg.charts[small].label) // 2


def _beside(surface: Surface, seg: Segmentation, chart_of: np.ndarray, chart: int, fans: Fans
            ) -> tuple[np.ndarray, list[int]]:
    """The triangles of ``chart``, and the other charts that share a vertex with it, in order:
    the charts a join may merge it into."""
    mine = np.asarray(seg.charts[chart].triangles)
    near = np.unique(np.concatenate([fans.fan(int(u)) for u in np.unique(surface.triangles[mine])]))
    return mine, sorted({int(c) for c in chart_of[near]} - {chart})


def _ends(seg: Segmentation, b: Boundary, axis: int) -> list[int]:
    """The labels across ``axis`` of the charts that meet the boundary ``b`` at its ends: a
    strip of them joins those charts (a thin part's rim, continued) instead of making a new
    chart."""
    charts = {c for k in (b.start, b.end) if k is not None for _, _, c in seg.corners[k].sides}
    return sorted({int(seg.charts[c].label) for c in charts} - {2 * axis, 2 * axis + 1})


# the careful strategy (Way.CAREFUL)
SWITCH = 8.0  # a strip's price for each change of label along its boundary, in its mean triangle areas
FILL = 0.002  # of the fidelity: a chart whose join would lose more has its missing side filled instead


def _careful(surface: Surface, seg: Segmentation, violations: Sequence[LocalViolation], lab: np.ndarray,
             worth: np.ndarray, fans: Fans) -> int:
    """One round of the careful strategy on ``lab`` (in place); how many remedies it made.

    Every boundary between opposite labels gets its strip first (smallest charts first), each
    strip labelled along its boundary by :func:`_smoothed`.  Then each chart named by another
    rule joins a chart beside it of another label, one that would meet no chart of the opposite
    label where there is such, the one its triangles face best; but where that join would lose
    more than :data:`FILL` of the fidelity (a large chart), a chart with too few boundaries gets
    its missing sides instead (:func:`_fill`), and a chart that has none to fill waits: the
    cheapest such join is made only in a round with nothing else to do."""
    chart_of = np.asarray(seg.chart_of_triangle)
    area = np.bincount(chart_of, weights=surface.areas, minlength=len(seg.charts))
    total = float(surface.areas.sum())
    touched: set[int] = set()
    count = 0
    waiting: list[tuple[float, np.ndarray, int]] = []
    order = sorted(violations, key=lambda v: (v.rule != "opposite-labels",
                                              min((area[c] for c in v.charts), default=0.0)))
    for v in order:
        if not v.charts or touched & set(v.charts):
            continue
        if v.rule == "opposite-labels":
            b, strip, axis = _strip(seg, v, area, chart_of, fans)
            across = [d for d in range(6) if d // 2 != axis]
            lab[strip] = _smoothed(surface, b, strip, across, lab, worth, fans)
            touched |= {b.left, b.right}
            count += 1
        elif v.rule in JOINS:
            small = min(v.charts, key=lambda c: area[c])
            own = int(seg.charts[small].label)
            mine, near = _beside(surface, seg, chart_of, small, fans)
            beside = [c for c in near if int(seg.charts[c].label) != own]
            if not beside:
                continue
            labels = {int(seg.charts[c].label) for c in beside}
            safe = [c for c in beside if int(seg.charts[c].label) ^ 1 not in labels] or beside
            best = max(safe, key=lambda c: (worth[mine, int(seg.charts[c].label)].sum(), -c))
            into = int(seg.charts[best].label)
            loss = float(worth[mine, own].sum() - worth[mine, into].sum())
            if loss > FILL * total:
                filled = _fill(surface, seg, small, mine, lab, fans) if v.rule == "few-boundaries" else 0
                if filled:
                    touched.add(small)
                    count += 1
                else:
                    waiting.append((loss, mine, into))
                continue
            lab[mine] = into
            touched |= {small, best}
            count += 1
    if not count and waiting:
        _, mine, into = min(waiting, key=lambda w: w[0])
        lab[mine] = into
        count = 1
    return count


def _smoothed(surface: Surface, b: Boundary, strip: np.ndarray, across: list[int], lab: np.ndarray,
              worth: np.ndarray, fans: Fans) -> np.ndarray:
    """Labels for the ``strip`` of triangles along boundary ``b``, among ``across``: each
    triangle placed at the first of its vertices along ``b``, the labels along ``b`` chosen by a
    dynamic programme that weighs what the triangles face (:data:`SWITCH` times their mean area
    for each change of label), a label opposite to a triangle's neighbour outside the strip
    refused, so that the strip's charts run along the boundary and make no new opposite pair."""
    index = {int(u): k for k, u in enumerate(b.vertices)}
    place = np.array([min(index.get(int(u), len(index)) for u in surface.triangles[t]) for t in strip])
    switch = SWITCH * float(surface.areas[strip].mean())
    value = worth[strip][:, across].copy()
    inside = np.zeros(len(lab), dtype=bool)
    inside[strip] = True
    for i, t in enumerate(strip.tolist()):
        for u in fans.across[t]:
            if not inside[u]:  # refused: four changes of label cost less
                value[i, [j for j, d in enumerate(across) if d == int(lab[u]) ^ 1]] -= 4 * switch
    cost = np.zeros((len(index) + 1, len(across)))
    np.add.at(cost, place, -value)
    return np.asarray(across)[_cheapest_run(cost, switch)[place]]


def _cheapest_run(cost: np.ndarray, switch: float) -> np.ndarray:
    """Per position (row of ``cost``, positions x labels), the label of the sequence whose
    costs plus ``switch`` for each change between neighbouring positions are least (Viterbi:
    O(positions x labels)).

    >>> _cheapest_run(np.array([[0.0, 1.0], [0.6, 0.0], [0.0, 1.0]]), 1.0).tolist()
    [0, 0, 0]
    """
    n, k = cost.shape
    best = cost[0].copy()
    back = np.zeros((n, k), dtype=np.int64)
    for i in range(1, n):
        j = int(best.argmin())
        stay = best <= best[j] + switch
        back[i] = np.where(stay, np.arange(k), j)
        best = np.where(stay, best, best[j] + switch) + cost[i]
    choice = np.zeros(n, dtype=np.int64)
    choice[-1] = int(best.argmin())
    for i in range(n - 1, 0, -1):
        choice[i - 1] = back[i, choice[i]]
    return choice


def _fill(surface: Surface, seg: Segmentation, chart: int, mine: np.ndarray, lab: np.ndarray,
          fans: Fans) -> int:
    """Missing sides given to ``chart``: where two neighbours of opposite labels follow each
    other round it (a side of the third axis missing between them, as at the tail of a
    fuselage whose top meets its side round the end), the triangles round the corner between
    them take the third axis's label towards the side of the chart that corner lies on.  How
    many sides it filled."""
    axis = int(seg.charts[chart].label) // 2
    centre = (surface.points[surface.triangles[mine]].mean(axis=1) * surface.areas[mine, None]).sum(axis=0)
    centre /= surface.areas[mine].sum()
    filled = 0
    for cycle in seg.charts[chart].cycles:
        if len(cycle) < 2:
            continue
        others = [int(seg.charts[seg.boundaries[b].right if seg.boundaries[b].left == chart
                                 else seg.boundaries[b].left].label) for b, _ in cycle]
        for i, (b, forward) in enumerate(cycle):
            here, there = others[i], others[(i + 1) % len(cycle)]
            corner = seg.boundaries[b].end if forward else seg.boundaries[b].start
            if here ^ 1 != there or here // 2 == axis or corner is None:
                continue
            third = 3 - axis - here // 2
            vertex = seg.corners[corner].vertex
            fan = np.asarray(fans.fan(vertex))
            lab[fan] = 2 * third + (0 if surface.points[vertex, third] >= centre[third] else 1)
            filled += 1
    return filled
