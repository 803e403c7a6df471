"""Reading a catalog directory as a census: typed entries, names, identification, queries.

A catalog directory (written by :func:`polyloops.catalog.run.build_catalog`) holds
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

import hashlib
import json
import re
from collections.abc import Iterator
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Any

from polyloops.catalog import records
from polyloops.catalog.records import CatalogEntry, CatalogError, CatalogMismatchError
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import Symmetry
from polyloops.io.files import InputError, read_bytes, read_text


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


def shipped_genera() -> list[int]:
    """The genera of the catalogs installed with the package (``catalogs/genusG``).

    >>> shipped_genera()[:2]
    [0, 1]
    """
    from importlib.resources import files

    root = Path(str(files("polyloops") / "catalogs"))
    found = [p.name.removeprefix("genus") for p in root.glob("genus*") if (p / "catalog.jsonl").is_file()]
    return sorted(int(g) for g in found if g.isdigit())


def default_catalog(genus: int = 0) -> Path:
    """The shipped catalog of ``genus``, installed with the package (``polyloops/catalogs``,
    package data; in the source tree also reached as ``catalogs/``).

    >>> (default_catalog() / "catalog.jsonl").is_file()
    True
    """
    from importlib.resources import files

    return Path(str(files("polyloops") / "catalogs" / f"genus{genus}"))


def _read_bytes(path: Path) -> bytes:
    try:
        return read_bytes(path, stdin=False)
    except InputError as err:
        raise CatalogError(str(err)) from None


def _read_text(path: Path) -> str:
    """A catalog file's text: a regular file only (a FIFO or ``/dev/zero`` in its place is
    refused, not read)."""
    try:
        return read_text(path, stdin=False)
    except InputError as err:
        raise CatalogError(str(err)) from None


def read_entries(directory: Path) -> list[CatalogEntry]:
    """The entries of ``directory/catalog.jsonl``, in file order; a bad line (not JSON, not a
    record, a name that is no class name, a signature that does not decode) raises
    :class:`CatalogError` naming the file and line."""
    return _read_entries(directory)[0]


def _read_entries(directory: Path) -> tuple[list[CatalogEntry], list[int]]:
    """The entries and the number of darts each one's signature names."""
    from polyloops.core.canonical import SignatureError, signature_darts, signatures_darts

    path = Path(directory) / "catalog.jsonl"
    lines = _read_text(path).splitlines()
    try:  # one parse for all the lines, and one pass for all the signatures' checks
        rows = json.loads("[" + ",".join(lines) + "]")
        out = [CatalogEntry.from_json(row) for row in rows]
        if len(out) == len(lines) and all(NAME.fullmatch(e.name) for e in out):
            return out, signatures_darts([e.signature for e in out])
    except (ValueError, KeyError, TypeError, AttributeError, RecursionError, SignatureError):
        pass  # read again line by line, to name the line at fault
    out, sizes = [], []
    for i, line in enumerate(lines):
        try:
            entry = CatalogEntry.from_json(json.loads(line))
            if not NAME.fullmatch(entry.name):
                raise ValueError(f"{entry.name[:40]!r} is not a class name such as P16.2 or T32.1")
            darts = signature_darts(entry.signature)
        except SignatureError as err:
            raise CatalogError(f"{path}: line {i + 1}: not a catalog record (its signature: {err})") from None
        except (ValueError, KeyError, TypeError, AttributeError, RecursionError) as err:
            raise CatalogError(f"{path}: line {i + 1}: not a catalog record ({err})") from None
        out.append(entry)
        sizes.append(darts)
    return out, sizes


NAME = re.compile(r"([PRL]|T[RL]?|G[2-9][0-9]{0,2}-[RL]?)[1-9][0-9]{0,5}\.[1-9][0-9]{0,8}")


def _digest(path: Path) -> str | None:
    digest = hashlib.sha256()
    try:
        digest.update(_read_bytes(path))
    except CatalogError:
        return None
    return digest.hexdigest()


