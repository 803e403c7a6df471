"""Listing and counting loop additions under a limit or a time budget: what the ``moves``
command asks of the kernel's enumerations (:mod:`polyloops.core.moves`), with the budget
shared across axes so that no axis starves the others.

>>> from polyloops.io.examples import load_example
>>> count_additions_within(load_example("cube").dualize(), limit=1)
AdditionCount(counts={'X': 1, 'Y': 1, 'Z': 1}, complete={'X': False, 'Y': False, 'Z': False})
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from polyloops.core.directions import Axis
from polyloops.core.moves import (
    Addition,
    SearchStopped,
    addition_index,
    additions,
    count_valid_additions,
    sample_additions,
    shortest_additions,
)
from polyloops.core.structure import LoopStructure

__all__ = ["AdditionCount", "AdditionListing", "TimeShares", "count_additions_within", "list_additions"]


@dataclass(frozen=True)
class AdditionCount:
    """Valid additions per label, and per label whether the count is complete: ``False`` where
    ``limit`` or the time limit stopped it, so that the number is only a lower bound."""

    counts: dict[str, int]
    complete: dict[str, bool]


def count_additions_within(ls: LoopStructure, axes: Sequence[Axis] = tuple(Axis),
                           limit: int | None = None, seconds: float | None = None,
                           progress: Callable[[str, int], None] | None = None) -> AdditionCount:
    """Count valid additions label by label, stopping a label at ``limit`` and everything when
    ``seconds`` have passed (checked inside the cycle search too, so a search that finds
    nothing for a long time still stops).  ``progress(label, count)`` is called now and then.

    >>> from polyloops.io.examples import load_example
    >>> count_additions_within(load_example("cube").dualize(), limit=1)
    AdditionCount(counts={'X': 1, 'Y': 1, 'Z': 1}, complete={'X': False, 'Y': False, 'Z': False})
    """
    budget = TimeShares(seconds, len(axes))
    counts = dict.fromkeys((a.name for a in axes), 0)
    complete = dict.fromkeys(counts, False)
    for a in axes:
        counts[a.name], complete[a.name] = count_valid_additions(ls, a, limit, budget.next_deadline())
        if progress is not None:
            progress(a.name, counts[a.name])
    return AdditionCount(counts, complete)


class TimeShares:
    """A time budget shared by ``parts`` searches done one after another: each gets an equal
    share of what is left when it starts, so time a quick search leaves over goes to the later
    ones and no search is starved by an earlier one (``seconds=None``: no bound).

    >>> shares = TimeShares(None, 3)
    >>> shares.next_share()()
    False
    """

    def __init__(self, seconds: float | None, parts: int):
        self.end = None if seconds is None else time.monotonic() + seconds
        self.left = max(parts, 1)

    def next_deadline(self) -> float | None:
        """The end (a :func:`time.monotonic` time) of the next search's share, or ``None``."""
        if self.end is None:
            return None
        now = time.monotonic()
        deadline = now + max(self.end - now, 0.0) / self.left
        self.left = max(self.left - 1, 1)
        return deadline

    def next_share(self) -> Callable[[], bool]:
        """The ``expired()`` test of the next search's share."""
        deadline = self.next_deadline()
        if deadline is None:
            return lambda: False
        return lambda: time.monotonic() > deadline


@dataclass(frozen=True)
class AdditionListing:
    """Additions found by :func:`list_additions`, each with its name, and per label whether
    the listing is complete (``False`` where a limit or the time limit stopped it)."""

    additions: tuple[tuple[str, Addition], ...]
    complete: dict[str, bool]
    stopped_by: str | None  # "a limit", "the time limit", or None when complete


def list_additions(ls: LoopStructure, axes: Sequence[Axis] = tuple(Axis), *, limit: int | None = None,
                   seconds: float | None = None, shortest: int | None = None,
                   sample: int | None = None, seed: int = 0,
                   on_found: Callable[[str, Addition], None] | None = None) -> AdditionListing:
    """Valid additions of the labels ``axes``: all of them in :func:`additions` order (named
    ``Y3``, at most ``limit`` in all), the ``shortest`` per label, or a random ``sample`` per
    label (named by their cycle, ``Y:0,4,5,1``, since their place in the full listing is
    unknown).  ``seconds`` bounds the time; ``on_found(name, move)`` is called as each is found,
    so a caller can show a long listing as it grows.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> listing = list_additions(box, [Axis.X], limit=2)
    >>> [name for name, _ in listing.additions], listing.complete, listing.stopped_by
    (['X0', 'X1'], {'X': False}, 'a limit')
    >>> [name for name, _ in list_additions(box, [Axis.Y], shortest=1).additions]
    ['Y:0,4,5,1']
    """
    found: list[tuple[str, Addition]] = []
    complete = {a.name: True for a in axes}
    budget = TimeShares(seconds, len(axes))

    def show(name: str, move: Addition) -> None:
        found.append((name, move))
        if on_found is not None:
            on_found(name, move)

    if shortest is not None or sample is not None:
        for a in axes:
            expired = budget.next_share()
            try:
                picked = (shortest_additions(ls, a, shortest, expired) if shortest is not None
                          else sample_additions(ls, a, sample or 0, seed, stop=expired))
            except SearchStopped:
                complete[a.name] = False
                continue
            if expired():
                complete[a.name] = False
            for move in picked:
                show(f"{a.name}:" + ",".join(map(str, move.cycle)), move)
        return AdditionListing(tuple(found), complete,
                               None if all(complete.values()) else "the time limit")
    total = 0
    for a in axes:
        expired = budget.next_share()
        i = 0
        try:
            for move in additions(ls, a, stop=expired):
                if (limit is not None and total >= limit) or expired():
                    complete[a.name] = False
                    break
                show(addition_index(a, i), move)
                i += 1
                total += 1
        except SearchStopped:
            complete[a.name] = False
    stopped = None
    if not all(complete.values()):
        stopped = "a limit" if limit is not None and total >= limit else "the time limit"
    return AdditionListing(tuple(found), complete, stopped)
