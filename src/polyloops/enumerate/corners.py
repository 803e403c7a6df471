"""The 126 polycube corner configurations.

A corner is a cyclic order of 3 to 6 distinct directions, counter-clockwise
seen from outside, in which cyclically adjacent directions have different
axes (loops of one axis do not cross).  Orders that differ by a rotation of
the cycle are the same configuration; the reversed order is a different one
(its mirror image).  The paper sorts them into six categories:

>>> from collections import Counter
>>> configs = corner_configurations()
>>> len(configs)
126
>>> dict(Counter(c.category for c in configs))  # doctest: +NORMALIZE_WHITESPACE
{'simple': 16, 'edge': 24, 'flat': 6, 'bent': 48, 'symmetric-complex': 8, 'asymmetric-complex': 24}
>>> classify([Direction.PX, Direction.PY, Direction.PZ]).category
'simple'
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cache
from itertools import combinations, permutations

from polyloops.core.directions import Direction
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import MODE_ALIASES, SYMMETRY_MODES, SignedPermutation
from polyloops.core.voxels import Cell, VoxelError, polycube_from_voxels

CATEGORIES = ("simple", "edge", "flat", "bent", "symmetric-complex", "asymmetric-complex")


@dataclass(frozen=True, order=True)
class CornerConfig:
    """One configuration: ``directions`` in its canonical rotation (the smallest)."""

    id: int
    degree: int
    category: str
    directions: tuple[Direction, ...]

    @property
    def label(self) -> str:
        return " ".join(str(d) for d in self.directions)

    def to_json(self) -> dict[str, object]:
        return {"id": self.id, "degree": self.degree, "category": self.category,
                "directions": [str(d) for d in self.directions]}


def canonical_rotation(directions: Sequence[Direction]) -> tuple[Direction, ...]:
    """The lexicographically smallest rotation of a cyclic sequence."""
    seq = tuple(directions)
    return min(seq[i:] + seq[:i] for i in range(len(seq)))


def is_corner(directions: Sequence[Direction]) -> bool:
    """3 to 6 distinct directions, cyclically adjacent ones on different axes."""
    k = len(directions)
    return (3 <= k <= 6 and len(set(directions)) == k
            and all(directions[i].axis != directions[(i + 1) % k].axis for i in range(k)))


def category_of(directions: Sequence[Direction]) -> str:
    """The paper's category of a corner (which must satisfy :func:`is_corner`)."""
    k = len(directions)
    if k == 3:
        return "simple"
    if k == 4:
        return "edge" if len({d.axis for d in directions}) == 3 else "flat"
    if k == 5:
        return "bent"
    symmetric = all(directions[(i + 3) % 6] == -directions[i] for i in range(6))
    return "symmetric-complex" if symmetric else "asymmetric-complex"


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
    """All configurations, numbered by degree, category, then directions."""
    return tuple(CornerConfig(i, len(s), category_of(s), s) for i, s in enumerate(_generate()))


@cache
def _by_directions() -> dict[tuple[Direction, ...], CornerConfig]:
    return {c.directions: c for c in corner_configurations()}


def classify(directions: Iterable[Direction | None]) -> CornerConfig | None:
    """The configuration of a corner's cyclic directions, or ``None`` if it is no polycube corner."""
    seq = tuple(directions)
    if any(d is None for d in seq):
        return None
    return _by_directions().get(canonical_rotation(seq))  # type: ignore[arg-type]


# -- symmetry ---------------------------------------------------------------------------

def transform(config: CornerConfig, g: SignedPermutation) -> CornerConfig:
    """The image of a configuration under ``g``; a reflection also reverses the cyclic order,
    because it reverses the orientation of the surface."""
    seq = [g(d) for d in config.directions]
    if g.det < 0:
        seq.reverse()
    image = classify(seq)
    assert image is not None
    return image


@dataclass(frozen=True)
class CornerClass:
    """An orbit of configurations under a symmetry group; its representative has the lowest id."""

    id: int
    category: str
    members: tuple[int, ...]

    @property
    def representative(self) -> CornerConfig:
        return corner_configurations()[self.members[0]]

    def to_json(self) -> dict[str, object]:
        return {"class": self.id, "category": self.category, "size": len(self.members),
                "representative": [str(d) for d in self.representative.directions],
                "members": list(self.members)}


