"""Polishing a labelled layout: triangles moved between patches where that agrees better with
their normals, without changing what the patches make.

A layout's patches (or a labelling's charts) cut the surface into discs meeting at corners; the
polycube they realise depends only on that cell complex and the patches' labels.  A triangle
``t`` on the edge of its patch ``f`` may move to a patch ``g`` beside it when the move keeps the
complex as it is, which is decided round ``t``'s three vertices alone (:func:`move_keeps`):

- round each vertex, the patches met in turn (runs of equal patches counted once) include no
  patch twice after the move: a patch that met the vertex twice would pinch there, which is
  how a patch would be cut in two, closed into a ring or made to touch itself;
- the corners (vertices met by three patches or more) have, together, the same cyclic
  sequences of patches before and after: a corner may move to another vertex of ``t`` (it is
  followed there), none appears or vanishes, and no two merge.

A patch gives up or takes a triangle only where its edge stays a simple curve through the same
corners in the same order, so each patch stays a disc with the same neighbours, and the labels'
checker sees the same charts, boundaries and corners.  The moves are made best gain first (the
area times the gain in ``n . label``, or in agreement with a guide, less the cost of the patch
edges the move adds, :func:`edge_costs`) until none is left; each lowers that energy, so it
ends.  ``tests/test_segment_polish.py`` checks, move by move on
generated layouts, that the complex computed from scratch is the same after every move allowed.

>>> import numpy as np
>>> from polyloops.io.examples import load_example
>>> from polyloops.surface.construct import labelled_mesh_from_polycube
>>> mesh = labelled_mesh_from_polycube(load_example("cube"))
>>> tris = np.array(mesh.triangles)
>>> patch = np.array([int(d) for d in mesh.labels])
>>> value = np.zeros((len(tris), 6))
>>> value[0, int(mesh.labels[0]) ^ 1] = 1.0   # the first triangle would rather face the other way
>>> polish(tris, value, patch, patch % 6).moves   # but its face has no other patch beside it
0
"""

from __future__ import annotations

import heapq
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from polyloops.core.directions import Direction
from polyloops.segment.embedded import Embedded
from polyloops.segment.labellings import DIRECTION_VECTORS, chart_indices, face_directions, label_indices
from polyloops.segment.layout import Layout
from polyloops.segment.refine import Refined
from polyloops.segment.search import nearest_faces
from polyloops.segment.surface import Surface

__all__ = ["COMPACTNESS", "Fans", "Polished", "edge_costs", "move_keeps", "polish", "polish_labels",
           "polish_layout", "polished_fidelity", "worth"]


