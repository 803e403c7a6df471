"""Triangle meshes of smooth shapes, for trying the segmentation constructor: an octahedron,
spheres and ellipsoids from a subdivided octahedron, tori, each as ``(points, triangles)`` with
triangles counter-clockwise seen from outside; ``jitter`` moves the points by a seeded random
amount.

>>> points, triangles = sphere(2)
>>> len(points), len(triangles)
(66, 128)
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

__all__ = ["MESH_EXAMPLES", "ellipsoid", "octahedron", "sphere", "torus"]


def octahedron() -> tuple[np.ndarray, np.ndarray]:
    """The regular octahedron with vertices at distance 1 on the axes."""
    points = np.array([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)], dtype=float)
    triangles = np.array([(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4),
                          (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)])
    return points, triangles


def _subdivide(points: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each triangle into four, by the midpoints of its edges (shared between neighbours)."""
    index: dict[tuple[int, int], int] = {}
    pts = [tuple(p) for p in points]

    def mid(a: int, b: int) -> int:
        key = (min(a, b), max(a, b))
        if key not in index:
            index[key] = len(pts)
            pts.append(tuple((points[a] + points[b]) / 2))
        return index[key]

    out = []
    for a, b, c in triangles.tolist():
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return np.array(pts, dtype=float), np.array(out)


def sphere(level: int = 3, jitter: float = 0.0, seed: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """The unit sphere: the octahedron subdivided ``level`` times, its points pushed onto the
    sphere (and moved radially by up to ``jitter``)."""
    points, triangles = octahedron()
    for _ in range(level):
        points, triangles = _subdivide(points, triangles)
    points = points / np.linalg.norm(points, axis=1)[:, None]
    if jitter:
        rng = np.random.default_rng(seed)
        points = points * (1 + jitter * rng.uniform(-1, 1, len(points)))[:, None]
    return points, triangles


def ellipsoid(a: float, b: float, c: float, level: int = 3, jitter: float = 0.0, seed: int = 0
              ) -> tuple[np.ndarray, np.ndarray]:
    """The ellipsoid with semi-axes ``a``, ``b``, ``c`` along X, Y, Z (a stretched sphere)."""
    points, triangles = sphere(level, jitter, seed)
    return points * np.array([a, b, c]), triangles


def torus(major: float = 2.0, minor: float = 0.7, rings: int = 32, sides: int = 16
          ) -> tuple[np.ndarray, np.ndarray]:
    """A torus round the Z axis: ``rings`` steps round the hole, ``sides`` round the tube."""
    u = np.arange(rings) * 2 * np.pi / rings
    v = np.arange(sides) * 2 * np.pi / sides
    uu, vv = np.meshgrid(u, v, indexing="ij")
    points = np.stack([(major + minor * np.cos(vv)) * np.cos(uu), (major + minor * np.cos(vv)) * np.sin(uu),
                       minor * np.sin(vv)], axis=-1).reshape(-1, 3)
    triangles = []
    for i in range(rings):
        for j in range(sides):
            a, b = i * sides + j, ((i + 1) % rings) * sides + j
            c, d = ((i + 1) % rings) * sides + (j + 1) % sides, i * sides + (j + 1) % sides
            triangles += [(a, b, c), (a, c, d)]
    return points, np.array(triangles)


# Meshes the command line names as ``example:NAME`` (made, not read: no file is bundled).
MESH_EXAMPLES: dict[str, Callable[[], tuple[np.ndarray, np.ndarray]]] = {
    "sphere": lambda: sphere(4),
    "egg": lambda: ellipsoid(1.6, 1.0, 0.8, level=4, jitter=0.01, seed=1),
    "pebble": lambda: ellipsoid(2.2, 1.3, 0.6, level=5, jitter=0.02, seed=2),
    "torus": lambda: torus(2.0, 0.7, 64, 32),
}
