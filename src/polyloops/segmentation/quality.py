"""How well a valid labelled segmentation follows its mesh: the share of boundary length that runs
backwards along its axis.

A boundary between two charts is a polycube edge, parallel to the axis of neither label, and the
realising polycube says which way along that axis it climbs (from its start corner to its end
corner).  Where the mesh's boundary path steps the other way along the axis, the polycube and
the mesh disagree: a parametrisation built on the segmentation folds there.  The measure is the
length of those steps over the length of all boundaries (0 for a polycube labelled by its own
normals; DualCube-style outputs and graph-cut labellings have some).

>>> from polyloops.io.examples import load_example
>>> from polyloops.segmentation import check_segmentation
>>> from polyloops.surface.construct import labelled_mesh_from_polycube
>>> backwards_fraction(check_segmentation(labelled_mesh_from_polycube(load_example("l-shape"))))
0.0
"""

from __future__ import annotations

import numpy as np

__all__ = ["backwards_fraction"]


def backwards_fraction(report) -> float | None:
    """The share of boundary length stepping against its polycube edge's direction, for a
    report with a realising polycube (``None`` without one, or without boundaries)."""
    if report.polycube is None:
        return None
    seg = report.segmentation
    corners = report.polycube.positions  # the realisation numbers the charts' corners first
    points = np.asarray(seg.mesh.points, dtype=float)
    total = against = 0.0
    for b in seg.boundaries:
        axis = seg.boundary_axis(b.id)
        if axis is None or b.start is None or b.end is None:
            continue
        climb = np.sign(corners[b.end][axis] - corners[b.start][axis])
        path = points[list(b.vertices)]
        steps = np.diff(path, axis=0)
        lengths = np.linalg.norm(steps, axis=1)
        total += float(lengths.sum())
        against += float(lengths[steps[:, axis] * climb < 0].sum())
    return against / total if total > 0 else None
