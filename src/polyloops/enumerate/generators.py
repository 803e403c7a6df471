"""Where a catalog's candidate maps come from: one small interface, and its generators.

A :class:`Generator` cuts a catalog run into :class:`Job`\\ s (its shares), prepares what its
jobs share (plantri's binary, the top of the loops search), and lists each job's candidate
maps, counting what it visited in a :class:`Tally`.  The pipeline
(:mod:`polyloops.enumerate.catalog_run`) classifies the maps, keeps each finished job as a
typed :class:`JobResult` in ``DIR/parts/``, and merges the results; nothing in it knows which
generator ran.  A new generator (genus 1, a pruned search) implements the interface and is
added with :func:`register`.

- ``plantri``: every quadrangulation plantri writes, filtered
  (:mod:`polyloops.enumerate.quadrangulations`); jobs are plantri's slices ``n res/mod``, one
  corner count each, and it counts the maps it reads;
- ``loops``: arrangements of loops built one loop at a time
  (:mod:`polyloops.enumerate.arrangements`); each job is a share of one search over every
  corner count, and it counts the arrangements it builds;
- ``torus``: the genus-1 candidate maps, in two stages (:mod:`polyloops.enumerate.torus`);
  each job is a share of the two-axis arrangements the second stage starts from.

>>> sorted(GENERATORS)
['loops', 'plantri', 'torus']
>>> GENERATORS["torus"].genus
1
>>> [job.name for job in GENERATORS["plantri"].plan(8, 12, None, 1)]
['n012-0of1', 'n010-0of1', 'n008-0of1']
"""

from __future__ import annotations

import time
from abc import ABC, abstractmethod
from collections import Counter
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.symmetry import Symmetry
from polyloops.enumerate.catalog import MODES, map_classes
from polyloops.enumerate.records import CatalogRecord

__all__ = ["GENERATORS", "CornerResult", "Generator", "Job", "JobResult", "LoopsGenerator",
           "PlantriGenerator", "Tally", "TorusGenerator", "register", "run_job"]

# Version 6: per corner count, the maps by the number of classes they carry.  Parts of older
# versions are recomputed.
SCHEMA_VERSION = 6


