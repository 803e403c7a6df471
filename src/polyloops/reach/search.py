"""Reachability: breadth-first search over loop additions and removals.

The *move graph* has a node per polycube loop structure (up to the chosen symmetry) and an
edge for each valid loop addition or removal.  It is undirected: if ``B`` is ``A`` with a loop
added, removing that loop from ``B`` gives back ``A``, and conversely (both are polycube loop
structures, so both moves are valid).  In genus 0 an addition past ``k`` corners adds ``k``
corners and a removal takes some away, so a bound ``M`` on the corners of every state keeps
the search finite.

States are named by their signature in a symmetry mode (:mod:`polyloops.core.canonical`);
a state is expanded from its canonical representative ``from_signature(sig)``, and a move is
recorded in that representative's numbering: the axis and corner cycle of an addition, or
the id of the removed loop.  So any path can be rebuilt from the stored parents without
searching again.

>>> from polyloops.io.examples import load_example
>>> result = explore(load_example("cube").dualize(), max_corners=16)
>>> result.by_corners
{8: 1, 12: 3, 16: 15}
"""

from __future__ import annotations

import json
import sqlite3
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import Any

from polyloops.core.canonical import canonical_form, from_signature
from polyloops.core.directions import Axis
from polyloops.core.errors import PolyloopsError
from polyloops.core.moves import (
    Addition,
    _AdditionGraph,
    add_loop,
    additions,
    removals,
    remove_loop,
    try_remove,
)
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import Symmetry
from polyloops.io.files import InputError, check_regular, read_only_uri
from polyloops.parallel import run_jobs

MODES = tuple(Symmetry)


class MoveKind(StrEnum):
    """A kind of loop move: an addition or a removal."""

    ADD = "add"
    REMOVE = "remove"


@dataclass(frozen=True)
class Move:
    """One loop move, in the numbering of the structure it applies to."""

    kind: MoveKind
    axis: Axis | None = None
    cycle: tuple[int, ...] = ()
    loop: int | None = None

    @classmethod
    def add(cls, move: Addition) -> Move:
        return cls(MoveKind.ADD, move.axis, tuple(move.cycle))

    @classmethod
    def remove(cls, loop: int) -> Move:
        return cls(MoveKind.REMOVE, loop=loop)

    def apply(self, ls: LoopStructure) -> LoopStructure:
        """The structure after the move (validity is not checked here)."""
        if self.kind is MoveKind.ADD:
            assert self.axis is not None
            return add_loop(ls, Addition(self.axis, self.cycle))
        assert self.loop is not None
        return remove_loop(ls, self.loop)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the move."""
        if self.kind is MoveKind.ADD:
            return {"add": str(self.axis), "corners": list(self.cycle)}
        return {"remove": self.loop}

    @classmethod
    def from_json(cls, data: Any) -> Move:
        """Parse ``{"add": "X", "corners": [...]}`` or ``{"remove": 3}``; ``ValueError`` else."""
        if isinstance(data, dict) and set(data) == {"add", "corners"}:
            corners = data["corners"]
            if not (isinstance(corners, list) and all(type(c) is int and c >= 0 for c in corners)):
                raise ValueError("an addition's corners must be a list of corner ids")
            return cls(MoveKind.ADD, Axis.parse(str(data["add"])), tuple(corners))
        if isinstance(data, dict) and set(data) == {"remove"} and type(data["remove"]) is int:
            return cls(MoveKind.REMOVE, loop=data["remove"])
        raise ValueError(f"not a move: {json.dumps(data)[:80]}")

    def __str__(self) -> str:
        if self.kind is MoveKind.ADD:
            return f"add {self.axis}:{','.join(map(str, self.cycle))}"
        return f"remove loop {self.loop}"


BOTH = (MoveKind.ADD, MoveKind.REMOVE)


def neighbours(ls: LoopStructure, max_corners: int,
               kinds: Sequence[MoveKind] = BOTH) -> Iterator[tuple[Move, LoopStructure]]:
    """Every valid move from ``ls`` whose result has at most ``max_corners`` corners, with the
    result: additions first (X, Y, Z, in :func:`~polyloops.core.moves.additions` order),
    then removals by loop id."""
    room = max_corners - ls.map.num_corners
    if MoveKind.ADD in kinds and room >= 3:
        for mv in additions(ls, max_length=room):
            child = add_loop(ls, mv, checked=False)  # the move tests accepted it: no re-check
            if child.map.num_corners <= max_corners:
                yield Move.add(mv), child
    if MoveKind.REMOVE in kinds:
        for loop in removals(ls):
            yield Move.remove(loop), remove_loop(ls, loop, checked=False)


def parse_kinds(text: str) -> tuple[MoveKind, ...]:
    """``"add"`` or ``"add,remove"`` (any order) -> the move kinds; ``ValueError`` otherwise."""
    parts = [p.strip() for p in text.split(",") if p.strip()]
    try:
        kinds = tuple(MoveKind(p) for p in parts)
    except ValueError:
        raise ValueError(f"moves must be add, remove or add,remove, not {text!r}") from None
    if not kinds or len(set(kinds)) != len(kinds):
        raise ValueError(f"moves must be add, remove or add,remove, not {text!r}")
    return tuple(k for k in MoveKind if k in kinds)


# -- one level of the search, as a job ----------------------------------------------------------

@dataclass(frozen=True)
class Child:
    """A state found one move from another, named by its signature."""

    signature: str
    corners: int
    move: Move


def expand(task: tuple[str, str, int, tuple[MoveKind, ...]]) -> list[Child]:
    """The children of one state (a job for a worker): every valid move within the bound,
    named by signature, duplicates kept in order of first appearance."""
    sig, mode, max_corners, kinds = task
    ls = from_signature(sig, checked=False)  # the search's own names, checked when first made
    out: list[Child] = []
    seen: set[str] = set()
    for move, child in neighbours(ls, max_corners, kinds):
        s = canonical_form(child, mode).signature
        if s not in seen:
            seen.add(s)
            out.append(Child(s, child.map.num_corners, move))
    return out


# -- storage -------------------------------------------------------------------------------------

SCHEMA = """
CREATE TABLE IF NOT EXISTS states (
    signature TEXT PRIMARY KEY, corners INTEGER NOT NULL, distance INTEGER NOT NULL,
    parent TEXT, move TEXT);
