"""Polycube-like heights of a surface: where plane sections of the surface itself fail.

A plane section of a jug's thin handle, or of an arm tilted between two axes, falls into many
small curves, and no choice of them makes a loop structure.  The surface is deformed towards a
polycube instead (the classic normal-alignment deformation): each triangle is turned so that
its normal becomes the signed axis nearest it, and the points are solved for, in the least
squares sense, from the turned edges (a Poisson problem: one sparse Laplacian, factored once);
a few rounds flatten the surface into axis-aligned faces.  The deformed points are *heights*
(:mod:`~polyloops.segment.refine`): the planes cut them, so each loop is a level set of a
deformed coordinate, a closed curve of the surface all the same, while everything measured
stays on the surface's own points.  Nothing here needs the deformation to be injective: a level
set of a function linear on each triangle is a union of closed curves whatever it does, and
every structure read off the surface is checked as before.

>>> from polyloops.shapes.meshes import torus
>>> from polyloops.segment.surface import surface_of
>>> s = surface_of(*torus(2.0, 0.7, 24, 12))
>>> h = polycube_heights(s)
>>> before, after = axis_alignment(s.points, s.triangles), axis_alignment(h, s.triangles)
>>> h.shape == s.points.shape, before < 0.9 < 0.99 < after
(True, True)
"""

from __future__ import annotations

import numpy as np
from scipy.sparse import csc_matrix, diags
from scipy.sparse.linalg import splu

from polyloops.segment.surface import Surface

__all__ = ["ROUNDS", "axis_alignment", "polycube_heights"]

ROUNDS = 10  # turns and solves; the alignment stops improving much after 5 to 10 on the shared meshes


def _unit_normals(points: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    tri = points[triangles]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = np.linalg.norm(cross, axis=1)
    return cross / np.maximum(area, 1e-300)[:, None], area


def axis_alignment(points: np.ndarray, triangles: np.ndarray) -> float:
    """The area-weighted mean of the largest ``|n_i|`` over the triangles' unit normals: 1 on a
    polycube, 1/sqrt(3) at worst."""
    n, area = _unit_normals(points, triangles)
    return float((np.abs(n).max(axis=1) * area).sum() / max(area.sum(), 1e-300))


def _turns(n: np.ndarray, target: np.ndarray) -> np.ndarray:
    """Per row, the rotation taking unit ``n`` to unit ``target`` by the shortest arc
    (Rodrigues; the targets are the nearest signed axes, so never opposite)."""
    v = np.cross(n, target)
    c = (n * target).sum(axis=1)
    k = np.zeros((len(n), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -v[:, 2], v[:, 1], -v[:, 0]
    k[:, 1, 0], k[:, 2, 0], k[:, 2, 1] = v[:, 2], -v[:, 1], v[:, 0]
    factor = 1.0 / np.maximum(1.0 + c, 1e-12)  # (1 - c) / |v|^2 = 1 / (1 + c)
    return np.eye(3)[None] + k + k @ k * factor[:, None, None]


def polycube_heights(surface: Surface, rounds: int = ROUNDS) -> np.ndarray:
    """Per vertex of ``surface``, its place on a polycube-like deformation of it (see the
    module docstring); deterministic, and the surface's centroid of vertices is kept."""
    points, triangles = surface.points, surface.triangles
    n = len(points)
    edges = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    owner = np.tile(np.arange(len(triangles)), 3)
    m = len(edges)
    rows = np.repeat(np.arange(m), 2)
    d = csc_matrix((np.tile([-1.0, 1.0], m), (rows, edges.ravel())), shape=(m, n))
    # the edge Laplacian is singular (a translation is free): pin vertex 0, then re-centre
    pin = np.zeros(n)
    pin[0] = 1.0
    lap = (d.T @ d + diags(pin)).tocsc()
    solve = splu(lap).solve
    x = points.astype(float).copy()
    centre = x.mean(axis=0)
    for _ in range(rounds):
        normals, area = _unit_normals(x, triangles)
        nearest = np.argmax(np.abs(normals), axis=1)
        target = np.zeros_like(normals)
        target[np.arange(len(triangles)), nearest] = np.sign(normals[np.arange(len(triangles)), nearest])
        turn = _turns(normals, target)
        turn[area <= 0] = np.eye(3)  # a degenerate triangle keeps its edges
        wanted = np.einsum("kij,kj->ki", turn[owner], x[edges[:, 1]] - x[edges[:, 0]])
        x = np.column_stack([solve(np.asarray(d.T @ wanted[:, a]) + pin * x[0, a]) for a in range(3)])
        x += centre - x.mean(axis=0)
    return x
