"""Checking a catalog against methods that share nothing with the generator that made it.

- :func:`plantri_sample`: some of plantri's slices ``n res/mod`` (chosen by a seed), run through
  plantri's generator; every class found must be in the catalog, and a class of the catalog
  that plantri's slices reach must be found (the slices partition plantri's maps, so a
  complete sample, ``k = mod``, is the full comparison);
- :func:`reach_agreement`: every class the breadth-first search over loop moves reaches from
  the cube within ``n`` corners must be in the catalog.

Each returns what it checked and what disagreed, so the docs can state exactly what was
compared at each size.

>>> from polyloops.catalog.census import default_catalog
>>> check = plantri_sample(default_catalog(), 16, mod=2, k=2, seed=1)
>>> check.slices, check.found, check.missing
((0, 1), 2, ())
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from pathlib import Path

from polyloops.catalog.census import Census, read_catalog
from polyloops.core.polycube import Polycube
from polyloops.core.symmetry import Symmetry

__all__ = ["ReachAgreement", "SampleCheck", "plantri_sample", "reach_agreement"]


@dataclass(frozen=True)
class SampleCheck:
    """A sampled comparison with plantri: the corner count, the slices ``res`` of ``mod`` run,
    the seed that chose them, the maps plantri wrote in them, the classes found, and the
    signatures found that the catalog lacks (empty when the sample agrees)."""

    corners: int
    mod: int
    slices: tuple[int, ...]
    seed: int
    maps: int
    found: int
    missing: tuple[str, ...]

    @property
    def agrees(self) -> bool:
        """Every class the sample found is in the catalog."""
        return not self.missing


def choose_slices(mod: int, k: int, seed: int) -> tuple[int, ...]:
    """``k`` of the ``mod`` slices, chosen by ``seed`` (reproducible), in increasing order.

    >>> choose_slices(64, 3, seed=2026)
    (13, 15, 40)
    """
    return tuple(sorted(random.Random(seed).sample(range(mod), k)))


def plantri_sample(catalog: Path | Census, n: int, mod: int, k: int = 1, seed: int = 0,
                   plantri: str | None = None) -> SampleCheck:
    """Run ``k`` of plantri's ``mod`` slices of ``n`` corners (chosen by ``seed``) through
    plantri's generator and check that every class found is in the catalog.

    Raises
    ------
    ValueError
        When ``k`` is not in ``1..mod``, or the catalog is not of full classes.
    """
    from polyloops.catalog.jobs import run_job
    from polyloops.generate.base import Job
    from polyloops.generate.plantri import PlantriGenerator

    if not 1 <= k <= mod:
        raise ValueError(f"choose 1 to {mod} slices, not {k}")
    census = catalog if isinstance(catalog, Census) else read_catalog(catalog)
    if census.symmetry != Symmetry.FULL:
        raise ValueError(f"{census.directory}: a sample is compared with a catalog of full classes")
    generator = PlantriGenerator(plantri)
    slices = choose_slices(mod, k, seed)
    jobs = [Job(generator.name, n, n, res, mod) for res in slices]
    contexts = generator.prepare(jobs)
    known = set(census.by_signature)
    found: set[str] = set()
    maps = 0
    for job, context in zip(jobs, contexts, strict=True):
        result = run_job((generator, job, context))
        maps += result.visited
        found |= {r.signature for c in result.corners.values() for r in c.records["full"]}
    return SampleCheck(n, mod, slices, seed, maps, len(found), tuple(sorted(found - known)))


@dataclass(frozen=True)
class ReachAgreement:
    """The classes (up to all 48 symmetries) reached from the cube within ``max_corners``, by
    corners, and those the catalog lacks."""

    max_corners: int
    reached: dict[int, int]
    missing: tuple[str, ...]

    @property
    def agrees(self) -> bool:
        """Every class reached is in the catalog."""
        return not self.missing


def reach_agreement(catalog: Path | Census, max_corners: int, workers: int = 1) -> ReachAgreement:
    """Breadth-first search over loop moves from the cube (states up to all 48 symmetries)
    within ``max_corners``: every class reached must be in the catalog.

    Raises
    ------
    ValueError
        When the catalog is not of full classes.
    """
    import tempfile

    from polyloops.io.examples import load_example
    from polyloops.reach.search import explore, stored_signatures

    census = catalog if isinstance(catalog, Census) else read_catalog(catalog)
    if census.symmetry != Symmetry.FULL:
        raise ValueError(f"{census.directory}: reachability is compared with a catalog of full classes")
    with tempfile.TemporaryDirectory() as tmp:
        cube = load_example("cube")
        assert isinstance(cube, Polycube)
        result = explore(cube.dualize(), max_corners, mode=Symmetry.FULL,
                         directory=Path(tmp) / "reach", workers=workers)
        reached = stored_signatures(Path(tmp) / "reach")
    missing = tuple(sorted(set(reached) - set(census.by_signature)))
    return ReachAgreement(max_corners, dict(result.by_corners), missing)
