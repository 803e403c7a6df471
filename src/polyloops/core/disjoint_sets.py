"""A small union-find on hashable items (path halving), created on first sight.

The kernel's one union-find: networkx has one too, but importing networkx costs a tenth of a
second, which ``import polyloops`` should not pay.

>>> s = DisjointSets(range(6))
>>> s.union(1, 2); s.union(3, 4); s.union(2, 4)
>>> s.find(1) == s.find(3), s.find(1) == s.find(5), s[5] == s.find(5)
(True, False, True)
>>> sorted(sorted(p) for p in s.to_sets())
[[0], [1, 2, 3, 4], [5]]
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Hashable, Iterable, Iterator
from typing import Generic, TypeVar

T = TypeVar("T", bound=Hashable)


class DisjointSets(Generic[T]):
    """Disjoint sets of hashable items; an item unseen so far is a set of its own.

    Parameters
    ----------
    items:
        Items to register now (each as its own set), so that :meth:`to_sets` lists them even
        if they are never joined.
    """

    def __init__(self, items: Iterable[T] = ()) -> None:
        self.parent: dict[T, T] = {x: x for x in items}

    def find(self, x: T) -> T:
        """The representative of ``x``'s set."""
        p = self.parent
        p.setdefault(x, x)
        while p[x] != x:
            p[x] = p[p[x]]
            x = p[x]
        return x

    __getitem__ = find

    def union(self, a: T, b: T) -> None:
        """Join the sets of ``a`` and ``b``."""
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[ra] = rb

    def to_sets(self) -> Iterator[set[T]]:
        """The sets, each once, over every item seen so far."""
        groups: dict[T, set[T]] = defaultdict(set)
        for x in list(self.parent):
            groups[self.find(x)].add(x)
        yield from groups.values()
