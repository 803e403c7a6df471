"""The catalog record, in one place: its fields, its JSON line, its SQLite row and schema, its
CSV, and the short names of a census.

A catalog directory holds ``catalog.jsonl`` (one :class:`CatalogEntry` a line: a name, the
symmetry mode, and a :class:`CatalogRecord`), ``catalog.sqlite`` (table ``polycubes``, one row
per entry, columns :data:`COLUMNS`; table ``meta`` with the mode) and ``summary.json``.  Every
writer and reader of the first two goes through this module.

>>> from polyloops.io.examples import load_example
>>> from polyloops.catalog.classes import map_classes
>>> record = map_classes(load_example("cube").map)["full"][0]
>>> entry = CatalogEntry("P8.1", Symmetry.FULL, record)
>>> CatalogEntry.from_json(entry.to_json()) == entry, row(entry)[2:7]
(True, [8, 6, 1, 1, 1])
"""

from __future__ import annotations

import csv
import io
import json
import os
import sqlite3
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

from polyloops.core.corners import CATEGORIES
from polyloops.core.errors import PolyloopsError
from polyloops.core.symmetry import Symmetry
from polyloops.io.files import InputError, check_regular, read_only_uri, write_atomic, writing

__all__ = [
    "COLUMNS",
    "CatalogEntry",
    "CatalogError",
    "CatalogMismatchError",
    "CatalogRecord",
    "class_names",
    "csv_text",
    "fill_tables",
    "genus_prefix",
    "query",
    "row",
    "write_jsonl",
    "write_sqlite",
]


class CatalogError(PolyloopsError, ValueError):
    """A catalog directory that cannot be read; the message names the file (and line).
    ``status`` is the command line's exit status for it: 2, bad input."""

    status = 2


class CatalogMismatchError(CatalogError):
    """A catalog read whole whose records do not prove what its summary claims (a count per
    corner count that differs, a record twice, a record whose corners its signature
    contradicts, files that do not match the digests the summary records): checked, and not a
    catalog, so the command line exits 1.  The message names both sides."""

    status = 1


@dataclass(frozen=True)
class CatalogRecord:
    """One polycube class in one symmetry mode."""

    signature: str
    corners: int
    faces: int
    loops: dict[str, int]
    categories: dict[str, int]
    automorphisms: int
    chiral: bool
    removable_loops: int  # loops whose removal leaves a polycube loop structure
    holes: str | None = None  # positive genus: the hole-orientation invariant (core.holes)

    @property
    def irreducible(self) -> bool:
        """No loop can be removed: additions alone cannot build it (the cube is one too)."""
        return self.removable_loops == 0

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict: the record's fields and whether it is irreducible."""
        out = {"signature": self.signature, "corners": self.corners, "faces": self.faces,
               "loops": self.loops, "corner_categories": self.categories,
               "automorphisms": self.automorphisms, "chiral": self.chiral,
               "removable_loops": self.removable_loops, "irreducible": self.irreducible}
        if self.holes is not None:
            out["holes"] = self.holes
        return out

    @classmethod
    def from_json(cls, data: Any) -> CatalogRecord:
        """The record of a parsed JSON object; raises ``KeyError``, ``TypeError`` or
        ``ValueError`` for anything that is not one."""
        if not isinstance(data, dict):
            raise TypeError("a record is a JSON object")
        signature, corners = data["signature"], data["corners"]
        if not isinstance(signature, str) or type(corners) is not int:
            raise TypeError("signature must be text and corners an integer")
        return cls(signature, corners, int(data["faces"]), {a: int(n) for a, n in data["loops"].items()},
                   {c: int(data["corner_categories"][c]) for c in CATEGORIES}, int(data["automorphisms"]),
                   bool(data["chiral"]), int(data["removable_loops"]),
                   None if data.get("holes") is None else str(data["holes"]))


