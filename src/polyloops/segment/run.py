"""``pl.segment``: a certified polycube segmentation of a triangle mesh, by loop moves.

>>> from polyloops.shapes.meshes import ellipsoid
>>> done = segment_mesh(*ellipsoid(2.0, 1.0, 0.7, level=3), budget=2.0)
>>> done.certified, done.genus, done.loops >= 3, done.fidelity <= done.naive_fidelity
(True, 0, True, True)
"""

from __future__ import annotations

import csv
import io
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np

from polyloops.core.directions import Direction
from polyloops.core.duality import dualize
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.parallel import run_jobs
from polyloops.segment import PRICE, Floor
from polyloops.segment.certify import layout_problem
from polyloops.segment.deform import polycube_heights
from polyloops.segment.embedded import Loop, NotAStructure
from polyloops.segment.from_polycube import UncertifiedError
from polyloops.segment.graft import graft_labels
from polyloops.segment.labellings import (
    fidelity,
    graphcut_labels,
    label_indices,
    label_vectors,
    naive_fidelity,
    naive_labels,
)
from polyloops.segment.layout import Layout, lay_out
from polyloops.segment.merge import merges
from polyloops.segment.polish import polish_labels, polish_layout, polished_fidelity
from polyloops.segment.refine import Refined
from polyloops.segment.repair import repair_labels
from polyloops.segment.search import SearchSettings, StartError, State, greedy_search
from polyloops.segment.seeds import polycube_map
from polyloops.segment.start import embed_start
from polyloops.segment.starts import (
    GRIDS,
    OVERRUN,
    Charts,
    Heights,
    Recipe,
    Start,
    build_start,
    grid_starts,
    recipes,
)
from polyloops.segment.surface import Surface, surface_of
from polyloops.segmentation import SegmentationReport, check_segmentation
from polyloops.segmentation.quality import backwards_fraction
from polyloops.surface.mesh import LabelledMesh

__all__ = ["COARSER", "FINER", "Candidate", "SegmentResult", "segment_mesh"]

# the lighter compactness weights of the graph-cut labellings that are candidates beside the
# standard one (weight 1): nearer the per-triangle labelling, often valid once repaired; their
# patches are grafted into the result
FINER = (0.5, 0.25, 0.125)
# the heavier ones: fewer charts and loops for a little fidelity, which the loops' price may
# prefer (a thin wing's many steps, cut by the lighter labellings, merged)
COARSER = (2.0, 3.0, 6.0)


@dataclass(frozen=True)
class Candidate:
    """What one start gave in a run (a row of ``segment --score-csv``): its name, whether its
    search ended certified (else ``reason``), and the terms of its score: the labels'
    ``fidelity``, their ``agreement`` with the guide (when there is one), the ``loops`` and
    their ``price``, ``score`` = (agreement with a guide, else fidelity) - price x loops; the
    ``estimate`` of that score that ranked the start (its scouting search's best state, a
    rough layout polished, no paths drawn); the charts and corners of its labelling, its wall
    ``seconds``, whether its searches ``converged``, and whether it was ``kept`` (the run's
    result)."""

    start: str
    certified: bool
    reason: str = ""
    fidelity: float | None = None
    agreement: float | None = None
    loops: int | None = None
    price: float | None = None
    score: float | None = None
    estimate: float | None = None
    charts: int | None = None
    corners: int | None = None
    seconds: float = 0.0
    converged: bool | None = None
    kept: bool = False

    FIELDS = ("start", "certified", "reason", "fidelity", "agreement", "loops", "price", "score", "estimate",
              "charts", "corners", "seconds", "converged", "kept")


