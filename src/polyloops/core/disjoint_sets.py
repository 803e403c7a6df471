"""The kernel's union-finds: disjoint sets of hashable items (path halving), created on first
sight, and their parity variant for sign constraints.

networkx has a union-find too, but importing networkx costs a tenth of a
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


class ParitySets(Generic[T]):
    """Disjoint sets whose items carry a sign (+1 or -1) relative to their set's representative:
    the union-find for parity constraints ``s_a * s_b = p`` (Condition 3 of Definition 4 between
    the sides of loops).  :meth:`relate` adds a constraint and says whether it is consistent
    with the ones before.

    >>> s = ParitySets(range(4))
    >>> s.relate(0, 1, -1), s.relate(1, 2, -1), s.relate(0, 2, 1), s.relate(0, 2, -1)
    (True, True, True, False)
    >>> sorted(sorted(c) for c in s.components())
    [[(0, 1), (1, -1), (2, 1)], [(3, 1)]]
    """

    def __init__(self, items: Iterable[T] = ()) -> None:
        self.parent: dict[T, T] = {x: x for x in items}
        self.parity: dict[T, int] = dict.fromkeys(self.parent, 1)  # sign relative to the parent
        self._joined: list[T] = []  # the representatives joined under another, in order

    def find(self, x: T) -> tuple[T, int]:
        """The representative of ``x``'s set and the sign of ``x`` relative to it."""
        p, q = self.parent, self.parity
        if x not in p:
            p[x], q[x] = x, 1
        sign = 1
        while p[x] != x:
            sign *= q[x]
            x = p[x]
        return x, sign

    def relate(self, a: T, b: T, product: int) -> bool:
        """Constrain ``s_a * s_b = product``; ``False`` (and nothing changed) when the sets
        already force the other product."""
        (ra, pa), (rb, pb) = self.find(a), self.find(b)
        if ra == rb:
            return pa * pb == product
        self.parent[ra], self.parity[ra] = rb, pa * pb * product
        self._joined.append(ra)
        return True

    def checkpoint(self) -> int:
        """A mark that :meth:`rollback` returns to (a backtracking search's undo).

        >>> s = ParitySets(range(3))
        >>> mark = s.checkpoint(); s.relate(0, 1, -1)
        True
        >>> s.rollback(mark); s.relate(0, 1, 1)
        True
        """
        return len(self._joined)

    def rollback(self, mark: int) -> None:
        """Undo every join made since ``mark`` (the items stay registered)."""
        while len(self._joined) > mark:
            x = self._joined.pop()
            self.parent[x], self.parity[x] = x, 1

    def components(self) -> list[list[tuple[T, int]]]:
        """The sets, each a list of ``(item, sign relative to the representative)`` in the
        order the items were first seen."""
        groups: dict[T, list[tuple[T, int]]] = defaultdict(list)
        for x in list(self.parent):
            root, sign = self.find(x)
            groups[root].append((x, sign))
        return list(groups.values())
