"""What a catalog run has finished so far (``polyloops catalog status DIR``): its shares done,
the classes they hold, the time they took and an estimate of what remains.

A long run (a genus-2 search, a catalog through 44 corners on a cluster) is kept as one part
file a finished share in ``DIR/parts`` (:mod:`polyloops.catalog.run`); the run resumes from
them, on any machine, once they are copied into its directory.  This reads them the way the
run does: a part counts only when its digest holds and it names its own job (its file is the
job's part file), so an edited or damaged part is reported, never counted.

>>> import tempfile
>>> from pathlib import Path
>>> from polyloops.catalog.run import build_catalog
>>> out = Path(tempfile.mkdtemp()) / "c16"
>>> _ = build_catalog(out, 16, workers=1)
>>> status = run_status(out)
>>> plan = status.plans[0]
>>> plan.generator, plan.max_corners, len(plan.done) == plan.shares, status.finished
('loops', 16, True, True)
>>> plan.classes
{8: 1, 9: 0, 10: 0, 11: 0, 12: 1, 13: 0, 14: 0, 15: 0, 16: 2}
"""

from __future__ import annotations

import statistics
from dataclasses import dataclass, field
from pathlib import Path

from polyloops.catalog.jobs import JobResult
from polyloops.catalog.run import CatalogRunError, existing_extent, part_path, read_part
from polyloops.core.symmetry import Symmetry
from polyloops.generate.base import Job

__all__ = ["PlanStatus", "RunStatus", "run_status"]


@dataclass(frozen=True)
class PlanStatus:
    """The finished shares of one plan: generator ``generator`` (with options ``variant``) from
    ``min_corners`` to ``max_corners`` corners cut into ``shares`` shares."""

    generator: str
    variant: str
    min_corners: int
    max_corners: int
    shares: int
    done: tuple[int, ...]
    """The finished shares (their ``res``), in order."""
    seconds: tuple[float, ...]
    """Each finished share's time in its worker (wall seconds, as the part records it)."""
    classes: dict[int, int] = field(default_factory=dict)
    """Classes up to all symmetries found by the finished shares, by corners (every count the
    plan covers, zeros included)."""
    statistics: dict[str, int] = field(default_factory=dict)
    """The generator's statistics summed over the finished shares."""

    @property
    def found(self) -> dict[int, int]:
        """The corner counts where the finished shares found classes, and how many."""
        return {n: c for n, c in self.classes.items() if c}

    @property
    def missing(self) -> int:
        """Shares not finished yet."""
        return self.shares - len(self.done)

    @property
    def estimate(self) -> float | None:
        """Seconds the missing shares would take at the finished ones' mean (``None`` before
        any share has finished); shares differ, so this is a guide, not a bound."""
        return statistics.fmean(self.seconds) * self.missing if self.seconds else None

    def describe(self) -> str:
        """The plan in words.

        >>> PlanStatus("torus", "", 8, 48, 256, (0, 1), (60.0, 80.0)).describe()
        'torus, 8 to 48 corners, 2 of 256 shares done (140 s; about 17,780 s for the 254 others)'
        """
        variant = f" ({self.variant})" if self.variant else ""
        text = f"{self.generator}{variant}, {self.min_corners} to {self.max_corners} corners, " \
               f"{len(self.done)} of {self.shares} shares done"
        if self.seconds:
            text += f" ({sum(self.seconds):,.0f} s"
            if self.missing:
                text += f"; about {self.estimate:,.0f} s for the {self.missing:,} others"
            text += ")"
        return text


@dataclass(frozen=True)
class RunStatus:
    """A run directory's finished shares, one :class:`PlanStatus` a plan found there (a
    directory normally holds one), the part files that would be recomputed (unreadable,
    edited, of another schema, or not at their job's file name), and whether the run's catalog
    is written (``summary.json`` there, naming its extent)."""

    directory: Path
    plans: tuple[PlanStatus, ...]
    damaged: tuple[str, ...]
    finished: bool

    def to_json(self) -> dict[str, object]:
        """A JSON-ready dict (``catalog status --json``)."""
        return {"directory": str(self.directory), "finished": self.finished, "damaged": list(self.damaged),
                "plans": [{"generator": p.generator, "variant": p.variant, "min_corners": p.min_corners,
                           "max_corners": p.max_corners, "shares": p.shares, "done": len(p.done),
                           "missing": p.missing, "seconds": round(sum(p.seconds), 1),
                           "estimate_seconds": None if p.estimate is None else round(p.estimate, 1),
                           "classes": {str(n): c for n, c in p.classes.items()},
                           "statistics": p.statistics} for p in self.plans]}


def run_status(directory: Path | str) -> RunStatus:
    """The finished shares of the run in ``directory`` (its ``parts/``).

    Raises
    ------
    CatalogRunError
        When ``directory`` is no directory, or holds neither parts nor a catalog.
    """
    directory = Path(directory)
    if not directory.is_dir():
        why = "not a directory" if directory.exists() else "no such directory"
        raise CatalogRunError(f"{directory}: {why}")
    parts = directory / "parts"
    files = sorted(parts.glob("*.json")) if parts.is_dir() else []
    extent = existing_extent(directory)
    if not files and extent is None:
        raise CatalogRunError(f"{directory}: holds no catalog run (no parts/*.json and no summary.json)")
    by_plan: dict[Job, list[JobResult]] = {}
    damaged = []
    for path in files:
        result = read_part(path, directory)
        if result is None or part_path(directory, result.job) != path:
            damaged.append(path.name)
            continue
        plan = Job(result.job.generator, result.job.n, result.job.low, 0, result.job.mod, result.job.variant)
        by_plan.setdefault(plan, []).append(result)
    plans = tuple(_plan_status(plan, results) for plan, results in sorted(
        by_plan.items(), key=lambda kv: (-len(kv[1]), kv[0].generator, kv[0].n, kv[0].mod)))
    return RunStatus(directory, plans, tuple(damaged), extent is not None)


def _plan_status(plan: Job, results: list[JobResult]) -> PlanStatus:
    results = sorted(results, key=lambda r: r.job.res)
    classes = dict.fromkeys(range(plan.low, plan.n + 1), 0)
    sums: dict[str, int] = {}
    for r in results:
        for n, c in r.corners.items():
            if n in classes:
                classes[n] += len(c.records[str(Symmetry.FULL)])
        for key, value in r.statistics.items():
            sums[key] = sums.get(key, 0) + value
    return PlanStatus(plan.generator, plan.variant, plan.low, plan.n, plan.mod,
                      tuple(r.job.res for r in results), tuple(r.seconds for r in results),
                      classes, dict(sorted(sums.items())))
