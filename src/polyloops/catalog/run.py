"""Running a catalog: jobs, workers, resuming, merging, storage.

The candidate maps come from a :class:`~polyloops.generate.base.Generator` (``loops``
by default where it was built, or ``plantri``; a new generator plugs in with
:func:`~polyloops.generate.base.register`).  The generator cuts the run into jobs; each
finished job is written to ``DIR/parts/`` as a typed result, atomically, so an interrupted run
resumes where it stopped.  When all jobs are done, the parts are merged into
``DIR/catalog.jsonl``, ``DIR/catalog.sqlite`` (records of the chosen symmetry mode; the record
format is :mod:`polyloops.catalog.records`) and ``DIR/summary.json`` (counts in every mode),
each written through a temporary file and a rename.
"""

from __future__ import annotations

import contextlib
import fcntl
import hashlib
import json
import os
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from polyloops.catalog.classes import MODES
from polyloops.catalog.jobs import JobResult, run_job
from polyloops.catalog.records import CatalogEntry, class_names, write_jsonl, write_sqlite
from polyloops.core.errors import PolyloopsError
from polyloops.core.symmetry import Symmetry
from polyloops.generate.base import Generator, Job, generators
from polyloops.generate.bounds import MAX_CATALOG_CORNERS
from polyloops.io.files import InputError, OutputError, check_within, read_text, write_atomic
from polyloops.parallel import run_jobs


def choose_generator(generator: str | None, method: str = "auto",
                     plantri: str | None = None, genus: int = 0) -> tuple[str, str | None]:
    """The generator a build of ``genus`` uses, and a note when the choice was not the one
    asked for.

    ``None`` asks for the most preferred one of that genus that can run here and takes the
    options given (a strip-filter ``method`` and a ``plantri`` binary are options of the plantri
    generator); when a more preferred one could not run, the note says why.  An option the
    named generator does not take, or a generator of another genus, is an error.

    >>> choose_generator(None, method="numpy")
    ('plantri', None)
    >>> choose_generator("loops", method="numpy")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    polyloops.catalog.run.CatalogRunError: the strip filter method and plantri's binary ...
    """
    given = {k for k, v in (("method", method), ("plantri", plantri)) if v not in (None, "auto")}
    if generator is not None:
        chosen = generators().get(generator)
        if chosen is not None and chosen.genus != genus:
            raise CatalogRunError(f"the {generator} generator makes maps of genus {chosen.genus}, "
                                  f"not {genus}")
        if chosen is not None and not given <= chosen.options:
            takers = " and ".join(sorted(g.name for g in generators().values() if given <= g.options))
            raise CatalogRunError(f"the strip filter method and plantri's binary are options of the {takers} "
                                  f"generator; the {generator} generator takes none of them")
        return generator, None
    ranked = sorted((g for g in generators().values() if given <= g.options and g.genus == genus),
                    key=lambda g: -g.preference)
    skipped: list[tuple[str, str]] = []
    for g in ranked:
        why = g.unavailable()
        if why is None:
            note = None if not skipped else (f"{skipped[0][1]}; using the {g.name} generator, which gives "
                                             "the same records")
            return g.name, note
        skipped.append((g.name, why))
    if not skipped:
        takes = " or ".join(f"--{k}" for k in sorted(given))
        raise CatalogRunError(f"no catalog generator of genus {genus} takes {takes}" if given
                              else f"no catalog generator makes maps of genus {genus}")
    raise CatalogRunError("no catalog generator can run here: " + "; ".join(why for _, why in skipped))


class CatalogRunError(PolyloopsError, ValueError):
    """A catalog run that cannot start or finish: bad arguments, an output that is no
    directory, a worker that failed; the message names the problem."""


class WouldLoseResultsError(CatalogRunError):
    """A build whose catalog would hold less than the one already in its directory (fewer
    corner counts, another symmetry mode, a share of a complete run): it is replaced only when
    asked (``overwrite``)."""


