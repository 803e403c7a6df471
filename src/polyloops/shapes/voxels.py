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

Cell = tuple[int, int, int]  # a unit cube by its least corner
Position = tuple[int, int, int]  # a point of Z^3


def _step(cell: Cell, n: Direction) -> Cell:
    v = n.vector
    return (cell[0] + v[0], cell[1] + v[1], cell[2] + v[2])


class VoxelError(PolyloopsError, ValueError):
    """A set of cubes whose boundary is not a polycube."""


def _face_corners(cell: Cell, normal: Direction) -> list[Position]:
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


def _boundary_faces(occupied: set[Cell]) -> list[tuple[Cell, list[Position]]]:
    """Each exposed unit square with the cube it bounds, counter-clockwise from outside."""
    faces: list[tuple[Cell, list[Position]]] = []
    for cell in sorted(occupied):
        for n in Direction:
            if _step(cell, n) not in occupied:
                faces.append((cell, _face_corners(cell, n)))
    return faces


def _corner_classes(faces: list[tuple[Cell, list[Position]]]) -> list[list[tuple[int, int]]]:
    """The corners of the split surface: classes of face slots ``(face, i)`` glued together.

    Faces glue along each edge: two faces glue; four (two cubes touching only along the edge)
    glue in pairs belonging to the same cube, which splits the surface there."""
    by_edge: dict[frozenset[Position], list[tuple[int, int]]] = defaultdict(list)
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
    return sorted(classes.values(), key=lambda cls: (faces[cls[0][0]][1][cls[0][1]], min(cls)))


def _meets_itself(faces: list[tuple[Cell, list[Position]]], cls: list[tuple[int, int]]) -> bool:
    """Whether two edges of one corner run in the same direction.  A corner where ``k`` faces
    meet has ``k`` edges, each the side of two of its faces: so ``k`` distinct directions."""
    directions = set()
    for f, i in cls:
        corners = faces[f][1]
        for other in (corners[(i + 1) % 4], corners[(i - 1) % 4]):
            directions.add(tuple(b - a for a, b in zip(corners[i], other, strict=True)))
    return len(directions) != len(cls)


def _bad_corners(occupied: set[Cell]) -> list[Position]:
    """The positions where the split boundary of ``occupied`` meets itself."""
    faces = _boundary_faces(occupied)
    return sorted({faces[cls[0][0]][1][cls[0][1]] for cls in _corner_classes(faces)
                   if _meets_itself(faces, cls)})


def _around(position: Position) -> list[Cell]:
    """The eight cells that have ``position`` as a corner."""
    x, y, z = position
    return [(x - a, y - b, z - c) for a in (0, 1) for b in (0, 1) for c in (0, 1)]


def _face_components(cells: set[Cell]) -> list[list[Cell]]:
    """The classes of ``cells`` joined by shared faces, each sorted, largest first."""
    parts: DisjointSets[Cell] = DisjointSets(cells)
    for cell in cells:
        for n in (Direction.PX, Direction.PY, Direction.PZ):
            if _step(cell, n) in cells:
                parts.union(cell, _step(cell, n))
    return sorted((sorted(group) for group in parts.to_sets()), key=lambda g: (-len(g), g[0]))


def _cavities(occupied: set[Cell]) -> list[list[Cell]]:
    """The empty cells enclosed by the cubes: classes of empty cells of the bounding box (grown
    by one) joined by faces that do not reach the box's border."""
    lo = [min(c[k] for c in occupied) - 1 for k in range(3)]
    hi = [max(c[k] for c in occupied) + 1 for k in range(3)]
    empty = {(x, y, z) for x in range(lo[0], hi[0] + 1) for y in range(lo[1], hi[1] + 1)
             for z in range(lo[2], hi[2] + 1)} - occupied
    return [group for group in _face_components(empty)
            if not any(c[k] in (lo[k], hi[k]) for c in group for k in range(3))]


def _cells(cells: list[Cell], limit: int = 3) -> str:
    shown = ", ".join(str(c) for c in cells[:limit])
    return shown + (f" and {len(cells) - limit} more" if len(cells) > limit else "")


