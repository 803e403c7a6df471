"""Reading a catalog directory as a census: typed entries, names, identification, queries.

A catalog directory (written by :func:`polyloops.enumerate.catalog_run.build_catalog`) holds
``catalog.jsonl`` (one record per class, in one symmetry mode), ``catalog.sqlite`` (the same
rows as a table, for SQL queries; the shipped catalog leaves it out and its queries build the
table in memory) and ``summary.json`` (counts in every mode).  This module
is the one place that reads them.

>>> census = read_catalog()
>>> entry = census.by_name["P16.2"]
>>> entry.corners, entry.symmetry, entry.record.loops
(16, <Symmetry.FULL: 'full'>, {'X': 1, 'Y': 2, 'Z': 2})
"""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

from polyloops.core.symmetry import Symmetry
from polyloops.enumerate import records
from polyloops.enumerate.records import CatalogEntry, CatalogError
from polyloops.io.files import InputError, read_text


@dataclass(frozen=True)
class Census:
    """A catalog directory, read: its entries (in catalog order) and its summary."""

    directory: Path
    entries: tuple[CatalogEntry, ...]
    summary: dict[str, Any]

    @property
    def symmetry(self) -> Symmetry:
        """The mode the catalog lists classes in."""
        return self.entries[0].symmetry if self.entries else Symmetry.FULL

    @property
    def max_corners(self) -> int:
        """How far the catalog goes (its largest corner count, counted or not)."""
        return max((int(n) for n in self.summary.get("counts", {})), default=0)

    @property
    def genus(self) -> int:
        """The genus of the catalog's polycubes."""
        return int(self.summary.get("genus", 0))

    def through(self, max_corners: int) -> Census:
        """The census cut at ``max_corners``: its entries and counts up to that size.

        >>> small = read_catalog().through(16)
        >>> [e.name for e in small.entries], small.max_corners
        (['P8.1', 'P12.1', 'P16.1', 'P16.2'], 16)
        """
        counts = {n: row for n, row in self.summary.get("counts", {}).items() if int(n) <= max_corners}
        return Census(self.directory, tuple(e for e in self.entries if e.corners <= max_corners),
                      {**self.summary, "counts": counts})

    @cached_property
    def by_name(self) -> dict[str, CatalogEntry]:
        """Entries by their short name (``P16.2``)."""
        return {e.name: e for e in self.entries}

    @cached_property
    def by_signature(self) -> dict[str, CatalogEntry]:
        """Entries by signature."""
        return {e.signature: e for e in self.entries}

    def __len__(self) -> int:
        return len(self.entries)

    def __iter__(self) -> Iterator[CatalogEntry]:
        """The entries in catalog order (by corners, then number), as SnapPy's censuses.

        >>> census = read_catalog()
        >>> [e.name for e in census][:3], len(census) == len(census.entries)
        (['P8.1', 'P12.1', 'P16.1'], True)
        """
        return iter(self.entries)

    def __getitem__(self, key: str | int) -> CatalogEntry:
        """An entry by name (``census["P26.20"]``), by signature, or by position.

        >>> census = read_catalog()
        >>> census["P16.2"].corners, census[0].name, census[census[1].signature].name
        (16, 'P8.1', 'P12.1')
        """
        if isinstance(key, int):
            return self.entries[key]
        found = self.by_name.get(key) or self.by_signature.get(key)
        if found is None:
            raise KeyError(f"{key!r}: no class of this name or signature in {self.directory}")
        return found

    def __contains__(self, key: object) -> bool:
        return isinstance(key, str) and (key in self.by_name or key in self.by_signature)


def default_catalog(genus: int = 0) -> Path:
    """The shipped catalog of ``genus``, installed with the package (``polyloops/catalogs``,
    package data; in the source tree also reached as ``catalogs/``).

    >>> (default_catalog() / "catalog.jsonl").is_file()
    True
    """
    from importlib.resources import files

    return Path(str(files("polyloops") / "catalogs" / f"genus{genus}"))


def _read_text(path: Path) -> str:
    """A catalog file's text: a regular file only (a FIFO or ``/dev/zero`` in its place is
    refused, not read)."""
    try:
        return read_text(path, stdin=False)
    except InputError as err:
        raise CatalogError(str(err)) from None


