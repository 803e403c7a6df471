"""Hole orientation: an invariant of polycube loop structures that every loop move preserves.

The loops live on a fixed closed surface ``S`` of genus ``g``.  For axes ``A != B`` let ``M_AB``
be the matrix of *algebraic intersection numbers* of the A-loops with the B-loops (each
crossing counts +1 or -1 by the orientations of the two loops, a loop's direction having its
``+`` side on the right).  Its nonzero invariant factors (Smith normal form over the integers)
depend only on the subgroups ``L_A`` and ``L_B`` of ``H_1(S)`` that the loops of each axis span,
and on the intersection form.  ``docs/reachability.md`` proves that a valid move never changes
``L_A``: an added A-loop separates its A-zone, so it is homologous to a sum of A-loops bounding
one side.  So the invariant factors of ``M_XY``, ``M_XZ`` and ``M_YZ`` are the same for every
structure reachable by moves.  They see the orientation of holes: a square ring whose hole
runs along Z has Z-loops around the hole and X- and Y-loops around the bar, so ``M_XZ`` and
``M_YZ`` have rank 1 and ``M_XY`` rank 0.

>>> from polyloops.io.examples import load_example
>>> print(hole_orientation(load_example("ring").dualize()))
XY: rank 0; XZ: rank 1 (1); YZ: rank 1 (1)
>>> hole_orientation(load_example("l-shape").dualize()).ranks
{'XY': 0, 'XZ': 0, 'YZ': 0}
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

from polyloops.core.directions import Axis
from polyloops.core.structure import LoopStructure

PAIRS = tuple(combinations(Axis, 2))


def pair_name(a: Axis, b: Axis) -> str:
    """The name of a pair of axes, such as ``XY``."""
    return f"{a.name}{b.name}"


def intersection_matrix(ls: LoopStructure, a: Axis, b: Axis) -> list[list[int]]:
    """Algebraic intersection numbers: rows are the ``a``-loops, columns the ``b``-loops (in
    loop id order).  Where loop ``l`` enters a quad through dart ``d`` and loop ``k`` through
    ``next(d)``, the stored walks cross as (+1): ``l`` runs up, ``k`` runs left."""
    if not ls.oriented:
        raise ValueError("intersection numbers need oriented loops")
    assert ls.signs is not None
    m = ls.map
    rows = [lp.id for lp in ls.loops if ls.axes[lp.id] == a]
    cols = [lp.id for lp in ls.loops if ls.axes[lp.id] == b]
    row_of = {loop: i for i, loop in enumerate(rows)}
    col_of = {loop: j for j, loop in enumerate(cols)}
    out = [[0] * len(cols) for _ in rows]
    entries: dict[int, list[tuple[int, int]]] = {}
    for lp in ls.loops:
        for d, f in zip(lp.darts, lp.faces, strict=True):
            entries.setdefault(f, []).append((lp.id, d))
    for items in entries.values():
        for (l1, d1), (l2, d2) in combinations(items, 2):
            if ls.axes[l2] == a and ls.axes[l1] == b:
                (l1, d1), (l2, d2) = (l2, d2), (l1, d1)
            if ls.axes[l1] != a or ls.axes[l2] != b:
                continue
            if m.next[d1] == d2:
                crossing = 1
            elif m.next[d2] == d1:
                crossing = -1
            else:
                continue  # opposite darts: the same loop's entry and exit, not a crossing
            out[row_of[l1]][col_of[l2]] += crossing * ls.signs[l1] * ls.signs[l2]
    return out


def invariant_factors(matrix: list[list[int]]) -> tuple[int, ...]:
    """The nonzero invariant factors of an integer matrix, in increasing divisibility order.
    Rows and columns that are zero or repeat another up to sign are dropped first (integer
    row and column operations), so sympy's Smith normal form sees a small matrix."""
    from sympy import Matrix
    from sympy.matrices.normalforms import smith_normal_form
    from sympy.polys.domains import ZZ

    def distinct(rows: list[list[int]]) -> list[list[int]]:
        seen, out = set(), []
        for r in rows:
            key = tuple(r)
            if any(r) and key not in seen and tuple(-x for x in r) not in seen:
                seen.add(key)
                out.append(r)
        return out

    rows = distinct(matrix)
    if not rows:
        return ()
    cols = distinct([list(c) for c in zip(*rows, strict=True)])
    if not cols:
        return ()
    snf = smith_normal_form(Matrix(cols).T, domain=ZZ)
    diag = [abs(int(snf[i, i])) for i in range(min(snf.shape))]
    return tuple(sorted(x for x in diag if x))


@dataclass(frozen=True)
class HoleOrientation:
    """Per pair of axes, the nonzero invariant factors of the intersection matrix."""

    factors: dict[str, tuple[int, ...]]

    @property
    def ranks(self) -> dict[str, int]:
        """Per pair of axes, the rank of the intersection matrix."""
        return {k: len(v) for k, v in self.factors.items()}

    def permuted(self, perm: tuple[int, int, int]) -> HoleOrientation:
        """The invariant of the image under a signed permutation with axis permutation
        ``perm`` (axis ``a`` goes to ``perm[a]``): the pairs are renamed, and signs do not
        change invariant factors."""
        out = {}
        for a, b in PAIRS:
            x, y = sorted((Axis(perm[int(a)]), Axis(perm[int(b)])))
            out[pair_name(x, y)] = self.factors[pair_name(a, b)]
        return HoleOrientation({pair_name(a, b): out[pair_name(a, b)] for a, b in PAIRS})  # XY, XZ, YZ

    def up_to_axes(self) -> HoleOrientation:
        """The least image (by text) under the six permutations of the axes: the invariant of
        a class up to rotations and reflections, where the three rings are one.

        >>> from polyloops.io.examples import load_example
        >>> print(hole_orientation(load_example("ring").dualize()).up_to_axes())
        XY: rank 0; XZ: rank 1 (1); YZ: rank 1 (1)
        """
        perms: list[tuple[int, int, int]] = [(0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)]
        return min((self.permuted(p) for p in perms), key=str)

    def to_json(self) -> dict[str, list[int]]:
        """A JSON-ready dict: per pair of axes, the invariant factors."""
        return {k: list(v) for k, v in self.factors.items()}

    def __str__(self) -> str:
        return "; ".join(f"{k}: rank {len(v)}" + (f" ({', '.join(map(str, v))})" if v else "")
                         for k, v in self.factors.items())


def hole_orientation(ls: LoopStructure) -> HoleOrientation:
    """The invariant of an oriented loop structure (see the module docstring)."""
    return HoleOrientation({pair_name(a, b): invariant_factors(intersection_matrix(ls, a, b))
                            for a, b in PAIRS})
