"""The genus-0 reachability conjecture, settled class by class with a checkable certificate.

The paper (Section 4.3) asks whether every genus-0 polycube can be reached from the cube by
adding and removing loops.  Induction on the number of corners: the cube is the only polycube
with 8 corners.  A polycube with a removable loop is one move from a polycube with fewer
corners, which is reachable by induction, and moves can be undone, so it is reachable too.
Only *irreducible* polycubes (no removable loop) need more: a path of moves to any polycube
with fewer corners.  Searching within ``corners + K`` corners for ``K = 2, 4, ...`` finds the
smallest such detour.

A certificate is JSON lines: a header, then one record per catalog class:
``{"signature", "corners", "base": true}`` for the cube, ``{"signature", "corners",
"removable": LOOP}`` or ``{"signature", "corners", "detour":
{"slack", "max_corners", "moves": [...]}}`` (moves replayed from ``from_signature(signature)``),
or ``{"signature", "corners", "unsettled": true, "searched": K}``.  :func:`check_certificate`
replays every record with the Definition-4 checker and trusts nothing else.

**Open classes.**  A class the search leaves unsettled is *open*, and the header says how many
there are (``"unsettled": k``, absent when none).  Its record says how far its detours were
searched in vain (``"searched": K``: every slack up to ``K``; without it, the header's slack), a
claim of the search that nothing replays.  A certificate with open classes still checks
when everything it states holds, and it proves what the induction gives: every class with fewer
corners than the smallest open one is reachable, and so is every other class with exactly that
many (its move or detour ends below, or at a base).  Larger classes may lean on an open one, so
their records prove nothing more (:meth:`CertificateCheck.statement`).

**Long detours.**  Past the breadth-first search's slack, an open class may be given to
:func:`find_long_detour` (added loops each followed by removals, far higher).  Its detour is
replayed like any other, and its record keeps, beside it, the slack the breadth-first search
went to in vain (``"searched": K``, below the detour's slack): the least slack of any detour of
that class lies above ``K`` and at most at the detour's.

**Genus 1.**  Moves never change the hole orientation (:mod:`polyloops.core.holes`), so the
question is asked within each *orientation type* (the invariant up to the symmetries of the
axes, :meth:`~polyloops.core.holes.HoleOrientation.up_to_axes`): is every class reachable from a
smallest class of its type?  The same induction, started at one *base* per type (the first
class of the catalog among those of the type with fewest corners); the other classes of that
size have no smaller class to go down to, so their detours end at the base instead.  The
certificate's header says ``genus1-reachability-certificate``, and each record carries its
type (``orientation``), which the checker computes again.
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, TypeGuard

from polyloops.catalog.census import Census, read_catalog
from polyloops.core.canonical import canonical_form, from_signature
from polyloops.core.errors import PolyloopsError
from polyloops.core.moves import check_removal
from polyloops.core.structure import LoopStructure
from polyloops.reach.search import Move


def certificate_kind(genus: int) -> str:
    """The ``kind`` of a certificate's header for a catalog of ``genus``.

    >>> certificate_kind(1), certificate_genus("genus2-reachability-certificate")
    ('genus1-reachability-certificate', 2)
    """
    return f"genus{genus}-reachability-certificate"


def certificate_genus(kind: object) -> int | None:
    """The genus a header's ``kind`` names, or ``None`` when it is no certificate kind."""
    found = re.fullmatch(r"genus(0|[1-9][0-9]{0,2})-reachability-certificate", kind) \
        if isinstance(kind, str) else None
    return int(found.group(1)) if found else None


CERTIFICATE_KIND = certificate_kind(0)
CUBE_CORNERS = 8  # the cube is the only polycube with 8 corners (and none has fewer)


def orientation_type(ls: LoopStructure) -> str:
    """The hole orientation of a structure up to the symmetries of the axes, as text: moves
    keep it, and it names the question's classes at genus 1."""
    from polyloops.core.holes import hole_orientation

    return str(hole_orientation(ls).up_to_axes())


def removable_loop(ls: LoopStructure) -> int | None:
    """The lowest loop whose removal leaves a polycube loop structure, or ``None``."""
    return next((lp.id for lp in ls.loops if check_removal(ls, lp.id).valid), None)


def find_detour(ls: LoopStructure, max_corners: int, target: str | None = None) -> list[Move] | None:
    """A shortest sequence of moves from ``ls`` to a structure with fewer corners (or, given a
    ``target`` signature up to all 48 symmetries, to that class), every structure on the way
    within ``max_corners`` (breadth-first, states up to all 48 symmetries); the moves apply one
    after the other starting from ``ls`` itself.

    Only a removal goes below the class's corners, so, without a ``target``, each level's
    removals are tried before any of its additions is built: the level that holds a detour's
    last move is not expanded. The detour is the one a plain breadth-first search (additions,
    then removals, node by node) meets first: the first node of the level with a removal below,
    and its first such removal. With a ``target`` (which an addition may reach) the level is
    searched in the plain order.
    """
    from polyloops.core.moves import add_loop, additions, removals, remove_loop

    n = ls.map.num_corners
    seen = {canonical_form(ls, "full").signature}
    level: list[tuple[LoopStructure, list[Move]]] = [(ls, [])]
    while level:
        removed: list[list[tuple[Move, LoopStructure]]] = []
        for current, moves in level:
            children = [(Move.remove(loop), remove_loop(current, loop, checked=False))
                        for loop in removals(current)]
            below = next((move for move, child in children if child.map.num_corners < n), None)
            if below is not None and target is None:
                return [*moves, below]
            removed.append(children)
        nxt = []
        for (current, moves), children in zip(level, removed, strict=True):
            room = max_corners - current.map.num_corners
            grown = ((Move.add(mv), add_loop(current, mv, checked=False))
                     for mv in additions(current, max_length=room)) if room >= 3 else iter(())
            for move, child in [*grown, *children]:
                if child.map.num_corners > max_corners:
                    continue
                if child.map.num_corners < n:  # with a target, met in the plain search's order
                    return [*moves, move]
                s = canonical_form(child, "full").signature
                if s == target:
                    return [*moves, move]
                if s not in seen:
                    seen.add(s)
                    nxt.append((child, [*moves, move]))
        level = nxt
    return None


