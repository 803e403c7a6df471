"""The ``plantri`` generator: every simple quadrangulation with minimum degree 3 that plantri
writes, read through the strip filter (:mod:`~polyloops.generate.plantri.quadrangulations`,
compiled in ``_strips.c`` with its numpy twin)."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from polyloops.core.halfedge import HalfEdgeMap
from polyloops.generate.base import Generator, Job, Tally, register


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
        """That the numpy filter stands in for the compiled one, when that does not run."""
        from polyloops.core import compiled

        if self.method == "auto" and not compiled.in_use("strips"):
            return [f"the compiled strip filter {compiled.why_not('strips')}; using the numpy filter, "
                    "which keeps the same maps"]
        return []

    def job_name(self, job: Job) -> str:
        """``n024-0of1``: plantri's slice of one corner count."""
        return f"n{job.n:03d}-{job.res}of{job.mod}"

    def corner_counts(self, job: Job) -> range:
        """A plantri job covers its one corner count."""
        return range(job.n, job.n + 1)

    def plan(self, low: int, high: int, share: tuple[int, int] | None, workers: int) -> list[Job]:
        """One job per even corner count (odd counts have no polycube:
        :func:`polyloops.generate.plantri.quadrangulations.odd_corners_have_no_polycube`), split into
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
        from polyloops.generate.plantri.quadrangulations import find_plantri, resolve_method

        context = PlantriContext(find_plantri(self.binary), resolve_method(self.method))
        return [context] * len(jobs)

    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The maps of the slice that pass the filter; every map read is counted."""
        from polyloops.generate.plantri.quadrangulations import FilteredBatch, candidate_maps

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


register(PlantriGenerator())
