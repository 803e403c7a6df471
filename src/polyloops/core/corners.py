"""Polycube corners: the 126 configurations, their categories, and the corners of a structure.

A corner is a cyclic order of 3 to 6 distinct directions, counter-clockwise
seen from outside, in which cyclically adjacent directions have different
axes (loops of one axis do not cross).  Orders that differ by a rotation of
the cycle are the same configuration; the reversed order is a different one
(its mirror image).  The paper sorts them into six categories:

>>> from collections import Counter
>>> configs = corner_configurations()
>>> len(configs)
126
>>> {str(k): n for k, n in Counter(c.category for c in configs).items()}  # doctest: +NORMALIZE_WHITESPACE
{'simple': 16, 'edge': 24, 'flat': 6, 'bent': 48, 'symmetric-complex': 8, 'asymmetric-complex': 24}
>>> str(classify([Direction.PX, Direction.PY, Direction.PZ]).category)
'simple'
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from enum import StrEnum
from functools import cache
from itertools import combinations, permutations
from typing import TYPE_CHECKING, TypeVar

from polyloops.core.directions import Direction

if TYPE_CHECKING:
    from _typeshed import SupportsRichComparison

    from polyloops.core.polycube import Polycube
    from polyloops.core.structure import LoopStructure
    from polyloops.core.symmetry import SignedPermutation

Ordered = TypeVar("Ordered", bound="SupportsRichComparison")


class CornerCategory(StrEnum):
    """The paper's six categories of polycube corners (a string enum: it prints, compares
    and serialises as its name)."""

    SIMPLE = "simple"
    EDGE = "edge"
    FLAT = "flat"
    BENT = "bent"
    SYMMETRIC_COMPLEX = "symmetric-complex"
    ASYMMETRIC_COMPLEX = "asymmetric-complex"


CATEGORIES = tuple(CornerCategory)


@dataclass(frozen=True, order=True)
class CornerConfig:
    """One configuration: ``directions`` in its canonical rotation (the smallest)."""

    id: int
    degree: int
    category: CornerCategory
    directions: tuple[Direction, ...]

    @property
    def label(self) -> str:
        """The directions as text, counter-clockwise: ``+X +Y +Z``."""
        return " ".join(str(d) for d in self.directions)

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict: id, degree, category and directions."""
        return {"id": self.id, "degree": self.degree, "category": str(self.category),
                "directions": [str(d) for d in self.directions]}


def canonical_rotation(items: Sequence[Ordered]) -> tuple[Ordered, ...]:
    """The lexicographically smallest rotation of a cyclic sequence (of directions, or of
    anything ordered: chart corners rotate pairs)."""
    seq = tuple(items)
    return min(seq[i:] + seq[:i] for i in range(len(seq)))


def is_corner(directions: Sequence[Direction]) -> bool:
    """3 to 6 distinct directions, cyclically adjacent ones on different axes."""
    k = len(directions)
    return (3 <= k <= 6 and len(set(directions)) == k
            and all(directions[i].axis != directions[(i + 1) % k].axis for i in range(k)))


def category_of(directions: Sequence[Direction]) -> CornerCategory:
    """The paper's category of a corner (which must satisfy :func:`is_corner`)."""
    k = len(directions)
    C = CornerCategory
    if k == 3:
        return C.SIMPLE
    if k == 4:
        return C.EDGE if len({d.axis for d in directions}) == 3 else C.FLAT
    if k == 5:
        return C.BENT
    symmetric = all(directions[(i + 3) % 6] == -directions[i] for i in range(6))
    return C.SYMMETRIC_COMPLEX if symmetric else C.ASYMMETRIC_COMPLEX


def _generate() -> list[tuple[Direction, ...]]:
    """Every cyclic order of every subset, keeping those that are corners, once per rotation class."""
    found = set()
    for k in range(3, 7):
        for subset in combinations(Direction, k):
            first, rest = subset[0], subset[1:]
            for perm in permutations(rest):  # fixing the first element fixes the rotation
                seq = (first, *perm)
                if is_corner(seq):
                    found.add(canonical_rotation(seq))
    return sorted(found, key=lambda s: (len(s), CATEGORIES.index(category_of(s)), s))


@cache
def corner_configurations() -> tuple[CornerConfig, ...]:
    """The 126 polycube corner configurations, numbered by degree, category, then directions.

    Returns
    -------
    tuple[CornerConfig, ...]
        Each with its ``id`` (its index), degree, category and directions counter-clockwise.

    Notes
    -----
    Nothing is raised: the table is derived, not read (and cached).

    >>> configs = corner_configurations()
    >>> len(configs), configs[0].degree, str(configs[-1].category)
    (126, 3, 'asymmetric-complex')
    """
    return tuple(CornerConfig(i, len(s), category_of(s), s) for i, s in enumerate(_generate()))


@cache
def _by_directions() -> dict[tuple[Direction, ...], CornerConfig]:
    return {c.directions: c for c in corner_configurations()}


def classify(directions: Iterable[Direction | None]) -> CornerConfig | None:
    """The configuration of a corner, from its edges' directions in counter-clockwise order.

    Parameters
    ----------
    directions:
        The corner's edge directions (any rotation of the cycle); a ``None`` (an edge that is
        not axis-aligned) makes it no polycube corner.

    Returns
    -------
    CornerConfig or None
        ``None`` when the sequence is no polycube corner.

    Raises
    ------
    TypeError
        When an item is neither a Direction nor ``None``.

    >>> from polyloops.core.directions import Direction as D
    >>> str(classify([D.PX, D.PY, D.PZ]).category), classify([D.PX, D.NX, D.PY])
    ('simple', None)
    """
    given = tuple(directions)
    seq = tuple(d for d in given if d is not None)
    if len(seq) != len(given):
        return None
    return _by_directions().get(canonical_rotation(seq))


def transform(config: CornerConfig, g: SignedPermutation) -> CornerConfig:
    """The image of a configuration under ``g``; a reflection also reverses the cyclic order,
    because it reverses the orientation of the surface."""
    seq = [g(d) for d in config.directions]
    if g.det < 0:
        seq.reverse()
    image = classify(seq)
    assert image is not None
    return image


def corner_histogram(obj: Polycube | LoopStructure) -> tuple[dict[int, int], dict[CornerCategory, int], int]:
    """Counts of configuration ids and of categories over the corners of a structure,
    and the number of corners that are no polycube corner (or need sides to tell)."""
    ids: dict[int, int] = {}
    categories = dict.fromkeys(CATEGORIES, 0)
    unclassified = 0
    if getattr(obj, "signs", 0) is None:  # a labelled loop structure: no sides, no directions
        return ids, categories, obj.map.num_corners
    for v in range(obj.map.num_corners):
        config = classify(obj.corner_directions(v))
        if config is None:
            unclassified += 1
            continue
        ids[config.id] = ids.get(config.id, 0) + 1
        categories[config.category] += 1
    return dict(sorted(ids.items())), categories, unclassified



def cross(a: Direction, b: Direction) -> Direction:
    """The cross product of two directions on different axes.

    >>> str(cross(Direction.PX, Direction.PY)), str(cross(Direction.PY, Direction.PX))
    ('+Z', '-Z')
    """
    if a.axis == b.axis:
        raise ValueError(f"{a} and {b} are parallel")
    third = 3 - a.axis - b.axis
    right_handed = (b.axis - a.axis) % 3 == 1
    return Direction.of(third, a.sign * b.sign * (1 if right_handed else -1))
