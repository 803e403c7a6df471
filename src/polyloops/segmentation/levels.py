"""The global test: level graphs of a labelled segmentation.

For an axis ``A``, corners that must share their ``A`` coordinate form a *zone*: the
corners of a chart normal to ``A``, and the two ends of a boundary not parallel to ``A``.
Each boundary parallel to ``A`` is an arc between two zones, from its low end to its high
end; as in the paper's level graphs (Definition 4, Condition 5), a polycube needs every such
arc to join two different zones and the arcs of each axis to have no directed cycle.

Which end of a boundary is low is not a function of the two labels alone: a boundary
between ``+Z`` and ``+X`` charts runs along ``+Y`` where the edge is convex and along ``-Y``
where it is concave.  So each boundary gets a Boolean variable, its direction.  What ties
them together are the corners: the directions of the boundaries around a corner, with the
labels of the charts between them, must be a corner some polycube has (the chart views of
the 126 configurations).  And the charts: a chart is a region of a plane, so the turns of
its boundary curves add up to its Euler characteristic (in whole turns; Hopf's
Umlaufsatz for each curve, outer ones counter-clockwise and holes clockwise seen from the
label's side).  At a corner, the directions of the two boundaries of a chart make its
angle there 90, 180 or 270 degrees, a turn of +1, 0 or -1 quarter; so a chart with ``N``
right angles or reflex angles needs exactly ``(N - 4 chi) / 2`` reflex ones, a cardinality
constraint.  A SAT solver (python-sat) looks for directions that satisfy every
corner and leave every level graph acyclic; acyclicity is added lazily, as in
:mod:`polyloops.solvers.sat`: each directed cycle found becomes the clause "one of its
boundaries points the other way".

When there are no such directions, the unsatisfiable core names a witness: the corners whose
rules and the cycles whose cuts cannot all hold.  Reversing every direction keeps every
corner rule (negating all the directions of a corner keeps the normals ``a x b``) and
reverses every arc, so solutions come in pairs: the two mirror images of one polycube, one
of them inside out (see :mod:`polyloops.segmentation.realise`).
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import product
from typing import Any

from pysat.card import CardEnc, EncType
from pysat.solvers import Solver

from polyloops.core.corners import canonical_rotation, cross
from polyloops.core.directions import Axis, Direction
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.zones import find_directed_cycle
from polyloops.generate.corners import chart_corners
from polyloops.segmentation.charts import Segmentation
from polyloops.solvers.sat import minimal_core


@dataclass(frozen=True)
class Cycle:
    """A cycle of one level graph, as the boundaries along it."""

    axis: Axis
    boundaries: tuple[int, ...]


@dataclass(frozen=True)
class Witness:
    """Why no polycube realises the labels."""

    kind: str  # "arc-inside-zone" or "no-directions"
    corners: tuple[int, ...] = ()
    cycles: tuple[Cycle, ...] = ()
    boundaries: tuple[int, ...] = ()  # for an arc inside a zone: that boundary
    turning: tuple[int, ...] = ()  # charts whose turning-number constraint takes part

    def charts(self, seg: Segmentation) -> tuple[int, ...]:
        """The charts whose turning numbers the witness uses."""
        found = set()
        for b in self.all_boundaries():
            found |= {seg.boundaries[b].left, seg.boundaries[b].right}
        for c in self.corners:
            found |= {chart for _, _, chart in seg.corners[c].sides}
        return tuple(sorted(found | set(self.turning)))

    def all_boundaries(self) -> tuple[int, ...]:
        """Every boundary the witness names."""
        return tuple(sorted({*self.boundaries, *(b for cyc in self.cycles for b in cyc.boundaries)}))

    def describe(self, seg: Segmentation) -> str:
        """The witness in one sentence."""
        if self.kind == "arc-inside-zone":
            b = seg.boundaries[self.boundaries[0]]
            axis = seg.boundary_axis(b.id)
            return (f"boundary {b.id} runs along {axis} but its two ends must have the same {axis} "
                    "coordinate (they are joined by charts normal to it and boundaries across it)")
        parts = []
        if self.corners:
            parts.append(f"the rules of corners {', '.join(map(str, self.corners))}")
        if self.turning:
            parts.append(f"the turning numbers of charts {', '.join(map(str, self.turning))}")
        for cyc in self.cycles:
            parts.append(f"a {cyc.axis} cycle through boundaries {', '.join(map(str, cyc.boundaries))}")
        return "no directions of the boundaries avoid " + " and ".join(parts)

    def to_json(self, seg: Segmentation) -> dict[str, object]:
        """A JSON-ready dict of the witness."""
        return {"kind": self.kind, "message": self.describe(seg), "corners": list(self.corners),
                "boundaries": list(self.all_boundaries()), "charts": list(self.charts(seg)),
                "turning": list(self.turning),
                "cycles": [{"axis": c.axis.name, "boundaries": list(c.boundaries)} for c in self.cycles]}


@dataclass(frozen=True)
class GlobalResult:
    """The global test's verdict, its reason, and a witness when invalid."""

    valid: bool | None
    reason: str = ""
    witness: Witness | None = None
    directions: tuple[int, ...] = ()  # per boundary: +1 when it runs from start to end along +axis
    zones: tuple[tuple[int, ...], ...] = ()  # per axis: the zone of each corner

    def to_json(self, seg: Segmentation) -> dict[str, object]:
        """A JSON-ready dict of the verdict."""
        return {"valid": self.valid, "reason": self.reason,
                "witness": None if self.witness is None else self.witness.to_json(seg)}


