"""The ``torus`` generator (genus 1): the two-axis arrangements of the first stage, listed once a
run and spilled, then the third axis region by region, compiled in ``_torus.c`` and
``_regions.c``.  The search's modules, each on the ones above it:

- :mod:`~polyloops.generate.torus.arrangement`: arrangements on the torus as marked maps, their
  canonical codes, the second stage's layer;
- :mod:`~polyloops.generate.torus.cuts`: what a state still needs, the tests every polycube
  passes, and the bound on the first stage (:func:`~polyloops.generate.torus.cuts.base_bound`);
- :mod:`~polyloops.generate.torus.drawing`: drawing a new curve on a state;
- :mod:`~polyloops.generate.torus.stages`: the search one loop at a time (both stages);
- :mod:`~polyloops.generate.torus.regions`: the second stage region by region;
- :mod:`~polyloops.generate.torus.decompositions`: a map's decompositions, its canonical one;
- :mod:`~polyloops.generate.torus.candidates`: the maps that carry a polycube, both stages
  together.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any

from polyloops.core.halfedge import HalfEdgeMap
from polyloops.generate.base import Generator, Job, Tally, register
from polyloops.generate.spill import SPILL_VERSION
from polyloops.generate.torus.cuts import base_bound


class TorusGenerator(Generator):
    """The maps of genus 1 that carry a polycube
    (:func:`polyloops.generate.torus.candidates.candidate_torus_arrangements`): a job is share
    ``res/mod`` of the two-axis arrangements of the second stage, covering every corner count at
    once; it counts the states it builds (the first stage's, and the regions the second cuts).
    Its option ``stage`` chooses the second stage
    (:class:`~polyloops.generate.torus.candidates.SecondStage`; the same records)."""

    name = "torus"
    genus = 1
    visits = "arrangements"
    statistics_key = "search"
    options = frozenset({"stage"})

    def __init__(self, stage: str = "regions"):
        self.stage = stage

    @property
    def variant(self) -> str:
        """``""``, or ``stage-loops`` for the loop-by-loop second stage."""
        return "" if self.stage == "regions" else f"stage-{self.stage}"

    def with_options(self, **options: Any) -> Generator:
        """This generator with another second ``stage`` (``"regions"`` or ``"loops"``)."""
        from polyloops.generate.torus.candidates import SecondStage

        super().with_options(**options)  # refuses what it does not take
        stage = options.get("stage")
        if stage is None:
            return self
        try:
            return type(self)(SecondStage(stage).value)
        except ValueError:
            raise ValueError(f"the {self.name} generator's stage is regions or loops, "
                             f"not {stage!r}") from None

    def notes(self) -> list[str]:
        """That the Python search stands in for the compiled one, when that does not run (the
        same note the genus-0 generators give)."""
        from polyloops.core import compiled

        if not compiled.in_use("torus"):
            return [f"the compiled torus search {compiled.why_not('torus')}; using the Python search, "
                    "which finds the same classes several times slower"]
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
        bounds = {job.n: base_bound(self.crossings(job.n)) for job in jobs}
        files = {c: str(spill_bases(c, where, self.genus)) for c in set(bounds.values())}
        return [files[bounds[job.n]] for job in jobs]

    def crossings(self, corners: int) -> int:
        """The crossings of a map of this genus with ``corners`` corners (quads: V - F = 2 - 2g)."""
        return corners + 2 * (self.genus - 1)

    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The share's candidate maps; the search's statistics go to ``tally``."""
        from polyloops.generate.torus.candidates import SecondStage, candidate_torus_arrangements
        from polyloops.generate.torus.stages import TorusSearchStats

        stats: list[TorusSearchStats] = []
        top = self.crossings(job.n)
        bases = read_bases(context, base_bound(top), self.genus) if context is not None else None
        for a in candidate_torus_arrangements(top, job.res, job.mod, on_stats=stats.append, bases=bases,
                                              stage=SecondStage(self.stage), genus=self.genus):
            if a.crossings >= self.crossings(job.low):
                yield a.quad_mesh()
        total = vars(stats[0]) if stats else {}
        tally.statistics.update(total)
        tally.visited += total.get("states", 0) + total.get("region_choices", 0)


def _bases_name(genus: int) -> str:
    return "torus-bases" if genus == 1 else f"genus{genus}-bases"


def bases_tag(max_crossings: int, genus: int = 1) -> Any:
    """What a spilled first stage must be to serve a run of ``genus`` to ``max_crossings``."""
    from polyloops.generate.spill import SpillTag

    # "listing": the first stage as square-tiled surfaces (the same B as the marked search that
    # listed the files before it, in another order and with other statistics: listed again)
    return SpillTag(_bases_name(genus), {"schema": SPILL_VERSION, "listing": "squares"}, max_crossings)


def spill_bases(max_crossings: int, where: Path, genus: int = 1) -> Path:
    """The first stage of the search (:func:`polyloops.generate.torus.stages.first_stage`) in
    ``where/torus-bases-K.bin`` (``genusG-bases-K.bin`` at genus ``G`` >= 2;
    :mod:`polyloops.generate.spill`; meta: the statistics; one
    record an arrangement's ``twin`` array).  Kept when the file there is proved to be this
    run's, computed and written atomically otherwise.

    Raises
    ------
    SpillRefused
        When the name is a link or not a regular file.
    """
    from polyloops.generate.spill import SpillMismatch, write_spill
    from polyloops.generate.torus.stages import first_stage, forget_first_stage

    path = where / f"{_bases_name(genus)}-{max_crossings}.bin"
    try:
        read_bases(str(path), max_crossings, genus)
        return path
    except SpillMismatch:
        pass  # another run's, damaged, or absent: listed again
    bases, stats = first_stage(max_crossings, genus)
    write_spill(path, bases_tag(max_crossings, genus), bases, {"search": vars(stats)})
    forget_first_stage()  # the workers read the file
    read_bases.cache_clear()
    return path


@lru_cache(maxsize=2)
def read_bases(path: str, max_crossings: int, genus: int = 1) -> tuple[tuple[bytes, ...], Any]:
    """The arrangements and statistics :func:`spill_bases` wrote for ``max_crossings`` on the
    surface of ``genus`` (kept for the process's later shares).

    Raises
    ------
    SpillMismatch
        When the file is not the first stage of a run to ``max_crossings`` (or was changed).
    """
    from polyloops.generate.spill import SpillMismatch, read_spill
    from polyloops.generate.torus.stages import TorusSearchStats

    spill = read_spill(Path(path), bases_tag(max_crossings, genus))
    try:
        stats = TorusSearchStats(**spill.meta["search"])
    except (KeyError, TypeError) as exc:  # TypeError: other statistics
        raise SpillMismatch(f"{path}: no statistics of this search ({exc})") from None
    if any(len(raw) % 2 or len(raw) > 0xFFFF for raw in spill.records):
        raise SpillMismatch(f"{path}: an arrangement of the wrong size")
    return spill.records, stats


register(TorusGenerator())
