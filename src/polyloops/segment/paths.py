"""Additions drawn as cheapest paths: a valid addition of the kernel, put on the surface.

A valid addition (:func:`polyloops.core.moves.valid_additions`) is a cycle of regions
``R_0, ..., R_{k-1}``, the new loop crossing the segment between each region and the next.
Its path on the surface is the cheapest closed path of mesh edges that runs through the inner
vertices of those regions in that order and crosses each of those segments at one vertex in
its middle (:data:`MIDDLE`: a loop hugging a crossing would cut off a sliver): a shortest path
in a graph *layered* by the cycle's regions (layer ``i``
holds the inner vertices of ``R_i``; a gate vertex of the segment between ``R_i`` and
``R_{i+1}`` leads from layer ``i`` to layer ``i + 1`` only), closed by leaving and reaching the
same gate vertex of the last segment.  The layers hold disjoint vertices, so the path is
simple; it touches the other loops only at its gates, where it crosses them; and reading the
structure off the surface gives the kernel's :func:`~polyloops.core.moves.add_loop` by
construction (tested).  An edge costs its length times ``1 + ALONG * |d . a| + FACING * |n . a|``
(``d`` its direction, ``n`` the mean normal of the triangles beside it, ``a`` the loop's axis):
a loop of axis X runs round the X axis, across faces whose normals are perpendicular to X.

Cycles that pass a region twice, and regions without inner vertices, get no path (``None``).

>>> from polyloops.core.directions import Axis
>>> from polyloops.core.moves import valid_additions
>>> from polyloops.segment.refine import Plane, Refined, cut
>>> from polyloops.segment.embedded import SurfaceLoop, read_structure
>>> from polyloops.segment.surface import surface_of
>>> from polyloops.shapes.meshes import sphere
>>> r = cut(Refined.of(surface_of(*sphere(3))), [Plane(0, 0.01), Plane(1, 0.02), Plane(2, 0.03)])
>>> e = read_structure(r, [SurfaceLoop(p, r.sections(p)[0]) for p in range(3)])
>>> move = next(valid_additions(e.structure, Axis.X))
>>> path = addition_path(e, move)
>>> path.axis, len(path.vertices) > 4
(0, True)
"""

from __future__ import annotations

import itertools

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import dijkstra

from polyloops.core.moves import Addition
from polyloops.segment.embedded import Embedded, PathLoop

__all__ = ["ALONG", "FACING", "GATES", "MIDDLE", "addition_path"]

ALONG = 2.0  # the price of running along the loop's axis, per unit length
FACING = 2.0  # the price of crossing faces that face along the loop's axis
GATES = 8  # vertices of the closing segment tried as the path's start
MIDDLE = 0.25  # a path crosses a segment this far (a share of its length) from either end or more


