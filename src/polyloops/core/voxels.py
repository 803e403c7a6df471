"""Polycubes as unions of unit cubes.

The boundary of a face-connected set of unit cubes is a quad mesh; where two
cubes touch only along an edge or at a corner, the surface is split there, so
each cube keeps its own sheet.  Shapes whose boundary is still not a
polycube after splitting (a void inside, or a corner where a split sheet
meets itself) raise :class:`VoxelError`.

>>> q = polycube_from_voxels([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
>>> q.map.num_corners, q.map.num_faces, q.genus
(16, 14, 0)
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable

from polyloops.core.directions import Direction
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import HalfEdgeMap, MapError
from polyloops.core.polycube import Polycube

Cell = tuple[int, int, int]


class VoxelError(PolyloopsError, ValueError):
    """A set of cubes whose boundary is not a polycube."""


def _face_corners(cell: Cell, normal: Direction) -> list[tuple[int, int, int]]:
    """The unit square of ``cell`` facing ``normal``, counter-clockwise from outside."""
    a = int(normal.axis)
    b, c = (a + 1) % 3, (a + 2) % 3
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]
    if normal.sign < 0:
        square.reverse()
    out = []
    for sb, sc in square:
        p = list(cell)
        p[a] += 1 if normal.sign > 0 else 0
        p[b] += sb
        p[c] += sc
        out.append((p[0], p[1], p[2]))
    return out


def polycube_from_voxels(cells: Iterable[Cell]) -> Polycube:
    """The boundary polycube of a set of unit cubes (cell ``(i, j, k)`` spans ``[i, i+1]`` and so
    on).  Where cubes touch only along an edge or at a corner, the surface is split there.

    Parameters
    ----------
    cells:
        Integer triples; duplicates are ignored.

    Returns
    -------
    Polycube
        Outward oriented.

    Raises
    ------
    VoxelError
        When there are no cubes, or the split surface is still not a polycube.

    >>> q = polycube_from_voxels([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    >>> q.map.num_corners, q.map.num_faces, q.genus
    (16, 14, 0)
    """
    occupied = {(int(c[0]), int(c[1]), int(c[2])) for c in cells}
    if not occupied:
        raise VoxelError("no cubes")
    faces: list[tuple[Cell, list[tuple[int, int, int]]]] = []
    for cell in sorted(occupied):
        for n in Direction:
            v = n.vector
            if (cell[0] + v[0], cell[1] + v[1], cell[2] + v[2]) not in occupied:
                faces.append((cell, _face_corners(cell, n)))

    # Glue faces along each edge: two faces glue; four (two cubes touching only
    # along the edge) glue in pairs belonging to the same cube.
    by_edge: dict[frozenset, list[tuple[int, int]]] = defaultdict(list)
    for f, (_, corners) in enumerate(faces):
        for i in range(4):
            by_edge[frozenset((corners[i], corners[(i + 1) % 4]))].append((f, i))
    slots: DisjointSets[tuple[int, int]] = DisjointSets()

    for sides in by_edge.values():
        if len(sides) == 2:
            pairs = [tuple(sides)]
        else:
            by_cell: dict[Cell, list[tuple[int, int]]] = defaultdict(list)
            for s in sides:
                by_cell[faces[s[0]][0]].append(s)
            pairs = [tuple(v) for v in by_cell.values()]
        for (f, i), (g, j) in pairs:
            # Face f runs corners[i] -> corners[i+1]; face g runs the other way.
            slots.union((f, i), (g, (j + 1) % 4))
            slots.union((f, (i + 1) % 4), (g, j))

    classes: dict[tuple[int, int], list[tuple[int, int]]] = defaultdict(list)
    for f in range(len(faces)):
        for i in range(4):
            classes[slots[(f, i)]].append((f, i))
    ordered = sorted(classes.values(), key=lambda cls: (faces[cls[0][0]][1][cls[0][1]], min(cls)))
    corner_id: dict[tuple[int, int], int] = {}
    positions = []
    for k, cls in enumerate(ordered):
        positions.append(faces[cls[0][0]][1][cls[0][1]])
        for slot in cls:
            corner_id[slot] = k
    face_list = [[corner_id[(f, i)] for i in range(4)] for f in range(len(faces))]
    try:
        q = Polycube(HalfEdgeMap.from_faces(face_list), tuple(positions))
    except MapError as err:
        raise VoxelError(f"the boundary of these cubes is not one closed surface: {err}") from None
    for c in range(q.map.num_corners):
        dirs = q.corner_directions(c)
        if len(set(dirs)) != len(dirs):
            raise VoxelError(f"the split surface meets itself at position {positions[c]}")
    return q


def voxels_from_grid(grid: object) -> list[Cell]:
    """Cubes from a 3D array: the indices ``(i, j, k)`` of its true (non-zero) entries.

    >>> import numpy as np
    >>> g = np.zeros((2, 2, 1), dtype=bool); g[0, 0, 0] = g[1, 0, 0] = True
    >>> voxels_from_grid(g)
    [(0, 0, 0), (1, 0, 0)]
    """
    import numpy as np

    array = np.asarray(grid)
    if array.ndim != 3 or array.dtype.kind not in "biu":
        raise ValueError(f"expected a 3D array of booleans or integers, not {array.ndim}D {array.dtype}")
    cells = [(int(i), int(j), int(k)) for i, j, k in np.argwhere(array)]
    if not cells:
        raise ValueError("no cubes: the grid is empty")
    return cells