@dataclass(frozen=True, eq=False)
class SegmentResult:
    """A certified segmentation: the labelled mesh (the input refined along the loops), per
    triangle the input triangle it lies in, the polycube primalized from the loops, the
    checker's report on the labels, and the figures of the run."""

    mesh: LabelledMesh
    face_map: tuple[int, ...]
    polycube: Polycube
    report: SegmentationReport
    genus: int
    input_triangles: int
    loops: int
    fidelity: float
    naive_fidelity: float
    seconds: float
    states: int
    converged: bool  # the search ended with no improving move, not by the budget
    layout: Layout | None  # the loops, regions, corners, paths and patches (None: a valid guide kept)
    start: str  # how the search began: the cube, a grid, or the given start and its turn
    guide_changed: float | None = None  # with a guide: the share of the area labelled otherwise
    score: float | None = None  # what the run maximised: fidelity (or agreement) less the loops' price
    candidates: tuple[Candidate, ...] = ()  # every start tried, the kept one marked

    @property
    def certified(self) -> bool:
        """Always true: an uncertified segmentation is never returned."""
        return self.report.valid is True

    @property
    def charts(self) -> int:
        """The charts of the labelling (maximal connected areas of one label)."""
        return len(self.report.segmentation.charts)

    @property
    def corners(self) -> int:
        """The corners of the labelling's charts."""
        return len(self.report.segmentation.corners)

    def to_json(self) -> dict[str, object]:
        """The figures of the run, for ``segment --json``."""
        return {"certified": self.certified, "genus": self.genus, "input_triangles": self.input_triangles,
                "triangles": len(self.mesh.triangles), "charts": self.charts, "corners": self.corners,
                "loops": self.loops, "polycube_corners": self.polycube.map.num_corners,
                "fidelity": round(self.fidelity, 6), "naive_fidelity": round(self.naive_fidelity, 6),
                "backwards": _rounded(backwards_fraction(self.report)), "seconds": round(self.seconds, 2),
                "states": self.states, "converged": self.converged, "start": self.start,
                "score": _rounded(self.score),
                **({} if self.guide_changed is None else {"guide_changed": round(self.guide_changed, 6)})}


    def scores_csv(self) -> str:
        """``segment --score-csv``: a header, then one row per start tried (see
        :class:`Candidate`; empty fields where a start gave nothing)."""
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(Candidate.FIELDS)
        for c in self.candidates:
            writer.writerow(["" if v is None else round(v, 6) if isinstance(v, float) else v
                             for v in (getattr(c, f) for f in Candidate.FIELDS)])
        return buf.getvalue()


def _rounded(x: float | None) -> float | None:
    return None if x is None else round(x, 6)


def _laid_out(r: Refined, loops: Sequence[Loop], ways: list[bool], guide: np.ndarray | None = None
              ) -> tuple[Layout, tuple[LabelledMesh, SegmentationReport]] | str:
    """The loops laid out, polished (:mod:`~polyloops.segment.polish`: towards the normals, or
    the ``guide``, a unit vector per input triangle) and certified, or why not: the layout
    that follows the per-triangle labels first, and where that is not certified (a patch folded
    over a thin part), the one by the sides' middles and lengths alone.  ``ways`` lists the
    layouts still tried in this search; one that failed is dropped from it (on the jug it fails
    for every state, and each try costs seconds).  A polished layout draws the same polycube
    and is certified anew; were it not, the layout as drawn would be kept."""
    why = ""
    for follow in list(ways):
        try:
            drawn = lay_out(r, loops, follow)
        except NotAStructure as err:
            why = str(err)
        else:
            target = None if guide is None else guide[drawn.embedded.refined.parent]
            polished = polish_layout(drawn, target)
            for lay in (polished, drawn) if polished is not drawn else (drawn,):
                checked = _certify(lay)
                if not isinstance(checked, str):
                    return lay, checked
                why = checked
        if follow and len(ways) > 1:
            ways.remove(True)
    return why


def _certify(lay: Layout) -> tuple[LabelledMesh, SegmentationReport] | str:
    """The labelled mesh and the checker's report when both checks pass, else what failed."""
    problem = layout_problem(lay)
    if problem is not None:
        return f"the layout does not draw the polycube: {problem}"
    r = lay.embedded.refined
    mesh = r.surface.labelled(lay.labels)
    report = check_segmentation(mesh)
    if report.valid is not True:
        return f"the checker finds the labels {'invalid' if report.valid is False else 'undecided'}"
    return mesh, report