def addition_path(e: Embedded, move: Addition) -> PathLoop | None:
    """The cheapest closed path on ``e``'s surface for the kernel's addition ``move`` (see the
    module docstring), or ``None`` when it has none."""
    cycle = list(move.cycle)
    k = len(cycle)
    if k < 2 or len(set(cycle)) != k:
        return None
    r = e.refined
    tris = r.triangles
    n = len(r.points)
    inner = np.ones(n, dtype=bool)  # on no loop
    for lp in e.loops:
        inner[list(lp.vertices)] = False
    vertex_region = np.full(n, -1)  # the region of an inner vertex
    vertex_region[tris.ravel()] = np.repeat(e.region, 3)
    layer_of_region = {g: i for i, g in enumerate(cycle)}
    pairs, ends = r.surface.adjacency
    ra, rb = e.region[pairs[:, 0]], e.region[pairs[:, 1]]
    # gates: the vertices in the middle of each segment the cycle crosses (two regions meet
    # along one segment at most, so the pair names it)
    segment_of = {frozenset((cycle[i], cycle[(i + 1) % k])): i for i in range(k)}
    gate_layer: dict[int, int] = {}  # gate vertex -> i: it leads from layer i to layer i + 1
    for x in _middles(e):
        regions = frozenset(int(e.region[t]) for t in r.incident[x])
        if regions in segment_of:
            gate_layer[x] = segment_of[regions]
    if len(set(gate_layer.values())) < k:
        return None  # a segment with no vertex strictly inside it
    # nodes: layer i's inner vertices, the gates, and the closing gates' second copies
    index: dict[tuple[int, int], int] = {}

    def node(kind: int, x: int) -> int:
        return index.setdefault((kind, x), len(index))

    # the edges the graph can use: inside a region of the cycle, or between an inner vertex and
    # a gate (the rest of the surface is left out before the loop below)
    u, v = ends[:, 0], ends[:, 1]
    gate = np.zeros(n, dtype=bool)
    gate[list(gate_layer)] = True
    within = inner[u] & inner[v] & (ra == rb) & np.isin(ra, cycle)
    used = within | (inner[u] & gate[v]) | (gate[u] & inner[v])
    pairs, u, v, ra, rb = pairs[used], u[used], v[used], ra[used], rb[used]
    axis = np.eye(3)[int(move.axis)]
    normals = r.surface.normals
    d = r.points[v] - r.points[u]
    length = np.linalg.norm(d, axis=1) + 1e-15
    facing = (np.abs(normals[pairs[:, 0]] @ axis) + np.abs(normals[pairs[:, 1]] @ axis)) / 2
    cost = length * (1 + ALONG * np.abs(d @ axis) / length + FACING * facing)
    src, dst, w = [], [], []
    for a, b, c, g1, g2 in zip(u.tolist(), v.tolist(), cost.tolist(), ra.tolist(), rb.tolist(), strict=True):
        for x, y in ((a, b), (b, a)):
            if inner[x] and inner[y]:
                if g1 == g2 and g1 in layer_of_region:
                    i = layer_of_region[g1]
                    src.append(node(i, x))
                    dst.append(node(i, y))
                    w.append(c)
            elif inner[x] and y in gate_layer:
                i, j = layer_of_region.get(int(vertex_region[x]), -1), gate_layer[y]
                if i == j:  # into the gate from its region
                    src.append(node(i, x))
                    dst.append(node(k + 1 if j == k - 1 else k, y))
                    w.append(c)
                if i == (j + 1) % k:  # out of the gate into the next region
                    src.append(node(k, y))
                    dst.append(node(i, x))
                    w.append(c)
    m = len(index)
    graph = coo_matrix((w, (src, dst)), shape=(m, m)).tocsr()
    closing = [x for x, j in gate_layer.items() if j == k - 1]
    starts = [closing[i] for i in np.linspace(0, len(closing) - 1, min(GATES, len(closing))).astype(int)]
    best: tuple[float, int, np.ndarray] | None = None
    sources = [index[(k, x)] for x in starts if (k, x) in index]
    if not sources:
        return None
    dist, pred = dijkstra(graph, directed=True, indices=sources, return_predecessors=True)
    for row, x in enumerate(x for x in starts if (k, x) in index):
        end = index.get((k + 1, x))
        if end is None or not np.isfinite(dist[row, end]):
            continue
        if best is None or dist[row, end] < best[0]:
            best = (float(dist[row, end]), row, pred[row])
    if best is None:
        return None
    _, row, pr = best
    vertex_of = {i: x for (_, x), i in index.items()}
    start = sources[row]
    walk, at = [], index[(k + 1, vertex_of[start])]
    while at != start:
        walk.append(vertex_of[at])
        at = int(pr[at])
    walk.append(vertex_of[start])
    vertices = tuple(walk[::-1][:-1])  # start .. (the closing copy of start dropped)
    return PathLoop(int(move.axis), vertices)


def _middles(e: Embedded) -> list[int]:
    """The vertices of the loops that lie on a segment at least :data:`MIDDLE` of its length
    from both its ends (the crossings), in the order of the loops."""
    points = e.refined.points
    crossing = set(e.crossings)
    out = []
    for lp in e.loops:
        vs = list(lp.vertices)
        first = next(i for i, x in enumerate(vs) if x in crossing)
        vs = vs[first:] + vs[:first + 1]  # from a crossing round to it again
        ends = [i for i, x in enumerate(vs) if x in crossing]
        for a, b in itertools.pairwise(ends):
            run = vs[a:b + 1]
            steps = np.linalg.norm(np.diff(points[run], axis=0), axis=1)
            along = np.concatenate([[0.0], np.cumsum(steps)]) / max(float(steps.sum()), 1e-15)
            inside = zip(run[1:-1], along[1:-1].tolist(), strict=True)
            out += [x for x, t in inside if MIDDLE <= t <= 1 - MIDDLE]
    return out
