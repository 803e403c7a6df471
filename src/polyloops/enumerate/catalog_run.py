"""Running the genus-0 catalog: jobs, workers, resuming, storage.

The candidate maps come from one of two generators: ``plantri`` (its quadrangulations, filtered;
:mod:`polyloops.enumerate.quadrangulations`) or ``loops`` (arrangements built one loop at a
time; :mod:`polyloops.enumerate.arrangements`).  A plantri run is split into jobs
``(n, res, mod)``: the maps plantri writes for ``-qc2 n res/mod``; a loops run into jobs
covering every corner count at once, each a share ``res/mod`` of the search tree.
Each finished job is written to ``DIR/parts/`` atomically, so an interrupted run resumes
where it stopped.  When all jobs are done, the parts are merged into ``DIR/catalog.jsonl``,
``DIR/catalog.sqlite`` (records of the chosen symmetry mode) and ``DIR/summary.json`` (counts
in every mode), each written through a temporary file and a rename.
"""

from __future__ import annotations

import json
import sqlite3
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from polyloops.core.corners import CATEGORIES
from polyloops.core.errors import PolyloopsError
from polyloops.core.symmetry import Symmetry
from polyloops.enumerate.catalog import MODES, map_classes
from polyloops.enumerate.parallel import run_jobs
from polyloops.enumerate.quadrangulations import FilteredBatch, candidate_maps, resolve_method
from polyloops.io.files import InputError, read_text, write_atomic, writing

GENERATORS = ("plantri", "loops")


def choose_generator(generator: str | None, method: str = "auto",
                     plantri: str | None = None) -> tuple[str, str | None]:
    """The generator a build uses, and a note when the choice was not the one asked for.

    ``None`` asks for the best one built: ``loops`` (arrangements of loops, cheaper from 26
    corners on) when its compiled search was built, else ``plantri`` with a note saying so.
    A strip-filter ``method`` or a ``plantri`` binary belongs to the plantri generator: given
    with ``None`` it chooses plantri, and with ``loops`` it is an error.

    >>> choose_generator(None, method="numpy")
    ('plantri', None)
    >>> choose_generator("loops", method="numpy")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    polyloops.enumerate.catalog_run.CatalogRunError: the strip filter method and plantri's binary ...
    """
    from polyloops.enumerate.arrangements import compiled_generator_available

    plantri_options = method != "auto" or plantri is not None
    if generator == "loops" and plantri_options:
        raise CatalogRunError("the strip filter method and plantri's binary are options of the plantri "
                              "generator; the loops generator builds arrangements and reads no "
                              "quadrangulations")
    if generator is not None:
        return generator, None
    if plantri_options:
        return "plantri", None
    if compiled_generator_available():
        return "loops", None
    return "plantri", ("the compiled arrangement search was not built (a C compiler is needed at "
                       "install time); using plantri's generator, which gives the same records")

# Version 2: chirality and loops per axis fixed; version 3: removable loops, irreducible,
# versioned signatures; version 4: the number of maps whose strips are all simple.  Parts of
# older versions are recomputed.
SCHEMA_VERSION = 4


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

    def covers(self, other: Extent) -> bool:
        """Whether a catalog of this extent holds everything one of ``other`` holds."""
        return (self.min_corners <= other.min_corners and self.max_corners >= other.max_corners
                and self.symmetry == other.symmetry
                and (self.share is None or self.share == other.share))

    def describe(self) -> str:
        """The extent in words, as error messages give it."""
        share = "" if self.share is None else f", share {self.share[0]} of {self.share[1]}"
        return f"{self.min_corners} to {self.max_corners} corners ({self.symmetry}{share})"


CATALOG_FILES = ("catalog.jsonl", "catalog.sqlite", "summary.json")


def existing_extent(out: Path) -> Extent | None:
    """The extent of the catalog already in ``out``, or ``None`` when it holds none (no
    directory, or only the ``parts/`` of an interrupted run).

    Raises
    ------
    CatalogRunError
        When catalog files are there but cannot be read as one (the message names the file).
    """
    present = [name for name in CATALOG_FILES if (out / name).exists() or (out / name).is_symlink()]
    if not present:
        return None
    path = out / "summary.json"
    try:
        summary = json.loads(read_text(path, stdin=False))
        counts = [int(n) for n in summary["counts"]]
        first = read_text(out / "catalog.jsonl", stdin=False).partition("\n")[0]
        symmetry = Symmetry.parse(json.loads(first)["symmetry"]) if first else Symmetry.FULL
        share = summary.get("share")
        share = (int(share[0]), int(share[1])) if share is not None else \
            ((-1, -1) if "partial" in summary else None)
        return Extent(min(counts), max(counts), symmetry, share)
    except InputError as err:
        raise CatalogRunError(f"{out}: holds a catalog that cannot be read ({err})") from None
    except (ValueError, KeyError, TypeError, IndexError, AttributeError) as err:
        raise CatalogRunError(f"{out}: holds catalog files that are not a catalog polyloops wrote "
                              f"({path.name}: {err!r})") from None