@dataclass(frozen=True)
class Extent:
    """What a catalog covers: its corner counts, the mode its records list, and the share of
    the search it holds (``None``: all of it)."""

    min_corners: int
    max_corners: int
    symmetry: Symmetry
    share: tuple[int, int] | None = None
    genus: int = 0

    def covers(self, other: Extent) -> bool:
        """Whether a catalog of this extent holds everything one of ``other`` holds."""
        return (self.min_corners <= other.min_corners and self.max_corners >= other.max_corners
                and self.symmetry == other.symmetry and self.genus == other.genus
                and (self.share is None or self.share == other.share))

    def describe(self) -> str:
        """The extent in words, as error messages give it."""
        share = "" if self.share is None else f", share {self.share[0]} of {self.share[1]}"
        genus = f"genus {self.genus}, " if self.genus else ""
        return f"{genus}{self.min_corners} to {self.max_corners} corners ({self.symmetry}{share})"


CATALOG_FILES = ("catalog.jsonl", "catalog.sqlite", "summary.json")



def existing_extent(out: Path) -> Extent | None:
    """The extent of the catalog already in ``out``, or ``None`` when it holds none (no
    directory, only the ``parts/`` of an interrupted run, or the records of a merge that was
    stopped before its ``summary.json``, the file written last: no reader accepts them, and
    the rerun writes them again).

    Raises
    ------
    CatalogRunError
        When catalog files are there but cannot be read as one (the message names the file).
    """
    present = [name for name in CATALOG_FILES if (out / name).exists() or (out / name).is_symlink()]
    if "summary.json" not in present:
        return None
    path = out / "summary.json"
    try:
        summary = json.loads(read_text(path, stdin=False))
        counts = [int(n) for n in summary["counts"]]
        symmetry = summary.get("symmetry")
        if symmetry is None:  # written before summaries named their mode: the first record does
            first = read_text(out / "catalog.jsonl", stdin=False).partition("\n")[0]
            symmetry = json.loads(first)["symmetry"] if first else "full"
        share = summary.get("share")
        share = (int(share[0]), int(share[1])) if share is not None else \
            ((-1, -1) if "partial" in summary else None)
        return Extent(min(counts), max(counts), Symmetry.parse(symmetry), share, int(summary.get("genus", 0)))
    except InputError as err:
        raise CatalogRunError(f"{out}: holds a catalog that cannot be read ({err})") from None
    except (ValueError, KeyError, TypeError, IndexError, AttributeError) as err:
        raise CatalogRunError(f"{out}: holds catalog files that are not a catalog polyloops wrote "
                              f"({path.name}: {err!r})") from None


LOCK_NAME = ".polyloops-lock"


@contextlib.contextmanager
def locked(out: Path) -> Iterator[None]:
    """Hold the directory's lock for a whole run: a second run into the same directory is
    refused at once (two runs finishing in either order would leave whichever ended last).
    The lock is the operating system's (``flock``): a run that dies releases it."""
    path = out / LOCK_NAME
    try:
        check_within(path, out)
        fd = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)
    except OutputError as err:
        raise CatalogRunError(str(err)) from None
    except OSError as err:
        raise CatalogRunError(f"{out}: cannot write: {err.strerror}") from None
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise CatalogRunError(f"{out}: another catalog run is writing into this directory; wait for it "
                                  "or choose another directory") from None
        yield
    finally:
        os.close(fd)


def part_path(out: Path, job: Job) -> Path:
    """Where a finished job's result is kept, so that a rerun skips it."""
    return out / "parts" / f"{job.name}.json"


def part_text(result: JobResult) -> str:
    """A finished job's part file: its result and the SHA-256 digest of that result's JSON, so
    that an edited part is recomputed rather than merged."""
    body = json.dumps(result.to_json(), separators=(",", ":"), sort_keys=True)
    return json.dumps({"sha256": hashlib.sha256(body.encode()).hexdigest(), "result": json.loads(body)},
                      separators=(",", ":"), sort_keys=True)


def read_part(path: Path, out: Path) -> JobResult | None:
    """The result in the part file ``path`` (inside ``out``), or ``None`` when it is missing,
    damaged, edited (its digest does not match) or of another schema version."""
    try:
        check_within(path, out)
        data = json.loads(read_text(path, stdin=False))
        body = json.dumps(data["result"], separators=(",", ":"), sort_keys=True)
        if hashlib.sha256(body.encode()).hexdigest() != data["sha256"]:
            return None
        return JobResult.from_json(data["result"])
    except (InputError, OutputError, ValueError, KeyError, TypeError, AttributeError, RecursionError):
        return None


def load_part(out: Path, job: Job) -> JobResult | None:
    """A finished job's result, or ``None`` when it is missing, damaged, edited, of another
    schema version or of another job (:func:`read_part`; it is then recomputed)."""
    result = read_part(part_path(out, job), out)
    return result if result is not None and result.job == job else None


