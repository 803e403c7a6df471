"""Cheapest vertex-disjoint paths from one vertex to several: a minimum-cost flow.

The corner of a region is joined to a point on each of its sides by paths that meet only at the
corner (:mod:`~polyloops.segment.layout`).  With every other vertex split into an entry and an
exit joined by an arc of capacity 1, such paths are a flow of value ``k`` from the corner, and
successive shortest augmenting paths (Dijkstra with potentials, costs non-negative) find the
cheapest one in ``k`` rounds.

>>> # a square with its centre 4: from 4 to the corners 0 and 2, apart
>>> edges = [(0, 1, 1.0), (1, 2, 1.0), (2, 3, 1.0), (3, 0, 1.0)] + [(4, c, 1.5) for c in range(4)]
>>> sorted(disjoint_paths(5, edges, 4, [0, 2]))
[[4, 0], [4, 2]]
"""

from __future__ import annotations

import heapq
from collections.abc import Sequence

__all__ = ["disjoint_paths"]


class _Network:
    def __init__(self, n: int):
        self.to: list[int] = []
        self.cap: list[int] = []
        self.cost: list[float] = []
        self.out: list[list[int]] = [[] for _ in range(n)]

    def arc(self, u: int, v: int, cap: int, cost: float) -> None:
        for a, b, c, w in ((u, v, cap, cost), (v, u, 0, -cost)):
            self.out[a].append(len(self.to))
            self.to.append(b)
            self.cap.append(c)
            self.cost.append(w)


def disjoint_paths(n: int, edges: Sequence[tuple[int, int, float]], source: int, targets: Sequence[int]
                   ) -> list[list[int]] | None:
    """Paths from ``source`` to each of ``targets`` (vertices ``0 .. n-1``, undirected ``edges``
    with non-negative lengths) that share no vertex but ``source``, of least total length;
    ``None`` when there are no such paths.  A target is a path's last vertex, never inside
    another path."""
    net = _Network(2 * n + 1)
    sink = 2 * n
    wanted = set(targets)
    for v in range(n):  # v's entry is v, its exit n + v
        net.arc(v, n + v, len(targets) if v == source else 1, 0.0)
    for u, v, w in edges:
        for a, b in ((u, v), (v, u)):
            if a not in wanted and b != source:
                net.arc(n + a, b, 1, w)
    for t in targets:
        net.arc(n + t, sink, 1, 0.0)
    potential = [0.0] * (2 * n + 1)
    for _ in targets:
        dist = [float("inf")] * (2 * n + 1)
        back = [-1] * (2 * n + 1)
        dist[source] = 0.0
        heap = [(0.0, source)]
        while heap:
            d, u = heapq.heappop(heap)
            if d > dist[u]:
                continue
            for i in net.out[u]:
                if net.cap[i] <= 0:
                    continue
                v = net.to[i]
                nd = d + net.cost[i] + potential[u] - potential[v]
                if nd < dist[v] - 1e-12:
                    dist[v] = nd
                    back[v] = i
                    heapq.heappush(heap, (nd, v))
        if dist[sink] == float("inf"):
            return None
        for v in range(2 * n + 1):
            if dist[v] < float("inf"):
                potential[v] += dist[v]
        v = sink
        while v != source:
            i = back[v]
            net.cap[i] -= 1
            net.cap[i ^ 1] += 1
            v = net.to[i ^ 1]
    return _paths(net, n, source, wanted)


def _paths(net: _Network, n: int, source: int, targets: set[int]) -> list[list[int]]:
    """The paths the flow takes, from the source's exit along arcs that carry flow."""
    used = [i for i in range(0, len(net.to), 2) if net.cap[i] == 0 and net.cap[i + 1] > 0]
    nxt: dict[int, list[int]] = {}
    for i in used:
        nxt.setdefault(net.to[i + 1], []).append(net.to[i])
    out = []
    for first in nxt.get(n + source, []):
        path, v = [source], first
        while True:
            path.append(v)  # an entry: v itself
            if v in targets:
                break
            v = nxt[n + v][0]  # from v's exit
        out.append(path)
    return out
