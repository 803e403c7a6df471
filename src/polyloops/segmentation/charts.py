"""Charts, boundaries and corners of a labelled triangle mesh.

A *chart* is a maximal edge-connected set of triangles with one label.  A *boundary* is a
maximal path of mesh edges between two charts; it runs from corner to corner, or is a closed
curve without corners.  A *corner* is a mesh vertex where three or more boundaries meet.

Boundaries are walked with their ``left`` chart on the left (seen from outside), so the
surface orientation fixes one of their two directions.  Around a corner, ``sides`` lists the
boundaries counter-clockwise seen from outside, each with the chart that follows it.

>>> from polyloops.io.examples import load_example
>>> from polyloops.surface.construct import labelled_mesh_from_polycube
>>> seg = segment(labelled_mesh_from_polycube(load_example("cube")))
>>> len(seg.charts), len(seg.boundaries), len(seg.corners)
(6, 12, 8)
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

from polyloops.core.directions import Axis, Direction
from polyloops.core.disjoint_sets import DisjointSets
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.surface.mesh import LabelledMesh


@dataclass(frozen=True)
class Chart:
    """A chart: a maximal connected set of triangles with one label, with its boundary cycles."""

    id: int
    label: Direction
    triangles: tuple[int, ...]
    euler_characteristic: int  # of the chart as a surface with boundary, split where it touches itself
    cycles: tuple[tuple[tuple[int, bool], ...], ...]  # its boundary curves: (boundary, walked forward)

    @property
    def holes(self) -> int:
        """The number of boundary cycles beyond the first."""
        return len(self.cycles)

    @property
    def genus(self) -> int:
        """Handles inside the chart (a planar region has none)."""
        return (2 - self.euler_characteristic - self.holes) // 2


@dataclass(frozen=True)
class Boundary:
    """A boundary: a maximal curve between two charts, from corner to corner (or closed)."""

    id: int
    left: int
    right: int
    vertices: tuple[int, ...]  # mesh vertices along it; for a closed one the first is not repeated
    start: int | None  # corner ids; None for a closed boundary
    end: int | None

    @property
    def closed(self) -> bool:
        """Whether the boundary is a closed curve without corners."""
        return self.start is None


@dataclass(frozen=True)
class Corner:
    """A corner of a segmentation: a point where three or more charts meet."""

    id: int
    vertex: int
    sides: tuple[tuple[int, bool, int], ...]  # (boundary, leaves from the boundary's start, next chart)


@dataclass(frozen=True)
class Segmentation:
    """The charts, boundaries and corners of a labelled mesh."""

    mesh: LabelledMesh
    map: HalfEdgeMap
    chart_of_triangle: tuple[int, ...]
    charts: tuple[Chart, ...]
    boundaries: tuple[Boundary, ...]
    corners: tuple[Corner, ...]

    def boundary_axis(self, b: int) -> Axis | None:
        """The axis a boundary runs along: the one normal to both its charts' labels (``None``
        when the labels share an axis, which no polycube allows)."""
        bd = self.boundaries[b]
        a, c = self.charts[bd.left].label.axis, self.charts[bd.right].label.axis
        return None if a == c else Axis(3 - a - c)

    @cached_property
    def chart_angles(self) -> dict[int, list[tuple[int, bool, int, bool]]]:
        """Per chart, its angles at corners between two perpendicular boundaries (see
        :func:`polyloops.segmentation.levels.chart_angles`), from one pass over the corners."""
        out: dict[int, list[tuple[int, bool, int, bool]]] = {}
        for corner in self.corners:
            sides = corner.sides
            for i, (b, forward, ch) in enumerate(sides):
                b2, forward2, _ = sides[(i + 1) % len(sides)]
                if self.boundary_axis(b) != self.boundary_axis(b2):
                    out.setdefault(ch, []).append((b2, forward2, b, forward))
        return out


def segment(mesh: LabelledMesh) -> Segmentation:
    """Charts, boundaries and corners; raises ``MapError`` when the triangles do not form a
    closed, connected, oriented surface."""
    m = HalfEdgeMap.from_faces(mesh.triangles)
    chart_of = _charts(m, mesh.labels)
    face_of, twin, nxt = m.face_of, m.twin, m.next
    on_boundary = [chart_of[face_of[d]] != chart_of[face_of[twin[d]]] for d in range(m.num_darts)]

    def onward(d: int) -> int:
        """The boundary dart leaving target(d) with the same chart on its left."""
        x = nxt[d]
        while not on_boundary[x]:
            x = nxt[twin[x]]
        return x

    boundary_darts_at: dict[int, list[int]] = {}
    for d in range(m.num_darts):
        if on_boundary[d]:
            boundary_darts_at.setdefault(m.origin(d), []).append(d)
    corner_vertices = sorted(v for v, ds in boundary_darts_at.items() if len(ds) >= 3)
    corner_id = {v: i for i, v in enumerate(corner_vertices)}

    # Boundaries from corners, then the closed ones.
    boundary_of_dart: dict[int, tuple[int, bool]] = {}
    boundaries: list[Boundary] = []

    def walk(first: int, stop) -> list[int]:
        darts = [first]
        while not stop(m.target(darts[-1])) and (d := onward(darts[-1])) != first:
            darts.append(d)
        return darts

    for v in corner_vertices:
        for d in m.outgoing(v):
            if on_boundary[d] and d not in boundary_of_dart:
                darts = walk(d, lambda w: w in corner_id)
                _add_boundary(boundaries, boundary_of_dart, darts, m, chart_of, twin,
                              corner_id[v], corner_id[m.target(darts[-1])])
    for d in range(m.num_darts):
        if on_boundary[d] and d not in boundary_of_dart:
            darts = walk(d, lambda w: False)
            _add_boundary(boundaries, boundary_of_dart, darts, m, chart_of, twin, None, None)

    corners = []
    for v in corner_vertices:
        sides = []
        for d in m.outgoing(v):
            if on_boundary[d]:
                b, forward = boundary_of_dart[d]
                sides.append((b, forward, chart_of[face_of[d]]))
        corners.append(Corner(corner_id[v], v, tuple(sides)))

    charts = _chart_records(m, mesh, chart_of, on_boundary, boundary_of_dart, onward)
    return Segmentation(mesh, m, tuple(chart_of), charts, tuple(boundaries), tuple(corners))


def _charts(m: HalfEdgeMap, labels) -> list[int]:
    sets: DisjointSets[int] = DisjointSets()
    for d in range(m.num_darts):
        f, g = m.face_of[d], m.face_of[m.twin[d]]
        sets.find(f)
        if f < g and labels[f] == labels[g]:
            sets.union(f, g)
    ids: dict[object, int] = {}
    return [ids.setdefault(sets.find(f), len(ids)) for f in range(m.num_faces)]


def _add_boundary(boundaries, boundary_of_dart, darts, m, chart_of, twin, start, end) -> None:
    b = len(boundaries)
    for d in darts:
        boundary_of_dart[d] = (b, True)
        boundary_of_dart[twin[d]] = (b, False)
    vertices = [m.origin(d) for d in darts]
    if start is not None:
        vertices.append(m.target(darts[-1]))
    boundaries.append(Boundary(b, chart_of[m.face_of[darts[0]]], chart_of[m.face_of[twin[darts[0]]]],
                               tuple(vertices), start, end))


def _chart_records(m, mesh, chart_of, on_boundary, boundary_of_dart, onward) -> tuple[Chart, ...]:
    n = max(chart_of) + 1
    triangles: list[list[int]] = [[] for _ in range(n)]
    for f, c in enumerate(chart_of):
        triangles[c].append(f)
    vertices: list[set[int]] = [set() for _ in range(n)]
    rim: list[set[int]] = [set() for _ in range(n)]  # vertices on the chart's boundary
    edges = [0] * n  # darts of the chart's triangles, counting each interior edge twice
    boundary_edges = [0] * n
    for d in range(m.num_darts):
        c = chart_of[m.face_of[d]]
        vertices[c].add(m.origin(d))
        edges[c] += 1
        if on_boundary[d]:
            boundary_edges[c] += 1
            rim[c].add(m.origin(d))
    cycles: list[list[tuple[tuple[int, bool], ...]]] = [[] for _ in range(n)]
    seen = set()
    for d in range(m.num_darts):
        if not on_boundary[d] or d in seen:
            continue
        sides: list[tuple[int, bool]] = []
        x = d
        while x not in seen:
            seen.add(x)
            side = boundary_of_dart[x]
            if not sides or sides[-1] != side:
                sides.append(side)
            x = onward(x)
        if len(sides) > 1 and sides[0] == sides[-1]:
            sides.pop()  # the walk started inside a boundary
        cycles[chart_of[m.face_of[d]]].append(tuple(sides))
    out = []
    for c in range(n):
        e = (edges[c] + boundary_edges[c]) // 2
        # A chart may touch itself at a corner; split there (one vertex per sector of the
        # chart, and a boundary vertex has one sector per boundary edge leaving it inside
        # the chart), it is a surface whose Euler characteristic the turning numbers obey.
        sectors = len(vertices[c]) - len(rim[c]) + boundary_edges[c]
        chi = sectors - e + len(triangles[c])
        out.append(Chart(c, mesh.labels[triangles[c][0]], tuple(triangles[c]), chi, tuple(cycles[c])))
    return tuple(out)