def catalog_problem(directory: Path, entries: list[CatalogEntry], summary: dict[str, Any],
                    darts: list[int]) -> str | None:
    """What makes the records of a catalog not prove what its summary claims, or ``None``:
    the files differ from the digests the summary records; two modes; the records out of
    catalog order or their names not the ones :func:`~polyloops.catalog.records.class_names`
    gives; a signature twice; a record whose corners or faces its signature contradicts; a
    count per corner count that differs from the summary's.  ``darts`` gives the size of the
    map each record's signature names (read from its head, after its check characters,
    :func:`~polyloops.core.canonical.signature_darts`): cheap enough for every reader."""
    genus = int(summary.get("genus", 0))
    for name, want in (summary.get("files") or {}).items():
        path = directory / str(name)
        if name == "catalog.sqlite" and not (path.exists() or path.is_symlink()):
            continue  # a shipped catalog leaves the database out: queries build it from the records
        if _digest(path) != want:
            return (f"{path} is not the file {directory / 'summary.json'} records (its digest differs: "
                    "edited, or written by a run that was stopped; run the build again)")
    modes = {e.symmetry for e in entries}
    stated = summary.get("symmetry")
    if len(modes) > 1 or (stated is not None and entries and str(entries[0].symmetry) != stated):
        return f"records in modes {sorted(str(m) for m in modes)}, the summary's mode {stated}"
    mode = str(entries[0].symmetry) if entries else (stated or "full")
    order = sorted(entries, key=lambda e: (e.corners, e.signature))
    seen: set[str] = set()
    for e in entries:
        if e.signature in seen:
            return f"class {e.name} is listed twice (its signature appears on two records)"
        seen.add(e.signature)
    if order != entries:
        return "the records are not in catalog order (by corners, then signature)"
    names = records.class_names([e.record for e in entries], mode, genus) if genus >= 0 \
        else [e.name for e in entries]
    for e, name in zip(entries, names, strict=True):
        if e.name != name:
            return f"record {e.name} should be named {name} (names rank each corner count's signatures)"
    for e, size in zip(entries, darts, strict=True):
        faces, corners = size // 4, size // 4 + 2 - 2 * genus
        if size % 4 or e.corners != corners or e.record.faces != faces:
            return (f"record {e.name} says {e.corners} corners and {e.record.faces} faces; its signature "
                    f"names a map of genus {genus} with {corners} corners and {faces} faces")
    counts = summary.get("counts", {})
    listed: dict[int, int] = {}
    for e in entries:
        listed[e.corners] = listed.get(e.corners, 0) + 1
    beyond = sorted(n for n in listed if str(n) not in counts)
    if beyond:
        return f"records with {beyond[0]} corners, which the summary does not count"
    for n, row in sorted(counts.items(), key=lambda kv: int(kv[0])):
        claimed, held = row.get(mode), listed.get(int(n), 0)
        if claimed != held:
            return (f"the summary counts {claimed} {mode} classes with {n} corners; "
                    f"catalog.jsonl holds {held}")
    return None


def read_catalog(directory: Path | str | None = None, *, genus: int | None = None) -> Census:
    """A catalog directory as a :class:`Census`, checked: its records must prove what its
    summary claims (:func:`catalog_problem`).

    Parameters
    ----------
    directory:
        A directory written by :func:`~polyloops.catalog.run.build_catalog`.
    genus:
        Without ``directory``: the shipped catalog of this genus (default 0); with it, the
        genus the catalog must have.

    Returns
    -------
    Census

    Raises
    ------
    CatalogError
        When a file is missing, a line is not a record (the message names file and line), or
        the catalog is of another genus than ``genus``.
    CatalogMismatchError
        When the records do not prove the summary's counts (the message names both numbers).

    >>> census = read_catalog()
    >>> census.symmetry, census.max_corners >= 26, census.by_name["P8.1"].record.automorphisms
    (<Symmetry.FULL: 'full'>, True, 48)
    >>> read_catalog(genus=1)["T32.1"].corners
    32
    """
    if directory is None:
        wanted = 0 if genus is None else genus
        directory = default_catalog(wanted)
        if not (directory / "catalog.jsonl").is_file():
            raise CatalogError(f"no catalog of genus {wanted} ships with polyloops (the shipped ones: "
                               f"genus {', '.join(str(g) for g in SHIPPED_GENERA)})")
    directory = Path(directory)
    key = _shipped_key(directory)
    census = _SHIPPED_READ.get(key) if key is not None else None
    if census is None:
        census = _read_checked(directory, genus)
        if key is not None and key == _shipped_key(directory):  # unchanged while it was read
            _SHIPPED_READ[key] = census
    if genus is not None and int(census.summary.get("genus", 0)) != genus:
        raise CatalogError(f"{directory}: a catalog of genus {census.summary.get('genus', 0)}, not {genus}")
    return census


def _read_checked(directory: Path, genus: int | None) -> Census:
    """:func:`read_catalog` of a directory, read and checked afresh."""
    entries, darts = _read_entries(directory)
    path = directory / "summary.json"
    if not (path.exists() or path.is_symlink()):
        raise CatalogError(f"{path}: missing (a catalog run that was stopped while it wrote its files; "
                           "run it again to finish them)")
    try:
        summary = json.loads(_read_text(path))
    except (ValueError, RecursionError) as err:
        raise CatalogError(f"{path}: not JSON ({err})") from None
    problem = summary_problem(summary)
    if problem:
        raise CatalogError(f"{path}: not a catalog summary ({problem})")
    if genus is not None and int(summary.get("genus", 0)) != genus:
        raise CatalogError(f"{directory}: a catalog of genus {summary.get('genus', 0)}, not {genus}")
    problem = catalog_problem(directory, entries, summary, darts)
    if problem:
        raise CatalogMismatchError(f"{directory}: not a catalog its records prove: {problem}")
    return Census(directory, tuple(entries), summary)