def find_long_detour(ls: LoopStructure, max_corners: int, target: str | None = None, rounds: int = 2,
                     depth: int = 8) -> list[Move] | None:
    """A detour of at most ``rounds`` added loops, each followed by removals alone (at most
    ``depth`` in a row), every structure on the way within ``max_corners``; ``None`` when there
    is none of that shape.  Most detours :func:`find_detour` finds have that shape (of the 56
    in the shipped certificates, 45 add one loop and then only remove, and 48 add at most two),
    and this search reaches far higher peaks than a breadth-first one, whose states grow too
    many beyond about 10 corners above a class of 48.  The detour it returns is not a shortest
    one, and finding none proves nothing; its moves apply one after the other from ``ls``
    (``target`` as in :func:`find_detour`).  States are taken up to all 48 symmetries, each
    once, in a fixed order.

    >>> from polyloops.io.examples import load_example
    >>> ls = load_example("non-incremental").dualize()
    >>> removable_loop(ls) is None, len(find_long_detour(ls, ls.map.num_corners + 8)) >= 2
    (True, True)
    """
    from polyloops.core.moves import add_loop, additions

    n = ls.map.num_corners
    seen = {canonical_form(ls, "full").signature}
    frontier: list[tuple[LoopStructure, list[Move]]] = [(ls, [])]
    for _ in range(rounds):
        reached: list[tuple[LoopStructure, list[Move]]] = []
        for current, moves in frontier:
            room = max_corners - current.map.num_corners
            for mv in (additions(current, max_length=room) if room >= 3 else ()):
                child = add_loop(current, mv, checked=False)
                if child.map.num_corners > max_corners:
                    continue
                s = canonical_form(child, "full").signature
                if s == target:
                    return [*moves, Move.add(mv)]
                if s in seen:
                    continue
                seen.add(s)
                found = _removed_below(child, [*moves, Move.add(mv)], n, target, depth, seen, reached)
                if found is not None:
                    return found
        frontier = reached
    return None


def _removed_below(ls: LoopStructure, moves: list[Move], n: int, target: str | None, depth: int,
                   seen: set[str], reached: list[tuple[LoopStructure, list[Move]]]) -> list[Move] | None:
    """Depth first through the removals from ``ls`` (at most ``depth`` in a row): the moves to
    a structure below ``n`` corners (or to ``target``), or ``None``; every structure met goes to
    ``reached``, ``ls`` first."""
    from polyloops.core.moves import removals, remove_loop

    reached.append((ls, moves))
    if depth == 0:
        return None
    for loop in removals(ls):
        child = remove_loop(ls, loop, checked=False)
        path = [*moves, Move.remove(loop)]
        if child.map.num_corners < n:
            return path
        s = canonical_form(child, "full").signature
        if s == target:
            return path
        if s in seen:
            continue
        seen.add(s)
        found = _removed_below(child, path, n, target, depth - 1, seen, reached)
        if found is not None:
            return found
    return None


