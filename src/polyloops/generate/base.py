"""Where a catalog's candidate maps come from: one small interface, and its registry.

A :class:`Generator` cuts a catalog run into :class:`Job`\\ s (its shares), prepares what its
jobs share (plantri's binary, the top of the loops search), and lists each job's candidate
maps, counting what it visited in a :class:`Tally`.  The pipeline
(:mod:`polyloops.catalog.run`) classifies the maps, keeps each finished job as a typed
:class:`~polyloops.catalog.jobs.JobResult` in ``DIR/parts/``, and merges the results; nothing
in it knows which generator ran.

Each generator is a folder of :mod:`polyloops.generate` that registers itself with
:func:`register` when imported; :func:`generators` imports every folder once and returns the
registry, so a new generator (a genus-2 search) is one new folder:

- ``plantri`` (:mod:`polyloops.generate.plantri`): every quadrangulation plantri writes,
  filtered; jobs are plantri's slices ``n res/mod``, one corner count each, and it counts the
  maps it reads;
- ``loops`` (:mod:`polyloops.generate.loops`): arrangements of loops built one loop at a time;
  each job is a share of one search over every corner count, and it counts the arrangements it
  builds;
- ``torus`` (:mod:`polyloops.generate.torus`): the genus-1 candidate maps, in two stages; each
  job is a share of the two-axis arrangements the second stage starts from.

>>> sorted(generators())
['handles', 'loops', 'plantri', 'torus']
>>> generators()["torus"].genus
1
>>> [job.name for job in generators()["plantri"].plan(8, 12, None, 1)]
['n012-0of1', 'n010-0of1', 'n008-0of1']
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

from polyloops.core.halfedge import HalfEdgeMap

__all__ = ["GENERATORS", "Generator", "Job", "Tally", "generators", "register"]


@dataclass(frozen=True)
class Job:
    """One share of a catalog run: the candidate maps of generator ``generator`` with ``low``
    to ``n`` corners in share ``res`` of ``mod``; ``variant``, the generator's options when they
    are not its defaults (:attr:`Generator.variant`), so that a run never reuses the parts of a
    run with other options."""

    generator: str
    n: int
    low: int
    res: int = 0
    mod: int = 1
    variant: str = ""

    @property
    def name(self) -> str:
        """The job's file name stem in ``DIR/parts`` (the generator's :meth:`Generator.job_name`)."""
        return generators()[self.generator].job_name(self)

    def to_json(self) -> dict[str, Any]:
        """A JSON-ready dict of the job."""
        out: dict[str, Any] = {"generator": self.generator, "n": self.n, "low": self.low, "res": self.res,
                               "mod": self.mod}
        if self.variant:
            out["variant"] = self.variant
        return out

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Job:
        """The job a stored result answers; raises ``KeyError`` or ``TypeError`` otherwise."""
        return cls(str(data["generator"]), int(data["n"]), int(data["low"]), int(data["res"]),
                   int(data["mod"]), str(data.get("variant", "")))


@dataclass
class Tally:
    """What a job's generator visited: ``maps[n]`` and ``simple_strips[n]`` per corner count
    (for generators that count maps they read), and ``statistics`` of its own (summed over
    jobs, such as the loops search's), and ``visited``, the objects its progress counts."""

    maps: dict[int, int] = field(default_factory=dict)
    simple_strips: dict[int, int] = field(default_factory=dict)
    statistics: dict[str, int] = field(default_factory=dict)
    visited: int = 0


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

    @property
    def variant(self) -> str:
        """The options that differ from the defaults, as a short word for file names (``""``
        at the defaults); the records do not depend on them, the work and statistics may."""
        return ""

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
        variant = f"-{job.variant}" if job.variant else ""
        return f"{self.name}{variant}-{job.low}to{job.n}-{job.res}of{job.mod}"

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
    """Make ``generator`` available to :func:`~polyloops.catalog.run.build_catalog` by its name
    (a later one of the same name replaces it).  A generator's folder calls it when imported."""
    GENERATORS[generator.name] = generator
    return generator


@lru_cache(maxsize=1)
def _import_folders() -> None:
    import importlib
    import pkgutil

    import polyloops.generate as here

    for info in pkgutil.iter_modules(here.__path__, "polyloops.generate."):
        if info.ispkg:  # each folder is a generator; it registers itself
            importlib.import_module(info.name)


def generators() -> dict[str, Generator]:
    """The registry: every generator folder of :mod:`polyloops.generate` (imported once), and
    any generator registered since (a test's, a plug-in's)."""
    _import_folders()
    return GENERATORS