def corner_zones(seg: Segmentation, axis: Axis) -> tuple[int, ...]:
    """The zone of each corner along ``axis``, numbered from 0 in order of first corner."""
    sets: DisjointSets[int] = DisjointSets()
    for c in seg.corners:
        sets.find(c.id)
    for b in seg.boundaries:
        if b.start is not None and b.end is not None and seg.boundary_axis(b.id) != axis:
            sets.union(b.start, b.end)
    for chart in seg.charts:
        if chart.label.axis == axis:
            ends = [e for cycle in chart.cycles for b, _ in cycle
                    for e in (seg.boundaries[b].start, seg.boundaries[b].end) if e is not None]
            for e in ends[1:]:
                sets.union(ends[0], e)
    ids: dict[object, int] = {}
    return tuple(ids.setdefault(sets.find(c.id), len(ids)) for c in seg.corners)


def corner_rule(seg: Segmentation, corner: int) -> tuple[tuple[int, ...], list[tuple[int, ...]]]:
    """The boundaries at a corner and the sign tuples (+1: from start to end along +axis) the
    chart views of the 126 configurations allow for them."""
    sides = seg.corners[corner].sides
    bs = tuple(sorted({b for b, _, _ in sides}))
    allowed = chart_corners()
    ok = []
    for signs in product((1, -1), repeat=len(bs)):
        sign = dict(zip(bs, signs, strict=True))
        pairs = []
        for b, forward, chart in sides:
            axis = seg.boundary_axis(b)
            assert axis is not None
            pairs.append((Direction.of(axis, sign[b] if forward else -sign[b]), seg.charts[chart].label))
        if canonical_rotation(pairs) in allowed:
            ok.append(signs)
    return bs, ok