def segment_surface(surface: Surface, budget: float = 20.0, seed: int = 0, planes: int = 9,
                    price: float = PRICE, on_step: Callable[[State], None] | None = None,
                    start: LoopStructure | None = None,
                    guide: Sequence[Direction] | None = None, direct: bool = True, workers: int = 1,
                    on_candidate: Callable[[Candidate], None] | None = None,
                    bound: Floor = Floor.REPAIRED, merge: bool = False) -> SegmentResult:
    """:func:`segment_mesh` on a checked surface: the search from the given start, or from
    each recipe of :func:`~polyloops.segment.starts.recipes` (``workers`` at a time): each
    scouted (searched for a share of the budget, ranked by an estimate), the
    best-ranked searched on and laid out while the budget lasts, the best certified result
    kept; then from the grids until one is certified;
    a ``guide`` that is already a valid labelling is returned as it is; with ``direct`` and
    without a start or a guide, the naive and graph-cut labellings that the checker finds
    valid are candidates too (:func:`_direct`), and the result is the best score among those
    at least as faithful as that labelling (where it is valid as it is, or repaired when
    ``bound`` is :attr:`Floor.REPAIRED`); so are the graph-cut labellings of other
    compactness made valid (:func:`_other_weights`), scored alike but no floor.  Last, the
    patches of the graph-cut labellings (or of the guide) that keep the result valid and raise
    its score are grafted into it (:func:`_grafted`), for at most :data:`GRAFTING` of the
    budget; then its charts are merged where that raises the score (:func:`_merged`), for at
    most :data:`MERGING` of the budget: with ``merge`` at any loss of fidelity the loops saved
    pay for, else only at none (:data:`FREE`)."""
    began = time.monotonic()
    if guide is not None and len(guide) != len(surface.triangles):
        raise ValueError(f"a guide of {len(guide)} labels for {len(surface.triangles)} triangles")
    knobs = SearchSettings(budget, seed, planes, price, None if guide is None else label_vectors(guide))
    kept_direct, which = None, Charts.GRAPH_CUT
    weighted: list[SegmentResult] = []
    donors: list[np.ndarray] = []  # labellings whose patches are grafted into the result
    if guide is not None:
        donors.append(label_indices(guide))
        kept = _kept_labelling(surface, guide, "the guide, already valid", began)
        if kept is not None:
            return _alone(replace(kept, guide_changed=0.0), knobs)
        # an invalid guide repaired by local remedies, where they make it valid: a candidate,
        # a floor on the agreement, and a seed
        repaired = repair_labels(surface, guide)
        if repaired is not None:
            how = f"the guide, repaired ({repaired.charts} charts changed)"
            kept = _kept_labelling(surface, repaired.labels, how, began, repaired.report)
            if kept is not None:
                assert knobs.guide is not None
                changed = _changed(surface.areas, knobs.guide, repaired.labels)
                kept_direct, which = replace(kept, guide_changed=changed), Charts.GUIDE
    elif start is None and direct:
        found_direct = _direct(surface, began, donors)
        if found_direct is not None:
            kept_direct, which = found_direct
            if which is Charts.NAIVE:  # no labelling is more faithful: merged only where none is lost
                return _merged_alone(_alone(kept_direct, knobs), knobs, began, FREE)
    if start is not None:
        r, loops, placed = embed_start(surface, start, GRIDS, budget)
        how = f"the given start, turned by {placed.symmetry}" + (
            " (sections of the polycube-like deformation)" if placed.deformed else "")
        searched = _search_from(surface, (r, loops, list(placed.curves), how), began, knobs, on_step)
        return _merged_alone(_alone(searched, knobs), knobs, began, None if merge else FREE)
    tried: list[tuple[Candidate, SegmentResult | None]] = []
    no_start: StartError | None = None

    def note(candidate: Candidate, result: SegmentResult | None) -> None:
        tried.append((candidate, result))
        if on_candidate is not None:
            on_candidate(candidate)

    deformed = polycube_heights(surface)
    own = recipes(surface.genus, planes)
    mapped = None
    if kept_direct is not None:
        # a valid labelling of the mesh (the graph-cut one, as it is or repaired) seeds a
        # search of its own, from its polycube's loops drawn on the surface
        try:
            mapped = polycube_map(surface, kept_direct.report)
        except ValueError:
            pass
        else:
            own = [Recipe("seed", Heights.POLYCUBE, charts=which), *own]
    # scouting: each start built and searched for a share of the budget, judged by an
    # estimate (a rough layout polished, no paths drawn); then the best-ranked are searched on
    # and laid out
    share = max(SCOUTING * budget * max(workers, 1) / len(own), 1.0)
    jobs = [(surface, recipe, began, knobs, deformed, mapped, share, on_step if workers <= 1 else None)
            for recipe in own]
    scouted = []
    for candidate, scout in run_jobs(_scout_job, jobs, workers=workers):
        if scout is None:
            note(candidate, None)
        else:
            scouted.append((candidate, scout))
    scouted.sort(key=lambda cf: -(cf[0].estimate or 0.0))
    batch = max(workers, LAID_OUT)
    for first in range(0, len(scouted), batch):
        # the next ones while the budget lasts, or until one is certified (at most OVERRUN
        # times the budget)
        spent = time.monotonic() - began
        certified = any(res is not None for _, res in tried)
        if first and (spent > OVERRUN * budget or (spent > budget and certified)):
            for candidate, _ in scouted[first:]:
                why = f"not laid out: its estimate ranks {first + 1} or lower"
                note(replace(candidate, reason=why), None)
            break
        laid = [(surface, scout, candidate, began, knobs, on_step if workers <= 1 else None)
                for candidate, scout in scouted[first:first + batch]]
        for candidate, result in run_jobs(_lay_out_job, laid, workers=workers):
            note(candidate, result)
    if not any(result is not None for _, result in tried):
        reasons = [f"from {c.start}: {c.reason}" for c, _ in tried]
        try:
            for found in grid_starts(surface, planes, budget, began, reasons=reasons, deformed=deformed):
                t0 = time.monotonic()
                try:
                    searched = _search_from(surface, found, began, knobs, on_step)
                except UncertifiedError as err:
                    note(Candidate(found[3], False, str(err), seconds=time.monotonic() - t0), None)
                    continue
                note(_candidate(searched, knobs, time.monotonic() - t0), searched)
                break
        except StartError as err:
            no_start = err
    if guide is None and direct:
        # after the search, so that they take nothing from its budget
        weighted = _other_weights(surface, began, workers, donors)
    if no_start is not None and kept_direct is None and not weighted:
        raise no_start
    order = {r.name: k for k, r in enumerate(own)}
    tried.sort(key=lambda cr: order.get(cr[0].start, len(order)))  # recipes in order, then grids
    found_results = [(c, res) for c, res in tried if res is not None]
    # the labellings of the mesh itself that are valid (as they are or repaired)
    own_rows = [(_candidate(res, knobs, res.seconds), res) for res in weighted]
    floor = None
    if kept_direct is not None:
        direct_row = _candidate(kept_direct, knobs, kept_direct.seconds)
        own_rows.insert(0, (direct_row, kept_direct))
        floor = _aim((direct_row, kept_direct), knobs)
    found_results += own_rows
    if not found_results:
        raise UncertifiedError("; ".join(f"from {c.start}: {c.reason}" for c, _ in tried))
    # the best score; where a labelling of the mesh itself is valid, among the results at
    # least as faithful as it (that labelling among them, scored by its realising polycube's
    # loops): never less faithful than a valid labelling the mesh already has; a repaired
    # one (the graph-cut labelling or the guide) is a floor too unless ``bound`` is
    # Floor.VALID (a coarser labelling may then score better with fewer loops)
    found_results = _above_floor(found_results, floor, which, bound, knobs)
    best_c, best = max(found_results,
                       key=lambda cr: cr[0].score if cr[0].score is not None else -float("inf"))
    rows = [*(c for c, _ in tried), *(c for c, _ in own_rows)]
    grafted = _grafted(surface, best, best_c, donors, knobs, began)
    if grafted is not None:
        best_c, best = grafted
        rows.append(best_c)
    merged = _merged(best, best_c, knobs, began, _floor_of(floor, which, bound), None if merge else FREE)
    if merged is not None:
        best_c, best = merged
        rows.append(best_c)
    return replace(best, seconds=time.monotonic() - began, score=best_c.score,
                   candidates=tuple(replace(c, kept=c is best_c) for c in rows),
                   converged=best.converged and all(c.converged is not False for c, _ in tried))


