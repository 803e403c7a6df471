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
or ``{"signature", "corners", "unsettled": true}``.  :func:`check_certificate` replays every
record with the Definition-4 checker and trusts nothing else.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from polyloops.core.canonical import canonical_form, from_signature
from polyloops.core.moves import check_removal
from polyloops.core.structure import LoopStructure
from polyloops.enumerate.census import read_entries
from polyloops.enumerate.reach import Move, neighbours

CERTIFICATE_KIND = "genus0-reachability-certificate"
CUBE_CORNERS = 8  # the cube is the only polycube with 8 corners (and none has fewer)


def removable_loop(ls: LoopStructure) -> int | None:
    """The lowest loop whose removal leaves a polycube loop structure, or ``None``."""
    return next((lp.id for lp in ls.loops if check_removal(ls, lp.id).valid), None)


def find_detour(ls: LoopStructure, max_corners: int) -> list[Move] | None:
    """A shortest sequence of moves from ``ls`` to a structure with fewer corners, every
    structure on the way within ``max_corners`` (breadth-first, states up to all 48
    symmetries); the moves apply one after the other starting from ``ls`` itself."""
    n = ls.map.num_corners
    start = canonical_form(ls, "full").signature
    seen = {start}
    level: list[tuple[LoopStructure, list[Move]]] = [(ls, [])]
    while level:
        nxt = []
        for current, moves in level:
            for move, child in neighbours(current, max_corners):
                if child.map.num_corners < n:
                    return [*moves, move]
                s = canonical_form(child, "full").signature
                if s not in seen:
                    seen.add(s)
                    nxt.append((child, [*moves, move]))
        level = nxt
    return None


@dataclass(frozen=True)
class ClassRecord:
    """How one catalog class is settled."""

    signature: str
    corners: int
    base: bool = False  # the cube, where the induction starts
    removable: int | None = None
    detour: list[Move] | None = None
    slack: int | None = None
    max_corners: int | None = None

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
        if self.detour is None:
            return 0
        ls, peak = from_signature(self.signature), 0
        for move in self.detour:
            ls = move.apply(ls)
            peak = max(peak, ls.map.num_corners - self.corners)
        return peak

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict, one line of the certificate."""
        out: dict[str, Any] = {"signature": self.signature, "corners": self.corners}
        if self.base:
            out["base"] = True
        elif self.removable is not None:
            out["removable"] = self.removable
        elif self.detour is not None:
            out["detour"] = {"slack": self.slack, "max_corners": self.max_corners,
                             "moves": [m.to_json() for m in self.detour]}
        else:
            out["unsettled"] = True
        return out


def settle(signature: str, slack: int) -> ClassRecord:
    """Settle one class: its lowest removable loop, or the shortest detour with the least
    slack ``K = 2, 4, ...`` up to ``slack``."""
    ls = from_signature(signature)
    n = ls.map.num_corners
    if n == CUBE_CORNERS:
        return ClassRecord(signature, n, base=True)
    loop = removable_loop(ls)
    if loop is not None:
        return ClassRecord(signature, n, removable=loop)
    for k in range(2, slack + 1, 2):
        moves = find_detour(ls, n + k)
        if moves is not None:
            return ClassRecord(signature, n, detour=moves, slack=k, max_corners=n + k)
    return ClassRecord(signature, n)


def _settle_job(task: tuple[str, int]) -> ClassRecord:
    return settle(*task)


@dataclass
class CornerRow:
    """The conjecture's table row for one number of corners."""

    corners: int
    classes: int = 0
    irreducible: int = 0
    settled_irreducible: int = 0
    largest_detour_corners: int = 0
    largest_detour_moves: int = 0

    def to_json(self) -> dict[str, int]:
        """A JSON-ready dict of the row."""
        return dict(self.__dict__)


