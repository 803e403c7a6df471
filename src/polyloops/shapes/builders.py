"""Small structures built by rule: boxes, flat tori, pillows.

>>> box(2, 1, 1).map.num_faces
10
>>> torus_grid(3, 4).genus
1
"""

from __future__ import annotations

from polyloops.core.directions import Axis, Direction
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.shapes.voxels import polycube_from_voxels


def box(a: int, b: int, c: int) -> Polycube:
    """The ``a x b x c`` box made of unit cubes."""
    return polycube_from_voxels([(i, j, k) for i in range(a) for j in range(b) for k in range(c)])


def ring(n: int = 3, height: int = 1, hole: Axis = Axis.Z) -> Polycube:
    """A square ring: the ``n x n x height`` box without its central column (genus 1), its
    hole along ``hole`` (the ring lies across that axis, ``height`` cubes thick along it).

    >>> [ring(hole=a).bounding_box()[1] for a in Axis]
    [(1, 3, 3), (3, 1, 3), (3, 3, 1)]
    """
    def cell(i: int, j: int, k: int) -> tuple[int, int, int]:
        # (i, j) across the hole, k along it
        return {Axis.X: (k, i, j), Axis.Y: (j, k, i), Axis.Z: (i, j, k)}[hole]

    return polycube_from_voxels([
        cell(i, j, k) for i in range(n) for j in range(n) for k in range(height)
        if not (0 < i < n - 1 and 0 < j < n - 1)
    ])


def torus_grid(n: int, m: int) -> LoopStructure:
    """The flat ``n x m`` torus grid (``n, m >= 3``): edges ``+X`` along i, ``+Y`` along j.

    Its X- and Y-graphs are cycles, so it is not a polycube loop structure.
    """
    if n < 3 or m < 3:
        raise ValueError("a torus grid needs n, m >= 3 so that no two corners share two edges")

    def v(i: int, j: int) -> int:
        return (i % n) * m + (j % m)

    faces = [[v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)] for i in range(n) for j in range(m)]
    labels = {}
    for i in range(n):
        for j in range(m):
            labels[(v(i, j), v(i + 1, j))] = Direction.PX
            labels[(v(i, j), v(i, j + 1))] = Direction.PY
    return LoopStructure.from_edge_labels(faces, labels)


def pillow() -> LoopStructure:
    """Two quads glued along their boundary: every region is bounded by two segments."""
    faces = [[0, 1, 2, 3], [3, 2, 1, 0]]
    labels = {(0, 1): Direction.PX, (3, 2): Direction.PX, (1, 2): Direction.PY, (0, 3): Direction.PY}
    return LoopStructure.from_edge_labels(faces, labels)


def self_crossing() -> LoopStructure:
    """A sphere quadrangulation (12 corners) one of whose two loops crosses itself.

    The map is the smallest simple quadrangulation of the sphere with minimum
    degree 3 that has a self-crossing loop; the self-crossing loop is labelled
    X and the other Y.
    """
    faces = [[0, 1, 7, 2], [0, 2, 8, 3], [0, 3, 9, 4], [0, 4, 5, 1], [1, 5, 10, 6],
             [1, 6, 11, 7], [2, 7, 11, 8], [3, 8, 11, 9], [4, 9, 10, 5], [6, 10, 9, 11]]
    from polyloops.core.halfedge import HalfEdgeMap

    m = HalfEdgeMap.from_faces(faces)
    axes = tuple(Axis.X if lp.self_crossings else Axis.Y for lp in m.loop_system.loops)
    return LoopStructure(m, axes, tuple(1 for _ in axes))


def double_plus_x() -> LoopStructure:
    """``box-2x1x1`` with its first X-loop flipped: the middle corners get two ``+X`` edges."""
    q = box(2, 1, 1)
    ls = q.dualize()
    m = ls.map
    first = next(lp.id for lp in ls.loops if ls.axes[lp.id] == Axis.X
                 and {q.positions[m.origin(lp.darts[0])][0], q.positions[m.target(lp.darts[0])][0]} == {0, 1})
    return ls.flipped(first)


def dented_slab() -> Polycube:
    """A 3x3x1 slab with a bump on top, its bump's Z-loop flipped: the bump becomes a dent whose
    floor lies in the plane of the slab's bottom, so the surface meets itself (Definition 1
    allows self-intersecting polycubes)."""
    q = polycube_from_voxels([(i, j, 0) for i in range(3) for j in range(3)] + [(1, 1, 1)])
    ls = q.dualize()
    top = max(p[2] for p in q.positions)
    m = ls.map
    bump = next(lp.id for lp in ls.loops if ls.axes[lp.id] == Axis.Z
                and top in {q.positions[m.origin(lp.darts[0])][2], q.positions[m.target(lp.darts[0])][2]})
    return ls.flipped(bump).primalize()