@dataclass(frozen=True)
class ClassRecord:
    """How one catalog class is settled."""

    signature: str
    corners: int
    base: bool = False  # where the induction starts: the cube (genus 0), one class a type (genus 1)
    removable: int | None = None
    detour: list[Move] | None = None
    slack: int | None = None
    max_corners: int | None = None
    orientation: str | None = None  # genus 1: the orientation type (orientation_type)
    searched: int | None = None  # detours searched in vain up to this slack (an open class, or one
    # whose detour the long search found past the breadth-first search's slack)

    @property
    def settled(self) -> bool:
        """Whether the class is the cube, has a removable loop, or has a detour to fewer corners."""
        return self.base or self.removable is not None or self.detour is not None

    @property
    def irreducible(self) -> bool:
        """No removable loop (the cube is not counted: it is where the induction starts)."""
        return not self.base and self.removable is None

    def detour_peak(self) -> int:
        """The most corners on the detour, beyond the class's own."""
        return 0 if self.detour is None else _peak(from_signature(self.signature), self.detour)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict, one line of the certificate."""
        out: dict[str, Any] = {"signature": self.signature, "corners": self.corners}
        if self.orientation is not None:
            out["orientation"] = self.orientation
        if self.base:
            out["base"] = True
        elif self.removable is not None:
            out["removable"] = self.removable
        elif self.detour is not None:
            out["detour"] = {"slack": self.slack, "max_corners": self.max_corners,
                             "moves": [m.to_json() for m in self.detour]}
            if self.searched is not None:
                out["searched"] = self.searched
        else:
            out["unsettled"] = True
            if self.searched is not None:
                out["searched"] = self.searched
        return out

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> ClassRecord:
        """The record :meth:`to_json` wrote (not checked: :func:`check_certificate` checks)."""
        detour = data.get("detour")
        return cls(data["signature"], data["corners"], base=bool(data.get("base")),
                   removable=data.get("removable"),
                   detour=[Move.from_json(m) for m in detour["moves"]] if detour else None,
                   slack=detour["slack"] if detour else None,
                   max_corners=detour["max_corners"] if detour else None,
                   orientation=data.get("orientation"),
                   searched=data.get("searched") if data.get("unsettled") or detour else None)


def settle(signature: str, slack: int, *, base: bool = False, target: str | None = None,
           orientation: str | None = None, searched: int = 0, long: int = 0) -> ClassRecord:
    """Settle one class: its lowest removable loop, or the shortest detour with the least
    slack ``K = 2, 4, ...`` up to ``slack`` (to fewer corners, or to the class ``target``).
    At genus 0 the cube is the base; at genus 1 the caller says which class is (``base``) and
    gives each class its ``orientation`` type.  A class whose detours were ``searched`` in vain
    up to some slack already (an earlier run) is searched from the next one on; an open class's
    record says how far the search went.  With ``long`` above ``slack``, a class the
    breadth-first search leaves open is given to :func:`find_long_detour` within ``long``
    corners above it; a detour found so keeps, as ``searched``, the slack searched in vain.

    >>> from polyloops.io.examples import load_example
    >>> settle(canonical_form(load_example("l-shape").dualize(), "full").signature, 4).removable
    1
    """
    ls = from_signature(signature)
    n = ls.map.num_corners
    if base or (orientation is None and n == CUBE_CORNERS):
        return ClassRecord(signature, n, base=True, orientation=orientation)
    loop = removable_loop(ls)
    if loop is not None:
        return ClassRecord(signature, n, removable=loop, orientation=orientation)
    for k in range(searched + 2, slack + 1, 2):
        moves = find_detour(ls, n + k, target)
        if moves is not None:
            return ClassRecord(signature, n, detour=moves, slack=k, max_corners=n + k,
                               orientation=orientation)
    searched = max(slack, searched)
    if long > searched:
        moves = find_long_detour(ls, n + long, target)
        if moves is not None:
            peak = _peak(ls, moves)
            return ClassRecord(signature, n, detour=moves, slack=peak, max_corners=n + peak,
                               orientation=orientation, searched=searched)
    return ClassRecord(signature, n, orientation=orientation, searched=searched)


def _peak(ls: LoopStructure, moves: list[Move]) -> int:
    """The most corners the moves reach from ``ls``, beyond its own."""
    n, peak = ls.map.num_corners, 0
    for move in moves:
        ls = move.apply(ls)
        peak = max(peak, ls.map.num_corners - n)
    return peak


@dataclass(frozen=True)
class _Task:
    signature: str
    slack: int
    base: bool = False
    target: str | None = None
    orientation: str | None = None
    searched: int = 0
    long: int = 0


def _settle_job(task: _Task) -> ClassRecord:
    return settle(task.signature, task.slack, base=task.base, target=task.target,
                  orientation=task.orientation, searched=task.searched, long=task.long)


def _orientation_job(signature: str) -> str:
    return orientation_type(from_signature(signature))


def orientation_bases(types: dict[str, str], corners: dict[str, int]) -> dict[str, str]:
    """Per orientation type, its base: the first signature (in the given order) among those of
    the type with fewest corners."""
    out: dict[str, str] = {}
    for sig, t in types.items():
        if t not in out or corners[sig] < corners[out[t]]:
            out[t] = sig
    return out


@dataclass
class CornerRow:
    """The conjecture's table row for one number of corners."""

    corners: int
    classes: int = 0
    irreducible: int = 0
    settled_irreducible: int = 0
    largest_detour_corners: int = 0
    largest_detour_moves: int = 0
    orientation: str | None = None  # genus 1: the orientation type the row counts

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the row."""
        return {k: v for k, v in self.__dict__.items() if v is not None}


@dataclass
class ConjectureResult:
    """Every class of the catalog with how it is settled."""

    max_corners: int
    slack: int
    records: list[ClassRecord] = field(default_factory=list)
    genus: int = 0

    @property
    def unsettled(self) -> list[ClassRecord]:
        """The classes neither removable nor with a detour within the slack."""
        return [r for r in self.records if not r.settled]

    def table(self) -> list[CornerRow]:
        """The results by number of corners (at genus 1, by orientation type and corners)."""
        rows: dict[tuple[str, int], CornerRow] = {}
        for r in self.records:
            key = (r.orientation or "", r.corners)
            row = rows.setdefault(key, CornerRow(r.corners, orientation=r.orientation))
            row.classes += 1
            if r.irreducible:
                row.irreducible += 1
                if r.settled:
                    row.settled_irreducible += 1
                    assert r.detour is not None
                    row.largest_detour_corners = max(row.largest_detour_corners, r.detour_peak())
                    row.largest_detour_moves = max(row.largest_detour_moves, len(r.detour))
        return [rows[k] for k in sorted(rows)]

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready summary: counts, unsettled classes, the table."""
        return {"genus": self.genus, "max_corners": self.max_corners, "slack": self.slack,
                "classes": len(self.records), "settled": len(self.records) - len(self.unsettled),
                "unsettled": [r.signature for r in self.unsettled],
                "by_corners": [row.to_json() for row in self.table()]}


