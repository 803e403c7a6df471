"""The ``loops`` generator: arrangements of loops built one loop at a time by a canonical
construction path (:mod:`~polyloops.generate.loops.arrangements`, compiled in
``_arrangements.c``), the top of the tree spilled once a run."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import fields
from pathlib import Path
from typing import Any

from polyloops.core.halfedge import HalfEdgeMap
from polyloops.generate.base import Generator, Job, Tally, register
from polyloops.generate.loops.arrangements import ALL_CUTS, Cuts
from polyloops.generate.spill import SPILL_VERSION


class LoopsGenerator(Generator):
    """Arrangements of loops built one loop at a time by a canonical construction path (the
    compiled search); a job is share ``res/mod`` of the subtrees below the top of the tree,
    covering every corner count at once.  Its option ``cuts`` switches cuts of the search off
    (:class:`~polyloops.generate.loops.arrangements.Cuts`: the same records, more work)."""

    name = "loops"
    visits = "arrangements"
    statistics_key = "search"
    preference = 2  # several times cheaper from 26 corners on
    options = frozenset({"cuts"})

    def __init__(self, cuts: Cuts = ALL_CUTS):
        self.cuts = cuts

    @property
    def variant(self) -> str:
        """``""``, or the cuts switched off (``no-colour``, ``no-meet``)."""
        off = [name for name, on in (("colour", self.cuts.colour), ("meet", self.cuts.meet)) if not on]
        return "-".join(f"no-{name}" for name in off)

    def with_options(self, **options: Any) -> Generator:
        """This generator with other ``cuts`` (a :class:`~polyloops.generate.loops.arrangements.Cuts`)."""
        super().with_options(**options)  # refuses what it does not take
        cuts = options.get("cuts")
        return LoopsGenerator(cuts) if cuts is not None else self

    def unavailable(self) -> str | None:
        """Why the compiled search cannot run (not built, or switched off), or ``None``."""
        from polyloops.core import compiled

        if compiled.in_use("arrangements"):
            return None
        return f"the compiled arrangement search {compiled.why_not('arrangements')}"

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
            tops = {n: loops_frontier(n, workers, dask, self.cuts) for n in bounds}
            return [(share_of(tops[job.n][0], job.res, job.mod), tops[job.n][1] if job.res == 0 else None)
                    for job in jobs]
        files = {n: spill_frontier(n, workers, dask, where, self.cuts) for n in bounds}
        return [(str(files[job.n]), job.res == 0) for job in jobs]

    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The share's candidate arrangements as quad maps; the search's statistics go to
        ``tally`` (share 0 adds the top's)."""
        from polyloops.generate.loops.arrangements import SearchStats, candidate_arrangements

        top, top_search = context if context is not None else (None, None)
        if isinstance(top, str):  # a spilled top: read this share's part
            top, top_search = read_frontier_share(top, job.n, job.res, job.mod, bool(top_search), self.cuts)
        stats = [SearchStats(**top_search)] if top_search else []
        # a given ``top`` is this share's part of the frontier (share_of): all of it is ours
        res, mod = (0, 1) if top is not None else (job.res, job.mod)
        for a in candidate_arrangements(job.n, res, mod, on_stats=stats.append, top=top, cuts=self.cuts):
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


def _expand_chunk(args: tuple[list[Any], int, Cuts]) -> list[Any]:
    from polyloops.generate.loops.arrangements import expand

    return expand(*args)


