"""Labellings of a surface and their fidelity: the naive one (each triangle its closest direction,
whose fidelity bounds every labelling's) and the graph-cut one (a Potts model), which other
methods start from and ``benchmarks/segment.py`` compares ``polyloops segment`` with.

The graph-cut labelling minimises

    sum over triangles t of  area_t (1 - n_t . d(L_t))  +  c * sum over edges st with L_s != L_t of  length_st

(fidelity, and compactness with weight ``c`` in units of the mean triangle area over the mean
edge length), by alpha-expansion: for each label alpha in turn, the triangles that switch to
alpha are a minimum cut (scipy's maximum flow), until no expansion lowers the energy.  Neither
labelling is certified: ``polyloops segmentation`` judges them.

>>> from polyloops.shapes.meshes import ellipsoid
>>> from polyloops.segment.surface import surface_of
>>> s = surface_of(*ellipsoid(2, 1, 0.7, level=3))
>>> cut = graphcut_labels(s)
>>> len(set(naive_labels(s))) == 6 and energy(s, cut) <= energy(s, naive_labels(s))
True
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.sparse import coo_matrix, csr_matrix
from scipy.sparse.csgraph import breadth_first_order, connected_components, maximum_flow

from polyloops.core.directions import Direction
from polyloops.core.polycube import Polycube
from polyloops.segment.surface import Surface

__all__ = ["DIRECTION_VECTORS", "chart_indices", "energy", "face_directions", "fidelity", "graphcut_labels",
           "label_indices", "label_vectors", "naive_fidelity", "naive_label_indices", "naive_labels"]

# the unit vector of each Direction, in its order (+X, -X, +Y, -Y, +Z, -Z)
DIRECTION_VECTORS = np.array([np.eye(3)[d // 2] * (1 if d % 2 == 0 else -1) for d in range(6)])
SCALE = 10_000  # capacities are integers: costs in units of 1 / SCALE


def naive_labels(s: Surface) -> tuple[Direction, ...]:
    """Each triangle labelled by the direction closest to its normal."""
    return tuple(Direction(int(k)) for k in naive_label_indices(s))


def naive_label_indices(s: Surface) -> np.ndarray:
    """:func:`naive_labels` as an array of the directions' indices."""
    return (s.normals @ DIRECTION_VECTORS.T).argmax(axis=1)


def chart_indices(s: Surface, labels: np.ndarray) -> np.ndarray:
    """Per triangle, its chart (a maximal edge-connected set of triangles with one label, given
    per triangle as a direction index), numbered from 0."""
    pairs, _ = s.adjacency
    same = labels[pairs[:, 0]] == labels[pairs[:, 1]]
    m = len(s.triangles)
    graph = coo_matrix((np.ones(int(same.sum())), (pairs[same, 0], pairs[same, 1])), shape=(m, m))
    return connected_components(graph, directed=False)[1]


def face_directions(q: Polycube) -> np.ndarray:
    """Per face of ``q``, its outward normal as a direction's index.

    Raises
    ------
    ValueError
        When a face is not axis-parallel.
    """
    out = np.zeros(len(q.faces), dtype=np.int64)
    for f in range(len(q.faces)):
        d = q.face_normal(f)
        if d is None:
            raise ValueError(f"face {f} of the polycube is not axis-parallel")
        out[f] = int(d)
    return out


def label_indices(labels: Sequence[Direction]) -> np.ndarray:
    """The labels as an array of the directions' indices (0..5)."""
    return np.array([int(d) for d in labels], dtype=np.int64)


def label_vectors(labels: Sequence[Direction]) -> np.ndarray:
    """Per label, its direction's unit vector (one row each)."""
    return DIRECTION_VECTORS[label_indices(labels)]


def fidelity(surface: Surface, labels: Sequence[Direction], target: np.ndarray | None = None) -> float:
    """The area-weighted mean of ``n . label`` over the triangles; with ``target`` (a unit
    vector per triangle, such as a guide's labels) the mean of ``target . label`` instead."""
    vectors = label_vectors(labels)
    wanted = surface.normals if target is None else target
    return float((surface.areas * (wanted * vectors).sum(axis=1)).sum() / surface.areas.sum())


def naive_fidelity(surface: Surface) -> float:
    """The fidelity of the naive labelling: the upper bound of every labelling's fidelity."""
    return float((surface.areas * np.abs(surface.normals).max(axis=1)).sum() / surface.areas.sum())