class ConjectureError(PolyloopsError, ValueError):
    """A request the catalog's evidence cannot support (a range beyond it, a partial catalog),
    or a certificate that is not one; the message names both sides."""


def complete_range(census: Census, genus: int = 0) -> int:
    """The largest ``N`` such that the catalog holds every class of ``genus`` with at most
    ``N`` corners: its counts start at the cube's 8 and it is not one share of a split run.

    Raises
    ------
    ConjectureError
        For a partial catalog, one of another genus, or one that starts above 8 corners.

    >>> from polyloops.catalog.census import read_catalog
    >>> complete_range(read_catalog()) >= 28
    True
    """
    where = census.directory
    if census.genus != genus:
        raise ConjectureError(f"{where}: a catalog of genus {census.genus}, not {genus}")
    if "partial" in census.summary or "share" in census.summary:
        raise ConjectureError(f"{where}: a partial catalog (one share of a split run): it does not "
                              "hold every class")
    counts = sorted(int(n) for n in census.summary.get("counts", {}))
    if not counts or counts[0] > CUBE_CORNERS:
        start = counts[0] if counts else "nothing"
        raise ConjectureError(f"{where}: the catalog's counts start at {start}, not at the cube's "
                              f"{CUBE_CORNERS} corners")
    return counts[-1]


def catalog_signatures(directory: Path | Census, max_corners: int) -> list[tuple[str, int]]:
    """``(signature, corners)`` of every record of a catalog directory with at most
    ``max_corners`` corners (the catalog of one symmetry mode)."""
    census = directory if isinstance(directory, Census) else read_catalog(directory)
    return [(e.signature, e.corners) for e in census.entries if e.corners <= max_corners]


def settle_catalog(directory: Path, max_corners: int, slack: int, workers: int = 1,
                   dask: str | None = None,
                   progress: Callable[[ClassRecord], None] | None = None,
                   journal: Path | None = None, earlier: Iterable[ClassRecord] = (),
                   long: int = 0) -> ConjectureResult:
    """Settle every class of the catalog with at most ``max_corners`` corners (the classes the
    breadth-first search within ``slack`` leaves open given to the long search within ``long``,
    :func:`settle`).

    With a ``journal`` (a file), each class's record is appended there as it is settled, and
    a later call with the same catalog, range and slack takes the records it holds instead of
    settling those classes again (a stopped run resumes; the journal's first line names the
    catalog by its digest, so another run's journal is started afresh).

    ``earlier`` records (an earlier certificate's, :func:`read_records`) are taken for the classes
    they settle, whatever their slack; an open one is searched again from the slack it was
    searched to, when that is below ``slack`` (and to the long search, with ``long``).  The
    result's slack is the largest of ``slack`` and the detours' slacks, so that its
    certificate's header bounds them all; as for any
    certificate, :func:`check_certificate` replays whatever was taken.

    Raises
    ------
    ConjectureError
        When ``max_corners`` goes beyond the catalog's complete range (:func:`complete_range`):
        classes the catalog does not hold cannot be settled.
    """
    from polyloops.parallel import run_jobs

    census = read_catalog(directory)
    genus = census.genus
    earlier = list(earlier)
    covered = complete_range(census, genus)
    if max_corners > covered:
        raise ConjectureError(f"{census.directory}: the catalog holds every class only through {covered} "
                              f"corners, not through {max_corners}")
    classes = catalog_signatures(census, max_corners)
    if genus == 0:
        tasks = [_Task(sig, slack, long=long) for sig, _ in classes]
    else:
        # the types earlier records state are taken (the certificate's check computes each again)
        stated = {r.signature: r.orientation for r in earlier if r.orientation is not None}
        unknown = [sig for sig, _ in classes if sig not in stated]
        computed = dict(zip(unknown, run_jobs(_orientation_job, unknown, workers, dask), strict=True))
        types = {sig: stated.get(sig) or computed[sig] for sig, _ in classes}
        corners = dict(classes)
        bases = orientation_bases(types, corners)
        lowest = {t: corners[b] for t, b in bases.items()}
        tasks = [_Task(sig, slack, base=bases[types[sig]] == sig,
                       target=bases[types[sig]] if n == lowest[types[sig]] else None, orientation=types[sig],
                       long=long)
                 for sig, n in classes]
    todo, taken = _resume(tasks, earlier, slack, long)
    done = _Journal(journal, census, max_corners, slack, long) if journal is not None else None
    known = {**taken, **(done.records if done is not None else {})}
    for record in known.values():
        if progress:
            progress(record)
    # as they finish (a class that takes hours holds back no other's record), in catalog order after
    by_signature = dict(known)
    for record in run_jobs(_settle_job, [t for t in todo if t.signature not in known], workers, dask,
                           ordered=False):
        by_signature[record.signature] = record
        if done is not None:
            done.add(record)
        if progress:
            progress(record)
    records = [by_signature[t.signature] for t in tasks]
    bound = max([slack, *(r.slack or 0 for r in records)])
    return ConjectureResult(max_corners, bound, records, genus)


