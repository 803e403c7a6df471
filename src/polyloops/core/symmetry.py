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
from enum import StrEnum
from itertools import permutations, product

from polyloops.core.directions import Axis, Direction


@dataclass(frozen=True)
class SignedPermutation:
    """A signed permutation of the axes: ``e_a`` goes to ``signs[a] * e_perm[a]``."""

    perm: tuple[int, int, int]
    signs: tuple[int, int, int]

    def __call__(self, d: Direction) -> Direction:
        a = int(d.axis)
        return Direction.of(self.perm[a], d.sign * self.signs[a])

    def axis(self, a: Axis | int) -> Axis:
        """The image of an axis (signs aside)."""
        return Axis(self.perm[int(a)])

    @property
    def det(self) -> int:
        """The determinant: ``+1`` for a rotation, ``-1`` for a reflection."""
        inversions = sum(1 for i in range(3) for j in range(i + 1, 3) if self.perm[i] > self.perm[j])
        return (-1) ** inversions * self.signs[0] * self.signs[1] * self.signs[2]

    @property
    def is_rotation(self) -> bool:
        """Whether it is one of the 24 rotations."""
        return self.det == 1

    def __str__(self) -> str:
        return "(" + ", ".join(str(self(Direction.of(a, 1))) for a in Axis) + ")"


SIGNED_PERMUTATIONS: tuple[SignedPermutation, ...] = tuple(
    SignedPermutation((p[0], p[1], p[2]), (s[0], s[1], s[2]))
    for p in permutations(range(3)) for s in product((1, -1), repeat=3)
)
ROTATIONS: tuple[SignedPermutation, ...] = tuple(g for g in SIGNED_PERMUTATIONS if g.is_rotation)
IDENTITY = SIGNED_PERMUTATIONS[0]

class Symmetry(StrEnum):
    """What two structures may differ by and still count as one: nothing but numbering
    (``labelled``: order-equivalence, axes and sides fixed), a rotation of space
    (``rotation``: 24), or any signed permutation of the axes (``full``: 48, mirror images
    identified).  One enum for corners, signatures, catalogs, reachability and the CLI; a
    string enum, so ``Symmetry.FULL == "full"`` and it serialises as its name.

    >>> Symmetry.parse("none"), len(Symmetry.FULL.group), len(Symmetry("rotation").group)
    (<Symmetry.LABELLED: 'labelled'>, 48, 24)
    """

    LABELLED = "labelled"
    ROTATION = "rotation"
    FULL = "full"

    @classmethod
    def parse(cls, value: str) -> Symmetry:
        """A mode from its name; ``none`` is the corners command's older name for ``labelled``.
        Raises ``ValueError`` naming the modes for anything else."""
        try:
            return cls(MODE_ALIASES.get(value, value))
        except ValueError:
            raise ValueError(f"unknown symmetry {value!r} (choose from "
                             f"{', '.join(m.value for m in cls)})") from None

    @property
    def group(self) -> tuple[SignedPermutation, ...]:
        """The signed permutations this mode identifies by."""
        return SYMMETRY_MODES[self]

    @property
    def prefix(self) -> str:
        """The letter of a genus-0 class name in this mode (``P26.3``, ``R26.3``, ``L26.3``).

        >>> [m.prefix for m in Symmetry]
        ['L', 'R', 'P']
        """
        return {"labelled": "L", "rotation": "R", "full": "P"}[self.value]

    @property
    def up_to(self) -> str:
        """What classes of this mode are taken up to, in words (``up to rotations``)."""
        return {"labelled": "renumbering", "rotation": "rotations",
                "full": "rotations and reflections"}[self.value]


def direction_permutation(g: SignedPermutation) -> list[int]:
    """``g`` as a permutation of the six directions (``Direction`` values 0..5).

    >>> direction_permutation(IDENTITY)
    [0, 1, 2, 3, 4, 5]
    """
    return [int(g(d)) for d in Direction]


def symmetry_group(mode: Symmetry | str = Symmetry.FULL):
    """The group of a symmetry mode as a sympy ``PermutationGroup`` on the six directions:
    the hyperoctahedral group of order 48 for ``full``, its rotation subgroup of order 24,
    the trivial group for ``labelled``.  (sympy loads on first use.)

    >>> symmetry_group("full").order(), symmetry_group("rotation").order()
    (48, 24)
    >>> symmetry_group("rotation").is_subgroup(symmetry_group("full"))
    True
    """
    from sympy.combinatorics import Permutation, PermutationGroup

    return PermutationGroup([Permutation(direction_permutation(g)) for g in Symmetry.parse(mode).group])


SYMMETRY_MODES: dict[Symmetry, tuple[SignedPermutation, ...]] = {
    Symmetry.LABELLED: (IDENTITY,), Symmetry.ROTATION: ROTATIONS, Symmetry.FULL: SIGNED_PERMUTATIONS}
MODE_ALIASES = {"none": "labelled"}