def check_global(seg: Segmentation, max_cuts: int = 10_000, try_mesh_first: bool = True) -> GlobalResult:
    """Directions for the boundaries that satisfy every corner and chart and keep every level
    graph acyclic, or a witness that there are none.  The directions the mesh's own
    coordinates give are tried first (``try_mesh_first``), then the solver's."""
    if any(seg.boundary_axis(b.id) is None for b in seg.boundaries):
        return GlobalResult(None, "a boundary lies between opposite labels, so it has no axis")
    if any(b.closed for b in seg.boundaries):
        return GlobalResult(None, "a boundary without corners has no ends to order")
    zones = tuple(corner_zones(seg, axis) for axis in Axis)
    for b in seg.boundaries:
        axis = seg.boundary_axis(b.id)
        assert axis is not None and b.start is not None and b.end is not None
        if zones[axis][b.start] == zones[axis][b.end]:
            return GlobalResult(False, "a boundary joins a zone to itself", Witness("arc-inside-zone",
                                corners=(b.start, b.end), boundaries=(b.id,)), zones=zones)
    arcs_by_axis = _arcs_by_axis(seg)
    rules = [corner_rule(seg, c.id) for c in seg.corners]
    geometric = mesh_directions(seg)
    if try_mesh_first and satisfies(seg, zones, geometric, rules):
        return GlobalResult(True, directions=geometric, zones=zones)
    nb = len(seg.boundaries)
    selectors: dict[int, tuple[str, Any]] = {}
    next_var = nb + 1
    with Solver(name="glucose4") as solver:
        for c, (bs, ok) in zip(seg.corners, rules, strict=True):
            sel, next_var = next_var, next_var + 1
            selectors[sel] = ("corner", c.id)
            okset = set(ok)
            for signs in product((1, -1), repeat=len(bs)):
                if signs not in okset:  # forbid this combination while the corner is assumed
                    solver.add_clause([-sel] + [-(b + 1) * s for b, s in zip(bs, signs, strict=True)])
        # Prefer the directions the mesh's own coordinates suggest, so that a realisation
        # can follow the mesh (any solution would do for the verdict).
        solver.set_phases([(b + 1) * d for b, d in enumerate(geometric)])
        for chart in seg.charts:
            sel, next_var = next_var, next_var + 1
            selectors[sel] = ("chart", chart.id)
            clauses, next_var = _turning_clauses(seg, chart.id, next_var)
            for clause in clauses:
                solver.add_clause([-sel, *clause])
        cuts = 0
        while True:
            if not solver.solve(assumptions=list(selectors)):
                # deletion-minimal, whatever its size: each part of the witness is needed
                core = minimal_core(solver, list(solver.get_core() or []), limit=None)
                corners = tuple(sorted(selectors[s][1] for s in core if selectors[s][0] == "corner"))
                charts = tuple(sorted(selectors[s][1] for s in core if selectors[s][0] == "chart"))
                cycles = tuple(selectors[s][1] for s in core if selectors[s][0] == "cycle")
                witness = Witness("no-directions", corners=corners, cycles=cycles, turning=charts)
                return GlobalResult(False, "no directions satisfy the corners and charts with acyclic "
                                    "level graphs", witness, zones=zones)
            model = solver.get_model()
            sign = [1 if model[b] > 0 else -1 for b in range(nb)]
            cycle = _find_cycle(seg, zones, arcs_by_axis, sign)
            if cycle is None:
                return GlobalResult(True, directions=tuple(sign), zones=zones)
            cuts += 1
            if cuts > max_cuts:
                return GlobalResult(None, f"gave up after {max_cuts} cycle cuts")
            sel, next_var = next_var, next_var + 1
            selectors[sel] = ("cycle", cycle)
            solver.add_clause([-sel] + [-(b + 1) * sign[b] for b in cycle.boundaries])


def mesh_steps(seg: Segmentation) -> tuple[float, ...]:
    """How far each boundary goes along its axis, from start to end, in the mesh's own
    coordinates."""
    out = []
    for b in seg.boundaries:
        axis = seg.boundary_axis(b.id)
        assert axis is not None and b.start is not None and b.end is not None
        out.append(seg.mesh.points[seg.corners[b.end].vertex][axis]
                   - seg.mesh.points[seg.corners[b.start].vertex][axis])
    return tuple(out)


def mesh_directions(seg: Segmentation) -> tuple[int, ...]:
    """Each boundary's direction in the mesh's own coordinates (+1 where its ends tie)."""
    return tuple(-1 if step < 0 else 1 for step in mesh_steps(seg))