def _resume(tasks: list[_Task], earlier: Iterable[ClassRecord],
            slack: int, long: int = 0) -> tuple[list[_Task], dict[str, ClassRecord]]:
    """The tasks with the earlier records applied: the records to take as they are (settled
    the way the task would be, or open and searched as far as ``slack`` when there is no long
    search to try), and the tasks left, open classes searched from where they stopped."""
    wanted = {t.signature: t for t in tasks}
    taken: dict[str, ClassRecord] = {}
    resumed: dict[str, _Task] = {}
    for r in earlier:
        task = wanted.get(r.signature)
        if task is None or r.base != task.base or r.orientation != task.orientation:
            continue  # not a class of this range, or one settled another way: settled afresh
        before = taken.get(r.signature)
        if r.settled or ((r.searched or 0) >= slack and long <= (r.searched or 0)):
            if before is None or not before.settled:  # a settled record over an open one
                taken[r.signature] = r
        else:  # searched again from the furthest any record went
            searched = max(r.searched or 0, resumed[r.signature].searched if r.signature in resumed else 0)
            resumed[r.signature] = replace(task, searched=searched)
    return [resumed.get(t.signature, t) for t in tasks if t.signature not in taken], taken


def read_records(lines: Iterable[str]) -> list[ClassRecord]:
    """The records of a certificate (its lines, the header first), an open one's search taken
    to be the header's slack when the record does not say; not checked (``settle_catalog``'s
    result is, when its certificate is).

    Raises
    ------
    ConjectureError
        When the header is no certificate's, or a line is no record.
    """
    it = iter(lines)
    header = read_header(next(it, ""))
    out = []
    for number, line in enumerate(it, 2):
        if not line.strip():
            continue
        try:
            record = ClassRecord.from_json(json.loads(line))
        except (ValueError, KeyError, TypeError, AttributeError) as err:
            raise ConjectureError(f"line {number} is not a certificate record ({err})") from None
        if not record.settled and record.searched is None:
            record = replace(record, searched=header["slack"])
        out.append(record)
    return out


class _Journal:
    """The records :func:`settle_catalog` has settled so far, one JSON line each after a
    header naming the catalog (its records' digest), the range, the slack and the long search's
    (when there is one)."""

    def __init__(self, path: Path, census: Census, max_corners: int, slack: int, long: int = 0):
        from polyloops.catalog.run import file_digest

        self.path = path
        self.header = json.dumps({"polyloops": 1, "kind": "settle-journal", "genus": census.genus,
                                  "catalog": file_digest(census.directory / "catalog.jsonl"),
                                  "max_corners": max_corners, "slack": slack,
                                  **({"long": long} if long else {})})
        self.records: dict[str, ClassRecord] = {}
        lines = path.read_bytes().decode("utf-8", "replace").splitlines() if path.is_file() else []
        if lines and not _is_journal_header(lines[0]):
            raise ConjectureError(f"{path}: exists and is no journal of settled classes; move it away")
        if lines and lines[0] == self.header:
            self.records = {r.signature: r for r in journal_lines(lines[1:])}
        from polyloops.io.files import write_atomic

        # what was read back, whole lines only, then each new record appended
        write_atomic(path, "\n".join([self.header, *(json.dumps(r.to_json()) for r in self.records.values())])
                     + "\n")

    def add(self, record: ClassRecord) -> None:
        with self.path.open("a") as out:
            out.write(json.dumps(record.to_json()) + "\n")


def journal_lines(lines: Iterable[str]) -> Iterator[ClassRecord]:
    """The records of a journal's lines after its header, up to the first that is not one (a
    line cut short when the run stopped: its class is settled again)."""
    for line in lines:
        try:
            yield ClassRecord.from_json(json.loads(line))
        except (ValueError, KeyError, TypeError, AttributeError):
            return


def _is_journal_header(line: str) -> bool:
    try:
        data = json.loads(line)
    except ValueError:
        return False
    return isinstance(data, dict) and data.get("kind") == "settle-journal"


def certificate_lines(result: ConjectureResult) -> Iterator[str]:
    """The certificate as JSON lines: a header (with the number of open classes, when there
    are any), then one line per class."""
    header = {"polyloops": 1, "kind": certificate_kind(result.genus),
              "max_corners": result.max_corners, "slack": result.slack, "classes": len(result.records)}
    if result.unsettled:
        header["unsettled"] = len(result.unsettled)
    yield json.dumps(header)
    for r in result.records:
        yield json.dumps(r.to_json(), separators=(",", ":"))


# -- checking -------------------------------------------------------------------------------------

@dataclass(frozen=True)
class CertificateProblem:
    """A line of a certificate that does not check, and why (``line`` 0: a catalog class with
    no record, named by ``name``)."""

    line: int
    signature: str
    message: str
    name: str = ""

    def __str__(self) -> str:
        if self.line == 0:
            return f"{self.name or self.signature[:24] + '...'}: {self.message}"
        who = f" ({self.name})" if self.name else f" ({self.signature[:24]}...)" if self.signature else ""
        return f"line {self.line}{who}: {self.message}"


def _valid(ls: LoopStructure) -> bool:
    from polyloops.verify import check_polycube_loop_structure

    return ls.oriented and check_polycube_loop_structure(ls).valid


def _is_count(value: Any) -> TypeGuard[int]:
    """A JSON integer (not a boolean, not a float such as ``1e999``)."""
    return type(value) is int


@dataclass(frozen=True)
class Bases:
    """Genus 1: per orientation type, the fewest corners of a catalog class of that type, and
    the certificate's base class of the type (if it names one)."""

    lowest: dict[str, int]
    base: dict[str, str]