def _edges(s: Surface) -> tuple[np.ndarray, np.ndarray]:
    """The pairs of triangles sharing an edge, and the edges' lengths."""
    pairs, ends = s.adjacency
    return pairs, np.linalg.norm(s.points[ends[:, 0]] - s.points[ends[:, 1]], axis=1)


def _costs(s: Surface, compactness: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    unary = s.areas[:, None] * (1 - s.normals @ DIRECTION_VECTORS.T) / s.areas.mean()
    pairs, lengths = _edges(s)
    return unary, pairs, compactness * lengths / lengths.mean()


def energy(s: Surface, labels: tuple[Direction, ...] | list[Direction], compactness: float = 1.0) -> float:
    """The graph-cut energy of a labelling (the units of :func:`graphcut_labels`)."""
    unary, pairs, weights = _costs(s, compactness)
    lab = label_indices(labels)
    return float(unary[np.arange(len(lab)), lab].sum() + weights[lab[pairs[:, 0]] != lab[pairs[:, 1]]].sum())


def graphcut_labels(s: Surface, compactness: float = 1.0, rounds: int = 5) -> tuple[Direction, ...]:
    """The Potts labelling by alpha-expansion from the naive one (at most ``rounds`` sweeps
    over the six labels)."""
    unary, pairs, weights = _costs(s, compactness)
    lab = naive_label_indices(s)
    best = energy(s, tuple(Direction(int(k)) for k in lab), compactness)
    for _ in range(rounds):
        improved = False
        for alpha in range(6):
            proposal = _expand(lab, alpha, unary, pairs, weights)
            e = float(unary[np.arange(len(lab)), proposal].sum()
                      + weights[proposal[pairs[:, 0]] != proposal[pairs[:, 1]]].sum())
            if e < best - 1e-9:
                lab, best, improved = proposal, e, True
        if not improved:
            break
    return tuple(Direction(int(k)) for k in lab)


def _expand(lab: np.ndarray, alpha: int, unary: np.ndarray, pairs: np.ndarray, weights: np.ndarray
            ) -> np.ndarray:
    """The best labelling that only switches triangles to ``alpha`` (a minimum cut).

    Node ``t`` on the source side keeps its label, on the sink side takes ``alpha``.  A pairwise
    Potts term ``E(x_s, x_t)`` with ``A = E00, B = E01, C = E10, D = E11`` adds ``C - A`` to ``s``
    taking alpha, ``D - C`` to ``t`` taking alpha, and an arc ``s -> t`` of ``B + C - A - D``."""
    m = len(lab)
    keep_cost = unary[np.arange(m), lab].copy()  # paid when a node keeps its label
    take_cost = unary[:, alpha].copy()  # paid when it takes alpha
    s_, t_ = pairs[:, 0], pairs[:, 1]
    ls, lt = lab[s_], lab[t_]
    a_ = np.where(ls != lt, weights, 0.0)
    b_ = np.where(ls != alpha, weights, 0.0)  # s keeps, t takes alpha
    c_ = np.where(lt != alpha, weights, 0.0)  # s takes alpha, t keeps
    d_ = np.zeros_like(weights)
    for node, delta in ((s_, c_ - a_), (t_, d_ - c_)):
        np.add.at(take_cost, node, np.maximum(delta, 0))
        np.add.at(keep_cost, node, np.maximum(-delta, 0))
    arc = b_ + c_ - a_ - d_
    source, sink = m, m + 1
    rows = np.concatenate([np.full(m, source), np.arange(m), s_, t_])
    cols = np.concatenate([np.arange(m), np.full(m, sink), t_, s_])
    caps = np.concatenate([take_cost, keep_cost, arc, np.zeros_like(arc)])
    caps = np.round(caps * SCALE).astype(np.int64)
    graph = csr_matrix((caps, (rows, cols)), shape=(m + 2, m + 2))
    graph.sum_duplicates()
    graph = graph.astype(np.int32)
    flow = maximum_flow(graph, source, sink).flow
    residual = graph - flow
    residual.data = np.maximum(residual.data, 0)
    residual.eliminate_zeros()
    reached = breadth_first_order(residual, source, directed=True, return_predecessors=False)
    on_source = np.zeros(m + 2, dtype=bool)
    on_source[reached] = True
    out = lab.copy()
    out[~on_source[:m]] = alpha
    return out
