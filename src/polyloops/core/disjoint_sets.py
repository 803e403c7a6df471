"""A small union-find on hashable items (path halving), created on first sight.

>>> s = DisjointSets()
>>> s.union(1, 2); s.union(3, 4); s.union(2, 4)
>>> s.find(1) == s.find(3), s.find(1) == s.find(5)
(True, False)
"""

from __future__ import annotations

from collections.abc import Hashable


class DisjointSets:
    def __init__(self) -> None:
        self.parent: dict[Hashable, Hashable] = {}

    def find(self, x: Hashable) -> Hashable:
        p = self.parent
        p.setdefault(x, x)
        while p[x] != x:
            p[x] = p[p[x]]
            x = p[x]
        return x

    def union(self, a: Hashable, b: Hashable) -> None:
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.parent[ra] = rb