UNSETTLED = "unsettled"  # what check_record says of a well-formed record of an open class


def check_record(data: Any, corners_bound: int, slack_bound: int | None = None,
                 bases: Bases | None = None, structure: LoopStructure | None = None) -> str | None:
    """Replay one record with the Definition-4 checker, and check every field it states
    against what the replay shows; the problem, :data:`UNSETTLED` for a well-formed record of
    an open class, or ``None`` when the record settles its class.  ``bases`` (genus 1) gives each
    orientation type's fewest corners and base class; ``structure``, the class its signature
    names when the caller has decoded it already."""
    if not isinstance(data, dict):
        return "not a certificate record (a JSON object)"
    sig, n = data.get("signature"), data.get("corners")
    if not isinstance(sig, str):
        return "not a certificate record: the signature is not text"
    if not _is_count(n):
        return f"not a certificate record: corners {n!r} is not an integer"
    try:
        ls = structure if structure is not None else from_signature(sig)
    except ValueError as err:
        return f"not a certificate record: {err}"
    if ls.map.num_corners != n:
        return f"claims {n} corners; the signature has {ls.map.num_corners}"
    if n > corners_bound:
        return f"has {n} corners, beyond the header's {corners_bound}"
    if not _valid(ls):
        return "the class itself is not a polycube loop structure"
    kinds = [k for k in ("base", "removable", "detour", "unsettled") if k in data]
    if len(kinds) > 1:
        return f"states more than one way of being settled ({', '.join(kinds)})"
    if not kinds:
        return "states no way of being settled (base, removable, detour, or unsettled)"
    if "unsettled" in data and data["unsettled"] is not True:
        return f"unsettled {data['unsettled']!r} is not true"
    if "searched" in data:
        searched = data["searched"]
        if "unsettled" not in data and "detour" not in data:
            return "states how far its detours were searched, but is neither open nor settled by a detour"
        if not _is_count(searched) or searched < 0 or (slack_bound is not None and searched > slack_bound):
            return f"searched {searched!r} is not a slack from 0 to the header's {slack_bound}"
        slack = data["detour"].get("slack") if isinstance(data.get("detour"), dict) else None
        if _is_count(slack) and searched >= slack:
            return (f"states that no detour within +{searched} exists, and gives one within +{slack}")
    target = None
    if bases is not None:
        kind = orientation_type(ls)
        if data.get("orientation") != kind:
            return f"states orientation {data.get('orientation')!r}; the class has {kind!r}"
        if "base" in data:
            if data["base"] is not True or n != bases.lowest[kind] or bases.base.get(kind) != sig:
                return (f"only one class of each orientation type with its fewest corners "
                        f"({bases.lowest[kind]}) is a base")
            return None
        target = bases.base.get(kind) if n == bases.lowest[kind] else None
        if "detour" in data:
            return _check_detour(ls, n, data["detour"], slack_bound, target)
    if n == CUBE_CORNERS and bases is None:
        if data.get("base") is not True:
            return "the cube is the base of the induction and must be marked so"
        return None
    if "base" in data:
        return "only the cube is the base of the induction"
    if "removable" in data:
        from polyloops.core.moves import try_remove

        loop = data["removable"]
        if not _is_count(loop) or not 0 <= loop < len(ls.loops):
            return f"no loop {loop!r}"
        smaller = try_remove(ls, loop)
        if smaller is None or not _valid(smaller) or smaller.map.num_corners >= n:
            return f"removing loop {loop} does not give a smaller polycube loop structure"
        return None
    if "detour" in data:
        return _check_detour(ls, n, data["detour"], slack_bound)
    return UNSETTLED


def _check_detour(ls: LoopStructure, n: int, detour: Any, slack_bound: int | None,
                  target: str | None = None) -> str | None:
    if not isinstance(detour, dict) or not isinstance(detour.get("moves"), list):
        return "bad detour: not an object with a list of moves"
    bound, slack = detour.get("max_corners"), detour.get("slack")
    if not _is_count(bound) or not _is_count(slack):
        return f"bad detour: max_corners {bound!r} and slack {slack!r} must be integers"
    if slack != bound - n:
        return f"bad detour: slack {slack} is not max_corners {bound} minus the class's {n} corners"
    if slack_bound is not None and slack > slack_bound:
        return f"bad detour: slack {slack} is above the header's {slack_bound}"
    try:
        moves = [Move.from_json(m) for m in detour["moves"]]
    except (KeyError, TypeError, ValueError) as err:
        return f"bad detour: {err}"
    for step, move in enumerate(moves):
        try:
            ls = move.apply(ls)
        except (KeyError, IndexError, ValueError, TypeError) as err:
            return f"detour step {step} ({move}) cannot be applied: {err}"
        if not _valid(ls):
            return f"detour step {step} ({move}) does not give a polycube loop structure"
        if ls.map.num_corners > bound:
            return f"detour step {step} has {ls.map.num_corners} corners, above {bound}"
    if ls.map.num_corners < n or (target is not None and canonical_form(ls, "full").signature == target):
        return None
    if target is not None:
        return "the detour ends neither below the class's corners nor at the base of its orientation type"
    return "the detour does not end below the class's corners"