@dataclass
class ConjectureResult:
    """Every class of the catalog with how it is settled."""

    max_corners: int
    slack: int
    records: list[ClassRecord] = field(default_factory=list)

    @property
    def unsettled(self) -> list[ClassRecord]:
        """The classes neither removable nor with a detour within the slack."""
        return [r for r in self.records if not r.settled]

    def table(self) -> list[CornerRow]:
        """The results by number of corners."""
        rows: dict[int, CornerRow] = {}
        for r in self.records:
            row = rows.setdefault(r.corners, CornerRow(r.corners))
            row.classes += 1
            if r.irreducible:
                row.irreducible += 1
                if r.settled:
                    row.settled_irreducible += 1
                    assert r.detour is not None
                    row.largest_detour_corners = max(row.largest_detour_corners, r.detour_peak())
                    row.largest_detour_moves = max(row.largest_detour_moves, len(r.detour))
        return [rows[n] for n in sorted(rows)]

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready summary: counts, unsettled classes, the table."""
        return {"max_corners": self.max_corners, "slack": self.slack,
                "classes": len(self.records), "settled": len(self.records) - len(self.unsettled),
                "unsettled": [r.signature for r in self.unsettled],
                "by_corners": [row.to_json() for row in self.table()]}


def catalog_signatures(directory: Path, max_corners: int) -> list[tuple[str, int]]:
    """``(signature, corners)`` of every record of a catalog directory with at most
    ``max_corners`` corners (the catalog of one symmetry mode)."""
    return [(e.signature, e.corners) for e in read_entries(directory) if e.corners <= max_corners]


def settle_catalog(directory: Path, max_corners: int, slack: int, workers: int = 1,
                   dask: str | None = None,
                   progress: Callable[[ClassRecord], None] | None = None) -> ConjectureResult:
    """Settle every class of the catalog with at most ``max_corners`` corners."""
    from polyloops.enumerate.parallel import run_jobs

    tasks = [(sig, slack) for sig, _ in catalog_signatures(directory, max_corners)]
    result = ConjectureResult(max_corners, slack)
    for record in run_jobs(_settle_job, tasks, workers, dask):
        result.records.append(record)
        if progress:
            progress(record)
    return result


def certificate_lines(result: ConjectureResult) -> Iterator[str]:
    """The certificate as JSON lines: a header, then one line per class."""
    yield json.dumps({"polyloops": 1, "kind": CERTIFICATE_KIND, "max_corners": result.max_corners,
                      "slack": result.slack, "classes": len(result.records)})
    for r in result.records:
        yield json.dumps(r.to_json(), separators=(",", ":"))


# -- checking -------------------------------------------------------------------------------------

@dataclass(frozen=True)
class CertificateProblem:
    """A line of a certificate that does not check, and why."""

    line: int
    signature: str
    message: str

    def __str__(self) -> str:
        return f"line {self.line} ({self.signature[:24]}...): {self.message}"


def _valid(ls: LoopStructure) -> bool:
    from polyloops.verify import check_polycube_loop_structure

    return ls.oriented and check_polycube_loop_structure(ls).valid


def check_record(data: Any, corners_bound: int) -> str | None:
    """Replay one record with the Definition-4 checker; the problem, or ``None``."""
    try:
        sig, n = data["signature"], data["corners"]
        ls = from_signature(sig)
    except (KeyError, TypeError, ValueError) as err:
        return f"not a certificate record: {err}"
    if ls.map.num_corners != n or n > corners_bound:
        return f"claims {n} corners; the signature has {ls.map.num_corners}"
    if not _valid(ls):
        return "the class itself is not a polycube loop structure"
    if n == CUBE_CORNERS:
        if data.get("base") is not True:
            return "the cube is the base of the induction and must be marked so"
        return None
    if "removable" in data:
        from polyloops.core.moves import try_remove

        loop = data["removable"]
        if type(loop) is not int or not 0 <= loop < len(ls.loops):
            return f"no loop {loop!r}"
        smaller = try_remove(ls, loop)
        if smaller is None or not _valid(smaller) or smaller.map.num_corners >= n:
            return f"removing loop {loop} does not give a smaller polycube loop structure"
        return None
    if "detour" in data:
        detour = data["detour"]
        try:
            bound = int(detour["max_corners"])
            moves = [Move.from_json(m) for m in detour["moves"]]
        except (KeyError, TypeError, ValueError) as err:
            return f"bad detour: {err}"
        for step, move in enumerate(moves):
            try:
                ls = move.apply(ls)
            except (KeyError, IndexError, ValueError) as err:
                return f"detour step {step} ({move}) cannot be applied: {err}"
            if not _valid(ls):
                return f"detour step {step} ({move}) does not give a polycube loop structure"
            if ls.map.num_corners > bound:
                return f"detour step {step} has {ls.map.num_corners} corners, above {bound}"
        if ls.map.num_corners >= n:
            return "the detour does not end below the class's corners"
        return None
    return "unsettled"


def check_certificate(lines: Iterable[str],
                      directory: Path) -> tuple[dict[str, Any], list[CertificateProblem]]:
    """Check a certificate against a catalog: a record for every class with at most the
    header's corners, each replayed by :func:`check_record`.  Returns the header and the
    problems (empty when the certificate holds)."""
    it = iter(enumerate(lines, 1))
    try:
        _, first = next(it)
        header = json.loads(first)
        if header.get("kind") != CERTIFICATE_KIND or type(header.get("max_corners")) is not int:
            raise ValueError("not a certificate header")
    except (StopIteration, ValueError, AttributeError) as err:
        return {}, [CertificateProblem(1, "", f"not a reachability certificate ({err})")]
    wanted = dict(catalog_signatures(directory, header["max_corners"]))
    problems, covered = [], set()
    for number, line in it:
        try:
            data = json.loads(line)
            sig = data["signature"]
        except (ValueError, KeyError, TypeError):
            problems.append(CertificateProblem(number, "", "not a JSON record with a signature"))
            continue
        if sig not in wanted:
            problems.append(CertificateProblem(number, sig, "not a class of the catalog"))
            continue
        covered.add(sig)
        why = check_record(data, header["max_corners"])
        if why is not None:
            problems.append(CertificateProblem(number, sig, why))
    for sig in wanted:
        if sig not in covered:
            problems.append(CertificateProblem(0, sig, "catalog class missing from the certificate"))
    return header, problems