@dataclass(frozen=True)
class CatalogEntry:
    """One line of ``catalog.jsonl``: a class's stable name, the symmetry mode the catalog
    lists classes in, and its record."""

    name: str
    symmetry: Symmetry
    record: CatalogRecord

    @property
    def signature(self) -> str:
        """The class's signature."""
        return self.record.signature

    @property
    def corners(self) -> int:
        """The class's number of corners."""
        return self.record.corners

    @classmethod
    def from_json(cls, data: Any) -> CatalogEntry:
        """An entry from a parsed JSON line; raises ``KeyError``, ``TypeError`` or
        ``ValueError`` for anything that is not a catalog record."""
        record = CatalogRecord.from_json(data)
        return cls(str(data.get("name", "")), Symmetry.parse(data.get("symmetry", "full")), record)

    def to_json(self) -> dict[str, Any]:
        """The entry as a ``catalog.jsonl`` line holds it."""
        return {"name": self.name, **self.record.to_json(), "symmetry": str(self.symmetry)}

    def structure(self):
        """The class's canonical representative (a :class:`~polyloops.core.structure.LoopStructure`)."""
        from polyloops.core.canonical import from_signature

        return from_signature(self.signature)


def genus_prefix(genus: int) -> str:
    """What a class name of ``genus`` starts with: nothing at genus 0 (``P26.3``), ``T`` for the
    torus (``T32.1``, ``TR32.1``, ``TL32.1``), ``G2-`` and so on from genus 2 (``G2-48.1``).

    >>> [genus_prefix(g) for g in (0, 1, 2, 12)]
    ['', 'T', 'G2-', 'G12-']
    """
    if genus < 0:
        raise ValueError(f"no class names for genus {genus}")
    return "" if genus == 0 else "T" if genus == 1 else f"G{genus}-"


def class_names(records: Sequence[CatalogRecord], symmetry: Symmetry | str, genus: int = 0) -> list[str]:
    """Short stable names, like a census's: ``P26.3`` is the third class with 26 corners up to
    all 48 symmetries (``R`` up to rotation, ``L`` labelled), classes of one corner count ranked
    by signature (as strings; ``records`` in that order); at genus 1 ``T32.1``, ``TR32.1`` and
    ``TL32.1``.  A name never changes once its corner count is complete.

    >>> rec = CatalogRecord("1o", 32, 32, {}, {}, 1, False, 0)
    >>> class_names([rec], "full", genus=1), class_names([rec], "rotation", genus=1)
    (['T32.1'], ['TR32.1'])
    """
    mode = str(Symmetry.parse(symmetry))
    prefix = genus_prefix(genus) + ("" if genus and mode == "full" else Symmetry.parse(mode).prefix)
    out, rank, last = [], 0, None
    for rec in records:
        rank = rank + 1 if rec.corners == last else 1
        last = rec.corners
        out.append(f"{prefix}{rec.corners}.{rank}")
    return out


COLUMNS = ["name", "signature", "corners", "faces", "loops_x", "loops_y", "loops_z",
           *[c.replace("-", "_") for c in CATEGORIES], "automorphisms", "chiral", "removable_loops",
           "irreducible"]


def row(entry: CatalogEntry) -> list[Any]:
    """The entry as a row of table ``polycubes`` (:data:`COLUMNS`)."""
    rec = entry.record
    return [entry.name, rec.signature, rec.corners, rec.faces, rec.loops["X"], rec.loops["Y"], rec.loops["Z"],
            *[rec.categories[c] for c in CATEGORIES], rec.automorphisms, int(rec.chiral), rec.removable_loops,
            int(rec.irreducible)]


def write_jsonl(path: str | os.PathLike[str], entries: Iterable[CatalogEntry], *,
                within: str | os.PathLike[str] | None = None) -> None:
    """``catalog.jsonl``: one compact JSON object a line, through the shared writer (confined
    to ``within``, as :func:`polyloops.io.files.write_atomic` says)."""
    lines = [json.dumps(e.to_json(), separators=(",", ":")) for e in entries]
    write_atomic(path, "\n".join(lines) + ("\n" if lines else ""), within=within)