GRAFTING = 0.5  # of the budget, the most the grafting of patches into the result takes


def _grafted(surface: Surface, best: SegmentResult, row: Candidate, donors: Sequence[np.ndarray],
             knobs: SearchSettings, began: float) -> tuple[Candidate, SegmentResult] | None:
    """The run's result with the patches of the ``donors`` (labellings of the input mesh: the
    graph-cut ones, or the guide) that keep it valid and raise its score grafted into it
    (:func:`~polyloops.segment.graft.graft_labels`), polished, and its row; ``None`` when
    nothing was grafted or the grafted labelling does not score better than ``row`` (its loops
    counted on the checker's polycube)."""
    if not donors:
        return None
    t0 = time.monotonic()
    mesh, parent, own = best.mesh, np.asarray(best.face_map), _own_surface(best)
    target = None if knobs.guide is None else knobs.guide[parent]
    done = graft_labels(own, mesh.labels, [d[parent] for d in donors], knobs.price,
                        t0 + GRAFTING * knobs.budget, target, best.report)
    if not done.kept:
        return None
    labels, moved = polish_labels(own, done.labels, target)
    whose = "the guide" if knobs.guide is not None else "graph-cut labellings"
    how = f"{best.start}, grafted ({done.kept} patches of {whose})"
    result = None
    if moved:
        result = _kept_labelling(own, labels, f"{how}, polished ({moved} triangles moved)", began,
                                 parent=parent, input_triangles=best.input_triangles)
    if result is None:
        result = _kept_labelling(own, done.labels, how, began, done.report, parent, best.input_triangles)
    if result is None:
        return None
    if knobs.guide is not None:
        result = replace(result, guide_changed=_changed(own.areas, knobs.guide[parent], result.mesh.labels))
    candidate = _candidate(result, knobs, time.monotonic() - t0)
    if candidate.score is None or row.score is None or candidate.score <= row.score:
        return None
    return candidate, replace(result, states=best.states, converged=best.converged)


MERGING = 0.25  # of the budget, the most the merges of the result's charts take
# the fidelity a merge may lose without --merge: none that normals computed from single-precision
# coordinates (STL) can tell, such as a 45-degree face's label turned to its other nearest axis
FREE = 1e-6