# The shipped catalogs, once read and checked, kept for the process (naming a structure reads
# the catalog each time: a sheet's captions, identify in a loop).  A file replaced or changed
# since has another key, and is read and checked again.
_SHIPPED_READ: dict[tuple[object, ...], Census] = {}


def _shipped_key(directory: Path) -> tuple[object, ...] | None:
    """What identifies a shipped catalog's files as read (their size, time and inode), or
    ``None`` for any other directory (never kept: a user's catalog is read afresh)."""
    try:
        where = directory.resolve()
        if where not in {default_catalog(g).resolve() for g in SHIPPED_GENERA}:
            return None
        stats = [(where / name).stat() for name in ("catalog.jsonl", "summary.json")]
    except OSError:
        return None
    return (str(where), *((st.st_size, st.st_mtime_ns, st.st_ino) for st in stats))


SHIPPED_GENERA = (0, 1)


def shipped_class(name: str) -> LoopStructure:
    """The representative of a class of a shipped catalog by its name (``P16.2``, ``T32.1``),
    the genus read from the name's prefix.

    >>> shipped_class("T32.1").genus, shipped_class("P8.1").map.num_corners
    (1, 8)

    Raises
    ------
    CatalogError
        For a name that is no class name, of a genus no catalog ships, or not in the catalog
        (the message says how far the catalog goes).
    """
    if not NAME.fullmatch(name):
        raise CatalogError(f"{name[:40]!r} is not a class name such as P16.2 or T32.1")
    genus = 1 if name.startswith("T") else int(name[1:name.index("-")]) if name.startswith("G") else 0
    census = read_catalog(genus=genus)
    entry = census.by_name.get(name)
    if entry is None:
        raise CatalogError(f"no class {name} in the shipped genus-{genus} catalog (names up to its "
                           f"{census.max_corners} corners, up to {census.symmetry.up_to})")
    return entry.structure()


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
    """Rows of a catalog matching an SQL WHERE clause (:func:`polyloops.catalog.records.query`),
    after the catalog is read and checked (:func:`read_catalog`): from ``DIR/catalog.sqlite``
    (its digest checked too), or, where the directory has none, from the same table built in
    memory from the records.

    >>> columns, rows = query(default_catalog(), "corners = 16")
    >>> columns[:3], [r[0] for r in rows]
    (['name', 'signature', 'corners'], ['P16.1', 'P16.2'])
    """
    census = read_catalog(out)
    return records.query(census.directory / "catalog.sqlite", where, _entries_without_database(census))


def export_csv(out: Path) -> str:
    """The whole ``polycubes`` table of a catalog (read and checked as :func:`query` says) as CSV."""
    census = read_catalog(out)
    return records.csv_text(census.directory / "catalog.sqlite", _entries_without_database(census))


def _entries_without_database(census: Census) -> list[CatalogEntry] | None:
    """The records of a catalog that has no ``catalog.sqlite`` (the shipped catalog: the table
    is built in memory, so the package carries each record once); ``None`` when the database
    is there."""
    database = census.directory / "catalog.sqlite"
    if database.exists() or database.is_symlink():
        return None
    return list(census.entries)


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
    not_polycube: str | None = None  # when not found: why it is no polycube (loop structure) at all

    @property
    def beyond(self) -> bool:
        """Outside what the catalog lists (another genus, or more corners)."""
        return self.name is None and (self.genus != self.catalog_genus or self.corners > self.max_corners)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the identification."""
        return {"name": self.name, "signature": self.signature, "corners": self.corners,
                "genus": self.genus, "catalog_max_corners": self.max_corners,
                "catalog_genus": self.catalog_genus, "in_catalog": self.name is not None,
                "polycube": self.not_polycube is None, "not_polycube": self.not_polycube}


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
    >>> print(identify(load_example("torus-cycle")).not_polycube)  # doctest: +ELLIPSIS
    Definition 4 condition 5: the X-graph has a cycle ...
    """
    from polyloops.core.canonical import canonical_form

    if catalog is None and obj.map.genus > 0 and (default_catalog(obj.map.genus) / "catalog.jsonl").is_file():
        catalog = default_catalog(obj.map.genus)
    census = catalog if isinstance(catalog, Census) else read_catalog(catalog)
    sig = canonical_form(obj, census.symmetry).signature
    found = census.by_signature.get(sig)
    why = None
    if found is None:  # a catalog lists polycubes only: say when that is why (checked on misses alone)
        from polyloops.verify import verify

        report = verify(obj)
        why = None if report.valid else report.first_violation()
    return Identification(found.name if found else None, sig, obj.map.num_corners, obj.map.genus,
                          census.max_corners, census.genus, why)


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