def fill_tables(con: sqlite3.Connection, entries: Iterable[CatalogEntry], symmetry: Symmetry) -> None:
    """Create and fill table ``polycubes`` (primary key ``signature``, unique ``name``, an index
    on ``corners``) and ``meta(key, value)`` with the symmetry mode: the one schema of
    ``catalog.sqlite`` and of the table queried in memory when a catalog ships without it."""
    cols = ", ".join(f"{c} {'TEXT' if c in ('name', 'signature') else 'INTEGER'}" for c in COLUMNS)
    con.execute(f"CREATE TABLE polycubes ({cols}, PRIMARY KEY (signature))")
    con.execute("CREATE UNIQUE INDEX by_name ON polycubes (name)")
    con.executemany(f"INSERT INTO polycubes VALUES ({', '.join('?' * len(COLUMNS))})",
                    [row(e) for e in entries])
    con.execute("CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT)")
    con.execute("INSERT INTO meta VALUES ('symmetry', ?)", (str(symmetry),))
    con.execute("CREATE INDEX by_corners ON polycubes (corners)")
    con.commit()


def write_sqlite(path: str | os.PathLike[str], entries: Iterable[CatalogEntry], symmetry: Symmetry, *,
                 within: str | os.PathLike[str] | None = None) -> None:
    """``catalog.sqlite`` (:func:`fill_tables`), built in a temporary file and put in place
    whole."""
    with writing(path, within=within) as pending:
        con = sqlite3.connect(pending.path)
        fill_tables(con, entries, symmetry)
        con.close()


def query(path: str | os.PathLike[str], where: str,
          entries: Sequence[CatalogEntry] | None = None) -> tuple[list[str], list[tuple[Any, ...]]]:
    """Rows of the ``catalog.sqlite`` at ``path`` matching an SQL WHERE clause (read-only
    connection): the column names and the rows, by corners then signature.  Given
    ``entries`` (a catalog shipped without its database), the same table is built in memory
    from them and ``path`` only names it in messages.

    Raises
    ------
    CatalogError
        When the file is missing, not a regular file, not a catalog database, or the clause
        is bad.
    """
    name = os.fspath(path)
    try:
        where.encode("utf-8")
    except UnicodeEncodeError:  # bytes the shell passed through that are not UTF-8
        raise CatalogError(f"{os.path.dirname(name) or '.'}: bad query: the WHERE clause is not UTF-8 "
                           "text") from None
    if entries is not None:
        con = sqlite3.connect(":memory:")
        fill_tables(con, entries, entries[0].symmetry if entries else Symmetry.FULL)
    else:
        if not (os.path.exists(name) or os.path.islink(name)):
            raise CatalogError(f"{name}: no catalog here")
        try:
            check_regular(name, limit=None)
        except InputError as err:
            raise CatalogError(str(err)) from None
        con = sqlite3.connect(read_only_uri(name), uri=True)
    try:
        try:
            tables = {t for (t,) in con.execute("SELECT name FROM sqlite_master WHERE type = 'table'")}
        except sqlite3.DatabaseError as err:
            raise CatalogError(f"{name}: not a catalog database ({err})") from None
        if "polycubes" not in tables:
            raise CatalogError(f"{name}: not a catalog database (no table polycubes)")
        cur = con.execute(f"SELECT * FROM polycubes WHERE {where} ORDER BY corners, signature")
        return [d[0] for d in cur.description], cur.fetchall()
    except sqlite3.Error as err:
        raise CatalogError(f"{os.path.dirname(name) or '.'}: bad query: {err}") from None
    finally:
        con.close()


def csv_text(path: str | os.PathLike[str], entries: Sequence[CatalogEntry] | None = None) -> str:
    """The whole ``polycubes`` table of a ``catalog.sqlite`` (or of ``entries``, as in
    :func:`query`) as CSV text (a header line, then one row per class)."""
    columns, rows = query(path, "1", entries)
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    writer.writerows(rows)
    return buf.getvalue()
