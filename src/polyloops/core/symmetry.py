"""The 48 signed permutations of the axes, of which 24 are rotations.

``g`` sends the unit vector ``e_a`` to ``signs[a] * e_perm[a]``.  It acts on
directions, on loop labels (axis ``a`` goes to ``perm[a]``) and sides (a loop's
sign is multiplied by ``signs[a]``).  A reflection (``det = -1``) also reverses
the orientation of the surface.

>>> len(SIGNED_PERMUTATIONS), len(ROTATIONS)
(48, 24)
>>> g = SIGNED_PERMUTATIONS[1]
>>> [str(g(d)) for d in Direction]
['+X', '-X', '+Y', '-Y', '-Z', '+Z']
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import permutations, product

from polyloops.core.directions import Axis, Direction


@dataclass(frozen=True)
class SignedPermutation:
    perm: tuple[int, int, int]
    signs: tuple[int, int, int]

    def __call__(self, d: Direction) -> Direction:
        a = int(d.axis)
        return Direction.of(self.perm[a], d.sign * self.signs[a])

    def axis(self, a: Axis | int) -> Axis:
        return Axis(self.perm[int(a)])

    @property
    def det(self) -> int:
        inversions = sum(1 for i in range(3) for j in range(i + 1, 3) if self.perm[i] > self.perm[j])
        return (-1) ** inversions * self.signs[0] * self.signs[1] * self.signs[2]

    @property
    def is_rotation(self) -> bool:
        return self.det == 1

    def __str__(self) -> str:
        return "(" + ", ".join(str(self(Direction.of(a, 1))) for a in Axis) + ")"


SIGNED_PERMUTATIONS: tuple[SignedPermutation, ...] = tuple(
    SignedPermutation(p, s) for p in permutations(range(3)) for s in product((1, -1), repeat=3)
)
ROTATIONS: tuple[SignedPermutation, ...] = tuple(g for g in SIGNED_PERMUTATIONS if g.is_rotation)
IDENTITY = SIGNED_PERMUTATIONS[0]

# The symmetry modes, one name each: "labelled" keeps the axes and sides as they are.
SYMMETRY_MODES = {"labelled": (IDENTITY,), "rotation": ROTATIONS, "full": SIGNED_PERMUTATIONS}
MODE_ALIASES = {"none": "labelled"}  # the corners command's older name for "labelled"