def _certificate_bases(parsed: list[tuple[int, Any]], wanted: dict[str, int],
                       structures: dict[str, LoopStructure]) -> Bases:
    """The orientation types of the catalog's classes in range (computed from ``structures``,
    the classes decoded, not read), their fewest corners, and the base each type's records
    name (the first, if several: the others are then refused by :func:`check_record`)."""
    types = {sig: orientation_type(structures[sig]) for sig in wanted}
    lowest: dict[str, int] = {}
    for sig, t in types.items():
        lowest[t] = min(lowest.get(t, wanted[sig]), wanted[sig])
    base: dict[str, str] = {}
    for _, data in parsed:
        named = data.get("signature") if isinstance(data, dict) else None
        if isinstance(named, str) and named in types and data.get("base") is True:
            base.setdefault(types[named], named)
    return Bases(lowest, base)


@dataclass(frozen=True)
class OpenClass:
    """A class the certificate records as unsettled: its line, signature, catalog name and
    corners."""

    line: int
    signature: str
    name: str
    corners: int
    searched: int  # detours searched in vain up to this slack


@dataclass(frozen=True)
class CertificateCheck:
    """What :func:`check_certificate` found: the header, the range it checked (every class of
    the catalog through ``checked_corners``), the catalog's own complete range, the problems
    (none when the certificate holds), and the open classes it records (as many as its header
    states, when it holds)."""

    header: dict[str, Any]
    checked_corners: int
    catalog_corners: int
    records: int
    problems: tuple[CertificateProblem, ...]
    genus: int = 0
    open: tuple[OpenClass, ...] = ()

    @property
    def valid(self) -> bool:
        """Whether every record checks, a record stands for every class through the header's
        range, that range is within the catalog's, and the header's counts (classes, open
        classes) are the certificate's: everything it states holds."""
        return not self.problems

    @property
    def complete(self) -> bool:
        """Whether it holds and settles every class of its range (no open class)."""
        return self.valid and not self.open

    @property
    def proven_corners(self) -> int | None:
        """The largest ``N`` such that, when the certificate holds, every class with at most
        ``N`` corners is reachable: one below the smallest open class (``None`` when it does
        not hold)."""
        if not self.valid:
            return None
        return min(c.corners for c in self.open) - 1 if self.open else self.checked_corners

    def statement(self) -> str:
        """What the certificate proves, in words (empty when it does not hold).

        A class with ``proven_corners + 1`` corners that is not open reaches a smaller class
        (or a base) in one move or detour, so it is reachable too; above that, a class may
        lean on an open one.
        """
        top = self.proven_corners
        if top is None:
            return ""
        start = "the cube" if self.genus == 0 else "the base class of its hole-orientation type"
        text = f"every genus-{self.genus} class through {top} corners is reachable from {start}"
        if not self.open:
            return text
        at = [c for c in self.open if c.corners == top + 1]
        searches = "; ".join(f"no detour within +{k}: " + ", ".join(c.name or c.signature for c in at
                                                                  if c.searched == k)
                             for k in sorted({c.searched for c in at}, reverse=True))
        text += f"; with {top + 1}, every class but {len(at)} (recorded as open, {searches})"
        if len(at) < len(self.open):
            text += (f"; {len(self.open) - len(at)} more open with more corners, on which the "
                     f"records above {top + 1} corners may lean")
        return text


def read_header(first: str) -> dict[str, Any]:
    """A certificate's header line, checked: the kind, and positive integer bounds.

    Raises
    ------
    ConjectureError
        Naming what is wrong.
    """
    try:
        header = json.loads(first)
    except ValueError as err:
        raise ConjectureError(f"not a reachability certificate (the first line is not JSON: {err})") from None
    if not isinstance(header, dict) or certificate_genus(header.get("kind")) is None:
        raise ConjectureError("not a reachability certificate (the first line is not a "
                              f"{certificate_kind(0).replace('0', 'G', 1)} header)")
    for key in ("max_corners", "slack"):
        if not _is_count(header.get(key)) or header[key] < 1:
            raise ConjectureError(f"the header's {key} {header.get(key)!r} is not a positive integer")
    for key in ("classes", "unsettled"):
        if key in header and (not _is_count(header[key]) or header[key] < 0):
            raise ConjectureError(f"the header's {key} {header[key]!r} is not a count")
    return header