def execute(generator: Generator, jobs: list[Job], out: Path, workers: int = 1, dask: str | None = None,
            progress: Callable[[JobResult], None] | None = None) -> list[JobResult]:
    """Run the jobs not yet in ``out/parts`` and return every job's result, in job order."""
    parts = out / "parts"
    try:
        check_within(parts / "x", out)
    except OutputError as err:
        raise CatalogRunError(str(err)) from None
    parts.mkdir(parents=True, exist_ok=True)
    done = {job: load_part(out, job) for job in jobs}
    todo = [job for job, part in done.items() if part is None]
    for part in done.values():
        if part is not None and progress:
            progress(part)
    contexts = generator.prepare(todo, workers, dask, parts) if todo else []
    tasks = [(generator, job, context) for job, context in zip(todo, contexts, strict=True)]
    for result in run_jobs(run_job, tasks, workers, dask, ordered=False):
        write_atomic(part_path(out, result.job), part_text(result), within=out)
        done[result.job] = result
        if progress:
            progress(result)
    return [done[job] for job in jobs]  # type: ignore[misc]


# -- merging and storage ---------------------------------------------------------------------

def summarize(generator: Generator, results: list[JobResult], min_n: int, max_n: int,
              partial: tuple[int, int] | None = None) -> dict[str, Any]:
    """The counts of a run by corners, in all three modes, with the numbers of maps the
    generator read (``None`` where it does not count them), the maps by the number of classes
    they carry, and the generator's summed statistics."""
    corners = [str(n) for n in range(min_n, max_n + 1)]
    counts = {n: dict.fromkeys(MODES, 0) for n in corners}
    # Odd counts are not generated (no polycube has them): their number of maps is unknown.
    # Every map with an odd number of corners has a self-crossing strip (the theorem of
    # odd_corners_have_no_polycube), so its count of all-simple maps is known: zero.
    maps: dict[str, list[int | None]] = {n: [] for n in corners}
    strips: dict[str, list[int | None]] = {n: [] for n in corners}
    statistics: dict[str, int] = {}
    carrying: dict[str, dict[int, int]] = {n: {} for n in corners}
    for r in results:
        for key, value in r.statistics.items():
            statistics[key] = statistics.get(key, 0) + value
        for n_int, c in r.corners.items():
            n = str(n_int)
            if n in counts:
                for mode in MODES:
                    counts[n][mode] += len(c.records[str(mode)])
                maps[n].append(c.maps)
                strips[n].append(c.simple_strips)
                for k, v in c.carrying.items():
                    carrying[n][k] = carrying[n].get(k, 0) + v

    def total(values: list[int | None]) -> int | None:  # known only when every job counted it
        return None if not values or None in values else sum(v for v in values if v is not None)

    if generator.genus == 0:
        quads = {n: None if int(n) % 2 else total(maps[n]) for n in corners}
        simple = {n: 0 if int(n) % 2 else total(strips[n]) for n in corners}
    else:  # odd counts occur on the torus, and no generator of positive genus reads all maps
        quads = {n: total(maps[n]) for n in corners}
        simple = {n: total(strips[n]) for n in corners}
    # quadrangulations: plantri's simple ones with minimum degree 3; simple_strips: those of
    # them whose strips are all simple closed curves (any degrees).
    # maps_by_classes[n][k]: the candidate maps with n corners that carry exactly k >= 1
    # polycube classes up to all symmetries (each class lies on one map).
    out: dict[str, Any] = {"genus": generator.genus, "counts": counts, "quadrangulations": quads,
                           "simple_strips": simple,
                           "maps_by_classes": {n: {str(k): v for k, v in sorted(carrying[n].items())}
                                               for n in corners}}
    if generator.statistics_key is not None:
        out["generator"] = generator.name
        if generator.variant:
            out["variant"] = generator.variant
        out[generator.statistics_key] = statistics
    if partial is not None:
        out["partial"] = "only the share res/mod given on the command line"
        out["share"] = list(partial)
    return out


def file_digest(path: Path) -> str:
    """The SHA-256 digest of a file, as ``summary.json`` records each catalog file's."""
    digest = hashlib.sha256()
    with open(path, "rb") as fh:
        while chunk := fh.read(1 << 22):
            digest.update(chunk)
    return digest.hexdigest()


