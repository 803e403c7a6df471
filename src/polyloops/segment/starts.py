"""Where the search of ``polyloops segment`` begins: the starts it tries on a mesh, and how each
is built.

A *start* is a cut surface, its candidate curves and the curves chosen, making a polycube loop
structure.  The first starts are *recipes*, each built and scouted (searched for a share of
the budget and ranked by the search's estimate), the best-ranked then searched on and laid out
(:func:`~polyloops.segment.run.segment_mesh`, in parallel with ``workers``), the best
certified result kept:

- the level starts (:mod:`~polyloops.segment.levels`): of the charts of the naive and of the
  graph-cut labelling in the polycube-like deformation, then of the triangles in the
  deformation and in the surface's own coordinates, with each gap of
  :data:`~polyloops.segment.levels.GAPS`;
- at genus 0, the cube of the central plane sections (:func:`~polyloops.segment.search.start_state`).

When none of them gives a certified segmentation, the grids follow, one at a time
(:func:`grid_starts`): every candidate curve of 9, 13 or 19 planes an axis, mended into a
polycube loop structure (:mod:`~polyloops.segment.grid`).

>>> [r.name for r in recipes(0)][-2:]
['the levels in the coordinates (gap 0.02)', 'the cube']
"""

from __future__ import annotations

import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from enum import Enum

import numpy as np

from polyloops.segment.deform import polycube_heights
from polyloops.segment.embedded import Loop
from polyloops.segment.grid import cut_grid, mend
from polyloops.segment.labellings import graphcut_labels, label_indices, naive_label_indices
from polyloops.segment.levels import GAPS, level_grid
from polyloops.segment.refine import Refined
from polyloops.segment.search import StartError, candidate_loops, start_state
from polyloops.segment.seeds import seed_grid
from polyloops.segment.surface import Surface

__all__ = ["GRIDS", "MENDING", "OVERRUN", "Charts", "Heights", "Recipe", "Start", "build_start",
           "grid_starts", "recipes"]

GRIDS = (9, 13, 19)  # candidate planes per axis for a grid start, coarse to fine
OVERRUN = 3.0  # times the budget after which no further start is begun (when the first ones fail)
MENDING = 20.0  # seconds a grid may be mended at least (half the budget when that is more)

Start = tuple[Refined, Sequence[Loop], list[int], str]  # the cut surface, its curves, the chosen, how


class Heights(Enum):
    """What the planes of a start cut: the surface's coordinates, its polycube-like
    deformation, or its map onto the polycube that realises a valid labelling of it
    (:mod:`~polyloops.segment.seeds`)."""

    COORDINATES = "coordinates"
    DEFORMATION = "deformation"
    POLYCUBE = "polycube"


class Charts(Enum):
    """What a level start groups into levels: the triangles, or the charts of a labelling of
    the surface (:func:`~polyloops.segment.levels.levels`); for a seed, the valid labelling
    whose loops it draws."""

    TRIANGLES = "triangles"
    NAIVE = "naive"
    GRAPH_CUT = "graph-cut"
    REPAIRED = "repaired graph-cut"  # a seed's only: the graph-cut labelling made valid
    GUIDE = "repaired guide"  # a seed's only: a guide made valid


@dataclass(frozen=True)
class Recipe:
    """One start to build: ``kind`` ``"levels"`` (of ``charts``, with its ``gap``), ``"cube"``
    (with ``planes`` candidate planes an axis) or ``"seed"`` (the loops of the valid labelling
    ``charts``), cutting the ``heights``."""

    kind: str
    heights: Heights
    gap: float = 0.0
    planes: int = 9
    charts: Charts = Charts.TRIANGLES

    @property
    def name(self) -> str:
        """How the start is named in a result (``start`` in the JSON)."""
        if self.kind == "cube":
            return "the cube"
        if self.kind == "seed":
            return f"the loops of the valid {self.charts.value} labelling"
        where = "polycube-like deformation" if self.heights is Heights.DEFORMATION else "coordinates"
        of = "" if self.charts is Charts.TRIANGLES else f" of the {self.charts.value} charts"
        return f"the levels{of} in the {where} (gap {self.gap:g})"


