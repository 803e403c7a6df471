"""The ``torus`` generator (genus 1): the two-axis arrangements of the first stage, each share
listing its own, then the third axis region by region, compiled in ``_squares.c``,
``_torus.c`` and ``_regions.c``.  The search's modules, each on the ones above it:

- :mod:`~polyloops.generate.torus.arrangement`: arrangements on the torus as marked maps, their
  canonical codes, the second stage's layer;
- :mod:`~polyloops.generate.torus.cuts`: what a state still needs, the tests every polycube
  passes, and the bound on the first stage (:func:`~polyloops.generate.torus.cuts.base_bound`);
- :mod:`~polyloops.generate.torus.drawing`: drawing a new curve on a state;
- :mod:`~polyloops.generate.torus.squares`: the first stage's ``B`` as square-tiled surfaces;
- :mod:`~polyloops.generate.torus.stages`: the search one loop at a time (both stages);
- :mod:`~polyloops.generate.torus.regions`: the second stage region by region;
- :mod:`~polyloops.generate.torus.decompositions`: a map's decompositions, its canonical one;
- :mod:`~polyloops.generate.torus.candidates`: the maps that carry a polycube, both stages
  together.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from polyloops.core.halfedge import HalfEdgeMap
from polyloops.generate.base import Generator, Job, Tally, register


class TorusGenerator(Generator):
    """The maps of genus 1 that carry a polycube
    (:func:`polyloops.generate.torus.candidates.candidate_torus_arrangements`): a job is share
    ``res/mod`` of the two-axis arrangements of the second stage (the listing's subtrees dealt
    round, :func:`~polyloops.generate.torus.stages.share_of_first_stage`), covering every corner
    count at once; it counts the states it builds (the first stage's, and the regions the second cuts).
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
        """One search over every corner count, cut into :meth:`shares` shares: a finished share
        is kept, so a stopped run loses at most the shares under way and resumes with any number
        of workers; each share lists its own two-axis arrangements."""
        if share is not None:
            return [Job(self.name, high, low, *share)]
        mod = self.shares(high, workers)
        return [Job(self.name, high, low, r, mod) for r in range(mod)]

    def shares(self, corners: int, workers: int = 1) -> int:
        """How many shares a search through ``corners`` is cut into: 16 while the map has at
        most 44 crossings, then 4 times as many every two crossings, as the second stage grows
        about that fast, so that a share stays minutes of CPU (genus 2 through 47 corners: 1,024
        shares of about 2.5 minutes); at least one a worker, in sixteens.

        >>> from polyloops.generate.base import generators
        >>> [generators()["handles"].shares(n) for n in (42, 44, 46, 47)]
        [16, 64, 256, 1024]
        >>> generators()["handles"].shares(42, workers=40)
        48
        """
        grow = max(0, (self.crossings(corners) - 43) // 2)
        return max(16 * -(-max(workers, 1) // 16), 16 * 4 ** grow)

    def crossings(self, corners: int) -> int:
        """The crossings of a map of this genus with ``corners`` corners (quads: V - F = 2 - 2g)."""
        return corners + 2 * (self.genus - 1)

    def candidates(self, job: Job, context: Any, tally: Tally) -> Iterator[HalfEdgeMap]:
        """The share's candidate maps, from the share's ``B``; the search's statistics (the
        share's listing of ``B`` and its second stage) go to ``tally``."""
        from polyloops.generate.torus.candidates import SecondStage, candidate_torus_arrangements
        from polyloops.generate.torus.stages import TorusSearchStats

        stats: list[TorusSearchStats] = []
        top = self.crossings(job.n)
        for a in candidate_torus_arrangements(top, job.res, job.mod, on_stats=stats.append,
                                              stage=SecondStage(self.stage), genus=self.genus):
            if a.crossings >= self.crossings(job.low):
                yield a.quad_mesh()
        total = vars(stats[0]) if stats else {}
        tally.statistics.update(total)
        tally.visited += total.get("states", 0) + total.get("region_choices", 0)


register(TorusGenerator())