def write_catalog(out: Path, results: list[JobResult], symmetry: Symmetry | str,
                  summary: dict[str, Any]) -> int:
    """Write ``catalog.jsonl`` and ``catalog.sqlite``, then ``summary.json`` last, each
    atomically; the summary records the mode and each file's digest, so a set whose merge was
    stopped half-way (new records under an old summary, or no summary) is refused by every
    reader and finished by a rerun.  ``summary`` gains the mode and the digests.  Returns the
    number of records."""
    symmetry = Symmetry.parse(symmetry)
    records = sorted((rec for r in results for c in r.corners.values() for rec in c.records[str(symmetry)]),
                     key=lambda rec: (rec.corners, rec.signature))
    names = class_names(records, symmetry, int(summary.get("genus", 0)))
    entries = [CatalogEntry(name, symmetry, rec) for name, rec in zip(names, records, strict=True)]
    write_jsonl(out / "catalog.jsonl", entries, within=out)
    write_sqlite(out / "catalog.sqlite", entries, symmetry, within=out)
    summary["symmetry"] = str(symmetry)
    summary["files"] = {name: file_digest(out / name) for name in ("catalog.jsonl", "catalog.sqlite")}
    write_atomic(out / "summary.json", json.dumps(summary, indent=1) + "\n", within=out)
    return len(entries)


@dataclass(frozen=True)
class CatalogBuild:
    """What :func:`build_catalog` wrote: the summary (counts in every mode, by corners) and the
    number of records listed in the chosen mode."""

    directory: Path
    symmetry: Symmetry
    summary: dict[str, Any]
    records: int


def build_catalog(out: Path | str, max_corners: int, min_corners: int = 8,
                  symmetry: Symmetry | str = Symmetry.FULL, *, workers: int = 1,
                  res: int | None = None, mod: int | None = None, dask: str | None = None,
                  plantri: str | None = None, method: str = "auto", generator: str | None = None,
                  progress: Callable[[JobResult], None] | None = None,
                  on_plan: Callable[[list[Job]], None] | None = None,
                  overwrite: bool = False, genus: int = 0,
                  options: Mapping[str, Any] | None = None) -> CatalogBuild:
    """Build (or resume) the catalog of the polycubes of genus ``genus`` in directory ``out``.

    Parameters
    ----------
    out:
        The catalog directory; its parent must exist.  Finished jobs are kept in
        ``out/parts``, so a second call resumes an interrupted one.
    max_corners, min_corners:
        The corner counts to cover.
    symmetry:
        The mode the records list (``summary.json`` counts all three).
    workers, dask, res, mod:
        Split the work over local processes or a Dask cluster, or do only the slice ``res``
        of ``mod``; the bytes written do not depend on the split.
    generator:
        ``plantri`` (filter every quadrangulation) or ``loops`` (build arrangements of loops,
        :mod:`polyloops.generate.loops.arrangements`); the records and their counts are the same,
        ``summary.json`` says which maps each visited.  ``None``: the best one built
        (:func:`choose_generator`).
    plantri, method:
        Which plantri binary and which strip filter (see
        :func:`polyloops.generate.plantri.quadrangulations.filtered_batches`), for ``plantri``.
    options:
        The generator's other options (``loops``: ``cuts``, a
        :class:`~polyloops.generate.loops.arrangements.Cuts`; ``torus``: ``stage``, ``"regions"``
        or ``"loops"``): the same records, other work; a run keeps its parts apart.
    progress, on_plan:
        Called with each finished job's result, and once with the list of jobs.
    genus:
        0 (the sphere) or 1 (the torus: the ``torus`` generator, :mod:`polyloops.generate.torus`).
    overwrite:
        Replace a catalog in ``out`` that covers more than this build (more corner counts,
        another mode, the whole search where this is a share); without it such a build is
        refused before any work.  A catalog this build covers is resumed or extended.

    Returns
    -------
    CatalogBuild

    Raises
    ------
    CatalogRunError
        For arguments that do not fit together, an output that is not a directory, or the
        ``loops`` generator without its compiled search.
    WouldLoseResultsError
        When ``out`` holds a catalog this build would replace with less (without ``overwrite``).
    PlantriError
        When plantri cannot be found or fails.

    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     built = build_catalog(Path(tmp) / "cat", max_corners=12)
    >>> built.records, {str(mode): n for mode, n in built.summary["counts"]["12"].items()}
    (2, {'labelled': 3, 'rotation': 1, 'full': 1})
    """
    out = Path(out)
    if not 0 <= max_corners <= MAX_CATALOG_CORNERS or min_corners < 0:
        raise CatalogRunError(f"max_corners {max_corners}: a catalog run goes to at most "
                              f"{MAX_CATALOG_CORNERS} corners")
    if max_corners < min_corners:
        raise CatalogRunError("max_corners must be at least min_corners")
    if (res is None) != (mod is None) or (mod is not None and not 0 <= res < mod):  # type: ignore[operator]
        raise CatalogRunError("a share is res and mod together, with 0 <= res < mod")
    if workers < 1:
        raise CatalogRunError("workers must be at least 1")
    symmetry = Symmetry.parse(symmetry)
    name, _ = choose_generator(generator, method, plantri, genus)
    if name not in generators():
        raise CatalogRunError(f"unknown generator {name!r}: choose one of {', '.join(sorted(generators()))}")
    try:
        chosen = generators()[name].with_options(plantri=plantri, method=method, **(options or {}))
    except ValueError as err:
        raise CatalogRunError(str(err)) from None
    why = chosen.unavailable()
    if why is not None:
        raise CatalogRunError(f"{why}: reinstall with them, or use the plantri generator")
    if out.exists() and not out.is_dir():
        raise CatalogRunError(f"{out}: exists and is not a directory")
    if not out.absolute().parent.is_dir():  # like every other output: the directory above must exist
        raise CatalogRunError(f"{out}: the directory {out.absolute().parent} does not exist")
    share = None if mod is None else (res or 0, mod)
    new = Extent(min_corners, max_corners, symmetry, share, genus)
    _refuse_less(out, new, overwrite)  # before any work, and again under the lock
    try:
        out.mkdir(exist_ok=True)
    except OSError as err:
        raise CatalogRunError(f"{out}: cannot write: {err.strerror}") from None
    with locked(out):
        _refuse_less(out, new, overwrite)
        planned = chosen.plan(min_corners, max_corners, share, workers)
        jobs = [replace(job, variant=chosen.variant) for job in planned]  # not the parts of other options
        if on_plan:
            on_plan(jobs)
        try:
            results = execute(chosen, jobs, out, workers, dask, progress)
            summary = summarize(chosen, results, min_corners, max_corners, share)
            written = write_catalog(out, results, symmetry, summary)
        except CatalogRunError:
            raise
        except OutputError as err:
            raise CatalogRunError(str(err)) from None
        except (RuntimeError, OSError) as err:
            raise CatalogRunError(f"{out}: {err}") from None
    return CatalogBuild(out, symmetry, summary, written)


