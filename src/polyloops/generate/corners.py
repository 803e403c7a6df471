"""Corner configurations seen through symmetry and through pictures of cubes: classes under
rotations or all signed permutations, small witness polycubes, and the corners a labelled
segmentation can have.  The configurations themselves are :mod:`polyloops.core.corners`.

>>> len(corner_classes("rotation")), len(corner_classes("full"))
(10, 9)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache

from polyloops.core.corners import (
    CornerCategory,
    CornerConfig,
    canonical_rotation,
    classify,
    corner_configurations,
    cross,
    transform,
)
from polyloops.core.directions import Direction
from polyloops.core.polycube import Polycube
from polyloops.core.symmetry import Symmetry
from polyloops.shapes.voxels import Cell, VoxelError, polycube_from_voxels


@dataclass(frozen=True)
class CornerClass:
    """An orbit of configurations under a symmetry group; its representative has the lowest id."""

    id: int
    category: CornerCategory
    members: tuple[int, ...]

    @property
    def representative(self) -> CornerConfig:
        """The member with the lowest id."""
        return corner_configurations()[self.members[0]]

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict: class id, category, size, representative and members."""
        return {"class": self.id, "category": str(self.category), "size": len(self.members),
                "representative": [str(d) for d in self.representative.directions],
                "members": list(self.members)}


@cache
def corner_classes(symmetry: Symmetry | str = Symmetry.ROTATION) -> tuple[CornerClass, ...]:
    """Orbits under ``"labelled"`` (each configuration alone), ``"rotation"`` (24) or ``"full"``
    (48 signed permutations); ``"none"`` is an older name for ``"labelled"``."""
    group = Symmetry.parse(symmetry).group
    seen: set[int] = set()
    out: list[CornerClass] = []
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


# -- the table the corners command prints ------------------------------------------------

def corner_rows(witnesses: bool = False) -> list[dict[str, object]]:
    """One JSON-ready row per configuration: its id, degree, category and directions, the
    valid bundled examples that have such a corner, and with ``witnesses`` the cubes of a
    small polycube that has one.

    >>> rows = corner_rows()
    >>> len(rows), rows[0]["category"], sum("cube" in row["examples"] for row in rows)
    (126, 'simple', 8)
    """
    from polyloops.core.corners import corner_histogram
    from polyloops.io.examples import EXAMPLES

    in_examples: dict[int, list[str]] = {c.id: [] for c in corner_configurations()}
    for name, ex in EXAMPLES.items():
        if ex.valid:
            for cid in corner_histogram(ex.build())[0]:
                in_examples[cid].append(name)
    rows = []
    for c in corner_configurations():
        row = {**c.to_json(), "examples": in_examples[c.id]}
        if witnesses:
            found = witness(c)
            row["witness_cubes"] = [list(cell) for cell in found[0]] if found else None
        rows.append(row)
    return rows


# -- the same classes by group theory (sympy) ----------------------------------------------

def corner_action(symmetry: Symmetry | str = Symmetry.FULL):
    """The symmetry group acting on the 126 configurations, as a sympy ``PermutationGroup`` on
    their ids: generated by the images of the generators of
    :func:`~polyloops.core.symmetry.symmetry_group` under :func:`~polyloops.core.corners.transform`.

    >>> G = corner_action("full")
    >>> G.degree, G.order()
    (126, 48)
    """
    from sympy.combinatorics import Permutation, PermutationGroup

    from polyloops.core.symmetry import SIGNED_PERMUTATIONS, direction_permutation, symmetry_group

    by_action = {tuple(direction_permutation(g)): g for g in SIGNED_PERMUTATIONS}
    configs = corner_configurations()
    generators = []
    for gen in symmetry_group(symmetry).generators:
        g = by_action[tuple(gen.array_form)]
        generators.append(Permutation([transform(c, g).id for c in configs]))
    return PermutationGroup(generators or [Permutation(list(range(len(configs))))])


def burnside_count(symmetry: Symmetry | str = Symmetry.FULL) -> int:
    """The number of classes of configurations, by Burnside's lemma: the average number of
    configurations each group element fixes.  It agrees with :func:`corner_classes`, which
    walks orbits instead.

    >>> [burnside_count(m) for m in ("labelled", "rotation", "full")]
    [126, 10, 9]
    """
    from sympy import Rational

    G = corner_action(symmetry)
    fixed = sum(sum(1 for i in range(G.degree) if g(i) == i) for g in G.generate())
    count = Rational(fixed, G.order())
    assert count.q == 1, "Burnside's average is always an integer"
    return int(count)