def loops_frontier(max_n: int, workers: int = 1, dask: str | None = None, cuts: Cuts = ALL_CUTS,
                   roots_to: Any = None) -> tuple[Any, dict[str, int]]:
    """The loops search's frontier for ``max_n`` corners and its statistics, each level spread
    over the workers.  It is not stored (hundreds of thousands of arrangements from 28 corners
    on): a rerun computes it again (5 s at 28 corners) and then skips the shares already done."""
    from polyloops.generate.loops.arrangements import SearchStats, frontier
    from polyloops.parallel import run_jobs

    # summed as they come: a record per node of the top, kept, took gigabytes at 38 corners
    names = [f.name for f in fields(SearchStats)]
    counts = [0] * len(names)

    def add(stats: SearchStats) -> None:
        for i, name in enumerate(names):
            counts[i] += getattr(stats, name)

    def spread(nodes: list[Any], max_corners: int, cuts: Cuts) -> Iterator[Any]:
        size = max(1, -(-len(nodes) // (4 * workers)))
        chunks = [(nodes[i:i + size], max_corners, cuts) for i in range(0, len(nodes), size)]
        for part in run_jobs(_expand_chunk, chunks, workers, dask, ordered=True):
            yield from part  # in order, a chunk at a time (a level's children are not all held)

    top = frontier(max_n, on_stats=add, expander=spread, cuts=cuts, roots_to=roots_to)
    return top, SearchStats(*counts).as_dict()


def frontier_tag(max_n: int, cuts: Cuts = ALL_CUTS) -> Any:
    """What a spilled top must be to serve a loops run to ``max_n`` corners: this search, its
    schema and cuts, and the bound."""
    from polyloops.generate.spill import SpillTag

    return SpillTag("loops-top", {"schema": SPILL_VERSION, "colour_cut": cuts.colour, "meet_cut": cuts.meet},
                    max_n)


def _node_bytes(kind: bytes, node: Any) -> bytes:
    return kind + bytes([node.candidate]) + node.code


def spill_frontier(max_n: int, workers: int, dask: str | None, where: Path, cuts: Cuts = ALL_CUTS) -> Path:
    """The top of the loops search for ``max_n`` corners in ``where/loops-top-N.bin``
    (:mod:`polyloops.generate.spill`; meta: the split level and the top's statistics; one
    record a node: ``R`` a root or ``S`` a shallow candidate, a byte whether it is a
    candidate, the code).  Kept when the file there is proved to be this run's, computed and
    written atomically otherwise.

    Raises
    ------
    SpillRefused
        When the name is a link or not a regular file.
    """
    from polyloops.generate.spill import SpillMismatch, iter_spill, spilling

    path = where / f"loops-top-{max_n}.bin"
    tag = frontier_tag(max_n, cuts)
    try:
        iter_spill(path, tag)  # proved (header, size, digest) before it is used
        return path
    except SpillMismatch:
        pass  # another run's, damaged, or absent: computed again
    # The roots go to the file as they are made, never all in memory (at 38 corners the top
    # held in memory peaked at 6.6 GB); the candidates above them follow, then the header.
    with spilling(path, tag) as out:
        top, top_search = loops_frontier(max_n, workers, dask, cuts,
                                         roots_to=lambda kids: out.extend(_node_bytes(b"R", k) for k in kids))
        out.extend(_node_bytes(b"S", node) for node in top.shallow)
        out.meta = {"loops": top.loops, "search": top_search}
    return path


def read_frontier_share(path: str, max_n: int, res: int, mod: int,
                        with_search: bool, cuts: Cuts = ALL_CUTS) -> tuple[Any, dict[str, int] | None]:
    """Share ``res`` of ``mod`` of a spilled top (:func:`spill_frontier`) for ``max_n``
    corners: its roots (rank ``res`` modulo ``mod``), the shallow candidates for share 0, and
    the top's statistics when ``with_search``; only this share's nodes are kept in memory.

    Raises
    ------
    SpillMismatch
        When the file is not the top of a run to ``max_n`` corners (or was changed).
    """
    from polyloops.generate.loops.arrangements import Arrangement, Frontier
    from polyloops.generate.spill import SpillMismatch, iter_spill

    meta, records = iter_spill(Path(path), frontier_tag(max_n, cuts))
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
    from polyloops.generate.loops.arrangements import Frontier

    return Frontier(top.loops, top.roots[res::mod], top.shallow if res == 0 else ())


register(LoopsGenerator())