def _refuse_less(out: Path, new: Extent, overwrite: bool) -> None:
    old = existing_extent(out)
    if old is not None and not overwrite and not new.covers(old):
        raise WouldLoseResultsError(f"{out}: holds a catalog of {old.describe()}; this build of "
                                    f"{new.describe()} would replace it with less")


def write_census(census: Any, out: Path | str) -> Path:
    """Write a :class:`~polyloops.catalog.census.Census` (a catalog read, or cut with
    :meth:`~polyloops.catalog.census.Census.through`) as a catalog directory ``out``: its
    records, then its summary with the mode and the records' digest, so that readers accept
    exactly these records.  The summary's other tables are cut to its counts' range.

    >>> import tempfile
    >>> from polyloops.catalog.census import read_catalog
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     small = read_catalog(write_census(read_catalog().through(20), Path(tmp) / "small"))
    >>> len(small), small.max_corners
    (11, 20)
    """
    out = Path(out)
    out.mkdir(exist_ok=True)
    counts = census.summary.get("counts", {})
    summary = {k: ({n: v for n, v in t.items() if n in counts}
                   if isinstance(t, dict) and t and all(n.isdigit() for n in t) else t)
               for k, t in census.summary.items() if k != "files"}
    write_jsonl(out / "catalog.jsonl", census.entries, within=out)
    (out / "catalog.sqlite").unlink(missing_ok=True)  # queries build it from the records
    summary["symmetry"] = str(census.symmetry)
    summary["files"] = {"catalog.jsonl": file_digest(out / "catalog.jsonl")}
    write_atomic(out / "summary.json", json.dumps(summary, indent=1) + "\n", within=out)
    return out
