"""Grafting: patches of other labellings of a mesh moved into a valid labelling of it, one at a
time, each kept only where the checker still finds the labelling valid and the score rises.

A search's segmentation and a repaired labelling are valid but often less faithful than the
graph-cut labellings of the same mesh, which are invalid as a whole for a few local reasons
(a thin part's two sides meeting, an island) while agreeing with the normals almost
everywhere else.  A *patch* of a donor labelling is a connected set of triangles (through
their edges) that the donor labels alike and otherwise than the valid labelling; its *gain*
is the area-weighted ``n . label`` the donor's label adds there (or the agreement with a
target, such as a guide).  The patches are tried best gain first: each is kept when the
checker finds the labelling with it valid and the gain pays for the loops it adds (at
``price`` each, counted on the checker's polycube before and after, so that both sides of the
comparison are counted alike); sweeps repeat while they keep something, until a deadline.
Nothing kept is ever unchecked: the last report is the certificate.

>>> import numpy as np
>>> from polyloops.shapes.meshes import ellipsoid
>>> from polyloops.segment.labellings import fidelity, graphcut_labels
>>> from polyloops.segment.surface import surface_of
>>> s = surface_of(*ellipsoid(2.0, 1.0, 0.7, level=3))
>>> good = np.array([int(d) for d in graphcut_labels(s)])  # valid, and the donor
>>> pairs, _ = s.adjacency
>>> worse = good.copy()  # the +X triangles along the +Y chart labelled +Y: valid, less faithful
>>> worse[pairs[(good[pairs[:, 0]] == 0) & (good[pairs[:, 1]] == 2), 0]] = 2
>>> done = graft_labels(s, [Direction(int(d)) for d in worse], [good], price=0.001)
>>> done.report.valid, done.kept, np.array_equal([int(d) for d in done.labels], good)
(True, 1, True)
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from polyloops.core.directions import Direction
from polyloops.core.duality import dualize
from polyloops.segment.labellings import chart_indices, label_indices
from polyloops.segment.polish import worth
from polyloops.segment.surface import Surface
from polyloops.segmentation import SegmentationReport, check_segmentation

__all__ = ["Grafted", "graft_labels", "patches"]

SWEEPS = 3  # sweeps over the donors' patches (the shared meshes keep little after the second)
LEAST = 1e-4  # of the surface's area times one: a patch gaining less is not tried


@dataclass(frozen=True)
class Grafted:
    """A valid labelling grafted from another: its ``labels``, the checker's ``report`` on
    them, the ``loops`` of the report's polycube (dual loops), the patches ``kept`` of those
    ``tried``, and the score's rise (``gain`` in the aim, fidelity or agreement, less the loops'
    price)."""

    labels: tuple[Direction, ...]
    report: SegmentationReport
    loops: int
    kept: int
    tried: int
    gain: float


def patches(surface: Surface, labels: np.ndarray, donor: np.ndarray, value: np.ndarray
            ) -> list[tuple[float, np.ndarray]]:
    """The donor's patches against ``labels`` (direction indices per triangle) with a positive
    gain of at least :data:`LEAST`, best first: (gain, triangles).  ``value`` is the worth of
    each triangle under each label (triangles x 6)."""
    pairs, _ = surface.adjacency
    differs = labels != donor
    alike = differs[pairs[:, 0]] & differs[pairs[:, 1]] & (donor[pairs[:, 0]] == donor[pairs[:, 1]])
    m = len(labels)
    graph = coo_matrix((np.ones(int(alike.sum())), (pairs[alike, 0], pairs[alike, 1])), shape=(m, m))
    comp = connected_components(graph, directed=False)[1]
    rows = np.arange(m)
    rise = value[rows, donor] - value[rows, labels]
    which = np.flatnonzero(differs)
    gains = np.bincount(comp[which], weights=rise[which], minlength=m)
    least = LEAST * float(surface.areas.sum())
    good = np.flatnonzero(gains > least)
    members = np.argsort(comp[which], kind="stable")
    sorted_comp = comp[which][members]
    out = []
    for c in good[np.argsort(-gains[good], kind="stable")]:
        lo, hi = np.searchsorted(sorted_comp, [c, c + 1])
        out.append((float(gains[c]), which[members[lo:hi]]))
    return out


def graft_labels(surface: Surface, labels: Sequence[Direction], donors: Sequence[np.ndarray],
                 price: float, deadline: float | None = None, target: np.ndarray | None = None,
                 report: SegmentationReport | None = None) -> Grafted:
    """``labels`` (valid; ``report`` the checker's on them, when made already) with the
    patches of the ``donors`` (direction indices per triangle) that keep them valid and raise
    the score, the patches of every donor tried best gain first, in sweeps while one keeps
    something, until ``deadline`` (a :func:`time.monotonic` time; ``None``: no limit).
    ``target``: a unit vector per triangle to agree with instead of the normals.  A patch is
    tried once; one that would be an island (a chart whose only neighbour is one chart) is not
    tried, as no polycube has a face with one neighbour.

    Raises
    ------
    ValueError
        When ``labels`` are not valid.
    """
    value = worth(surface, target)
    area = float(surface.areas.sum())
    least = LEAST * area
    lab = label_indices(labels)
    report = check_segmentation(surface.labelled(list(labels))) if report is None else report
    if report.valid is not True or report.polycube is None:
        raise ValueError("grafting starts from a valid labelling")
    loops = len(dualize(report.polycube).loops)
    pairs, _ = surface.adjacency
    seen: set[tuple[bytes, int]] = set()
    kept = tried = 0
    rise = 0.0
    for _ in range(SWEEPS):
        found = [(gain, where, int(donor[where[0]])) for donor in donors
                 for gain, where in patches(surface, lab, donor, value)]
        found.sort(key=lambda f: -f[0])
        kept_before = kept
        chart = chart_indices(surface, lab)
        for _gain, where, label in found:
            key = (where.tobytes(), label)
            if key in seen:
                continue
            if deadline is not None and time.monotonic() > deadline:
                break
            gain = float((value[where, label] - value[where, lab[where]]).sum())
            if gain <= least:
                continue
            seen.add(key)
            if _island(pairs, chart, lab, where, label):
                continue
            trial = lab.copy()
            trial[where] = label
            tried += 1
            checked = check_segmentation(surface.labelled([Direction(int(d)) for d in trial]))
            if checked.valid is not True or checked.polycube is None:
                continue
            more = len(dualize(checked.polycube).loops)
            step = gain / area - price * (more - loops)
            if step > 0:
                lab, report, loops, rise, kept = trial, checked, more, rise + step, kept + 1
                chart = chart_indices(surface, lab)
        if kept == kept_before or (deadline is not None and time.monotonic() > deadline):
            break
    return Grafted(tuple(Direction(int(d)) for d in lab), report, loops, kept, tried, rise)


def _island(pairs: np.ndarray, chart: np.ndarray, lab: np.ndarray, where: np.ndarray, label: int) -> bool:
    """Whether the triangles ``where``, labelled ``label``, would be a chart whose only
    neighbour is one chart of another label (``chart`` numbers the charts of ``lab``)."""
    inside = np.zeros(len(lab), dtype=bool)
    inside[where] = True
    rim = pairs[inside[pairs[:, 0]] != inside[pairs[:, 1]]]
    outside = np.where(inside[rim[:, 0]], rim[:, 1], rim[:, 0])
    return len(outside) > 0 and len(np.unique(chart[outside])) == 1 and int(lab[outside[0]]) != label
