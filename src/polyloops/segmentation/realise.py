"""A polycube that realises a labelled segmentation, from directions that pass the global test.

Method (exact when it succeeds, a heuristic when it does not):

1. *Coordinates.*  Along each axis, the zones of the corners are ordered by their level
   graph, following the mesh's own coordinates where they agree with it, and each zone gets
   its rank, so every boundary goes up by at least one.  When the quads below fail, other
   orders of the zones that keep the level graph's are tried (:data:`TRIES` of them, each a
   topological order by the mesh's coordinates plus a seeded jitter that grows from try to
   try until the order is nearly any): the first that passes every check is kept.  A chart
   that bends in space can need an order far from the mesh's: a hole of the top of DualCube's
   plane lies outside its outer boundary in the mesh's projection, inside it in the polycube.
2. *Orientation.*  Reversing all directions gives the same normals and the mirror image
   through the origin, with the opposite signed volume; the one with positive volume is kept
   (zero volume: undecided).
3. *Quads.*  Each chart is a rectilinear polygon (possibly with holes) in the plane of its
   zone.  It is cut along every integer level into unit squares: a square belongs to the
   chart when the chart's boundary curves wind once around its centre (in the sense of the
   label).  Points on a boundary are shared with the chart on its other side, points at
   corners with every chart there.  Any other winding, or a grid point where the chart
   would touch itself, leaves the question undecided: partitioning rectilinear faces so that
   a polycube stays valid is open (the paper, Section 1).
4. *Check.*  The quads must pass Definition 1, and each chart's quads must have its label as
   their normal.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

import networkx as nx
import numpy as np

from polyloops.core.directions import Axis
from polyloops.core.halfedge import FaceListError, MapError
from polyloops.core.polycube import Polycube
from polyloops.segmentation.charts import Segmentation
from polyloops.segmentation.levels import GlobalResult, mesh_steps


@dataclass(frozen=True)
class Realisation:
    """A polycube that realises a labelling, or the reason the construction failed."""

    polycube: Polycube | None
    reason: str = ""  # why there is none
    chart_of_face: tuple[int, ...] = ()


TRIES = 256  # orders of the zones tried first (a few ms each)
JITTER = 4.0  # the last of those tries' jitter, in spans of the mesh's coordinates: nearly any order
# then as many orders again, three times over, with new seeds and a jitter growing four times
# more slowly: an order a little off the mesh's is what a chart that bends in space needs, and
# which seeds give one is luck (half DualCube's aeroplane, repaired: try 316)
FINE_TRIES = 768


def corner_positions(seg: Segmentation, result: GlobalResult, attempt: int = 0) -> list[list[int]]:
    """Integer coordinates of each corner: per axis, a level for each zone that every
    boundary along the axis climbs.  Where the mesh's own coordinates order the zones
    consistently with the level graph, the levels are their ranks (so the polycube keeps the
    mesh's order type, which places holes inside the charts around them); otherwise zones
    take distinct levels in a topological order that follows the mesh where it can.  A later
    ``attempt`` takes a topological order of the mesh's coordinates jittered by a seeded
    amount that grows with the attempt."""
    rng = random.Random(attempt)
    if attempt < TRIES:
        jitter = JITTER * attempt / TRIES
    else:
        jitter = JITTER * (attempt - TRIES) / (TRIES + FINE_TRIES)
    pos = [[0, 0, 0] for _ in seg.corners]
    directions = _closer_to_mesh(seg, result.directions)
    for axis in Axis:
        zones = result.zones[axis]
        n = max(zones, default=-1) + 1
        total = [0.0] * n
        count = [0] * n
        for c, z in enumerate(zones):
            total[z] += seg.mesh.points[seg.corners[c].vertex][axis]
            count[z] += 1
        mean = [t / k for t, k in zip(total, count, strict=True)]
        arcs = []
        for b in seg.boundaries:
            if seg.boundary_axis(b.id) == axis:
                u, v = zones[b.start], zones[b.end]  # type: ignore[index]
                arcs.append((u, v) if directions[b.id] > 0 else (v, u))
        if attempt:
            span = (max(mean) - min(mean)) if mean else 0.0
            level = _topological_levels(n, arcs, [m + jitter * span * rng.uniform(-1, 1) for m in mean])
        else:
            level = _ranks(mean)
            if any(level[u] >= level[v] for u, v in arcs):
                level = _topological_levels(n, arcs, mean)
        for c in range(len(seg.corners)):
            pos[c][axis] = level[zones[c]]
    return pos


def _closer_to_mesh(seg: Segmentation, directions: tuple[int, ...]) -> tuple[int, ...]:
    """The directions or all of them reversed (the same labels, see
    :mod:`~polyloops.segmentation.levels`), whichever more boundaries of the mesh follow."""
    agree = sum(d * ((s > 0) - (s < 0)) for s, d in zip(mesh_steps(seg), directions, strict=True))
    return directions if agree >= 0 else tuple(-d for d in directions)


def _ranks(values: list[float]) -> list[int]:
    """The rank of each value among the distinct values (closer than 1e-9 of the spread: one)."""
    spread = (max(values) - min(values)) if values else 0.0
    tol = 1e-9 * max(spread, 1.0)
    order = sorted(range(len(values)), key=values.__getitem__)
    out = [0] * len(values)
    rank, last = -1, None
    for i in order:
        if last is None or values[i] - last > tol:
            rank += 1
            last = values[i]
        out[i] = rank
    return out


def _topological_levels(n: int, arcs: list[tuple[int, int]], mean: list[float]) -> list[int]:
    """Distinct levels in a topological order of the arcs, lowest mean coordinate first."""
    g = nx.DiGraph()
    g.add_nodes_from(range(n))
    g.add_edges_from(arcs)
    order = nx.lexicographical_topological_sort(g, key=mean.__getitem__)
    level = [0] * n
    for i, z in enumerate(order):
        level[z] = i
    return level


def realise(seg: Segmentation, result: GlobalResult) -> Realisation:
    """The polycube of the module docstring, or the reason the first order of the zones gave
    none (when none of the :data:`TRIES` orders, nor the :data:`FINE_TRIES` after them, gives
    one)."""
    first = None
    for attempt in range(TRIES + FINE_TRIES):
        found = _realise_at(seg, result, corner_positions(seg, result, attempt))
        if found.polycube is not None:
            return found
        first = first or found
    assert first is not None
    return first


def _realise_at(seg: Segmentation, result: GlobalResult, corner_pos: list[list[int]]) -> Realisation:
    from polyloops.verify import check_polycube

    points: list[tuple[int, int, int]] = [tuple(p) for p in corner_pos]  # type: ignore[misc]
    # Lattice points strictly inside each boundary, from its start to its end.
    inner: list[list[int]] = []
    for b in seg.boundaries:
        axis = seg.boundary_axis(b.id)
        assert axis is not None and b.start is not None and b.end is not None
        p, q = corner_pos[b.start], corner_pos[b.end]
        step = 1 if q[axis] > p[axis] else -1
        ids = []
        for t in range(p[axis] + step, q[axis], step):
            x = list(p)
            x[axis] = t
            ids.append(len(points))
            points.append((x[0], x[1], x[2]))
        inner.append(ids)
    faces: list[list[int]] = []
    chart_of_face: list[int] = []
    for chart in seg.charts:
        quads = _chart_quads(seg, chart.id, corner_pos, inner, points)
        if isinstance(quads, str):
            return Realisation(None, quads)
        faces += quads
        chart_of_face += [chart.id] * len(quads)
    try:
        cube = Polycube.from_faces(faces, points)
    except (MapError, FaceListError) as err:
        return Realisation(None, f"the quads do not close up: {err}")
    volume = cube.signed_volume()
    if volume == 0:
        return Realisation(None, "the realisation has zero volume, so no side is outside")
    if volume < 0:
        cube = Polycube(cube.map, tuple((-x, -y, -z) for x, y, z in cube.positions))
    report = check_polycube(cube)
    if not report.valid:
        v = report.violations[0]
        return Realisation(None, f"the quads fail Definition 1 condition {v.condition}: {v.message}")
    for f, c in enumerate(chart_of_face):
        if cube.face_normal(f) != seg.charts[c].label:
            facing = cube.face_normal(f)
            return Realisation(None, f"a quad of chart {c} faces {facing}, not {seg.charts[c].label}")
    return Realisation(cube, chart_of_face=tuple(chart_of_face))


def _chart_quads(seg: Segmentation, c: int, corner_pos, inner, points) -> list[list[int]] | str:
    chart = seg.charts[c]
    a = chart.label.axis
    u, v = (a + 1) % 3, (a + 2) % 3  # (a, u, v) right-handed: counter-clockwise seen from +a
    sign = chart.label.sign
    # The chart's boundary curves as closed 2D polylines, and the id of every lattice point on them.
    on_boundary: dict[tuple[int, int], int] = {}
    edges_v: list[tuple[int, int, int]] = []  # (u, v from, v to) of the sides parallel to v
    level = None
    for cycle in chart.cycles:
        for b, forward in cycle:
            bd = seg.boundaries[b]
            ids = [bd.start, *inner[b], bd.end] if forward else [bd.end, *reversed(inner[b]), bd.start]
            ends = [corner_pos[i] for i in ids[:1]] + [list(points[i]) for i in ids[1:-1]] + \
                   [corner_pos[i] for i in ids[-1:]]
            for i, p in zip(ids, ends, strict=True):
                if level is None:
                    level = p[a]
                key = (p[u], p[v])
                if on_boundary.setdefault(key, i) != i:
                    return f"chart {c} would touch itself at a point"
            first, last = corner_pos[ids[0]], corner_pos[ids[-1]]
            if first[u] == last[u]:
                edges_v.append((first[u], first[v], last[v]))
    if not on_boundary or level is None:
        return f"chart {c} has no corners"
    plane: int = level
    us = [k[0] for k in on_boundary]
    vs = [k[1] for k in on_boundary]
    u0, v0 = min(us), min(vs)
    nu, nv = max(us) - u0, max(vs) - v0
    centres_u = np.arange(nu)[:, None] + u0 + 0.5
    centres_v = np.arange(nv)[None, :] + v0 + 0.5
    winding = np.zeros((nu, nv), dtype=int)
    for eu, va, vb in edges_v:
        lo, hi = min(va, vb), max(va, vb)
        crossed = (centres_u < eu) & (centres_v > lo) & (centres_v < hi)
        winding += np.where(crossed, 1 if vb > va else -1, 0)
    if not np.isin(winding, (0, sign)).all():
        bad = int(winding[~np.isin(winding, (0, sign))][0]) * sign
        return f"chart {c} would cover part of its plane {bad} times (once is a face)"
    inside = winding == sign
    interior: dict[tuple[int, int], int] = {}

    def point(pu: int, pv: int) -> int | None:
        key = (pu, pv)
        if key in on_boundary:
            return on_boundary[key]
        iu, iv = pu - u0, pv - v0
        around = [inside[x, y] for x in (iu - 1, iu) for y in (iv - 1, iv) if 0 <= x < nu and 0 <= y < nv]
        if len(around) < 4 or not all(around):
            return None  # on the chart's outline without being on one of its boundaries
        if key not in interior:
            x = [0, 0, 0]
            x[a], x[u], x[v] = plane, pu, pv
            interior[key] = len(points)
            points.append((x[0], x[1], x[2]))
        return interior[key]

    quads = []
    for iu, iv in zip(*np.nonzero(inside), strict=True):
        pu, pv = int(iu) + u0, int(iv) + v0
        ring = [point(pu, pv), point(pu + 1, pv), point(pu + 1, pv + 1), point(pu, pv + 1)]
        if any(x is None for x in ring):
            return f"chart {c} touches itself along its outline"
        quads.append(ring if sign > 0 else ring[::-1])
    if not quads:
        return f"chart {c} covers no area"
    return quads  # type: ignore[return-value]