def _arcs_by_axis(seg: Segmentation) -> dict[Axis, list[int]]:
    """The boundaries along each axis (the arcs of its level graph)."""
    out: dict[Axis, list[int]] = {axis: [] for axis in Axis}
    for b in seg.boundaries:
        out[seg.boundary_axis(b.id)].append(b.id)  # type: ignore[index]
    return out


def satisfies(seg: Segmentation, zones: tuple[tuple[int, ...], ...], directions: tuple[int, ...],
              rules: list[tuple[tuple[int, ...], list[tuple[int, ...]]]] | None = None) -> bool:
    """Whether directions meet every corner rule (``rules``: :func:`corner_rule` of each
    corner, computed here if not given) and chart turning number and leave the level graphs
    acyclic, checked directly (the SAT encoding's slow twin)."""
    for c in seg.corners:
        bs, ok = rules[c.id] if rules is not None else corner_rule(seg, c.id)
        if tuple(directions[b] for b in bs) not in ok:
            return False
    for chart in seg.charts:
        angles = chart_angles(seg, chart.id)
        reflex = 0
        for b2, f2, b, f in angles:
            d = Direction.of(seg.boundary_axis(b), directions[b] if f else -directions[b])  # type: ignore[arg-type]
            d2 = Direction.of(seg.boundary_axis(b2), directions[b2] if f2 else -directions[b2])  # type: ignore[arg-type]
            reflex += cross(d, d2) != chart.label
        if len(angles) - 2 * reflex != 4 * chart.euler_characteristic:
            return False
    return _find_cycle(seg, zones, _arcs_by_axis(seg), directions) is None


def chart_angles(seg: Segmentation, chart: int) -> list[tuple[int, bool, int, bool]]:
    """The chart's angles at corners between two perpendicular boundaries, each as (boundary
    arriving, leaves from its start, boundary leaving, leaves from its start) at that corner,
    the first counter-clockwise after the second."""
    return seg.chart_angles.get(chart, [])


def _turning_clauses(seg: Segmentation, chart: int, next_var: int) -> tuple[list[list[int]], int]:
    """Clauses for "exactly (N - 4 chi) / 2 of the chart's N right-or-reflex angles are
    reflex", with one new variable per angle, and the next free variable."""
    label = seg.charts[chart].label
    clauses: list[list[int]] = []
    reflex_lits = []
    for b2, f2, b, f in chart_angles(seg, chart):
        r, next_var = next_var, next_var + 1
        reflex_lits.append(r)
        a, a2 = seg.boundary_axis(b), seg.boundary_axis(b2)
        assert a is not None and a2 is not None
        for x, x2 in product((1, -1), repeat=2):
            if b == b2 and x != x2:
                continue
            d = Direction.of(a, x if f else -x)  # leaving the corner along b, then ccw to b2
            d2 = Direction.of(a2, x2 if f2 else -x2)
            is_reflex = cross(d, d2) != label
            # (b has sign x and b2 has sign x2) implies r has the value is_reflex
            clauses.append([-(b + 1) * x, -(b2 + 1) * x2, r if is_reflex else -r])
    n = len(reflex_lits)
    chi = seg.charts[chart].euler_characteristic
    want = n - 4 * chi
    if want < 0 or want % 2 or want // 2 > n:
        return [[]], next_var  # impossible: an empty clause, active with the chart's selector
    if n == 0:
        return [], next_var
    card = CardEnc.equals(lits=reflex_lits, bound=want // 2, top_id=next_var - 1, encoding=EncType.seqcounter)
    return clauses + card.clauses, max(next_var, card.nv + 1)


def _find_cycle(seg: Segmentation, zones, arcs_by_axis, sign) -> Cycle | None:
    for axis in Axis:
        arcs = []
        for b in arcs_by_axis[axis]:
            bd = seg.boundaries[b]
            u, v = zones[axis][bd.start], zones[axis][bd.end]
            arcs.append((u, v, b) if sign[b] > 0 else (v, u, b))
        found = find_directed_cycle(max(zones[axis], default=-1) + 1, arcs)
        if found is not None:
            return Cycle(axis, tuple(b for _, _, b in found))
    return None
