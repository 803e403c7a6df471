"""The maps of genus 1 that carry a polycube, in two stages.

Deleting every loop of one axis from a polycube loop structure of positive genus merges its
corners along paths of edges of that axis, so the two other axes' loops form a cellular
arrangement ``B`` (its crossing graph is bipartite), and the deleted loops are pairwise disjoint,
each crossing every region of ``B`` at most once.  Taking the axis whose deletion leaves fewest
crossings, ``B`` has at most a third of the crossings (:func:`~polyloops.generate.torus.cuts.base_bound`).
:func:`candidate_torus_arrangements` lists every such ``B``
(:func:`~polyloops.generate.torus.stages.first_stage`) and then its third axis
(:class:`SecondStage`): region by region (:mod:`~polyloops.generate.torus.regions`, where the
level graphs of ``B`` cut early), or, as the twin kept for the tests, one loop at a time
(:func:`~polyloops.generate.torus.stages.second_stage`).  ``docs/searches.md`` proves it.

>>> list(candidate_torus_arrangements(26))  # the smallest genus-1 polycube has 32 corners
[]
>>> SecondStage("loops")
<SecondStage.LOOPS: 'loops'>
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from enum import StrEnum

from polyloops.generate.torus.arrangement import TorusArrangement, arrangement_of_twin, layered_code
from polyloops.generate.torus.cuts import base_bound
from polyloops.generate.torus.decompositions import canonical_decomposition, carries_polycube, decomposes
from polyloops.generate.torus.regions import third_axis_systems
from polyloops.generate.torus.stages import TorusSearchStats, second_stage, share_of_first_stage

__all__ = ["SecondStage", "candidate_torus_arrangements"]


class SecondStage(StrEnum):
    """How the third axis is added to a two-axis arrangement."""

    REGIONS = "regions"  # region by region, every third axis at once (the search the catalogs use)
    LOOPS = "loops"  # one loop at a time (its twin, kept for the tests)


def candidate_torus_arrangements(max_crossings: int, res: int = 0, mod: int = 1,
                                 on_stats: Callable[[TorusSearchStats], None] | None = None,
                                 polycubes: bool = True,
                                 stage: SecondStage = SecondStage.REGIONS, genus: int = 1,
                                 ) -> Iterator[TorusArrangement]:
    """Every map of ``genus`` (1 or more) with at most ``max_crossings`` crossings that carries a polycube
    loop structure, once up to homeomorphism, through the two stages: each ``B`` with at most
    a third of the crossings, then its third axis by ``stage``; a map is listed from its
    canonical decomposition
    (:func:`~polyloops.generate.torus.decompositions.polycube_decompositions`).  ``res``/``mod``
    takes share ``res`` of ``mod`` of the first stage
    (:func:`~polyloops.generate.torus.stages.share_of_first_stage`: independent shares).  With
    ``polycubes`` false (the loop-by-loop stage only) every map with a decomposition is listed,
    from its canonical one among
    :func:`~polyloops.generate.torus.decompositions.two_stage_decompositions`.  The maps come
    without a ``code``
    (:func:`~polyloops.generate.torus.arrangement.canonical` gives it)."""
    stage = SecondStage(stage)
    if not polycubes and stage is not SecondStage.LOOPS:
        raise ValueError("only the loop-by-loop second stage lists maps that carry no polycube")
    stats = TorusSearchStats()
    listed, first_stats = share_of_first_stage(base_bound(max_crossings), genus, res, mod)
    stats.add(first_stats)
    for raw in listed:
        for kid in _third_axes(arrangement_of_twin(raw), max_crossings, stats, stage):
            if (not polycubes or carries_polycube(kid)) and canonical_decomposition(kid, polycubes):
                yield TorusArrangement(kid.twin)
    if on_stats:
        on_stats(stats)


def _third_axes(base: TorusArrangement, max_crossings: int, stats: TorusSearchStats, stage: SecondStage
                ) -> Iterator[TorusArrangement]:
    """The decompositions with ``B = base`` (:func:`decomposes`), each once up to homeomorphism,
    that ``stage`` reaches (the region search leaves out those whose loops of ``B`` no
    orientation fits)."""
    if stage is SecondStage.LOOPS:
        yield from second_stage(base, max_crossings, stats)
        return
    seen: set[bytes | tuple] = set()
    for twin, layer in third_axis_systems(base, max_crossings, stats):
        kid = TorusArrangement(twin, (), layer)
        key = layered_code(kid)
        if key in seen:
            continue
        seen.add(key)
        if decomposes(TorusArrangement(twin), frozenset(kid.third_loops()), max_crossings):
            yield kid