def read_entries(directory: Path) -> list[CatalogEntry]:
    """The entries of ``directory/catalog.jsonl``, in file order; a bad line raises
    :class:`CatalogError` naming the file and line."""
    path = Path(directory) / "catalog.jsonl"
    out = []
    for i, line in enumerate(_read_text(path).splitlines()):
        try:
            out.append(CatalogEntry.from_json(json.loads(line)))
        except (ValueError, KeyError, TypeError, AttributeError) as err:
            raise CatalogError(f"{path}: line {i + 1}: not a catalog record ({err})") from None
    return out


def read_catalog(directory: Path | None = None) -> Census:
    """A catalog directory as a :class:`Census`: its entries in catalog order and its summary.

    Parameters
    ----------
    directory:
        A directory written by :func:`~polyloops.enumerate.catalog_run.build_catalog` (default:
        the shipped ``catalogs/genus0``).

    Returns
    -------
    Census

    Raises
    ------
    CatalogError
        When a file is missing or a line is not a record (the message names file and line).

    >>> census = read_catalog()
    >>> census.symmetry, census.max_corners >= 26, census.by_name["P8.1"].record.automorphisms
    (<Symmetry.FULL: 'full'>, True, 48)
    """
    directory = Path(directory) if directory is not None else default_catalog()
    entries = read_entries(directory)
    path = directory / "summary.json"
    try:
        summary = json.loads(_read_text(path))
    except ValueError as err:
        raise CatalogError(f"{path}: not JSON ({err})") from None
    problem = summary_problem(summary)
    if problem:
        raise CatalogError(f"{path}: not a catalog summary ({problem})")
    return Census(directory, tuple(entries), summary)


def summary_problem(summary: Any) -> str | None:
    """What makes ``summary`` (parsed ``summary.json``) not a catalog summary, or ``None``:
    counts by corner counts (decimal integer keys) of non-negative integers in each mode."""
    if not isinstance(summary, dict):
        return "not a JSON object"
    counts = summary.get("counts", {})
    if not isinstance(counts, dict):
        return "counts is not an object"
    for key, row in counts.items():
        if not (key.isascii() and key.isdigit()):
            return f"corner count {key!r} is not an integer"
        if not isinstance(row, dict) or not all(type(v) is int and v >= 0 for v in row.values()):
            return f"the counts of {key} corners are not non-negative integers"
    genus = summary.get("genus", 0)
    if type(genus) is not int or genus < 0:
        return f"genus {genus!r} is not a non-negative integer"
    return None


def query(out: Path, where: str) -> tuple[list[str], list[tuple[Any, ...]]]:
    """Rows of ``DIR/catalog.sqlite`` (or, where the directory has none, of the same table built
    in memory from ``DIR/catalog.jsonl``) matching an SQL WHERE clause
    (:func:`polyloops.enumerate.records.query`).

    >>> columns, rows = query(default_catalog(), "corners = 16")
    >>> columns[:3], [r[0] for r in rows]
    (['name', 'signature', 'corners'], ['P16.1', 'P16.2'])
    """
    return records.query(Path(out) / "catalog.sqlite", where, _entries_without_database(Path(out)))


def export_csv(out: Path) -> str:
    """The whole ``polycubes`` table of ``DIR/catalog.sqlite`` as CSV text."""
    return records.csv_text(Path(out) / "catalog.sqlite", _entries_without_database(Path(out)))


def _entries_without_database(out: Path) -> list[CatalogEntry] | None:
    """The records of a catalog that has ``catalog.jsonl`` but no ``catalog.sqlite`` (the
    shipped catalog: the table is built in memory, so the package carries each record once);
    ``None`` when the database is there (or neither is, and the query says so)."""
    database = out / "catalog.sqlite"
    if database.exists() or database.is_symlink() or not (out / "catalog.jsonl").exists():
        return None
    return read_entries(out)