def _repairs(occupied: set[Cell], position: Position) -> list[str]:
    """The single cubes that, added or removed among the eight around ``position``, make the
    surface there a polycube corner (judged on those eight cells alone)."""
    local = {c for c in _around(position) if c in occupied}
    mends = [cell for cell in sorted(_around(position))
             if local ^ {cell} and position not in _bad_corners(local ^ {cell})]
    # filling a gap is what one usually means: additions first
    mends.sort(key=lambda cell: cell in local)
    return [f"{'remove' if cell in local else 'add'} the cube {cell}" for cell in mends]


def diagnose_voxels(cells: Iterable[Cell]) -> str | None:
    """Why the split boundary of a set of cubes is not a polycube, naming cubes and positions and
    suggesting a repair; ``None`` when it is one.

    >>> print(diagnose_voxels([(0, 0, 0), (1, 1, 0)]))  # doctest: +NORMALIZE_WHITESPACE
    the cubes form 2 pieces joined by no face (one holds (0, 0, 0), another (1, 1, 0)): join
    them with cubes that share faces, or give each piece alone
    >>> block = [(x, y, z) for x in range(3) for y in range(3) for z in range(3)]
    >>> print(diagnose_voxels([c for c in block if c != (1, 1, 1)]))  # doctest: +NORMALIZE_WHITESPACE
    the cubes enclose a cavity of 1 empty cell, (1, 1, 1), whose wall would be a second surface:
    fill it, or open it to the outside
    >>> diagnose_voxels([(0, 0, 0), (1, 0, 0)]) is None
    True
    """
    occupied = {(int(c[0]), int(c[1]), int(c[2])) for c in cells}
    if not occupied:
        return "no cubes"
    pieces = _face_components(occupied)
    if len(pieces) > 1:
        return (f"the cubes form {len(pieces)} pieces joined by no face (one holds {pieces[0][0]}, "
                f"another {pieces[1][0]}): join them with cubes that share faces, or give each "
                "piece alone")
    cavities = _cavities(occupied)
    if cavities:
        first = cavities[0]
        count = f"{len(cavities)} cavities; the first has" if len(cavities) > 1 else "a cavity of"
        noun = "empty cell" if len(first) == 1 else "empty cells"
        return (f"the cubes enclose {count} {len(first)} {noun}, {_cells(first)}, whose wall would "
                "be a second surface: fill it, or open it to the outside")
    bad = _bad_corners(occupied)
    if bad:
        position = bad[0]
        meeting = [c for c in sorted(_around(position)) if c in occupied]
        repairs = _repairs(occupied, position)
        more = f" (and at {len(bad) - 1} more)" if len(bad) > 1 else ""
        advice = f": {' or '.join(repairs[:3])} to mend it" if repairs else ""
        return (f"the surface meets itself at the position {position}{more}, where the cubes "
                f"{_cells(meeting, 8)} meet{advice}")
    return None


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
        When there are no cubes, or the split surface is still not a polycube; the message names
        the cubes and positions at fault and suggests a repair (:func:`diagnose_voxels`).

    >>> q = polycube_from_voxels([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    >>> q.map.num_corners, q.map.num_faces, q.genus
    (16, 14, 0)
    """
    occupied = {(int(c[0]), int(c[1]), int(c[2])) for c in cells}
    if not occupied:
        raise VoxelError("no cubes")
    faces = _boundary_faces(occupied)
    classes = _corner_classes(faces)
    corner_id: dict[tuple[int, int], int] = {}
    positions = []
    for k, cls in enumerate(classes):
        positions.append(faces[cls[0][0]][1][cls[0][1]])
        for slot in cls:
            corner_id[slot] = k
    face_list = [[corner_id[(f, i)] for i in range(4)] for f in range(len(faces))]
    if any(_meets_itself(faces, cls) for cls in classes):
        raise VoxelError(diagnose_voxels(occupied) or "the split surface meets itself")
    try:
        q = Polycube(HalfEdgeMap.from_faces(face_list), tuple(positions))
    except MapError as err:
        raise VoxelError(diagnose_voxels(occupied)
                         or f"the boundary of these cubes is not one closed surface: {err}") from None
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