@dataclass(frozen=True)
class Job:
    """One slice of a catalog run: the maps plantri writes for ``-qc2 n res/mod``, or, for the
    ``loops`` generator, share ``res/mod`` of the search for every corner count from ``low``
    through ``n``."""

    n: int
    res: int = 0
    mod: int = 1
    generator: str = "plantri"
    low: int | None = None

    @property
    def name(self) -> str:
        """The job's file name stem, such as ``n024-0of1`` or ``loops-8to28-0of16``."""
        if self.generator == "loops":
            return f"loops-{self.low}to{self.n}-{self.res}of{self.mod}"
        return f"n{self.n:03d}-{self.res}of{self.mod}"

    @classmethod
    def of(cls, result: dict[str, Any]) -> Job:
        """The job a result answers."""
        return cls(result["n"], result["res"], result["mod"], result.get("generator", "plantri"),
                   result.get("low"))


def run_job(job: Job, plantri: str, method: str = "auto") -> dict[str, Any]:
    """Generate and classify one slice of the quadrangulations with ``job.n`` vertices.
    ``method`` is the strip filter's (:func:`polyloops.enumerate.quadrangulations.filtered_batches`);
    the result does not depend on it.  A ``loops`` job runs :func:`run_loops_job`."""
    if job.generator == "loops":
        return run_loops_job(job)
    start = time.perf_counter()
    maps, simple = [0], [0]
    candidates = 0
    records: dict[str, list[dict[str, Any]]] = {mode: [] for mode in MODES}

    def seen(batch: FilteredBatch) -> None:
        maps[0] += batch.maps
        simple[0] += batch.simple_strips

    for m in candidate_maps(job.n, plantri, job.res, job.mod, on_batch=seen, method=method):
        candidates += 1
        for mode, recs in map_classes(m).items():
            records[mode].extend(r.to_json() for r in recs)
    return {"version": SCHEMA_VERSION, "n": job.n, "res": job.res, "mod": job.mod,
            "quadrangulations": maps[0], "simple_strips": simple[0], "candidates": candidates,
            "records": records, "seconds": time.perf_counter() - start}


def run_loops_job(job: Job, top: Any = None, top_search: dict[str, int] | None = None) -> dict[str, Any]:
    """Generate and classify share ``job.res/job.mod`` of the candidate maps with ``job.low``
    to ``job.n`` corners, from arrangements of loops: below ``top``, the share's part of the
    frontier (:func:`share_of`), or when it is not given, below the frontier computed here.
    The result holds the records by corner count and the search's statistics; share 0 adds the
    frontier's (``top_search``), so the shares add up to one search."""
    from polyloops.enumerate.arrangements import SearchStats, candidate_arrangements

    start = time.perf_counter()
    low = job.low if job.low is not None else job.n
    stats = [SearchStats(**top_search)] if job.res == 0 and top_search else []
    per_n: dict[str, dict[str, Any]] = {
        str(n): {"candidates": 0, "records": {mode: [] for mode in MODES}} for n in range(low, job.n + 1)}
    # a given ``top`` is this share's part of the frontier (share_of): all of it is ours
    res, mod = (0, 1) if top is not None else (job.res, job.mod)
    for a in candidate_arrangements(job.n, res, mod, on_stats=stats.append, top=top):
        if a.corners < low:
            continue
        entry = per_n[str(a.corners)]
        entry["candidates"] += 1
        for mode, recs in map_classes(a.quad_mesh()).items():
            entry["records"][mode].extend(r.to_json() for r in recs)
    search = sum(stats, SearchStats()).as_dict()
    return {"version": SCHEMA_VERSION, "generator": "loops", "n": job.n, "low": low, "res": job.res,
            "mod": job.mod, "per_n": per_n, "search": search, "seconds": time.perf_counter() - start}


def _expand_chunk(args: tuple[list[Any], int]) -> list[Any]:
    from polyloops.enumerate.arrangements import expand

    return expand(*args)