def check_certificate(lines: Iterable[str], directory: Path | Census) -> CertificateCheck:
    """Check a certificate against a catalog: the header's range within the catalog's complete
    range, a record for every class through it, each replayed by :func:`check_record`, and the
    header's counts.  A certificate proves, when it checks, that every genus-0 polycube class
    with at most ``checked_corners`` corners is reachable from the cube (by the induction of the
    module docstring), given that the catalog is complete through that range; at genus 1, that
    every class is reachable from the base of its orientation type.  With open classes it
    proves less: :meth:`CertificateCheck.statement`.

    Raises
    ------
    ConjectureError
        When the first line is not a certificate header (bad input, not a failed check).
    CatalogError
        When the catalog cannot be read.
    """
    census = directory if isinstance(directory, Census) else read_catalog(directory)
    it = iter(enumerate(lines, 1))
    first = next(it, (1, ""))[1]
    header = read_header(first)
    genus = certificate_genus(header["kind"])
    assert genus is not None  # read_header checked it
    claimed, covered = header["max_corners"], complete_range(census, genus)
    checked = min(claimed, covered)
    problems: list[CertificateProblem] = []
    if claimed > covered:
        problems.append(CertificateProblem(1, "", f"the header claims every class through {claimed} corners; "
                                           f"the catalog holds every class only through {covered}"))
    names = {e.signature: e.name for e in census.entries}
    wanted = dict(catalog_signatures(census, checked))
    covered_sigs: set[str] = set()
    open_: list[OpenClass] = []
    records = 0
    parsed: list[tuple[int, Any]] = []
    for number, line in it:
        if not line.strip():
            continue
        records += 1
        try:
            parsed.append((number, json.loads(line)))
        except (ValueError, RecursionError):
            problems.append(CertificateProblem(number, "", "not JSON"))
    # Genus 1 needs every class decoded for the bases; each is decoded once, here.
    structures = {sig: from_signature(sig) for sig in wanted} if genus else {}
    bases = _certificate_bases(parsed, wanted, structures) if genus else None
    for number, data in parsed:
        sig = data.get("signature") if isinstance(data, dict) else None
        if not isinstance(sig, str):
            problems.append(CertificateProblem(number, "", "not a JSON record with a signature (text)"))
            continue
        if sig not in wanted:
            where = "beyond the checked range" if sig in names else "not a class of the catalog"
            problems.append(CertificateProblem(number, sig, where, names.get(sig, "")))
            continue
        if sig in covered_sigs:
            problems.append(CertificateProblem(number, sig, "a second record for this class", names[sig]))
            continue
        covered_sigs.add(sig)
        why = check_record(data, checked, header["slack"], bases, structures.get(sig))
        if why == UNSETTLED:
            open_.append(OpenClass(number, sig, names[sig], data["corners"],
                                   data.get("searched", header["slack"])))
        elif why is not None:
            problems.append(CertificateProblem(number, sig, why, names[sig]))
    if "classes" in header and header["classes"] != records:
        problems.append(CertificateProblem(1, "", f"the header counts {header['classes']} classes; "
                                           f"the certificate has {records} records"))
    if header.get("unsettled", 0) != len(open_):
        first = f" ({open_[0].name or open_[0].signature[:24] + '...'} first)" if open_ else ""
        problems.append(CertificateProblem(1, "", f"the header states {header.get('unsettled', 0)} "
                                           f"unsettled classes; the certificate has {len(open_)}{first}"))
    for sig in wanted:
        if sig not in covered_sigs:
            problems.append(CertificateProblem(0, sig, "catalog class missing from the certificate",
                                               names[sig]))
    return CertificateCheck(header, checked, covered, records, tuple(problems), genus, tuple(open_))


CERTIFICATE_NAME = "reachability-certificate.jsonl"


def shipped_certificate(genus: int = 0) -> Path:
    """Where the certificate of the shipped catalog of ``genus`` is installed.

    >>> shipped_certificate(1).name
    'reachability-certificate.jsonl'
    """
    from polyloops.catalog.census import default_catalog

    return default_catalog(genus) / CERTIFICATE_NAME


@dataclass(frozen=True)
class Certificate:
    """A reachability certificate read from a file: its checked header and its lines.  It
    proves nothing until :meth:`check` replays it against a catalog."""

    path: Path
    header: dict[str, Any]
    lines: tuple[str, ...]

    @property
    def genus(self) -> int:
        """The genus the header's kind names."""
        genus = certificate_genus(self.header["kind"])
        assert genus is not None  # read_header checked it
        return genus

    @property
    def max_corners(self) -> int:
        """The range the header claims (what :meth:`check` confirms or refuses)."""
        return int(self.header["max_corners"])

    def check(self, catalog: Path | Census | None = None) -> CertificateCheck:
        """:func:`check_certificate` against ``catalog`` (default: the shipped catalog of the
        certificate's genus).  It replays every record: for the shipped genus-1 certificate
        (2,403 classes) about 10 s, so the example checks a catalog cut to 36 corners, which the
        certificate claims more than, and is refused; a slow plain-install test checks the whole.

        >>> from polyloops.catalog.census import read_catalog
        >>> small = read_catalog(genus=1).through(36)
        >>> check = read_certificate(genus=1).check(small)
        >>> check.valid, check.genus
        (False, 1)
        """
        return check_certificate(self.lines, read_catalog(genus=self.genus) if catalog is None else catalog)


def read_certificate(path: Path | str | None = None, *, genus: int | None = None) -> Certificate:
    """A certificate file (default: the shipped one of ``genus``, 0 unless given), its header
    checked (:func:`read_header`).

    Parameters
    ----------
    path:
        A certificate written by ``polyloops conjecture genus0`` or ``genus1``.
    genus:
        Without ``path``: which shipped certificate; with it, the genus it must have.

    Returns
    -------
    Certificate
        Its header and lines; :meth:`Certificate.check` replays it against a catalog.

    Raises
    ------
    ConjectureError
        When the first line is not a certificate header, or its genus is not ``genus``.
    polyloops.io.files.InputError
        When the file cannot be read.

    >>> cert = read_certificate(genus=1)
    >>> cert.genus, cert.max_corners >= 44
    (1, True)
    """
    from polyloops.io.files import read_text

    where = shipped_certificate(0 if genus is None else genus) if path is None else Path(path)
    lines = tuple(read_text(where, stdin=False).splitlines())
    header = read_header(lines[0] if lines else "")
    cert = Certificate(where, header, lines)
    if genus is not None and cert.genus != genus:
        raise ConjectureError(f"{where}: a genus-{cert.genus} certificate, not genus {genus}")
    return cert