@dataclass(frozen=True)
class Identification:
    """What :func:`identify` found: the class name (or ``None``), the signature, and how far the
    catalog goes."""

    name: str | None  # None: not in the catalog
    signature: str
    corners: int
    genus: int
    max_corners: int  # how far the catalog goes
    catalog_genus: int

    @property
    def beyond(self) -> bool:
        """Outside what the catalog lists (another genus, or more corners)."""
        return self.name is None and (self.genus != self.catalog_genus or self.corners > self.max_corners)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the identification."""
        return {"name": self.name, "signature": self.signature, "corners": self.corners,
                "genus": self.genus, "catalog_max_corners": self.max_corners,
                "catalog_genus": self.catalog_genus, "in_catalog": self.name is not None}


def identify(obj: Any, catalog: Path | Census | None = None) -> Identification:
    """The catalog name of a polycube or loop structure (any numbering, position or mirror
    image): its signature up to the catalog's symmetry, looked up in the catalog.

    Parameters
    ----------
    obj:
        A :class:`~polyloops.core.polycube.Polycube` (dualized first) or an oriented
        :class:`~polyloops.core.structure.LoopStructure`.
    catalog:
        A catalog directory or a :class:`Census` already read (default: the shipped catalog
        of the structure's genus, ``catalogs/genus0`` or ``catalogs/genus1``).

    Returns
    -------
    Identification
        ``name`` is ``None`` when the class is not in the catalog.

    Raises
    ------
    CatalogError
        When the catalog directory cannot be read.

    >>> from polyloops.io.examples import load_example
    >>> identify(load_example("l-shape")).name, identify(load_example("ring-y")).name
    ('P16.2', 'T32.1')
    """
    from polyloops.core.canonical import canonical_form

    if catalog is None and obj.map.genus > 0 and (default_catalog(obj.map.genus) / "catalog.jsonl").is_file():
        catalog = default_catalog(obj.map.genus)
    census = catalog if isinstance(catalog, Census) else read_catalog(catalog)
    sig = canonical_form(obj, census.symmetry).signature
    found = census.by_signature.get(sig)
    return Identification(found.name if found else None, sig, obj.map.num_corners, obj.map.genus,
                          census.max_corners, census.genus)


@dataclass(frozen=True)
class OrbitCounts:
    """Classes with one number of corners, in the three modes, as the orbit-stabiliser theorem
    derives them from the catalog's ``full`` records (see :func:`orbit_counts`)."""

    corners: int
    labelled: int
    rotation: int
    full: int


def orbit_counts(census: Census) -> dict[int, OrbitCounts]:
    """Per number of corners, the numbers of labelled and rotation classes derived from the
    ``full`` classes alone, by the orbit-stabiliser theorem.

    The group ``G`` of 48 signed permutations acts on labelled classes.  A structure's
    automorphisms in a mode with group ``H`` are the pairs (``h`` in ``H``, map automorphism)
    that preserve it, so ``|Aut_H| = |Stab_H| * |Aut_labelled|``.  A full class is one
    ``G``-orbit of ``|G| / |Stab_G| = |G| * aut_labelled / aut_full`` labelled classes, and it
    splits into ``[G : R] * |Stab_R| / |Stab_G| = 2 * aut_rotation / aut_full`` rotation
    classes (two exactly when it is chiral).  Summed over a shipped catalog, these must equal
    the counts ``summary.json`` states from three separate canonical forms, tying the columns
    ``automorphisms``, ``chiral`` and the three counts together.  The group orders come from
    :func:`~polyloops.core.symmetry.symmetry_group`.

    >>> counts = orbit_counts(read_catalog().through(20))
    >>> counts[16]
    OrbitCounts(corners=16, labelled=15, rotation=2, full=2)
    """
    from polyloops.core.canonical import canonical_form
    from polyloops.core.symmetry import symmetry_group

    if census.symmetry != Symmetry.FULL:
        raise CatalogError(f"{census.directory}: orbit counts start from a catalog of full classes")
    order_g, order_r = symmetry_group(Symmetry.FULL).order(), symmetry_group(Symmetry.ROTATION).order()
    totals: dict[int, list[int]] = {}
    for entry in census.entries:
        ls = entry.structure()
        aut_l = canonical_form(ls, Symmetry.LABELLED).automorphisms
        aut_r = canonical_form(ls, Symmetry.ROTATION).automorphisms
        aut_f = entry.record.automorphisms
        labelled, rem_l = divmod(order_g * aut_l, aut_f)
        rotation, rem_r = divmod(order_g // order_r * aut_r, aut_f)
        if rem_l or rem_r:
            raise CatalogError(f"{entry.name}: automorphism counts {aut_l}, {aut_r}, {aut_f} break "
                               "the orbit-stabiliser theorem")
        row = totals.setdefault(entry.corners, [0, 0, 0])
        row[0] += labelled
        row[1] += rotation
        row[2] += 1
    return {n: OrbitCounts(n, *row) for n, row in sorted(totals.items())}