def loops_frontier(max_n: int, workers: int = 1, dask: str | None = None) -> tuple[Any, dict[str, int]]:
    """The loops search's frontier for ``max_n`` corners and its statistics, each level spread
    over the workers.  It is not stored (hundreds of thousands of arrangements from 28 corners
    on): a rerun computes it again (5 s at 28 corners) and then skips the shares already done."""
    from polyloops.enumerate.arrangements import SearchStats, frontier

    stats: list[SearchStats] = []

    def spread(nodes: list[Any], max_corners: int) -> list[Any]:
        size = max(1, -(-len(nodes) // (4 * workers)))
        chunks = [(nodes[i:i + size], max_corners) for i in range(0, len(nodes), size)]
        parts = run_jobs(_expand_chunk, chunks, workers, dask, ordered=True)
        return [pair for part in parts for pair in part]

    top = frontier(max_n, on_stats=stats.append, expander=spread)
    return top, sum(stats, SearchStats()).as_dict()


def share_of(top: Any, res: int, mod: int) -> Any:
    """The part of a frontier one share needs: its roots (rank ``res`` modulo ``mod``), and the
    candidates above the frontier for share 0."""
    from polyloops.enumerate.arrangements import Frontier

    return Frontier(top.loops, top.roots[res::mod], top.shallow if res == 0 else ())


def per_corner(results: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Results by corner count, whichever generator made them: each with ``n``, ``records``,
    ``candidates``, and plantri's ``quadrangulations`` and ``simple_strips`` (``None`` for loops)."""
    out: list[dict[str, Any]] = []
    for r in results:
        if r.get("generator") == "loops":
            out.extend({"n": int(n), "quadrangulations": None, "simple_strips": None, **entry}
                       for n, entry in r["per_n"].items())
        else:
            out.append(r)
    return out


def loops_slices(max_n: int, workers: int) -> int:
    """How many shares a loops run is cut into.  The frontier is computed once a run, and
    finished shares are what a rerun keeps, so eight a worker from 26 corners on (a share
    then takes about 10 s of CPU at 28 corners, 70 s at 30)."""
    return 1 if workers <= 1 and max_n < 26 else max(workers, 1) * (8 if max_n >= 26 else 1)


def slices(n: int, workers: int) -> int:
    """How many plantri slices a corner count is split into.  Each slice of ``plantri -qc2 n
    res/mod`` first regenerates the part of plantri's search tree above its split level, about
    1.5 s whatever ``n`` (measured at 28 and 30 corners), so slices are kept long: the number of
    maps grows about 3.6 times per corner, the slices about 2 times per two corners (about 15 s
    of plantri each at 28 corners, 100 s at 30)."""
    return 1 if workers <= 1 or n < 24 else workers * 2 ** ((n - 22) // 2)


def plan_jobs(min_n: int, max_n: int, res: int | None, mod: int | None, workers: int,
              generator: str = "plantri") -> list[Job]:
    """One job per even corner count, split further for large counts when several workers
    run; with ``res/mod`` given, just that slice of each corner count.  Odd counts have no
    polycube (:func:`polyloops.enumerate.quadrangulations.odd_corners_have_no_polycube`) and
    get no job.  The ``loops`` generator covers all counts in each job, cut into
    :func:`loops_slices` shares (or just share ``res/mod``)."""
    if generator == "loops":
        if mod is not None:
            return [Job(max_n, res or 0, mod, "loops", min_n)]
        parts = loops_slices(max_n, workers)
        return [Job(max_n, r, parts, "loops", min_n) for r in range(parts)]
    jobs = []
    for n in range(min_n, max_n + 1):
        if n % 2:
            continue
        if mod is not None:
            jobs.append(Job(n, res or 0, mod))
        else:
            parts = slices(n, workers)
            jobs.extend(Job(n, r, parts) for r in range(parts))
    # Largest first, so that workers finish together.
    return sorted(jobs, key=lambda j: (-j.n, j.res))


def part_path(out: Path, job: Job) -> Path:
    """Where a finished job's result is kept, so that a rerun skips it."""
    return out / "parts" / f"{job.name}.json"


def load_part(out: Path, job: Job) -> dict[str, Any] | None:
    """A finished job's result, or ``None`` when it is missing, damaged or of another schema version."""
    path = part_path(out, job)
    try:
        data = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    ok = data.get("version") == SCHEMA_VERSION and Job.of(data) == job
    return data if ok else None


def execute(jobs: list[Job], out: Path, plantri: str, workers: int = 1, dask: str | None = None,
            progress: Callable[[dict[str, Any]], None] | None = None,
            method: str = "auto") -> list[dict[str, Any]]:
    """Run the jobs not yet in ``out/parts`` and return every job's result."""
    method = resolve_method(method)  # once here: a missing compiled filter fails before any work
    (out / "parts").mkdir(parents=True, exist_ok=True)
    done = {job: load_part(out, job) for job in jobs}
    todo = [job for job, part in done.items() if part is None]
    for part in done.values():
        if part is not None and progress:
            progress(part)

    def finish(result: dict[str, Any]) -> None:
        job = Job.of(result)
        write_atomic(part_path(out, job), json.dumps(result, separators=(",", ":")))
        done[job] = result
        if progress:
            progress(result)

    tops = {n: loops_frontier(n, workers, dask) for n in {job.n for job in todo if job.generator == "loops"}}
    tasks = [(job, plantri, method, share_of(tops[job.n][0], job.res, job.mod), tops[job.n][1])
             if job.generator == "loops" else (job, plantri, method, None, None) for job in todo]
    for result in run_jobs(_run_job_star, tasks, workers, dask, ordered=False):
        finish(result)
    return [done[job] for job in jobs]  # type: ignore[misc]


def _run_job_star(args: tuple[Job, str, str, Any, Any]) -> dict[str, Any]:
    job, plantri, method, top, top_search = args
    if job.generator == "loops":
        return run_loops_job(job, top, top_search)
    return run_job(job, plantri, method)


# -- merging and storage ---------------------------------------------------------------------

def summarize(results: list[dict[str, Any]], min_n: int, max_n: int,
              partial: tuple[int, int] | None = None) -> dict[str, Any]:
    """The counts of a run by corners, in all three modes, with the numbers of maps seen
    (plantri) or the statistics of the search (loops: ``generator`` and ``search`` are added,
    and the counts of quadrangulations, which that search does not visit, are ``None``)."""
    loops = [r for r in results if r.get("generator") == "loops"]
    corners = [str(n) for n in range(min_n, max_n + 1)]
    counts = {n: dict.fromkeys(MODES, 0) for n in corners}
    # Odd counts are not generated (no polycube has them): their number of maps is unknown.
    # Every map with an odd number of corners has a self-crossing strip (the theorem of
    # odd_corners_have_no_polycube), so its count of all-simple maps is known: zero.
    quads: dict[str, int | None] = {n: None if loops or int(n) % 2 else 0 for n in corners}
    simple: dict[str, int | None] = {n: None if loops and int(n) % 2 == 0 else 0 for n in corners}
    for r in per_corner(results):
        n = str(r["n"])
        if not loops:
            quads[n] = (quads[n] or 0) + r["quadrangulations"]
            simple[n] = (simple[n] or 0) + r["simple_strips"]
        for mode in MODES:
            counts[n][mode] += len(r["records"][mode])
    # quadrangulations: plantri's simple ones with minimum degree 3; simple_strips: those of
    # them whose strips are all simple closed curves (any degrees).
    out: dict[str, Any] = {"genus": 0, "counts": counts, "quadrangulations": quads,
                           "simple_strips": simple}
    if loops:
        out["generator"] = "loops"
        from polyloops.enumerate.arrangements import SearchStats

        out["search"] = sum((SearchStats(**r["search"]) for r in loops), SearchStats()).as_dict()
    if partial is not None:
        out["partial"] = (f"only the {'share of the search' if loops else 'plantri slice'} res/mod "
                          "given on the command line")
        out["share"] = list(partial)
    return out


NAME_PREFIX = {"full": "P", "rotation": "R", "labelled": "L"}


def class_names(records: list[dict[str, Any]], symmetry: Symmetry | str) -> list[str]:
    """Short stable names, like a census's: ``P26.3`` is the third class with 26 corners up to
    all 48 symmetries (``R`` up to rotation, ``L`` labelled), classes of one corner count ranked
    by signature (as strings).  A name never changes once its corner count is complete."""
    out, rank, last = [], 0, None
    for rec in records:
        rank = rank + 1 if rec["corners"] == last else 1
        last = rec["corners"]
        out.append(f"{NAME_PREFIX[symmetry]}{rec['corners']}.{rank}")
    return out


COLUMNS = ["name", "signature", "corners", "faces", "loops_x", "loops_y", "loops_z",
           *[c.replace("-", "_") for c in CATEGORIES], "automorphisms", "chiral", "removable_loops",
           "irreducible"]


def _row(rec: dict[str, Any]) -> list[Any]:
    return [rec["name"], rec["signature"], rec["corners"], rec["faces"], rec["loops"]["X"], rec["loops"]["Y"],
            rec["loops"]["Z"], *[rec["corner_categories"][c] for c in CATEGORIES],
            rec["automorphisms"], int(rec["chiral"]), rec["removable_loops"], int(rec["irreducible"])]


def write_catalog(out: Path, results: list[dict[str, Any]], symmetry: Symmetry | str,
                  summary: dict[str, Any]) -> int:
    """Write ``catalog.jsonl``, ``catalog.sqlite`` and ``summary.json`` atomically; returns the number
    of records."""
    records = sorted((rec for r in per_corner(results) for rec in r["records"][symmetry]),
                     key=lambda rec: (rec["corners"], rec["signature"]))
    symmetry = Symmetry.parse(symmetry)
    names = class_names(records, symmetry)
    records = [{"name": name, **rec} for name, rec in zip(names, records, strict=True)]
    lines = [json.dumps({**rec, "symmetry": str(symmetry)}, separators=(",", ":")) for rec in records]
    write_atomic(out / "catalog.jsonl", "\n".join(lines) + ("\n" if lines else ""))
    with writing(out / "catalog.sqlite") as pending:
        con = sqlite3.connect(pending.path)
        cols = ", ".join(f"{c} {'TEXT' if c in ('name', 'signature') else 'INTEGER'}" for c in COLUMNS)
        con.execute(f"CREATE TABLE polycubes ({cols}, PRIMARY KEY (signature))")
        con.execute("CREATE UNIQUE INDEX by_name ON polycubes (name)")
        con.executemany(f"INSERT INTO polycubes VALUES ({', '.join('?' * len(COLUMNS))})",
                        [_row(rec) for rec in records])
        con.execute("CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT)")
        con.execute("INSERT INTO meta VALUES ('symmetry', ?)", (str(symmetry),))
        con.execute("CREATE INDEX by_corners ON polycubes (corners)")
        con.commit()
        con.close()
    write_atomic(out / "summary.json", json.dumps(summary, indent=1) + "\n")
    return len(records)


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
                  progress: Callable[[dict[str, Any]], None] | None = None,
                  on_plan: Callable[[list[Job]], None] | None = None,
                  overwrite: bool = False) -> CatalogBuild:
    """Build (or resume) the genus-0 catalog in directory ``out``.

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
        :mod:`polyloops.enumerate.arrangements`); the records and their counts are the same,
        ``summary.json`` says which maps each visited.  ``None``: the best one built
        (:func:`choose_generator`).
    plantri, method:
        Which plantri binary and which strip filter (see
        :func:`polyloops.enumerate.quadrangulations.filtered_batches`), for ``plantri``.
    progress, on_plan:
        Called with each finished job's result, and once with the list of jobs.
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
    from polyloops.enumerate.quadrangulations import find_plantri

    out = Path(out)
    if max_corners < min_corners:
        raise CatalogRunError("--max-corners must be at least --min-corners")
    if (res is None) != (mod is None) or (mod is not None and not 0 <= res < mod):  # type: ignore[operator]
        raise CatalogRunError("--res R --mod M go together, with 0 <= R < M")
    if workers < 1:
        raise CatalogRunError("--workers must be at least 1")
    symmetry = Symmetry.parse(symmetry)
    generator, _ = choose_generator(generator, method, plantri)
    if generator not in GENERATORS:
        raise CatalogRunError(f"unknown generator {generator!r}: choose one of {', '.join(GENERATORS)}")
    if generator == "loops":
        from polyloops.enumerate.arrangements import compiled_generator_available

        if not compiled_generator_available():
            raise CatalogRunError("the compiled arrangement search was not built (a C compiler and "
                                  "the Python headers are needed at install time): reinstall with "
                                  "them, or use --generator plantri")
        binary = ""
    else:
        binary = find_plantri(plantri)
    if out.exists() and not out.is_dir():
        raise CatalogRunError(f"{out}: exists and is not a directory")
    if not out.absolute().parent.is_dir():  # like every other output: the directory above must exist
        raise CatalogRunError(f"{out}: the directory {out.absolute().parent} does not exist")
    old = existing_extent(out)
    new = Extent(min_corners, max_corners, symmetry, None if mod is None else (res or 0, mod))
    if old is not None and not overwrite and not new.covers(old):
        raise WouldLoseResultsError(f"{out}: holds a catalog of {old.describe()}; this build of "
                                    f"{new.describe()} would replace it with less")
    jobs = plan_jobs(min_corners, max_corners, res, mod, workers, generator)
    if on_plan:
        on_plan(jobs)
    try:
        results = execute(jobs, out, binary, workers, dask, progress, method=method)
    except (RuntimeError, OSError) as err:
        raise CatalogRunError(f"{out}: {err}") from None
    summary = summarize(results, min_corners, max_corners, None if mod is None else (res or 0, mod))
    written = write_catalog(out, results, symmetry, summary)
    return CatalogBuild(out, symmetry, summary, written)