def _merged(best: SegmentResult, row: Candidate, knobs: SearchSettings, began: float,
            floor: float | None, lose: float | None = None) -> tuple[Candidate, SegmentResult] | None:
    """The run's result with whole charts relabelled as a neighbour, merged
    (:func:`~polyloops.segment.merge.merges`), where that scores better than ``row`` (fewer
    loops on the checker's polycube paying for the fidelity, or the agreement with the guide,
    lost), and its row; ``None`` when no merge does.  No merge aims lower than ``floor``, or
    than its aim less the price of all the result's loops (it could not score better), or
    less ``lose`` when given."""
    if row.score is None:
        return None
    t0 = time.monotonic()
    mesh, parent, own = best.mesh, np.asarray(best.face_map), _own_surface(best)
    target = None if knobs.guide is None else knobs.guide[parent]
    aim = _aim((row, best), knobs)
    loss = knobs.price * best.loops if lose is None else min(lose, knobs.price * best.loops)
    least = max(aim - loss, -1.0 if floor is None else floor)
    chosen, to_beat = None, row.score
    for k, step in enumerate(merges(own, label_indices(mesh.labels), least,
                                    deadline=t0 + MERGING * knobs.budget, target=target), start=1):
        how = f"{best.start}, merged ({k} chart{'s' if k > 1 else ''} relabelled)"
        result = _kept_labelling(own, tuple(Direction(int(d)) for d in step.labels), how, began, step.report,
                                 parent, best.input_triangles)
        if result is None:
            continue
        if target is not None:
            result = replace(result, guide_changed=_changed(own.areas, target, result.mesh.labels))
        candidate = _candidate(result, knobs, time.monotonic() - t0)
        if candidate.score is not None and candidate.score > to_beat:
            chosen = candidate, replace(result, states=best.states, converged=best.converged)
            to_beat = candidate.score
    return chosen


Scouted = tuple[Start, tuple[frozenset[int], ...]]  # a start at its best state, and its search's last states


def _scout_job(job: tuple[Surface, Recipe, float, SearchSettings, np.ndarray, np.ndarray | None, float,
                          Callable[[State], None] | None]
               ) -> tuple[Candidate, Scouted | None]:
    """One recipe built and searched for ``share`` seconds (in a worker process or here): its
    row (with the estimate of its best state), and the start of its best state (the cut
    surface, the candidates and paths drawn, the chosen loops) with its search's last states
    (their loops, the last first), or ``None`` when it gave none.
    A recipe begun after the budget is spent is skipped."""
    surface, recipe, began, knobs, deformed, mapped, share, on_step = job
    t0 = time.monotonic()
    if t0 - began > knobs.budget:
        return Candidate(recipe.name, False, "not begun: the time budget was spent"), None
    try:
        deadline = t0 + max(knobs.budget / 4, 3.0)
        r, loops, chosen, how = build_start(surface, recipe, deadline, deformed, mapped)
    except StartError as err:
        return Candidate(recipe.name, False, str(err), seconds=time.monotonic() - t0), None
    path = greedy_search(r, loops, chosen, replace(knobs, budget=share), on_step)
    best = path.states[-1]
    # ranked by its rough layout polished (the search's own score is optimistic where regions
    # are large: a cube's octant may take any of its three labels anywhere)
    target = None if knobs.guide is None else knobs.guide[r.parent]
    estimate = polished_fidelity(r, best.embedded, target) - knobs.price * len(best.loops)
    row = Candidate(how, False, "", estimate=estimate, loops=len(best.loops), price=knobs.price,
                    seconds=time.monotonic() - t0, converged=path.converged)
    return row, ((r, list(path.loops), sorted(best.loops), how),
                 tuple(state.loops for state in reversed(path.states[-FINALISTS:])))


def _lay_out_job(job: tuple[Surface, Scouted, Candidate, float, SearchSettings,
                           Callable[[State], None] | None]) -> tuple[Candidate, SegmentResult | None]:
    """A scouted start searched on from its best state and laid out (the scouting search's
    last states among the finalists): its row, and its result when certified."""
    surface, (found, earlier), scouted, began, knobs, on_step = job
    t0 = time.monotonic()
    try:
        result = _search_from(surface, found, began, knobs, on_step, earlier)
    except UncertifiedError as err:
        return replace(scouted, reason=str(err), seconds=scouted.seconds + time.monotonic() - t0), None
    row = replace(_candidate(result, knobs, scouted.seconds + time.monotonic() - t0),
                  estimate=scouted.estimate, converged=bool(scouted.converged and result.converged))
    return row, replace(result, candidates=())


def _merged_alone(given: SegmentResult, knobs: SearchSettings, began: float, lose: float | None
                  ) -> SegmentResult:
    """``given``, the only start tried, or its charts merged (:func:`_merged`, no floor) where
    that scores better: then both are rows, the merged one kept."""
    merged = _merged(given, given.candidates[0], knobs, began, None, lose)
    if merged is None:
        return given
    row, coarser = merged
    return replace(coarser, seconds=time.monotonic() - began, score=row.score,
                   candidates=(replace(given.candidates[0], kept=False), replace(row, kept=True)))


