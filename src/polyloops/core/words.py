"""Counts in words, one home for every layer's messages and titles.

>>> plural(1, "arc"), plural(3, "arc"), plural(0, "vertex", "vertices")
('1 arc', '3 arcs', '0 vertices')
"""

from __future__ import annotations


def plural(n: int, word: str, many: str | None = None) -> str:
    """``1 problem``, ``2 problems`` (``many`` for irregular plurals)."""
    return f"{n} {word if n == 1 else many or word + 's'}"