@dataclass(frozen=True)
class Job:
    """One share of a catalog run: the candidate maps of generator ``generator`` with ``low``
    to ``n`` corners in share ``res`` of ``mod``."""

    generator: str
    n: int
    low: int
    res: int = 0
    mod: int = 1

    @property
    def name(self) -> str:
        """The job's file name stem in ``DIR/parts`` (the generator's :meth:`Generator.job_name`)."""
        return GENERATORS[self.generator].job_name(self)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the job."""
        return {"generator": self.generator, "n": self.n, "low": self.low, "res": self.res, "mod": self.mod}

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Job:
        """The job a stored result answers; raises ``KeyError`` or ``TypeError`` otherwise."""
        return cls(str(data["generator"]), int(data["n"]), int(data["low"]), int(data["res"]),
                   int(data["mod"]))


@dataclass
class Tally:
    """What a job's generator visited: ``maps[n]`` and ``simple_strips[n]`` per corner count
    (for generators that count maps they read), and ``statistics`` of its own (summed over
    jobs, such as the loops search's), and ``visited``, the objects its progress counts."""

    maps: dict[int, int] = field(default_factory=dict)
    simple_strips: dict[int, int] = field(default_factory=dict)
    statistics: dict[str, int] = field(default_factory=dict)
    visited: int = 0


@dataclass(frozen=True)
class CornerResult:
    """One corner count of a job: its candidate maps, its classes in every mode, the maps the
    generator read there (``None`` when it does not count them), and ``carrying[k]``, how many
    of its candidate maps carry exactly ``k >= 1`` polycube classes up to all symmetries."""

    candidates: int
    records: dict[str, tuple[CatalogRecord, ...]]
    maps: int | None = None
    simple_strips: int | None = None
    carrying: dict[int, int] = field(default_factory=dict)


@dataclass(frozen=True)
class JobResult:
    """A finished job: its results by corner count, what its generator visited, its time."""

    job: Job
    corners: dict[int, CornerResult]
    statistics: dict[str, int]
    visited: int
    seconds: float

    def to_json(self) -> dict[str, Any]:
        """The part file's content."""
        return {"version": SCHEMA_VERSION, **self.job.to_json(), "visited": self.visited,
                "statistics": self.statistics, "seconds": self.seconds,
                "corners": {str(n): {"candidates": c.candidates, "maps": c.maps,
                                     "simple_strips": c.simple_strips,
                                     "carrying": {str(k): v for k, v in c.carrying.items()},
                                     "records": {str(m): [r.to_json() for r in recs]
                                                 for m, recs in c.records.items()}}
                            for n, c in self.corners.items()}}

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> JobResult:
        """A stored part; raises ``KeyError``, ``TypeError`` or ``ValueError`` when it is not
        one of this schema."""
        if data.get("version") != SCHEMA_VERSION:
            raise ValueError("a part of another schema version")
        corners = {int(n): CornerResult(int(c["candidates"]),
                                        {m: tuple(CatalogRecord.from_json(r) for r in recs)
                                         for m, recs in c["records"].items()},
                                        c["maps"], c["simple_strips"],
                                        {int(k): int(v) for k, v in c["carrying"].items()})
                   for n, c in data["corners"].items()}
        return cls(Job.from_json(data), corners, {k: int(v) for k, v in data["statistics"].items()},
                   int(data["visited"]), float(data["seconds"]))


class Generator(ABC):
    """A source of candidate maps for the catalog (see the module docstring).

    Subclasses set ``name`` and ``visits`` (what :attr:`Tally.visited` counts, for progress),
    and implement :meth:`plan` and :meth:`candidates`; :meth:`prepare` computes what the jobs
    of one run share, and :meth:`unavailable` says why the generator cannot run here."""

    name: str = ""
    genus: int = 0  # the genus of the maps it makes
    visits: str = "maps"
    statistics_key: str | None = None  # summary.json's key for the summed statistics
    options: frozenset[str] = frozenset()  # what with_options takes
    preference: int = 0  # the default generator is the most preferred that can run

    def unavailable(self) -> str | None:
        """Why this generator cannot run here (a part not built), or ``None``."""
        return None

    def notes(self) -> list[str]:
        """What a user should know about how this generator will run here (a slower fallback)."""
        return []

    def with_options(self, **options: Any) -> Generator:
        """This generator with the build's options (``plantri``: a binary, ``method``: the
        strip filter); one that takes none refuses any that is set.

        Raises
        ------
        ValueError
            For an option this generator does not take.
        """
        given = [k for k, v in options.items() if v not in (None, "auto") and k not in self.options]
        if given:
            raise ValueError(f"the {self.name} generator takes no option {', '.join(given)}")
        return self

    @abstractmethod
    def plan(self, low: int, high: int, share: tuple[int, int] | None, workers: int) -> list[Job]:
        """The jobs covering ``low`` to ``high`` corners: just share ``(res, mod)`` when given,
        else cut for ``workers`` local processes."""

    def job_name(self, job: Job) -> str:
        """A job's file name stem in ``DIR/parts``."""
        return f"{self.name}-{job.low}to{job.n}-{job.res}of{job.mod}"

    def corner_counts(self, job: Job) -> range:
        """The corner counts a job reports (each gets a :class:`CornerResult`)."""
        return range(job.low, job.n + 1)

    def prepare(self, jobs: Sequence[Job], workers: int = 1, dask: str | None = None,
                where: Path | None = None) -> list[Any]:
        """What each job needs besides itself (picklable), computed once for the run;
        ``where`` is a directory for what is too large to send (the run's ``parts/``)."""
        return [None] * len(jobs)

    @abstractmethod
    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The job's candidate maps (each once up to isomorphism, mirror images identified);
        ``tally`` records what was visited."""


GENERATORS: dict[str, Generator] = {}


def register(generator: Generator) -> Generator:
    """Make ``generator`` available to :func:`~polyloops.enumerate.catalog_run.build_catalog`
    by its name (a later one of the same name replaces it)."""
    GENERATORS[generator.name] = generator
    return generator


def run_job(task: tuple[Generator, Job, Any]) -> JobResult:
    """Classify one job's candidate maps (:func:`~polyloops.enumerate.catalog.map_classes`)."""
    generator, job, context = task
    start = time.perf_counter()
    tally = Tally()
    counts = dict.fromkeys(generator.corner_counts(job), 0)
    records: dict[int, dict[str, list[CatalogRecord]]] = {n: {str(m): [] for m in MODES} for n in counts}
    carrying: dict[int, Counter[int]] = {n: Counter() for n in counts}
    for m in generator.candidates(job, context, tally):
        if m.num_corners in counts:
            counts[m.num_corners] += 1
            classes = map_classes(m)
            for mode, recs in classes.items():
                records[m.num_corners][str(mode)].extend(recs)
            if classes[Symmetry.FULL]:
                carrying[m.num_corners][len(classes[Symmetry.FULL])] += 1
    corners = {n: CornerResult(count, {m: tuple(r) for m, r in records[n].items()},
                               tally.maps.get(n), tally.simple_strips.get(n),
                               dict(sorted(carrying[n].items())))
               for n, count in counts.items()}
    return JobResult(job, corners, dict(tally.statistics), tally.visited, time.perf_counter() - start)


# -- plantri's quadrangulations, filtered -----------------------------------------------------------

@dataclass(frozen=True)
class PlantriContext:
    """What every plantri job of a run shares: the binary, and the strip filter resolved."""

    binary: str
    method: str


class PlantriGenerator(Generator):
    """Every simple quadrangulation with minimum degree 3 plantri writes, read through the strip
    filter; a job is plantri's slice ``-qc2 n res/mod`` of one even corner count."""

    name = "plantri"
    visits = "maps"
    options = frozenset({"plantri", "method"})
    preference = 1  # the reference, and the fallback without a compiler

    def __init__(self, binary: str | None = None, method: str = "auto"):
        self.binary, self.method = binary, method

    def with_options(self, **options: Any) -> Generator:
        """This generator with another plantri binary (``plantri``) or strip-filter ``method``."""
        extra = set(options) - {"plantri", "method"}
        if extra:
            raise ValueError(f"the plantri generator takes no option {', '.join(sorted(extra))}")
        return PlantriGenerator(options.get("plantri"), options.get("method") or "auto")

    def notes(self) -> list[str]:
        """That the numpy filter stands in for the compiled one, when that was not built."""
        from polyloops.enumerate.quadrangulations import compiled_filter_available

        if self.method == "auto" and not compiled_filter_available():
            return ["the compiled strip filter was not built (a C compiler is needed at install time); "
                    "using the numpy filter, which keeps the same maps"]
        return []

    def job_name(self, job: Job) -> str:
        """``n024-0of1``: plantri's slice of one corner count."""
        return f"n{job.n:03d}-{job.res}of{job.mod}"

    def corner_counts(self, job: Job) -> range:
        """A plantri job covers its one corner count."""
        return range(job.n, job.n + 1)

    def plan(self, low: int, high: int, share: tuple[int, int] | None, workers: int) -> list[Job]:
        """One job per even corner count (odd counts have no polycube:
        :func:`polyloops.enumerate.quadrangulations.odd_corners_have_no_polycube`), split into
        :func:`slices` for several workers, largest first so that workers finish together."""
        jobs = []
        for n in range(low, high + 1):
            if n % 2:
                continue
            if share is not None:
                jobs.append(Job(self.name, n, n, *share))
            else:
                parts = slices(n, workers)
                jobs.extend(Job(self.name, n, n, r, parts) for r in range(parts))
        return sorted(jobs, key=lambda j: (-j.n, j.res))

    def prepare(self, jobs: Sequence[Job], workers: int = 1, dask: str | None = None,
                where: Path | None = None) -> list[Any]:
        """The binary and the filter, found once (a missing one fails before any work)."""
        from polyloops.enumerate.quadrangulations import find_plantri, resolve_method

        context = PlantriContext(find_plantri(self.binary), resolve_method(self.method))
        return [context] * len(jobs)

    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The maps of the slice that pass the filter; every map read is counted."""
        from polyloops.enumerate.quadrangulations import FilteredBatch, candidate_maps

        tally.maps[job.n] = tally.simple_strips[job.n] = 0

        def seen(batch: FilteredBatch) -> None:
            tally.maps[job.n] += batch.maps
            tally.simple_strips[job.n] += batch.simple_strips
            tally.visited += batch.maps

        yield from candidate_maps(job.n, context.binary, job.res, job.mod, on_batch=seen,
                                  method=context.method)


def slices(n: int, workers: int) -> int:
    """How many plantri slices a corner count is split into.  Each slice of ``plantri -qc2 n
    res/mod`` first regenerates the part of plantri's search tree above its split level, about
    1.5 s whatever ``n`` (measured at 28 and 30 corners), so slices are kept long: the number of
    maps grows about 3.6 times per corner, the slices about 2 times per two corners (about 15 s
    of plantri each at 28 corners, 100 s at 30)."""
    return 1 if workers <= 1 or n < 24 else workers * 2 ** ((n - 22) // 2)


# -- arrangements of loops -----------------------------------------------------------------------

class LoopsGenerator(Generator):
    """Arrangements of loops built one loop at a time by a canonical construction path (the
    compiled search); a job is share ``res/mod`` of the subtrees below the top of the tree,
    covering every corner count at once."""

    name = "loops"
    visits = "arrangements"
    statistics_key = "search"
    preference = 2  # several times cheaper from 26 corners on

    def unavailable(self) -> str | None:
        """Why the compiled search cannot run (it was not built), or ``None``."""
        from polyloops.enumerate.arrangements import compiled_generator_available

        if compiled_generator_available():
            return None
        return ("the compiled arrangement search was not built (a C compiler and the Python headers "
                "are needed at install time)")

    def plan(self, low: int, high: int, share: tuple[int, int] | None, workers: int) -> list[Job]:
        """One search over every corner count, cut into :func:`loops_slices` shares."""
        if share is not None:
            return [Job(self.name, high, low, *share)]
        parts = loops_slices(high, workers)
        return [Job(self.name, high, low, r, parts) for r in range(parts)]

    def prepare(self, jobs: Sequence[Job], workers: int = 1, dask: str | None = None,
                where: Path | None = None) -> list[Any]:
        """The top of the search, computed once for each bound (spread over the workers) and
        spilled to ``where`` (a run's ``parts/``; a temporary directory otherwise), so that no
        process holds all of it while the shares run: each job reads its own roots from the
        file.  A rerun reads the file instead of computing the top again."""
        bounds = {job.n for job in jobs}
        if where is None:  # kept in memory, each job sent its share
            tops = {n: loops_frontier(n, workers, dask) for n in bounds}
            return [(share_of(tops[job.n][0], job.res, job.mod), tops[job.n][1] if job.res == 0 else None)
                    for job in jobs]
        files = {n: spill_frontier(n, workers, dask, where) for n in bounds}
        return [(str(files[job.n]), job.res == 0) for job in jobs]

    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The share's candidate arrangements as quad maps; the search's statistics go to
        ``tally`` (share 0 adds the top's)."""
        from polyloops.enumerate.arrangements import SearchStats, candidate_arrangements

        top, top_search = context if context is not None else (None, None)
        if isinstance(top, str):  # a spilled top: read this share's part
            top, top_search = read_frontier_share(top, job.n, job.res, job.mod, bool(top_search))
        stats = [SearchStats(**top_search)] if top_search else []
        # a given ``top`` is this share's part of the frontier (share_of): all of it is ours
        res, mod = (0, 1) if top is not None else (job.res, job.mod)
        for a in candidate_arrangements(job.n, res, mod, on_stats=stats.append, top=top):
            if a.corners >= job.low:
                yield a.quad_mesh()
        total = sum(stats, SearchStats()).as_dict()
        tally.statistics.update(total)
        tally.visited += total["arrangements"]


def loops_slices(max_n: int, workers: int) -> int:
    """How many shares a loops run is cut into.  The frontier is computed once a run, and
    finished shares are what a rerun keeps, so eight a worker from 26 corners on (a share
    then takes about 10 s of CPU at 28 corners, 70 s at 30)."""
    return 1 if workers <= 1 and max_n < 26 else max(workers, 1) * (8 if max_n >= 26 else 1)


def _expand_chunk(args: tuple[list[Any], int]) -> list[Any]:
    from polyloops.enumerate.arrangements import expand

    return expand(*args)


def loops_frontier(max_n: int, workers: int = 1, dask: str | None = None) -> tuple[Any, dict[str, int]]:
    """The loops search's frontier for ``max_n`` corners and its statistics, each level spread
    over the workers.  It is not stored (hundreds of thousands of arrangements from 28 corners
    on): a rerun computes it again (5 s at 28 corners) and then skips the shares already done."""
    from polyloops.enumerate.arrangements import SearchStats, frontier
    from polyloops.enumerate.parallel import run_jobs

    stats: list[SearchStats] = []

    def spread(nodes: list[Any], max_corners: int) -> list[Any]:
        size = max(1, -(-len(nodes) // (4 * workers)))
        chunks = [(nodes[i:i + size], max_corners) for i in range(0, len(nodes), size)]
        parts = run_jobs(_expand_chunk, chunks, workers, dask, ordered=True)
        return [pair for part in parts for pair in part]

    top = frontier(max_n, on_stats=stats.append, expander=spread)
    return top, sum(stats, SearchStats()).as_dict()


def frontier_tag(max_n: int) -> Any:
    """What a spilled top must be to serve a loops run to ``max_n`` corners: this search, its
    schema and cuts, and the bound."""
    import polyloops.enumerate.arrangements as arrangements
    from polyloops.enumerate.spill import SpillTag

    return SpillTag("loops-top", {"schema": SCHEMA_VERSION, "colour_cut": arrangements.COLOUR_CUT,
                                  "meet_cut": arrangements.MEET_CUT}, max_n)


def _node_bytes(kind: bytes, node: Any) -> bytes:
    return kind + bytes([node.candidate]) + node.code


def spill_frontier(max_n: int, workers: int, dask: str | None, where: Path) -> Path:
    """The top of the loops search for ``max_n`` corners in ``where/loops-top-N.bin``
    (:mod:`polyloops.enumerate.spill`; meta: the split level and the top's statistics; one
    record a node: ``R`` a root or ``S`` a shallow candidate, a byte whether it is a
    candidate, the code).  Kept when the file there is proved to be this run's, computed and
    written atomically otherwise.

    Raises
    ------
    SpillRefused
        When the name is a link or not a regular file.
    """
    from polyloops.enumerate.spill import SpillMismatch, iter_spill, write_spill

    path = where / f"loops-top-{max_n}.bin"
    tag = frontier_tag(max_n)
    try:
        iter_spill(path, tag)  # proved (header, size, digest) before it is used
        return path
    except SpillMismatch:
        pass  # another run's, damaged, or absent: computed again
    top, top_search = loops_frontier(max_n, workers, dask)
    nodes = [_node_bytes(b"R", node) for node in top.roots]
    nodes += [_node_bytes(b"S", node) for node in top.shallow]
    write_spill(path, tag, nodes, {"loops": top.loops, "search": top_search})
    del top, nodes  # the workers read their shares from the file
    return path


def read_frontier_share(path: str, max_n: int, res: int, mod: int,
                        with_search: bool) -> tuple[Any, dict[str, int] | None]:
    """Share ``res`` of ``mod`` of a spilled top (:func:`spill_frontier`) for ``max_n``
    corners: its roots (rank ``res`` modulo ``mod``), the shallow candidates for share 0, and
    the top's statistics when ``with_search``; only this share's nodes are kept in memory.

    Raises
    ------
    SpillMismatch
        When the file is not the top of a run to ``max_n`` corners (or was changed).
    """
    from polyloops.enumerate.arrangements import Arrangement, Frontier
    from polyloops.enumerate.spill import SpillMismatch, iter_spill

    meta, records = iter_spill(Path(path), frontier_tag(max_n))
    roots, shallow = [], []
    rank = 0
    for rec in records:
        kind, node = rec[:1], Arrangement(rec[2:], bool(rec[1]))
        if kind == b"R":
            if rank % mod == res:
                roots.append(node)
            rank += 1
        elif kind == b"S":
            if res == 0:
                shallow.append(node)
        else:
            raise SpillMismatch(f"{path}: a node of unknown kind")
    if type(meta.get("loops")) is not int or not isinstance(meta.get("search"), dict):
        raise SpillMismatch(f"{path}: no statistics of the top")
    return Frontier(meta["loops"], tuple(roots), tuple(shallow)), meta["search"] if with_search else None


def share_of(top: Any, res: int, mod: int) -> Any:
    """The part of a frontier one share needs: its roots (rank ``res`` modulo ``mod``), and the
    candidates above the frontier for share 0."""
    from polyloops.enumerate.arrangements import Frontier

    return Frontier(top.loops, top.roots[res::mod], top.shallow if res == 0 else ())


# -- the torus ------------------------------------------------------------------------------------

class TorusGenerator(Generator):
    """The maps of genus 1 that carry a polycube
    (:func:`polyloops.enumerate.torus.candidate_torus_arrangements`): a job is share ``res/mod``
    of the two-axis arrangements of the second stage, covering
    every corner count at once; it counts the states it builds (the first stage's, and the
    regions the second cuts)."""

    name = "torus"
    genus = 1
    visits = "arrangements"
    statistics_key = "search"

    def notes(self) -> list[str]:
        """That the Python search stands in for the compiled one, when that was not built (the
        same note the genus-0 generators give)."""
        from polyloops.enumerate.torus import compiled_search_available

        if not compiled_search_available():
            return ["the compiled torus search was not built (a C compiler and the Python headers are "
                    "needed at install time); using the Python search, which finds the same classes "
                    "several times slower"]
        return []

    def plan(self, low: int, high: int, share: tuple[int, int] | None, workers: int) -> list[Job]:
        """One search over every corner count, cut into 16 shares (more with more than 16
        workers): a finished share is kept, so a stopped run loses at most the shares under way
        and resumes with any number of workers up to 16; each worker process lists the two-axis
        arrangements once for all its shares."""
        if share is not None:
            return [Job(self.name, high, low, *share)]
        mod = 16 * -(-max(workers, 1) // 16)
        return [Job(self.name, high, low, r, mod) for r in range(mod)]

    def prepare(self, jobs: Sequence[Job], workers: int = 1, dask: str | None = None,
                where: Path | None = None) -> list[Any]:
        """The first stage, listed once for the run and spilled to ``where`` (a run's
        ``parts/``), so that the workers read it instead of each listing it again (through
        13 crossings that takes minutes and gigabytes at its peak); a rerun reads the file."""
        if where is None:
            return [None] * len(jobs)
        files = {job.n // 3: str(spill_bases(job.n // 3, where)) for job in jobs}
        return [files[job.n // 3] for job in jobs]

    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The share's candidate maps; the search's statistics go to ``tally``."""
        from polyloops.enumerate.torus import TorusSearchStats, candidate_torus_arrangements

        stats: list[TorusSearchStats] = []
        bases = read_bases(context, job.n // 3) if context is not None else None
        for a in candidate_torus_arrangements(job.n, job.res, job.mod, on_stats=stats.append, bases=bases):
            if a.crossings >= job.low:
                yield a.quad_mesh()
        total = vars(stats[0]) if stats else {}
        tally.statistics.update(total)
        tally.visited += total.get("states", 0) + total.get("region_choices", 0)


def bases_tag(max_crossings: int) -> Any:
    """What a spilled first stage must be to serve a torus run to ``max_crossings``."""
    from polyloops.enumerate.spill import SpillTag

    return SpillTag("torus-bases", {"schema": SCHEMA_VERSION}, max_crossings)


def spill_bases(max_crossings: int, where: Path) -> Path:
    """The first stage of the torus search (:func:`polyloops.enumerate.torus.first_stage`) in
    ``where/torus-bases-K.bin`` (:mod:`polyloops.enumerate.spill`; meta: the statistics; one
    record an arrangement's ``twin`` array).  Kept when the file there is proved to be this
    run's, computed and written atomically otherwise.

    Raises
    ------
    SpillRefused
        When the name is a link or not a regular file.
    """
    from polyloops.enumerate import torus
    from polyloops.enumerate.spill import SpillMismatch, write_spill

    path = where / f"torus-bases-{max_crossings}.bin"
    try:
        read_bases(str(path), max_crossings)
        return path
    except SpillMismatch:
        pass  # another run's, damaged, or absent: listed again
    bases, stats = torus.first_stage(max_crossings)
    write_spill(path, bases_tag(max_crossings), bases, {"search": vars(stats)})
    torus._bases.cache_clear()  # the workers read the file
    read_bases.cache_clear()
    return path


@lru_cache(maxsize=2)
def read_bases(path: str, max_crossings: int) -> tuple[tuple[bytes, ...], Any]:
    """The arrangements and statistics :func:`spill_bases` wrote for ``max_crossings`` (kept
    for the process's later shares).

    Raises
    ------
    SpillMismatch
        When the file is not the first stage of a run to ``max_crossings`` (or was changed).
    """
    from polyloops.enumerate.spill import SpillMismatch, read_spill
    from polyloops.enumerate.torus import TorusSearchStats

    spill = read_spill(Path(path), bases_tag(max_crossings))
    try:
        stats = TorusSearchStats(**spill.meta["search"])
    except (KeyError, TypeError) as exc:  # TypeError: other statistics
        raise SpillMismatch(f"{path}: no statistics of this search ({exc})") from None
    if any(len(raw) % 2 or len(raw) > 0xFFFF for raw in spill.records):
        raise SpillMismatch(f"{path}: an arrangement of the wrong size")
    return spill.records, stats


register(PlantriGenerator())
register(LoopsGenerator())
register(TorusGenerator())