def _alone(result: SegmentResult, knobs: SearchSettings) -> SegmentResult:
    """``result`` as the only start tried."""
    row = replace(_candidate(result, knobs, result.seconds), kept=True)
    return replace(result, candidates=(row,), score=row.score)


def _above_floor(rows: list[tuple[Candidate, SegmentResult]], floor: float | None, which: Charts,
                 bound: Floor, knobs: SearchSettings) -> list[tuple[Candidate, SegmentResult]]:
    """The ``rows`` whose aim (:func:`_aim`) is at least ``floor``, the aim of the mesh's own
    valid labelling (``None``: there is none, all rows), ``which`` says what that labelling is:
    a repaired one (the graph-cut labelling or the guide) bounds the rows only when ``bound``
    is :attr:`Floor.REPAIRED`."""
    floor = _floor_of(floor, which, bound)
    return rows if floor is None else [row for row in rows if _aim(row, knobs) >= floor]


def _floor_of(floor: float | None, which: Charts, bound: Floor) -> float | None:
    """The floor that holds (see :func:`_above_floor`), or ``None``."""
    if floor is None or (bound is Floor.VALID and which in (Charts.REPAIRED, Charts.GUIDE)):
        return None
    return floor


def _aim(row: tuple[Candidate, SegmentResult], knobs: SearchSettings) -> float:
    """What a run maximises before the loops' price: the agreement with the guide, or the
    fidelity."""
    candidate, result = row
    if knobs.guide is not None and candidate.agreement is not None:
        return candidate.agreement
    return result.fidelity


def _own_surface(result: SegmentResult) -> Surface:
    """The surface of a result's (refined) labelled mesh, for labellings of it."""
    mesh = result.mesh
    return Surface(np.asarray(mesh.points, dtype=float), np.asarray(mesh.triangles, dtype=np.int64))


def _changed(areas: np.ndarray, wanted: np.ndarray, labels: Sequence[Direction]) -> float:
    """The share of the area whose label is not the one ``wanted`` (a unit vector per
    triangle)."""
    given = label_vectors(labels)
    return float(areas[(wanted * given).sum(axis=1) < 0.5].sum() / areas.sum())


def _candidate(result: SegmentResult, knobs: SearchSettings, seconds: float) -> Candidate:
    """The row of a certified result."""
    agreement = None
    if knobs.guide is not None:
        if result.layout is not None:
            refined = result.layout.embedded.refined
            agreement = fidelity(refined.surface, result.layout.labels, knobs.guide[refined.parent])
        else:  # a labelling of the mesh itself
            own = _own_surface(result)
            agreement = fidelity(own, result.mesh.labels, knobs.guide[np.asarray(result.face_map)])
    aim = result.fidelity if agreement is None else agreement
    score = result.score if result.score is not None else aim - knobs.price * result.loops
    return Candidate(result.start, True, "", fidelity=result.fidelity, agreement=agreement,
                     loops=result.loops, price=knobs.price, score=score, charts=result.charts,
                     corners=result.corners, seconds=seconds, converged=result.converged)


def _direct(surface: Surface, began: float, donors: list[np.ndarray] | None = None
            ) -> tuple[SegmentResult, Charts] | None:
    """A valid labelling of the mesh itself and which it is, or ``None``: the per-triangle
    labelling when the checker finds it valid (it builds a polycube that realises it; no
    labelling is more faithful, so it is kept as it is); else the graph-cut labelling, made
    valid by :func:`_made_valid`.  Where there is one, a search's result is kept only when it
    is at least as faithful and scores better (:func:`segment_surface`).  The graph-cut
    labelling is appended to ``donors``."""
    how = "the per-triangle labelling, valid as it is"
    naive = _kept_labelling(surface, naive_labels(surface), how, began)
    if naive is not None:
        return naive, Charts.NAIVE
    standard = graphcut_labels(surface)
    if donors is not None:
        donors.append(label_indices(standard))
    return _made_valid(surface, standard, "the graph-cut labelling", began)