CREATE INDEX IF NOT EXISTS by_distance ON states (distance);
CREATE TABLE IF NOT EXISTS meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);
"""


class ReachError(PolyloopsError, ValueError):
    """A reach directory that does not belong to this search, or bad parameters."""


class WouldReplaceSearchError(ReachError):
    """A reach directory that holds another search, or files that are not a search: it is
    replaced only when asked (``overwrite``)."""


def _open_store(path: Path) -> sqlite3.Connection:
    """The reach database at ``path``, created when missing; anything that is not one (a
    FIFO, a damaged file, another program's database) is refused untouched."""
    if path.exists() or path.is_symlink():
        try:
            check_regular(path, limit=None)
        except InputError as err:
            raise ReachError(str(err)) from None
    try:
        con = sqlite3.connect(path)
        tables = {name for (name,) in con.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
    except sqlite3.DatabaseError as err:
        raise ReachError(f"{path}: not a reach database ({err})") from None
    if tables and not {"states", "meta"} <= tables:
        con.close()
        raise ReachError(f"{path}: a database of another kind (tables {', '.join(sorted(tables))}), "
                         "not a reach search")
    try:
        con.executescript(SCHEMA)
        if tables:  # a stored search knows its last complete level
            int(con.execute("SELECT value FROM meta WHERE key = 'level'").fetchone()[0])
    except (sqlite3.DatabaseError, TypeError, ValueError) as err:
        con.close()
        raise ReachError(f"{path}: not a reach database ({err})") from None
    return con


@dataclass(frozen=True)
class State:
    """A state of the search: its signature, corners, distance from the start, and how it was reached."""

    signature: str
    corners: int
    distance: int
    parent: str | None
    move: Move | None


class ReachStore:
    """``DIR/reach.sqlite``: one row per reached state; ``meta`` holds the search parameters
    and the last level written.  Each level is written in one transaction, so an interrupted
    run loses at most the level it was computing."""

    def __init__(self, directory: Path, params: dict[str, Any], overwrite: bool = False):
        self.path = directory / "reach.sqlite"
        foreign = [name for name in ("catalog.jsonl", "catalog.sqlite") if (directory / name).exists()]
        if foreign:
            raise ReachError(f"{directory}: holds a catalog ({', '.join(foreign)}); a search would "
                             "replace its summary.json: use another directory")
        if not overwrite and (directory / "summary.json").exists() and not self.path.exists():
            raise WouldReplaceSearchError(f"{directory}: holds a summary.json but no reach.sqlite; a "
                                          "search would replace it")
        try:
            directory.mkdir(exist_ok=True)
            self.con = _open_store(self.path)
            stored = dict(self.con.execute("SELECT key, value FROM meta"))
        except OSError as err:
            raise ReachError(f"{directory}: cannot write: {err.strerror or err}") from None
        except sqlite3.Error as err:  # a directory it may not write into, a full disk
            raise ReachError(f"{self.path}: cannot write: {err}") from None
        wanted = {k: json.dumps(v) for k, v in params.items()}
        if stored:
            differ = [k for k in wanted if stored.get(k) != wanted[k]]
            if differ and not overwrite:
                self.con.close()
                raise WouldReplaceSearchError(f"{self.path}: a search with other parameters "
                                              f"({', '.join(differ)}) is stored here")
            if differ:  # replace it: start afresh in the same file
                with self.con:
                    self.con.execute("DELETE FROM states")
                    self.con.execute("DELETE FROM meta")
                stored = {}
        if not stored:
            with self.con:
                self.con.executemany("INSERT INTO meta VALUES (?, ?)", [*wanted.items(), ("level", "-1")])

    @property
    def level(self) -> int:
        """The last complete level (-1 before the start state is written)."""
        return int(self.con.execute("SELECT value FROM meta WHERE key = 'level'").fetchone()[0])

    def write_level(self, level: int, states: list[State]) -> None:
        """Store one finished level of states, in one transaction."""
        with self.con:
            self.con.executemany("INSERT INTO states VALUES (?, ?, ?, ?, ?)", [
                (s.signature, s.corners, s.distance, s.parent,
                 None if s.move is None else json.dumps(s.move.to_json())) for s in states])
            self.con.execute("UPDATE meta SET value = ? WHERE key = 'level'", (str(level),))

    def distances(self) -> dict[str, tuple[int, int]]:
        """signature -> (distance, corners) of every stored state."""
        return {s: (d, c) for s, d, c in self.con.execute("SELECT signature, distance, corners FROM states")}

    def state(self, signature: str) -> State | None:
        """The stored state with this signature, or ``None``."""
        row = self.con.execute("SELECT signature, corners, distance, parent, move FROM states "
                               "WHERE signature = ?", (signature,)).fetchone()
        return None if row is None else _state(row)

    def close(self) -> None:
        """Close the database."""
        self.con.close()


def _state(row: tuple[Any, ...]) -> State:
    sig, corners, distance, parent, move = row
    return State(sig, corners, distance, parent, None if move is None else Move.from_json(json.loads(move)))


def stored_signatures(store_dir: Path) -> list[str]:
    """The signatures of every state stored in ``store_dir/reach.sqlite``, by distance."""
    con = sqlite3.connect(read_only_uri(store_dir / "reach.sqlite"), uri=True)
    try:
        return [sig for (sig,) in con.execute("SELECT signature FROM states ORDER BY distance, signature")]
    finally:
        con.close()


def path_to(store_dir: Path, signature: str) -> list[State]:
    """The stored states from the start to ``signature``, following parents; each state's
    move applies to ``from_signature`` of the state before it."""
    con = sqlite3.connect(read_only_uri(store_dir / "reach.sqlite"), uri=True)
    try:
        out = []
        sig: str | None = signature
        while sig is not None:
            row = con.execute("SELECT signature, corners, distance, parent, move FROM states "
                              "WHERE signature = ?", (sig,)).fetchone()
            if row is None:
                raise ReachError(f"{signature[:40]}...: not reached in {store_dir}")
            out.append(_state(row))
            sig = out[-1].parent
        return out[::-1]
    finally:
        con.close()


# -- the search ----------------------------------------------------------------------------------

@dataclass
class ReachResult:
    """What :func:`explore` found: states by corners and by distance."""

    start: str
    mode: Symmetry
    max_corners: int
    kinds: tuple[MoveKind, ...]
    by_corners: dict[int, int] = field(default_factory=dict)
    by_distance: dict[int, int] = field(default_factory=dict)
    seconds: float = 0.0
    complete: bool = True  # False when --max-depth stopped a frontier that was not empty

    @property
    def states(self) -> int:
        """The number of states found."""
        return sum(self.by_corners.values())

    @property
    def max_distance(self) -> int:
        """The largest distance from the start."""
        return max(self.by_distance, default=0)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the result (the reach command's summary.json)."""
        return {"start": self.start, "symmetry": self.mode, "max_corners": self.max_corners,
                "moves": ",".join(k.value for k in self.kinds), "states": self.states,
                "by_corners": {str(k): v for k, v in sorted(self.by_corners.items())},
                "by_distance": {str(k): v for k, v in sorted(self.by_distance.items())},
                "max_distance": self.max_distance, "complete": self.complete,
                "seconds": round(self.seconds, 3)}


def explore(start: LoopStructure, max_corners: int, max_depth: int | None = None,
            kinds: Sequence[MoveKind] = BOTH, mode: Symmetry | str = Symmetry.LABELLED,
            directory: Path | None = None, workers: int = 1, dask: str | None = None,
            progress: Callable[[dict[str, Any]], None] | None = None,
            overwrite: bool = False) -> ReachResult:
    """Breadth-first search of the move graph from ``start``: every state within ``max_corners``
    reachable by loop additions and removals (see the module docstring).

    Levels are expanded in parallel with ``workers`` processes or on a Dask cluster; parents are
    then chosen in signature order, so the result does not depend on how the work was split.

    Parameters
    ----------
    start:
        A polycube loop structure.
    max_corners:
        No state has more corners.
    max_depth:
        Stop after this many moves (the result then says it is incomplete).
    kinds:
        Which moves: additions, removals, or both (the default).
    mode:
        States up to renumbering (``labelled``, the default), rotation or all 48 symmetries.
    directory:
        Store states in ``directory/reach.sqlite`` level by level; a rerun resumes after the
        last complete level.
    workers, dask:
        Local worker processes, or a Dask scheduler address (``local`` for a local cluster).
    progress:
        Called after each level with its counts.
    overwrite:
        Replace a search of other parameters stored in ``directory`` (without it, refused).

    Returns
    -------
    ReachResult
        States by corners and by distance, and whether the search was complete.

    Raises
    ------
    ValueError
        When ``start`` has no sides or the mode is unknown.
    ReachError
        When ``directory`` holds a catalog or a damaged or foreign database.
    WouldReplaceSearchError
        When ``directory`` holds another search (without ``overwrite``).

    >>> from polyloops.io.examples import load_example
    >>> result = explore(load_example("cube").dualize(), max_corners=16)
    >>> result.by_corners
    {8: 1, 12: 3, 16: 15}
    """
    try:
        return _explore(start, max_corners, max_depth, kinds, mode, directory, workers, dask, progress,
                        overwrite)
    except sqlite3.Error as err:  # a store that cannot be written on (read-only, full disk)
        raise ReachError(f"{directory}: cannot write the search's store: {err}") from None


def _explore(start: LoopStructure, max_corners: int, max_depth: int | None, kinds: Sequence[MoveKind],
             mode: Symmetry | str, directory: Path | None, workers: int, dask: str | None,
             progress: Callable[[dict[str, Any]], None] | None, overwrite: bool) -> ReachResult:
    mode = Symmetry.parse(mode)
    if not start.oriented:
        raise ValueError("reachability needs an oriented loop structure")
    kinds = tuple(k for k in MoveKind if k in kinds)
    began = time.perf_counter()
    start_sig = canonical_form(start, mode).signature
    result = ReachResult(start_sig, mode, max_corners, kinds)
    if start.map.num_corners > max_corners:
        raise ValueError(f"the start has {start.map.num_corners} corners, more than max_corners "
                         f"{max_corners}")
    store = None
    if directory is not None:
        store = ReachStore(directory, {"start": start_sig, "mode": mode, "max_corners": max_corners,
                                       "moves": [k.value for k in kinds]}, overwrite)
    try:
        known: dict[str, tuple[int, int]] = store.distances() if store else {}
        level = store.level if store else -1
        if level < 0:
            known = {start_sig: (0, start.map.num_corners)}
            if store:
                store.write_level(0, [State(start_sig, start.map.num_corners, 0, None, None)])
            level = 0
        frontier = sorted(s for s, (d, _) in known.items() if d == level)
        while frontier and (max_depth is None or level < max_depth):
            tasks = [(sig, mode, max_corners, kinds) for sig in frontier]
            new: list[State] = []
            # Many small jobs: a few batches per worker, not a message per state.
            batch = max(1, len(tasks) // (8 * max(1, workers)))
            results = run_jobs(expand, tasks, workers, dask, batch=batch)
            for sig, children in zip(frontier, results, strict=True):
                for child in children:
                    if child.signature not in known:
                        known[child.signature] = (level + 1, child.corners)
                        new.append(State(child.signature, child.corners, level + 1, sig, child.move))
            level += 1
            if store:
                store.write_level(level, new)
            frontier = sorted(s.signature for s in new)
            if progress:
                progress({"level": level, "states": len(known), "frontier": len(frontier),
                          "seconds": time.perf_counter() - began})
        result.complete = not frontier
    finally:
        if store:
            store.close()
    for d, c in known.values():
        result.by_corners[c] = result.by_corners.get(c, 0) + 1
        result.by_distance[d] = result.by_distance.get(d, 0) + 1
    result.by_corners = dict(sorted(result.by_corners.items()))
    result.by_distance = dict(sorted(result.by_distance.items()))
    result.seconds = time.perf_counter() - began
    return result


# -- shortest paths ------------------------------------------------------------------------------

def shortest_path(source: LoopStructure, target: LoopStructure, max_corners: int,
                  kinds: Sequence[MoveKind] = BOTH) -> list[LoopStructure] | None:
    """A shortest sequence of structures from ``source`` to one isomorphic to ``target``
    (labelled mode), each one move from the one before up to renumbering, all within
    ``max_corners``.  Bidirectional: the move graph is undirected, so the target side expands
    with the same moves.

    Parameters
    ----------
    source, target:
        Polycube loop structures.
    max_corners:
        No structure on the path has more corners.
    kinds:
        Which moves: additions, removals, or both (the default).

    Returns
    -------
    list[LoopStructure] or None
        From ``source`` to a structure isomorphic to ``target``; ``None`` when there is none.

    Raises
    ------
    ValueError
        When a structure has no sides.

    >>> from polyloops.io.examples import load_example
    >>> path = shortest_path(load_example("cube").dualize(), load_example("l-shape").dualize(), 16)
    >>> [ls.map.num_corners for ls in path]
    [8, 12, 16]
    """
    def sig(ls: LoopStructure) -> str:
        return canonical_form(ls, "labelled").signature

    if no_path_reason(source, target) is not None:  # no search can find one
        return None
    # Per side: signature -> (structure, parent signature); structures are the actual results
    # of applying a move to the parent's structure.
    sides: list[dict[str, tuple[LoopStructure, str | None]]] = [{sig(source): (source, None)},
                                                                   {sig(target): (target, None)}]
    frontiers = [list(sides[0]), list(sides[1])]
    meet = next((s for s in sides[0] if s in sides[1]), None)
    while meet is None and frontiers[0] and frontiers[1]:
        i = 0 if len(frontiers[0]) <= len(frontiers[1]) else 1
        mine, other = sides[i], sides[1 - i]
        nxt = []
        for s in frontiers[i]:
            ls = mine[s][0]
            for _, child in neighbours(ls, max_corners, kinds):
                c = sig(child)
                if c not in mine:
                    mine[c] = (child, s)
                    nxt.append(c)
                    if c in other and meet is None:
                        meet = c
        frontiers[i] = nxt
    if meet is None:
        return None

    def chain(side: dict[str, tuple[LoopStructure, str | None]], s: str | None) -> list[LoopStructure]:
        out = []
        while s is not None:
            ls, s = side[s]
            out.append(ls)
        return out

    forward = chain(sides[0], meet)[::-1]
    backward = chain(sides[1], meet)
    return forward + backward[1:]


# -- checking a path, without trusting how it was found ---------------------------------------

@dataclass(frozen=True)
class PathCheck:
    """Whether a path checks: every step valid, every pair one move apart; else the first bad step."""

    valid: bool
    steps: int
    bad_step: int | None = None
    reason: str = ""


def one_move_apart(a: LoopStructure, b: LoopStructure) -> bool:
    """Whether ``b`` is, up to renumbering, ``a`` with one loop added or removed (see
    :func:`move_between`)."""
    return move_between(a, b) is not None


def move_between(a: LoopStructure, b: LoopStructure) -> Move | None:
    """A move that turns ``a`` into ``b`` up to renumbering, in ``a``'s numbering, or ``None``.
    Every candidate is tried (every simple cycle of the paper's graphs of the right length,
    before any separation test, and every loop) and compared by labelled signature; validity
    of both ends is the caller's business, so this never trusts the fast move tests.

    >>> from polyloops.io.examples import load_example
    >>> cube, box = load_example("cube").dualize(), load_example("box-2x1x1").dualize()
    >>> print(move_between(cube, box).kind, move_between(box, cube))
    add remove loop 2
    """
    target = canonical_form(b, "labelled").signature
    grow = b.map.num_corners - a.map.num_corners
    if grow >= 3:
        for axis in Axis:
            for cycle in _AdditionGraph(a, axis).cycles(grow):
                if len(cycle) == grow:
                    child = add_loop(a, Addition(axis, cycle))
                    if canonical_form(child, "labelled").signature == target:
                        return Move(MoveKind.ADD, axis, tuple(cycle))
    elif grow < 0:
        for lp in a.loops:
            smaller = try_remove(a, lp.id)
            if smaller is not None and canonical_form(smaller, "labelled").signature == target:
                return Move.remove(lp.id)
    return None


@dataclass(frozen=True)
class MovePath:
    """A path in the move graph told both ways: ``steps[i + 1]`` is ``moves[i]`` applied to
    ``steps[i]`` (so replaying the moves from the first step gives every step exactly)."""

    steps: tuple[LoopStructure, ...]
    moves: tuple[Move, ...]

    def describe(self, i: int) -> str:
        """Move ``i`` in words, such as ``add an X-loop past corners 0 1 3 2 (8 -> 12 corners)``."""
        move, before, after = self.moves[i], self.steps[i], self.steps[i + 1]
        sizes = f"({before.map.num_corners} -> {after.map.num_corners} corners)"
        if move.kind is MoveKind.ADD:
            article = "an" if move.axis is Axis.X else "a"
            return f"add {article} {move.axis}-loop past corners {' '.join(map(str, move.cycle))} {sizes}"
        assert move.loop is not None
        return f"remove loop {move.loop} ({before.axes[move.loop]}) {sizes}"

    def to_json(self) -> dict[str, Any]:
        """The path document ``polyloops path -o`` writes: the steps, and the moves in the
        conjecture certificate's format."""
        from polyloops.io.formats import to_data

        return {"polyloops": 1, "kind": "path", "steps": [to_data(s) for s in self.steps],
                "moves": [m.to_json() for m in self.moves]}


def no_path_reason(source: LoopStructure, target: LoopStructure) -> str | None:
    """Why no sequence of moves, of any size, leads from ``source`` to ``target``, or ``None``
    when the invariants moves keep agree: the genus (a move keeps the surface), and at
    positive genus the hole orientation (:mod:`polyloops.core.holes`; a move never changes the
    subgroup of homology each axis's loops span, docs/reachability.md).  Paths are asked up to
    renumbering, axes fixed, so the invariant is compared as it is, not up to the axes.

    >>> from polyloops.io.examples import load_example
    >>> ring, ring_x = load_example("ring").dualize(), load_example("ring-x").dualize()
    >>> no_path_reason(load_example("cube").dualize(), ring)
    'moves keep the genus: 0 and 1'
    >>> no_path_reason(ring, ring_x).split(":")[0]
    'moves keep the hole orientation'
    """
    from polyloops.core.holes import hole_orientation

    if source.map.genus != target.map.genus:
        return f"moves keep the genus: {source.map.genus} and {target.map.genus}"
    if source.map.genus > 0:
        a, b = hole_orientation(source), hole_orientation(target)
        if a != b:
            return f"moves keep the hole orientation: {a} and {b}"
    return None


def find_path(source: LoopStructure, target: LoopStructure, max_corners: int,
              kinds: Sequence[MoveKind] = BOTH) -> MovePath | None:
    """:func:`shortest_path` with its moves: a shortest path from ``source`` to a structure
    isomorphic to ``target``, each step the previous one with its move applied.

    >>> from polyloops.io.examples import load_example
    >>> path = find_path(load_example("cube").dualize(), load_example("l-shape").dualize(), 16)
    >>> [path.describe(i).split(" (")[1] for i in range(len(path.moves))]
    ['8 -> 12 corners)', '12 -> 16 corners)']
    """
    found = shortest_path(source, target, max_corners, kinds)
    if found is None:
        return None
    steps, moves = [source], []
    for nxt in found[1:]:
        move = move_between(steps[-1], nxt)
        if move is None:  # pragma: no cover - shortest_path's steps are one move apart
            raise AssertionError("consecutive steps of a shortest path are not one move apart")
        moves.append(move)
        steps.append(move.apply(steps[-1]))
    return MovePath(tuple(steps), tuple(moves))


def check_path(steps: Sequence[LoopStructure], moves: Sequence[Move] | None = None) -> PathCheck:
    """Every step a polycube loop structure (Definition 4, full checker) and every consecutive
    pair one move apart; with ``moves``, each move applied to its step gives the next step up
    to renumbering.  The first bad step is named (0-based)."""
    from polyloops.verify import check_polycube_loop_structure

    if moves is not None and len(moves) != len(steps) - 1:
        return PathCheck(False, len(steps), None, f"{len(moves)} moves for {len(steps)} steps")
    for i, ls in enumerate(steps):
        if not ls.oriented:
            return PathCheck(False, len(steps), i, "a labelled structure without sides")
        report = check_polycube_loop_structure(ls)
        if not report.valid:
            v = report.violations[0]
            return PathCheck(False, len(steps), i, f"not a polycube loop structure: {v.definition} "
                             f"condition {v.condition}: {v.message}")
        if i and moves is not None:
            try:
                after = moves[i - 1].apply(steps[i - 1])
            except (KeyError, IndexError, ValueError, TypeError) as err:
                return PathCheck(False, len(steps), i, f"move {i - 1} ({moves[i - 1]}) cannot be applied "
                                 f"to step {i - 1}: {err}")
            if canonical_form(after, "labelled").signature != canonical_form(ls, "labelled").signature:
                return PathCheck(False, len(steps), i, f"move {i - 1} ({moves[i - 1]}) applied to step "
                                 f"{i - 1} does not give this step")
        elif i and not one_move_apart(steps[i - 1], ls):
            return PathCheck(False, len(steps), i, f"not one loop addition or removal from step {i - 1}")
    return PathCheck(True, len(steps))


def path_moves(data: dict[str, Any]) -> list[Move] | None:
    """The moves of a path document, or ``None`` when it has none (files written before paths
    told their moves).  Raises :class:`~polyloops.io.formats.FormatError` for a bad move."""
    from polyloops.io.formats import FormatError

    moves = data.get("moves")
    if moves is None:
        return None
    if not isinstance(moves, list):
        raise FormatError('a path\'s "moves" must be a list')
    out = []
    for i, move in enumerate(moves):
        try:
            out.append(Move.from_json(move))
        except ValueError as err:
            raise FormatError(f"move {i}: {err}") from None
    return out


def path_steps(data: dict[str, Any]) -> list[LoopStructure]:
    """The steps of a path document (``{"polyloops": 1, "kind": "path", "steps": [...]}``, as
    ``polyloops path -o`` writes it), each built as a loop structure.  Raises
    :class:`~polyloops.io.formats.FormatError` naming the step for anything else.

    >>> from polyloops.io.examples import load_example
    >>> from polyloops.io.formats import to_data
    >>> cube = load_example("cube").dualize()
    >>> len(path_steps({"kind": "path", "steps": [to_data(cube)]}))
    1
    """
    from polyloops.io.formats import FormatError, parse_document

    steps = data.get("steps")
    if not isinstance(steps, list) or not steps:
        raise FormatError('a path needs a non-empty list "steps"')
    out = []
    for i, step in enumerate(steps):
        try:
            doc = parse_document(json.dumps(step))
            if doc.kind != "loop-structure":
                raise FormatError("a step must be a loop structure")
            built = doc.build()
        except (ValueError, RecursionError) as err:
            raise FormatError(f"step {i}: {err}") from None
        assert isinstance(built, LoopStructure)
        out.append(built)
    return out