def recipes(genus: int, planes: int = 9) -> list[Recipe]:
    """The recipes tried first on a surface of ``genus``, in order (see the module docstring):
    the most often best first, as a short budget may not begin the last."""
    out = [Recipe("levels", Heights.DEFORMATION, GAPS[0], charts=c) for c in (Charts.NAIVE, Charts.GRAPH_CUT)]
    out += [Recipe("levels", h, gap) for h in (Heights.DEFORMATION, Heights.COORDINATES) for gap in GAPS]
    if genus == 0:
        out.append(Recipe("cube", Heights.COORDINATES, planes=planes))
    return out


def build_start(surface: Surface, recipe: Recipe, deadline: float = float("inf"),
                deformed: np.ndarray | None = None, mapped: np.ndarray | None = None) -> Start:
    """The start of ``recipe`` on ``surface`` (mending within ``deadline``, a
    :func:`time.monotonic` time; ``deformed``: the polycube-like heights, computed when needed
    and not given; ``mapped``: for a seed, the surface mapped onto the polycube of its valid
    labelling, :func:`~polyloops.segment.seeds.polycube_map`).

    Raises
    ------
    StartError
        When the recipe gives no polycube loop structure (the message says why).
    """
    if recipe.kind == "cube":
        r, loops, _ = candidate_loops(surface, recipe.planes)
        return r, loops, start_state(r, loops), recipe.name
    if recipe.kind == "seed":
        if mapped is None:
            raise StartError(f"{recipe.name}: no map onto its polycube was given")
        r, loops, chosen = seed_grid(surface, mapped, recipe.name, deadline)
        return r, loops, chosen, recipe.name
    heights = None
    if recipe.heights is Heights.DEFORMATION:
        heights = polycube_heights(surface) if deformed is None else deformed
    labels = None
    if recipe.charts is Charts.NAIVE:
        labels = naive_label_indices(surface)
    elif recipe.charts is Charts.GRAPH_CUT:
        labels = label_indices(graphcut_labels(surface))
    r, loops, chosen = mend(level_grid(surface, heights, recipe.gap, labels, deadline), deadline=deadline)
    return r, loops, chosen, recipe.name


def grid_starts(surface: Surface, planes: int, budget: float, began: float, given: int = 0,
                reasons: list[str] | None = None, deformed: np.ndarray | None = None) -> Iterator[Start]:
    """The grid starts in turn: each grid of :data:`GRIDS` mended into a polycube loop
    structure (:mod:`~polyloops.segment.grid`), each size cut in the surface's coordinates and
    in a polycube-like deformation of it (:mod:`~polyloops.segment.deform`), the one with fewer
    violations as cut mended first; nothing more is begun once :data:`OVERRUN` times ``budget``
    seconds have gone since ``began`` (a :func:`time.monotonic` time) and some start was given
    (``given`` of them before these; ``reasons`` gathers why the others failed; ``deformed``:
    the polycube-like heights, computed when needed and not given).

    Raises
    ------
    StartError
        When no start was found at all (the message gives each reason).
    """
    reasons = [] if reasons is None else reasons
    for k in sorted({planes, *GRIDS}):
        if (given or reasons) and time.monotonic() - began > OVERRUN * budget:
            if not given:
                raise StartError(f"no start on this genus-{surface.genus} mesh: " + "; ".join(
                    [*reasons, "nothing more tried: the time budget is spent"]))
            return
        if deformed is None:
            deformed = polycube_heights(surface)
        # both grids of this size as cut, the one nearer a polycube loop structure (fewer
        # violations of Definition 4) mended first
        grids = []
        for kind, heights in (("coordinates", None), ("deformation", deformed)):
            try:
                grids.append((cut_grid(surface, k, heights), kind))
            except StartError as err:
                reasons.append(f"{k} planes an axis in the {kind}: {err}")
        grids.sort(key=lambda g: g[0].violations)
        for grid, kind in grids:
            if given and time.monotonic() - began > OVERRUN * budget:
                return
            try:
                r, loops, chosen = mend(grid, deadline=time.monotonic() + max(budget / 2, MENDING))
            except StartError as err:
                reasons.append(f"{k} planes an axis in the {kind}: {err}")
                continue
            given += 1
            yield r, loops, chosen, f"a grid of {k} planes an axis" + (
                " of the polycube-like deformation" if kind == "deformation" else "")
    if not given:
        raise StartError(f"no start on this genus-{surface.genus} mesh: " + "; ".join(reasons))