def _made_valid(surface: Surface, labels: Sequence[Direction], name: str, began: float
                ) -> tuple[SegmentResult, Charts] | None:
    """``labels`` as a result where the checker finds them valid as they are or repaired
    (:func:`~polyloops.segment.repair.repair_labels`), polished where that makes them more
    faithful (the same charts, boundaries and corners, triangles moved to a chart beside them:
    :func:`~polyloops.segment.polish.polish_labels`), with which they are (valid as given or
    repaired); ``None`` where the repair fails."""
    how, which = f"{name}, valid", Charts.GRAPH_CUT
    as_it_is = _kept_labelling(surface, labels, f"{how} as it is", began)
    if as_it_is is None:
        # invalid for local reasons (a thin part's sides meeting, specks, islands): repaired
        repaired = repair_labels(surface, labels)
        if repaired is None:
            return None
        labels, which = repaired.labels, Charts.REPAIRED
        how = f"{name}, repaired ({repaired.charts} charts changed)"
        as_it_is = _kept_labelling(surface, labels, how, began, repaired.report)
        if as_it_is is None:
            return None
    polished, moved = polish_labels(surface, labels)
    if moved and fidelity(surface, polished) > as_it_is.fidelity:
        how = f"{how}, polished ({moved} triangles moved)"
        return _kept_labelling(surface, polished, how, began) or as_it_is, which
    return as_it_is, which


def _other_weights(surface: Surface, began: float, workers: int, donors: list[np.ndarray]
                   ) -> list[SegmentResult]:
    """The valid labellings (as they are or repaired, polished) of the graph-cut labellings of
    lighter compactness (:data:`FINER`: closer to the per-triangle labelling, with more
    charts) and of heavier (:data:`COARSER`: fewer charts and loops); candidates beside the
    others, scored alike.  The lighter graph-cut labellings are appended to ``donors``."""
    jobs = [(surface, compactness, began) for compactness in (*FINER, *COARSER)]
    out = []
    made = run_jobs(_weight_job, jobs, workers=workers)
    for (_, compactness, _), (labels, found) in zip(jobs, made, strict=True):
        if compactness in FINER:
            donors.append(labels)
        if found is not None:
            out.append(found)
    return out


def _weight_job(job: tuple[Surface, float, float]) -> tuple[np.ndarray, SegmentResult | None]:
    surface, compactness, began = job
    name = f"the graph-cut labelling of compactness {compactness:g}"
    labels = graphcut_labels(surface, compactness)
    made = _made_valid(surface, labels, name, began)
    return label_indices(labels), None if made is None else made[0]


def _kept_labelling(surface: Surface, labels: Sequence[Direction], how: str, began: float,
                    report: SegmentationReport | None = None, parent: np.ndarray | None = None,
                    input_triangles: int | None = None) -> SegmentResult | None:
    """A labelling of the mesh itself as the result, when the checker finds it valid and
    builds a polycube that realises it (no loops were drawn: the layout is ``None``;
    ``report``: the checker's, when it was made already).  ``surface`` may be the input
    refined, ``parent`` giving each of its triangles' input triangle, of ``input_triangles``."""
    mesh = surface.labelled(labels)
    report = check_segmentation(mesh) if report is None else report
    if report.valid is not True or report.polycube is None:
        return None
    loops = len(dualize(report.polycube).loops)
    face_map = tuple(range(len(surface.triangles))) if parent is None else tuple(int(p) for p in parent)
    return SegmentResult(mesh, face_map, report.polycube, report, surface.genus,
                         len(surface.triangles) if input_triangles is None else input_triangles, loops,
                         fidelity(surface, labels), naive_fidelity(surface),
                         time.monotonic() - began, 0, True, None, how)


def _search_from(surface: Surface, found: Start, began: float, knobs: SearchSettings,
                 on_step: Callable[[State], None] | None,
                 earlier: Sequence[frozenset[int]] = ()) -> SegmentResult:
    """The search from one start, its last states laid out and certified; the finalist whose
    labels score best (fidelity, or agreement with the guide, less the loops' price) is kept.
    ``earlier``: the states of a search before this one (their loops, the last first), the
    finalists after this search's own."""
    budget, price = knobs.budget, knobs.price
    r, loops, first, how = found
    # the budget covers the whole run: the cut above, the search, and a reserve for the layout
    # and the checks of the finalists after it (each about 0.5 to 1.5 s on the shared meshes);
    # a start that took longer (a grid mended at positive genus) still leaves the search a
    # quarter of the budget, as a start is seldom the best state and may not lay out
    left = budget - (time.monotonic() - began)
    settings = replace(knobs, budget=max(SEARCH_SHARE * budget, 0.65 * left))
    searched = greedy_search(r, loops, first, settings, on_step)
    pool = searched.loops  # the candidates and the paths the search drew
    path = searched.states
    # The last states are laid out and certified, and the one whose labels score best is kept
    # (the search's estimate and the labels' fidelity mostly agree, not always); when none of
    # them passes, the states before them are tried, best first, until one does (past the
    # finalists, only while the budget lasts: the next start may do better).
    why, best = "", None
    ways = [True, False]  # the layouts tried: following the labels, then by the middles
    deadline = time.monotonic() + max(budget - (time.monotonic() - began), SEARCH_SHARE * budget)
    finalists = [state.loops for state in reversed(path)] + [e for e in earlier if e != path[0].loops]
    for k, loops_of in enumerate(finalists):
        if k >= FINALISTS and (best is not None or time.monotonic() > deadline):
            break
        if best is not None and time.monotonic() - began > budget:
            break
        laid = _laid_out(r, [pool[i] for i in sorted(loops_of)], ways, knobs.guide)
        if isinstance(laid, str):
            why = laid
            continue
        lay, checked = laid
        refined = lay.embedded.refined
        fid = fidelity(refined.surface, lay.labels)
        aim = fid if knobs.guide is None else fidelity(refined.surface, lay.labels,
                                                       knobs.guide[refined.parent])
        score = aim - price * len(loops_of)
        if best is None or score > best[0]:
            best = (score, fid, loops_of, lay, checked)
    if best is None:
        raise UncertifiedError(f"no state of the search was certified: {why}")
    score, fid, kept, lay, (mesh, report) = best
    refined = lay.embedded.refined
    changed = None
    if knobs.guide is not None:  # the share of the area whose label is not the guide's
        changed = _changed(refined.surface.areas, knobs.guide[refined.parent], lay.labels)
    return SegmentResult(mesh, tuple(int(p) for p in refined.parent.tolist()), lay.polycube, report,
                         surface.genus, len(surface.triangles), len(kept), fid,
                         naive_fidelity(surface), time.monotonic() - began, len(path), searched.converged,
                         lay, how, changed, score)