@cache
def corner_classes(symmetry: str = "rotation") -> tuple[CornerClass, ...]:
    """Orbits under ``"labelled"`` (each configuration alone), ``"rotation"`` (24) or ``"full"``
    (48 signed permutations); ``"none"`` is an older name for ``"labelled"``."""
    group = SYMMETRY_MODES[MODE_ALIASES.get(symmetry, symmetry)]
    seen: set[int] = set()
    out = []
    for c in corner_configurations():
        if c.id in seen:
            continue
        orbit = sorted({transform(c, g).id for g in group})
        seen.update(orbit)
        out.append(CornerClass(len(out), c.category, tuple(orbit)))
    return tuple(out)


# -- witnesses --------------------------------------------------------------------------

OCTANT_CELLS = tuple((i, j, k) for i in range(2) for j in range(2) for k in range(2))


@cache
def _octant_witnesses() -> dict[int, tuple[Cell, ...]]:
    """For each configuration, the first set of cubes in a 2x2x2 block (fewest cubes first,
    then by bit mask) whose boundary polycube has a corner of that configuration."""
    found: dict[int, tuple[Cell, ...]] = {}
    masks = sorted(range(1, 256), key=lambda m: (m.bit_count(), m))
    for mask in masks:
        cells = tuple(c for b, c in enumerate(OCTANT_CELLS) if mask >> b & 1)
        try:
            q = polycube_from_voxels(cells)
        except VoxelError:
            continue
        for v in range(q.map.num_corners):
            config = classify(q.corner_directions(v))
            if config is not None:
                found.setdefault(config.id, cells)
    return found


def witness(config: CornerConfig | int) -> tuple[tuple[Cell, ...], Polycube] | None:
    """A small polycube with a corner of this configuration, as its cubes and its polycube."""
    cid = config if isinstance(config, int) else config.id
    cells = _octant_witnesses().get(cid)
    return None if cells is None else (cells, polycube_from_voxels(cells))


def corner_histogram(obj: Polycube | LoopStructure) -> tuple[dict[int, int], dict[str, int], int]:
    """Counts of configuration ids and of categories over the corners of a structure,
    and the number of corners that are no polycube corner (or need sides to tell)."""
    ids: dict[int, int] = {}
    categories = dict.fromkeys(CATEGORIES, 0)
    unclassified = 0
    if isinstance(obj, LoopStructure) and not obj.oriented:
        return ids, categories, obj.map.num_corners
    for v in range(obj.map.num_corners):
        config = classify(obj.corner_directions(v))
        if config is None:
            unclassified += 1
            continue
        ids[config.id] = ids.get(config.id, 0) + 1
        categories[config.category] += 1
    return dict(sorted(ids.items())), categories, unclassified


# -- corners of labelled segmentations ----------------------------------------------------

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


ChartCorner = tuple[tuple[Direction, Direction], ...]


def chart_corner(directions: Sequence[Direction]) -> ChartCorner:
    """A corner as a labelled segmentation sees it: the creased edges only, each as (its
    direction, the normal of the face that follows it counter-clockwise), from the smallest
    rotation.  The face between cyclically consecutive directions ``a, b`` has normal
    ``a x b``; an edge between two faces of one normal is flat, so no boundary of charts.

    >>> [(str(d), str(n)) for d, n in chart_corner([Direction.NX, Direction.NY, Direction.NZ])]
    [('-X', '+Z'), ('-Y', '+X'), ('-Z', '+Y')]
    """
    k = len(directions)
    normals = [cross(directions[i], directions[(i + 1) % k]) for i in range(k)]
    pairs = tuple((directions[i], normals[i]) for i in range(k) if normals[i - 1] != normals[i])
    return min(pairs[i:] + pairs[:i] for i in range(len(pairs))) if pairs else ()


@cache
def chart_corners() -> frozenset[ChartCorner]:
    """Every corner of a labelled segmentation that a polycube can have: the chart views of
    the 126 configurations with three or more creased edges (with two, the point lies
    inside a boundary; with none, inside a chart)."""
    return frozenset(c for c in (chart_corner(cfg.directions) for cfg in corner_configurations())
                     if len(c) >= 3)


@cache
def chart_label_cycles() -> frozenset[tuple[Direction, ...]]:
    """The cyclic sequences of chart labels, from the smallest rotation, that some corner of
    :func:`chart_corners` has around it."""
    return frozenset(canonical_rotation([n for _, n in c]) for c in chart_corners())
