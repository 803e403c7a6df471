"""Array kernels for large maps: connected components and permutation cycles in C (scipy).

The kernel's objects keep tuples of Python integers, which small structures (the catalog's
millions of maps) handle fastest.  Past :data:`LARGE` darts, the same computations run on
numpy arrays; every such kernel has its tuple twin, and the tests compare the two.

>>> import numpy as np
>>> count, labels = components(5, np.array([3, 1]), np.array([4, 0]))
>>> count, labels.tolist()
(3, [0, 0, 1, 2, 2])
"""

from __future__ import annotations

import functools
import gc
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, TypeVar

import numpy as np

from polyloops.core.directions import Axis, Direction

if TYPE_CHECKING:
    from polyloops.core.halfedge import HalfEdgeMap

LARGE = 512  # darts: from here on, maps use the array kernels


def use_arrays(darts: int) -> bool:
    """The one switch between the tuple kernels and their array twins: whether a structure of
    ``darts`` darts uses the arrays (from :data:`LARGE` on).  Every kernel with an array twin
    asks here, so setting ``LARGE`` (to 0: arrays always; to a huge number: never) moves all of
    them at once, which is how the tests run the twins against each other.

    >>> use_arrays(LARGE - 1), use_arrays(LARGE)
    (False, True)
    """
    return darts >= LARGE

F = TypeVar("F", bound=Callable)


def gc_paused(func: F) -> F:
    """Run ``func`` with the cyclic garbage collector paused.  The large kernels allocate
    hundreds of thousands of tuples of integers, which hold no cycles; without the pause,
    each allocation burst triggers full collections that scan every live object, so the
    cost of building a structure would grow with everything else in memory."""
    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        if not gc.isenabled():
            return func(*args, **kwargs)
        gc.disable()
        try:
            return func(*args, **kwargs)
        finally:
            gc.enable()
    return wrapper  # type: ignore[return-value]


def components(n: int, a: np.ndarray, b: np.ndarray) -> tuple[int, np.ndarray]:
    """Connected components of the graph on ``0..n-1`` with edges ``a[i] -- b[i]``, numbered
    by their lowest member (so the same numbering as a union-find read in order)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    graph = coo_matrix((np.ones(len(a), dtype=np.int8), (a, b)), shape=(n, n))
    count, labels = connected_components(graph, directed=False)
    return count, renumber_by_first(labels, count)


def renumber_by_first(labels: np.ndarray, count: int) -> np.ndarray:
    """Labels renumbered in the order in which they first occur."""
    first = np.full(count, len(labels), dtype=np.int64)
    np.minimum.at(first, labels, np.arange(len(labels)))
    order = np.empty(count, dtype=np.int64)
    order[np.argsort(first, kind="stable")] = np.arange(count)
    return order[labels]


def cycles(perm: np.ndarray) -> tuple[int, np.ndarray]:
    """The cycles of a permutation, numbered by their lowest element."""
    n = len(perm)
    return components(n, np.arange(n), perm)


def per_loop(loop_of: np.ndarray, values: np.ndarray, loops: int) -> np.ndarray | None:
    """The value each loop's darts share (``loop_of[i]`` is the loop of ``values[i]``), or
    ``None`` when the darts of some loop disagree."""
    low = np.full(loops, np.iinfo(np.int64).max)
    high = np.full(loops, np.iinfo(np.int64).min)
    np.minimum.at(low, loop_of, values)
    np.maximum.at(high, loop_of, values)
    return None if np.any(low != high) else low


def all_distinct(values: np.ndarray) -> bool:
    """No value twice: by counting when the values are small non-negative integers (linear),
    else by sorting (faster than hashing for integer arrays)."""
    if not len(values):
        return True
    if values.min() >= 0 and values.max() < 8 * len(values) + 64:
        return int(np.bincount(values).max()) <= 1
    s = np.sort(values)
    return not np.any(s[1:] == s[:-1])


def as_array(values) -> np.ndarray:
    """A flat sequence of integers as an int64 array (``fromiter``: several times faster than
    ``asarray`` on a tuple)."""
    return np.fromiter(values, dtype=np.int64, count=len(values))


def points_array(points) -> np.ndarray:
    """``(x, y, z)`` integer triples as an ``(n, 3)`` int64 array."""
    from itertools import chain

    return np.fromiter(chain.from_iterable(points), dtype=np.int64, count=3 * len(points)).reshape(-1, 3)


@dataclass(frozen=True, eq=False)
class MapArrays:
    """A map's darts as arrays: ``origin``, ``target``, ``face_of``, ``next``, ``prev``,
    ``twin``, ``face_start``, and ``edge_id`` (edges numbered by their lower dart)."""

    origin: np.ndarray
    target: np.ndarray
    face_of: np.ndarray
    next: np.ndarray
    prev: np.ndarray
    twin: np.ndarray
    face_start: np.ndarray
    edge_id: np.ndarray
    edge_darts: np.ndarray  # the lower dart of each edge

    @classmethod
    def of(cls, m: HalfEdgeMap) -> MapArrays:
        origin, nxt, twin = as_array(m.origin_of), as_array(m.next), as_array(m.twin)
        darts = np.arange(len(origin))
        lower = np.minimum(darts, twin)
        rank = np.cumsum(darts < twin) - 1
        return cls(origin, origin[nxt], as_array(m.face_of), nxt, as_array(m.prev), twin,
                   as_array(m.face_start), rank[lower], np.flatnonzero(darts < twin))


class EdgeLabels(Mapping):
    """``{(u, v): label}`` held as three arrays (ends and label codes: ``int(d)`` for a
    Direction, ``6 + axis`` for an Axis), so that a large file is not turned into a dictionary
    of hundreds of thousands of tuples unless someone asks for one; the array kernels read
    the arrays."""

    def __init__(self, us, vs, codes):
        self.us, self.vs, self.codes = us, vs, codes

    @cached_property
    def _dict(self) -> dict[tuple[int, int], Direction | Axis]:
        members: list[Direction | Axis] = [*Direction, *Axis]
        return dict(zip(zip(self.us.tolist(), self.vs.tolist(), strict=True),
                        (members[c] for c in self.codes.tolist()), strict=True))

    def __getitem__(self, key: tuple[int, int]) -> Direction | Axis:
        return self._dict[key]

    def __iter__(self):
        return iter(self._dict)

    def __len__(self) -> int:
        return len(self.us)