SEARCH_SHARE = 0.25  # of the budget, the least the search is given whatever the start took
SCOUTING = 0.4  # of the budget (times the workers), shared by the starts' scouting searches
LAID_OUT = 2  # the best-ranked scouted starts searched on and laid out (at least; one per worker)
FINALISTS = 4  # the last states of the search laid out and certified, the best labels kept


def segment_mesh(points: Sequence[Sequence[float]] | np.ndarray,
                 triangles: Sequence[Sequence[int]] | np.ndarray, budget: float = 20.0, seed: int = 0,
                 planes: int = 9, price: float = PRICE,
                 on_step: Callable[[State], None] | None = None,
                 start: LoopStructure | None = None,
                 guide: Sequence[Direction] | None = None, direct: bool = True, workers: int = 1,
                 on_candidate: Callable[[Candidate], None] | None = None,
                 bound: Floor = Floor.REPAIRED, merge: bool = False) -> SegmentResult:
    """A certified polycube segmentation of the closed triangle mesh ``points``, ``triangles``
    (counter-clockwise seen from outside), by the greedy loop search of
    :mod:`~polyloops.segment.search` within ``budget`` seconds (its order fixed by ``seed``):
    from ``start`` when given (a polycube loop structure of the mesh's genus, embedded by
    :mod:`~polyloops.segment.start`), else from each start of
    :func:`~polyloops.segment.starts.recipes` (the levels of the surface and of its
    polycube-like deformation, and the cube at genus 0), ``workers`` at a time, scouted and
    the best-ranked laid out, the best score kept (``candidates`` lists each, and
    ``on_candidate`` is called with each as it ends), and from grids of section curves when
    none of them is certified.  ``on_step`` is called with
    each state a search moves to, in this process only (not with ``workers`` > 1).  With a
    ``guide`` (a label per triangle, from any method, valid or not) the search keeps as much
    of it as it can instead of following the normals: a valid guide is returned unchanged,
    and otherwise ``guide_changed`` reports the share of the area labelled otherwise.
    Without a start or a guide, the mesh's own naive and graph-cut labellings are candidates
    where the checker finds them valid (``direct=False``: the search's segmentation, with its
    loops, whatever they are): the result is then the best score among the results at least
    as faithful as that labelling (it included, priced by its realising polycube's loops);
    ``bound`` says whether the graph-cut labelling (or the guide) repaired is such a floor
    (:attr:`Floor.REPAIRED`, the default) or only a candidate (:attr:`Floor.VALID`).  Whole
    charts of the result are relabelled as a neighbour where that costs no fidelity and saves
    loops; with ``merge``, wherever the loops saved pay for the fidelity lost (fewer charts
    and loops, a little less faithful, never below the floor; :mod:`~polyloops.segment.merge`).

    Raises
    ------
    SurfaceError
        When the mesh is not a closed, oriented, connected manifold surface with some area.
    StartMismatch
        When ``start`` has another genus than the mesh, or is no polycube loop structure.
    StartError
        When no start was found (no cube, and no grid that is a polycube loop structure; or
        the given start is not reproduced by plane sections).
    UncertifiedError
        When no state of the search passed both checks (nothing is returned then).
    """
    return segment_surface(surface_of(points, triangles), budget, seed, planes, price, on_step, start, guide,
                           direct, workers, on_candidate, bound, merge)