class Fans:
    """The triangles round each vertex of a closed, oriented triangle mesh, in turn."""

    def __init__(self, triangles: np.ndarray):
        self.triangles = np.asarray(triangles, dtype=np.int64)
        m, n = len(self.triangles), int(self.triangles.max()) + 1
        tails, heads = self.triangles, np.roll(self.triangles, -1, axis=1)  # edge k runs from k to k + 1
        keys = (tails * n + heads).ravel()
        order = np.argsort(keys)
        twins = order[np.searchsorted(keys, (heads * n + tails).ravel(), sorter=order)]
        self.across = (twins // 3).reshape(m, 3)  # per triangle and edge, the triangle beside it
        self.some = np.zeros(n, dtype=np.int64)
        self.some[self.triangles.ravel()] = np.repeat(np.arange(m), 3)
        self._rows: dict[int, list[int]] = {}  # rows as lists, made as the loops below meet them
        self._across: dict[int, list[int]] = {}
        self._fans: dict[int, tuple[int, ...]] = {}

    def row(self, t: int) -> list[int]:
        """Triangle ``t``'s three vertices."""
        got = self._rows.get(t)
        if got is None:
            got = self._rows[t] = self.triangles[t].tolist()
        return got

    def fan(self, v: int) -> tuple[int, ...]:
        """The triangles round ``v``, each next across the edge from the last one's third
        vertex to ``v``."""
        got = self._fans.get(v)
        if got is not None:
            return got
        out, t = [], int(self.some[v])
        while True:
            out.append(t)
            t = self.neighbours(t)[(self.row(t).index(v) + 2) % 3]
            if t == out[0]:
                break
        self._fans[v] = tuple(out)
        return self._fans[v]

    def neighbours(self, t: int) -> list[int]:
        """The three triangles across ``t``'s edges."""
        got = self._across.get(t)
        if got is None:
            got = self._across[t] = self.across[t].tolist()
        return got


def _runs(patches: Sequence[int]) -> tuple[int, ...]:
    """The cyclic sequence of patches with runs counted once, rotated to start at its least."""
    out = [p for i, p in enumerate(patches) if p != patches[i - 1]]
    if not out:
        return (patches[0],)
    k = out.index(min(out))
    return tuple(out[k:] + out[:k])


def move_keeps(fans: Fans, patch: Sequence[int], t: int, g: int) -> dict[int, int] | None:
    """Whether moving triangle ``t`` to patch ``g`` keeps the patches' cell complex (see the
    module docstring): ``None`` when it does not, else where the corners among ``t``'s vertices
    go (old vertex to new vertex; a corner that stays is mapped to itself)."""
    if patch[t] == g or all(patch[u] != g for u in fans.neighbours(t)):
        return None
    before: dict[int, tuple[int, ...]] = {}
    after: dict[int, tuple[int, ...]] = {}
    for v in fans.row(t):
        around = [patch[u] for u in fans.fan(v)]
        before[v] = _runs(around)
        after[v] = _runs([g if u == t else p for u, p in zip(fans.fan(v), around, strict=True)])
        if len(set(after[v])) != len(after[v]):
            return None
    old = {v: s for v, s in before.items() if len(s) >= 3}
    new = {s: v for v, s in after.items() if len(s) >= 3}
    if sorted(old.values()) != sorted(new) or len(new) != len(old):
        return None  # a corner appears, vanishes, changes, or two share a sequence
    return {v: new[s] for v, s in old.items()}


@dataclass(frozen=True)
class Polished:
    """The patches after polishing, the corners where they went, and the moves made."""

    patch: np.ndarray
    corners: tuple[int, ...]
    moves: int
    gain: float  # the sum of the moves' gains (in the units of ``value``)


def polish(triangles: np.ndarray, value: np.ndarray, patch: np.ndarray, direction: np.ndarray,
           corners: Sequence[int] = (), max_moves: int | None = None,
           edge_cost: np.ndarray | None = None) -> Polished:
    """Move triangles between patches, best gain first, while the complex stays the same.

    ``value[t, d]``: what triangle ``t`` is worth labelled with direction ``d`` (0..5, say its
    area times ``n . d``); ``patch[t]``: its patch; ``direction[p]``: patch ``p``'s label;
    ``corners``: vertices to follow where the corners move (a layout's corner per region);
    ``edge_cost[t, k]``: what it costs that ``t``'s edge ``k`` (from its vertex ``k`` to the
    next) lies between two patches (none by default), so that a move's gain is its worth less
    the cost of the patch edges it adds.
    """
    start = np.asarray(patch, dtype=np.int64)
    fans = Fans(np.asarray(triangles))
    where = {int(v): i for i, v in enumerate(corners)}
    moved_corners = [int(v) for v in corners]
    now_in: list[int] = start.tolist()
    value = np.asarray(value, dtype=float)
    label: list[int] = np.asarray(direction, dtype=np.int64).tolist()
    rows: dict[int, list[float]] = {}
    costs = np.zeros((len(start), 3)) if edge_cost is None else np.asarray(edge_cost, dtype=float)
    cost_rows: dict[int, list[float]] = {}

    def best(t: int) -> tuple[float, int]:
        """The best gain of moving ``t`` to a patch beside it: its worth there, and the cost
        of the edges beside its own patch (which start to lie between patches) less that of
        those beside the other (which stop)."""
        mine = now_in[t]
        row = rows.get(t)
        if row is None:
            row = rows[t] = value[t].tolist()
        edges = cost_rows.get(t)
        if edges is None:
            edges = cost_rows[t] = costs[t].tolist()
        beside = [now_in[u] for u in fans.neighbours(t)]
        gains = [(row[label[g]] - row[label[mine]]
                  + sum(c * ((b == g) - (b == mine)) for c, b in zip(edges, beside, strict=True)), g)
                 for g in sorted(set(beside) - {mine})]
        return max(gains, default=(0.0, -1))

    heap: list[tuple[float, int, int]] = []

    def push(t: int) -> None:
        gain, g = best(t)
        if gain > 1e-15:
            heapq.heappush(heap, (-gain, t, g))

    for t in np.nonzero((start[fans.across] != start[:, None]).any(axis=1))[0].tolist():
        push(t)  # every triangle on a patch edge; push keeps those with a gain
    moves, total = 0, 0.0
    while heap and (max_moves is None or moves < max_moves):
        neg, t, g = heapq.heappop(heap)
        gain, now = best(t)
        if now != g or abs(gain + neg) > 1e-15:
            continue  # stale: pushed again with its current gain when its patch changed
        went = move_keeps(fans, now_in, t, g)
        if went is None:
            continue  # blocked now; pushed again when something round it moves
        now_in[t] = g
        moves += 1
        total += gain
        followed = {w: where.pop(v) for v, w in went.items() if v in where}
        for w, i in followed.items():  # all at once: two corners of t may trade vertices
            where[w] = i
            moved_corners[i] = w
        for v in fans.row(t):
            for u in fans.fan(v):
                push(u)
    return Polished(np.array(now_in, dtype=np.int64), tuple(moved_corners), moves, total)


COMPACTNESS = 0.25  # what a length of patch edge costs, in mean triangle areas per mean edge length
# (the graph-cut labelling's weight is 1): enough that a lone triangle does not reach into the
# next patch for a slightly better normal, so the edges stay clean on noisy meshes


def edge_costs(surface: Surface, compactness: float = COMPACTNESS) -> np.ndarray:
    """Per triangle and edge (from its vertex ``k`` to the next), what it costs that the edge
    lies between two patches: its length times ``compactness`` mean triangle areas per mean
    edge length."""
    tris, pts = surface.triangles, surface.points
    lengths = np.linalg.norm(pts[np.roll(tris, -1, axis=1)] - pts[tris], axis=2)
    return compactness * float(surface.areas.mean()) / float(lengths.mean()) * lengths


def worth(surface: Surface, target: np.ndarray | None = None) -> np.ndarray:
    """Per triangle and direction (0..5), its area times ``n . d`` (or ``target . d``, a unit
    vector per triangle such as a guide's labels): what :func:`polish` maximises."""
    wanted = surface.normals if target is None else target
    return surface.areas[:, None] * (wanted @ DIRECTION_VECTORS.T)


def polish_layout(lay: Layout, target: np.ndarray | None = None, compactness: float = COMPACTNESS) -> Layout:
    """``lay`` with its patches polished (see the module docstring), its corners followed:
    the same polycube, drawn on the same refined surface, the labels nearer the normals (or
    the ``target``, per refined triangle)."""
    r = lay.embedded.refined
    try:
        direction = face_directions(lay.polycube)
    except ValueError:
        return lay  # a face without an axis: the layout is not certified anyway
    done = polish(r.triangles, worth(r.surface, target), lay.patch, direction, lay.corners,
                  edge_cost=edge_costs(r.surface, compactness))
    if done.moves == 0:
        return lay
    labels = tuple(Direction(int(d)) for d in direction[done.patch])
    return replace(lay, patch=done.patch, labels=labels, corners=done.corners)


def polished_fidelity(r: Refined, e: Embedded, target: np.ndarray | None = None,
                      compactness: float = COMPACTNESS) -> float:
    """A quick foretaste of a structure's certified fidelity (or agreement with ``target``, per
    refined triangle): its rough patches (each triangle the face of the nearest crossing in its
    region, :func:`~polyloops.segment.search.nearest_faces`) polished, with no layout."""
    direction = face_directions(e.polycube)
    value = worth(r.surface, target)
    done = polish(r.triangles, value, nearest_faces(r, e), direction,
                  edge_cost=edge_costs(r.surface, compactness))
    chosen = value[np.arange(len(done.patch)), direction[done.patch]]
    return float(chosen.sum() / r.surface.areas.sum())


def polish_labels(surface: Surface, labels: Sequence[Direction], target: np.ndarray | None = None,
                  compactness: float = COMPACTNESS) -> tuple[tuple[Direction, ...], int]:
    """A labelling with the same charts, boundaries and corners as ``labels`` (so valid exactly
    when it is), polished; and the number of triangles moved."""
    index = label_indices(labels)
    chart = chart_indices(surface, index)
    direction = np.zeros(int(chart.max()) + 1, dtype=np.int64)
    direction[chart] = index
    done = polish(surface.triangles, worth(surface, target), chart, direction,
                  edge_cost=edge_costs(surface, compactness))
    return tuple(Direction(int(d)) for d in direction[done.patch]), done.moves
