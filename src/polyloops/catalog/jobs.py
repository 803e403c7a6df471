"""The pipeline's record of a finished job: what it classified per corner count
(:class:`CornerResult`), kept in ``DIR/parts/`` as a :class:`JobResult`, and :func:`run_job`,
which runs a generator's job and classifies its maps (:func:`~polyloops.catalog.classes.map_classes`)."""

from __future__ import annotations

import time
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

from polyloops.catalog.classes import MODES, map_classes
from polyloops.catalog.records import CatalogRecord
from polyloops.core.symmetry import Symmetry
from polyloops.generate.base import Generator, Job, Tally

__all__ = ["SCHEMA_VERSION", "CornerResult", "JobResult", "run_job"]

SCHEMA_VERSION = 6


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


def run_job(task: tuple[Generator, Job, Any]) -> JobResult:
    """Classify one job's candidate maps (:func:`~polyloops.catalog.classes.map_classes`)."""
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
