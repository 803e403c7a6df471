"""Running the genus-0 catalog: jobs, workers, resuming, storage.

A run is split into jobs ``(n, res, mod)``: the maps plantri writes for ``-qc2 n res/mod``.
Each finished job is written to ``DIR/parts/`` atomically, so an interrupted run resumes
where it stopped.  When all jobs are done, the parts are merged into ``DIR/catalog.jsonl``,
``DIR/catalog.sqlite`` (records of the chosen symmetry mode) and ``DIR/summary.json`` (counts
in every mode), each written through a temporary file and a rename.
"""

from __future__ import annotations

import json
import os
import sqlite3
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from polyloops.core.corners import CATEGORIES
from polyloops.core.errors import PolyloopsError
from polyloops.core.files import replace_atomic, write_atomic
from polyloops.core.symmetry import Symmetry
from polyloops.enumerate.catalog import MODES, map_classes
from polyloops.enumerate.parallel import run_jobs
from polyloops.enumerate.quadrangulations import FilteredBatch, candidate_maps, resolve_method

# Version 2: chirality and loops per axis fixed; version 3: removable loops, irreducible,
# versioned signatures; version 4: the number of maps whose strips are all simple.  Parts of
# older versions are recomputed.
SCHEMA_VERSION = 4


class CatalogRunError(PolyloopsError, ValueError):
    """A catalog run that cannot start or finish: bad arguments, an output that is no
    directory, a worker that failed; the message names the problem."""


@dataclass(frozen=True)
class Job:
    """One slice of a catalog run: the maps plantri writes for ``-qc2 n res/mod``."""

    n: int
    res: int = 0
    mod: int = 1

    @property
    def name(self) -> str:
        """The job's file name stem, such as ``n024-0of1``."""
        return f"n{self.n:03d}-{self.res}of{self.mod}"


def run_job(job: Job, plantri: str, method: str = "auto") -> dict[str, Any]:
    """Generate and classify one slice of the quadrangulations with ``job.n`` vertices.
    ``method`` is the strip filter's (:func:`polyloops.enumerate.quadrangulations.filtered_batches`);
    the result does not depend on it."""
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


def slices(n: int, workers: int) -> int:
    """How many plantri slices a corner count is split into.  Each slice of ``plantri -qc2 n
    res/mod`` first regenerates the part of plantri's search tree above its split level, about
    1.5 s whatever ``n`` (measured at 28 and 30 corners), so slices are kept long: the number of
    maps grows about 3.6 times per corner, the slices about 2 times per two corners (about 15 s
    of plantri each at 28 corners, 100 s at 30)."""
    return 1 if workers <= 1 or n < 24 else workers * 2 ** ((n - 22) // 2)


def plan_jobs(min_n: int, max_n: int, res: int | None, mod: int | None, workers: int) -> list[Job]:
    """One job per even corner count, split further for large counts when several workers
    run; with ``res/mod`` given, just that slice of each corner count.  Odd counts have no
    polycube (:func:`polyloops.enumerate.quadrangulations.odd_corners_have_no_polycube`) and
    get no job."""
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
    ok = data.get("version") == SCHEMA_VERSION and (data["n"], data["res"], data["mod"]) == (
        job.n, job.res, job.mod)
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
        job = Job(result["n"], result["res"], result["mod"])
        write_atomic(part_path(out, job), json.dumps(result, separators=(",", ":")))
        done[job] = result
        if progress:
            progress(result)

    tasks = [(job, plantri, method) for job in todo]
    for result in run_jobs(_run_job_star, tasks, workers, dask, ordered=False):
        finish(result)
    return [done[job] for job in jobs]  # type: ignore[misc]


def _run_job_star(args: tuple[Job, str, str]) -> dict[str, Any]:
    return run_job(*args)


# -- merging and storage ---------------------------------------------------------------------

def summarize(results: list[dict[str, Any]], min_n: int, max_n: int, partial: bool) -> dict[str, Any]:
    """The counts of a run by corners, in all three modes, with the numbers of maps seen."""
    counts = {str(n): dict.fromkeys(MODES, 0) for n in range(min_n, max_n + 1)}
    # Odd counts are not generated (no polycube has them): their number of maps is unknown.
    quads: dict[str, int | None] = {str(n): None if n % 2 else 0 for n in range(min_n, max_n + 1)}
    # Every map with an odd number of corners has a self-crossing strip (the theorem of
    # odd_corners_have_no_polycube), so its count of all-simple maps is known: zero.
    simple = {str(n): 0 for n in range(min_n, max_n + 1)}
    for r in results:
        quads[str(r["n"])] = (quads[str(r["n"])] or 0) + r["quadrangulations"]
        simple[str(r["n"])] += r["simple_strips"]
        for mode in MODES:
            counts[str(r["n"])][mode] += len(r["records"][mode])
    # quadrangulations: plantri's simple ones with minimum degree 3; simple_strips: those of
    # them whose strips are all simple closed curves (any degrees).
    out: dict[str, Any] = {"genus": 0, "counts": counts, "quadrangulations": quads,
                           "simple_strips": simple}
    if partial:
        out["partial"] = "only the plantri slice res/mod given on the command line"
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
    records = sorted((rec for r in results for rec in r["records"][symmetry]),
                     key=lambda rec: (rec["corners"], rec["signature"]))
    symmetry = Symmetry.parse(symmetry)
    names = class_names(records, symmetry)
    records = [{"name": name, **rec} for name, rec in zip(names, records, strict=True)]
    lines = [json.dumps({**rec, "symmetry": str(symmetry)}, separators=(",", ":")) for rec in records]
    write_atomic(out / "catalog.jsonl", "\n".join(lines) + ("\n" if lines else ""))
    fd, tmp = tempfile.mkstemp(dir=out, prefix=".catalog.sqlite.", suffix=".tmp")
    os.close(fd)
    try:
        con = sqlite3.connect(tmp)
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
        replace_atomic(tmp, out / "catalog.sqlite")
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
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
                  plantri: str | None = None, method: str = "auto",
                  progress: Callable[[dict[str, Any]], None] | None = None,
                  on_plan: Callable[[list[Job]], None] | None = None) -> CatalogBuild:
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
        Split the work over local processes or a Dask cluster, or do only plantri's slice
        ``res`` of ``mod``; the bytes written do not depend on the split.
    plantri, method:
        Which plantri binary and which strip filter (see
        :func:`polyloops.enumerate.quadrangulations.filtered_batches`).
    progress, on_plan:
        Called with each finished job's result, and once with the list of jobs.

    Returns
    -------
    CatalogBuild

    Raises
    ------
    CatalogRunError
        For arguments that do not fit together or an output that is not a directory.
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
    binary = find_plantri(plantri)
    if out.exists() and not out.is_dir():
        raise CatalogRunError(f"{out}: exists and is not a directory")
    if not out.absolute().parent.is_dir():  # like every other output: the directory above must exist
        raise CatalogRunError(f"{out}: the directory {out.absolute().parent} does not exist")
    jobs = plan_jobs(min_corners, max_corners, res, mod, workers)
    if on_plan:
        on_plan(jobs)
    try:
        results = execute(jobs, out, binary, workers, dask, progress, method=method)
    except (RuntimeError, OSError) as err:
        raise CatalogRunError(f"{out}: {err}") from None
    summary = summarize(results, min_corners, max_corners, partial=mod is not None)
    written = write_catalog(out, results, symmetry, summary)
    return CatalogBuild(out, symmetry, summary, written)
