"""Polycubes: a quad map with an integer position per corner (Definition 1).

>>> from polyloops.io.examples import load_example
>>> box = load_example("box-2x1x1")
>>> box.map.num_corners, box.map.num_faces, box.bounding_box()
(12, 10, ((0, 0, 0), (2, 1, 1)))
>>> str(box.direction(box.map.dart(0, 1)))
'+Z'
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from polyloops.core.directions import Direction
from polyloops.core.halfedge import FaceListError, HalfEdgeMap

if TYPE_CHECKING:
    from polyloops.core.structure import LoopStructure

Position = tuple[int, int, int]


def signed_volume(faces: Sequence[Sequence[int]], positions: Sequence[Sequence[int]]) -> float:
    """The volume a closed surface of polygons encloses, positive when its faces are
    counter-clockwise seen from outside and negative when it is inside out (divergence
    theorem: a sum over faces of a corner's coordinates dotted with the face's vector area).

    >>> signed_volume([[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]],
    ...               [(0, 0, 0), (0, 1, 0), (1, 0, 0), (0, 0, 1)])  # a tetrahedron
    0.16666666666666666
    """
    # The array path multiplies in int64: only for coordinates whose triple products stay exact.
    from polyloops.core.arrays import use_arrays

    if use_arrays(4 * len(faces)) and set(map(len, faces)) == {4} and _small(positions):
        from itertools import chain

        import numpy as np

        from polyloops.core.arrays import points_array

        corners = np.fromiter(chain.from_iterable(faces), dtype=np.int64, count=4 * len(faces))
        return quad_volume(corners.reshape(-1, 4), points_array(positions))
    total = 0
    for face in faces:
        p = [positions[c] for c in face]
        area = [0, 0, 0]  # twice the vector area of the polygon
        for i in range(len(p)):
            a, b = p[i], p[(i + 1) % len(p)]
            area[0] += a[1] * b[2] - a[2] * b[1]
            area[1] += a[2] * b[0] - a[0] * b[2]
            area[2] += a[0] * b[1] - a[1] * b[0]
        total += sum(p[0][k] * area[k] for k in range(3))
    try:
        return total / 6  # exact integers so far; the float keeps at least the sign
    except OverflowError:  # integer coordinates beyond 10^100, say: only the sign is representable
        return math.inf if total > 0 else -math.inf


def _small(positions: Sequence[Sequence[int]], bound: int = 2**18) -> bool:
    return all(-bound < c < bound for p in positions for c in p)


def quad_volume(corners, points) -> float:
    """:func:`signed_volume` of quads given as arrays: corner ids ``(F, 4)`` and positions
    ``(n, 3)``."""
    import numpy as np

    p = points[corners]  # (F, 4, 3)
    a, b, c, d = p[:, 0], p[:, 1], p[:, 2], p[:, 3]
    area = np.cross(a, b) + np.cross(b, c) + np.cross(c, d) + np.cross(d, a)  # twice the vector area
    return float(np.einsum("fk,fk->", a, area)) / 6


@dataclass(frozen=True, eq=False)
class Polycube:
    """A closed oriented quad map with corner positions in Z^3; immutable.

    The constructor does not check Definition 1; use
    :func:`polyloops.verify.check_polycube` for that.
    """

    map: HalfEdgeMap
    positions: tuple[Position, ...]

    def __post_init__(self) -> None:
        if set(map(len, self.map.faces)) != {4}:
            bad = [f for f, face in enumerate(self.map.faces) if len(face) != 4]
            raise FaceListError(f"face {bad[0]} has {len(self.map.faces[bad[0]])} corners; "
                                "polycube faces are quads")
        if len(self.positions) != self.map.num_corners:
            raise FaceListError(f"{len(self.positions)} positions for {self.map.num_corners} corners")

    @classmethod
    def from_faces(cls, faces: Iterable[Sequence[int]],
                   positions: Iterable[Sequence[int]]) -> Polycube:
        pos = tuple((int(p[0]), int(p[1]), int(p[2])) for p in positions)
        return cls(HalfEdgeMap.from_faces(faces), pos)

    @property
    def faces(self) -> tuple[tuple[int, ...], ...]:
        """The faces as corner lists, counter-clockwise seen from outside."""
        return self.map.faces

    @property
    def genus(self) -> int:
        """The genus of its surface."""
        return self.map.genus

    def direction(self, d: int) -> Direction | None:
        """Direction of dart ``d``, or ``None`` unless its ends differ in exactly one coordinate."""
        m = self.map
        return Direction.between(self.positions[m.origin(d)], self.positions[m.target(d)])

    def corner_directions(self, corner: int) -> tuple[Direction | None, ...]:
        """Directions of the edges at a corner, counter-clockwise seen from outside."""
        return tuple(self.direction(d) for d in self.map.outgoing(corner))

    def face_normal(self, f: int) -> Direction | None:
        """The normal of face ``f``, pointing outside when the faces are counter-clockwise seen
        from outside; ``None`` for a face that is not an axis-parallel rectangle's plane.

        >>> from polyloops.io.examples import load_example
        >>> sorted(str(load_example("cube").face_normal(f)) for f in range(6))
        ['+X', '+Y', '+Z', '-X', '-Y', '-Z']
        """
        p = [self.positions[c] for c in self.faces[f]]
        a = [p[1][k] - p[0][k] for k in range(3)]
        b = [p[2][k] - p[1][k] for k in range(3)]
        n = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
        nz = [i for i in range(3) if n[i]]
        if len(nz) != 1:
            return None
        return Direction.of(nz[0], 1 if n[nz[0]] > 0 else -1)

    def bounding_box(self) -> tuple[Position, Position]:
        """The lowest and highest corner coordinates, per axis."""
        lo = tuple(min(p[i] for p in self.positions) for i in range(3))
        hi = tuple(max(p[i] for p in self.positions) for i in range(3))
        return (lo[0], lo[1], lo[2]), (hi[0], hi[1], hi[2])

    def signed_volume(self) -> float:
        """The enclosed volume, positive when the faces are counter-clockwise seen from outside
        (see :func:`signed_volume`)."""
        return signed_volume(self.faces, self.positions)

    def outward(self) -> Polycube:
        """``self``, or its inverse if its faces are clockwise seen from outside."""
        return self if self.signed_volume() >= 0 else self.inverse()

    def inverse(self) -> Polycube:
        """Every face reversed; order-equivalent to ``self`` (Definition 2)."""
        return Polycube(self.map.reversed(), self.positions)

    def dualize(self) -> LoopStructure:
        """The oriented loop structure of Theorem 1; see :func:`polyloops.core.duality.dualize`."""
        from polyloops.core.duality import dualize

        return dualize(self)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Polycube) and self.map == other.map and self.positions == other.positions

    def __hash__(self) -> int:
        return hash((self.map, self.positions))

    def __repr__(self) -> str:
        return (f"Polycube(corners={self.map.num_corners}, faces={self.map.num_faces}, "
                f"genus={self.genus})")
