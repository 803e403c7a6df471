"""Loop structures: the loops of a map with axis labels and, optionally, sides.

A :class:`LoopStructure` is a view of a :class:`HalfEdgeMap`.  In the paper's
words, and in the primal terms of the quad mesh (docs/model.md, "Dictionary"):

=====================  ======================================
loop structure         map
=====================  ======================================
loop                   strip of faces (:attr:`loops`)
loop segment           edge (:attr:`segments`)
loop region            corner (:attr:`regions`)
loop intersection      face (:attr:`intersections`)
=====================  ======================================

Each loop has an axis label.  An *oriented* structure also gives each loop a
sign: ``+1`` when the loop's ``+`` side is on the right of its stored walk
(see :mod:`polyloops.core.loops`).  A *labelled* structure has ``signs=None``;
it is the input of the orientation solvers.

>>> from polyloops.io.examples import load_example
>>> cube = load_example("cube").dualize()
>>> [str(a) for a in cube.axes], cube.genus
(['Y', 'Z', 'X'], 0)
>>> sorted(str(d) for d in cube.corner_directions(0))
['+X', '+Y', '+Z']
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from functools import cached_property
from itertools import chain
from typing import TYPE_CHECKING

from polyloops.core.arrays import gc_paused, use_arrays
from polyloops.core.directions import Axis, Direction
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.loops import Loop, LoopSystem

if TYPE_CHECKING:
    import networkx as nx

    from polyloops.core.polycube import Polycube
    from polyloops.core.zones import Zones


class LabelError(PolyloopsError, ValueError):
    """Edge labels that do not describe a loop structure on the map."""


@dataclass(frozen=True, eq=False)
class LoopStructure:
    """Axis labels (and optionally signs) on the loops of a map; immutable."""

    map: HalfEdgeMap
    axes: tuple[Axis, ...]
    signs: tuple[int, ...] | None = None

    def __post_init__(self) -> None:
        n = len(self.map.loop_system.loops)
        if len(self.axes) != n:
            raise LabelError(f"{len(self.axes)} axis labels for {n} loops")
        if self.signs is not None and (len(self.signs) != n or any(s not in (1, -1) for s in self.signs)):
            raise LabelError(f"signs must be {n} values of +1 or -1")

    # -- construction -----------------------------------------------------------------
    @classmethod
    def from_edge_labels(cls, faces: Iterable[Sequence[int]],
                         labels: Mapping[tuple[int, int], Direction | Axis]) -> LoopStructure:
        """Build from one label per edge: ``{(u, v): Direction}`` or ``{(u, v): Axis}``.

        ``(u, v): +X`` says that ``v`` lies on the ``+`` side of the X-loop
        crossing edge ``uv``.  Every edge must be labelled exactly once; labels
        must all be signed or all unsigned, and agree along each loop.
        """
        m = HalfEdgeMap.from_faces(faces)
        if use_arrays(m.num_darts):
            found = cls._from_valid_edge_labels_arrays(m, labels)
            if found is not None:
                return found
        return cls._from_edge_labels_tuples(m, labels)

    @classmethod
    def from_trusted_edge_labels(cls, faces: Sequence[Sequence[int]],
                                 labels: Mapping[tuple[int, int], Direction]) -> LoopStructure:
        """:meth:`from_edge_labels` for faces and labels already known to form a loop structure
        (a loop move's result): the map is built without its checks
        (:meth:`~polyloops.core.halfedge.HalfEdgeMap.from_trusted_faces`) and each loop takes
        its axis and sign from one of its edges, without comparing the others.

        >>> from polyloops.io.examples import load_example
        >>> ls = load_example("cube").dualize()
        >>> m = ls.map
        >>> labels = {(m.origin(d), m.target(d)): ls.direction(d) for d in m.edge_darts}
        >>> LoopStructure.from_trusted_edge_labels(ls.map.faces, labels) == ls
        True
        """
        m = HalfEdgeMap.from_trusted_faces(faces)
        axes: list[Axis] = []
        signs: list[int] = []
        origin, nxt = m.origin_of, m.next
        for lp in m.loop_system.loops:
            d = lp.darts[0]
            u, v = origin[d], origin[nxt[d]]
            lab = labels.get((u, v))
            if lab is None:
                lab = labels[(v, u)]
                axes.append(lab.axis)
                signs.append(-lab.sign)
            else:
                axes.append(lab.axis)
                signs.append(lab.sign)
        return cls(m, tuple(axes), tuple(signs))

    @classmethod
    @gc_paused
    def _from_valid_edge_labels_arrays(cls, m: HalfEdgeMap, labels: Mapping[tuple[int, int], Direction | Axis]
                                       ) -> LoopStructure | None:
        """:meth:`from_edge_labels` on arrays for valid labels, ``None`` when anything is off
        (the tuple code then names the problem)."""
        import numpy as np

        from polyloops.core.arrays import all_distinct, per_loop

        a = m.arrays
        n = m.num_corners
        if len(labels) != m.num_edges:
            return None
        from polyloops.core.arrays import EdgeLabels

        if isinstance(labels, EdgeLabels):  # as read from a file: arrays already
            us, vs, codes = labels.us, labels.vs, labels.codes
        else:
            ends = np.fromiter(chain.from_iterable(labels), dtype=np.int64, count=2 * len(labels))
            us, vs = ends[0::2], ends[1::2]
            # Direction d as int(d) (0..5), Axis x as 6 + x; IntEnums hash as ints, so no dict.
            kinds = set(map(type, labels.values()))
            if not kinds <= {Direction, Axis} or len(kinds) != 1:
                return None  # not labels, or signed and unsigned mixed
            codes = np.fromiter(map(int, labels.values()), dtype=np.int64, count=len(labels))
            if kinds == {Axis}:
                codes += 6
        if min(us.min(), vs.min()) < 0 or max(us.max(), vs.max()) >= n:
            return None
        if codes.min() < 6 <= codes.max():
            return None  # signed and unsigned mixed
        dart_keys = a.origin * n + a.target
        order = np.argsort(dart_keys)
        where = np.searchsorted(dart_keys[order], us * n + vs)
        where[where == len(order)] = 0
        darts = order[where]
        if not np.array_equal(dart_keys[darts], us * n + vs):
            return None  # not an edge
        if not all_distinct(a.edge_id[darts]):
            return None  # an edge labelled twice (so another one missing)
        oriented = codes.max() < 6
        axis = np.where(codes < 6, codes // 2, codes - 6)
        sign = np.where(codes < 6, 1 - 2 * (codes % 2), 0)
        axis_of = np.empty(m.num_darts, dtype=np.int64)
        sign_of = np.empty(m.num_darts, dtype=np.int64)
        axis_of[darts], axis_of[a.twin[darts]] = axis, axis
        sign_of[darts], sign_of[a.twin[darts]] = sign, -sign
        system = m.loop_system
        loop_of = system.loop_array
        walked = system.side_array > 0
        low = per_loop(loop_of[walked], (axis_of * 3 + sign_of + 1)[walked], len(system.loops))
        if low is None:
            return None  # labels disagree along a loop
        axes = tuple(Axis(x) for x in (low // 3).tolist())
        signs = tuple((low % 3 - 1).tolist()) if oriented else None
        return cls(m, axes, signs)

    @classmethod
    def _from_edge_labels_tuples(cls, m: HalfEdgeMap, labels: Mapping[tuple[int, int], Direction | Axis]
                                 ) -> LoopStructure:
        system = m.loop_system
        dart_label: dict[int, Direction | Axis] = {}
        for (u, v), label in labels.items():
            try:
                d = m.dart(u, v)
            except KeyError:
                raise LabelError(f"edge ({u}, {v}) is not an edge of the faces") from None
            if m.twin[d] in dart_label or d in dart_label:
                raise LabelError(f"edge ({u}, {v}) is labelled twice")
            dart_label[d] = label
        for e, d in enumerate(m.edge_darts):
            if d not in dart_label and m.twin[d] not in dart_label:
                u, v = m.edge_corners(e)
                raise LabelError(f"edge ({u}, {v}) is missing from the edge labels")
        signed = {isinstance(lab, Direction) for lab in dart_label.values()}
        if len(signed) > 1:
            raise LabelError("some edges have a signed label (+X) and others an unsigned one (X)")
        oriented = signed == {True}
        axes: list[Axis] = []
        signs: list[int] = []
        for lp in system.loops:
            seen: set[tuple[Axis, int]] = set()
            for d in lp.darts:
                if d in dart_label:
                    lab, flip = dart_label[d], 1
                else:
                    lab, flip = dart_label[m.twin[d]], -1
                if isinstance(lab, Direction):
                    seen.add((lab.axis, lab.sign * flip))
                else:
                    seen.add((Axis(lab), 0))
            if len(seen) > 1:
                u, v = m.edge_corners(lp.edges[0])
                what = "signs" if len({a for a, _ in seen}) == 1 else "axis labels"
                raise LabelError(f"{what} disagree along the loop through edge ({u}, {v})")
            (axis, sign), = seen
            axes.append(axis)
            signs.append(sign)
        return cls(m, tuple(axes), tuple(signs) if oriented else None)

    # -- the paper's vocabulary ---------------------------------------------------------
    @property
    def oriented(self) -> bool:
        """Whether the loops have sides (an oriented structure) or labels only."""
        return self.signs is not None

    @property
    def loop_system(self) -> LoopSystem:
        """The loops of the map, with the loop and side of every dart."""
        return self.map.loop_system

    @property
    def loops(self) -> tuple[Loop, ...]:
        """The loops, by id."""
        return self.map.loop_system.loops

    @property
    def segments(self) -> range:
        """Loop segments are the edges of the map."""
        return range(self.map.num_edges)

    @property
    def regions(self) -> range:
        """Loop regions are the corners of the map."""
        return range(self.map.num_corners)

    @property
    def intersections(self) -> range:
        """Loop intersections are the faces of the map."""
        return range(self.map.num_faces)

    @property
    def genus(self) -> int:
        """The genus of its surface."""
        return self.map.genus

    def loop_of_segment(self, e: int) -> int:
        """The loop that crosses segment (edge) ``e``."""
        return self.map.loop_system.loop_of_dart[self.map.edge_darts[e]]

    def region_segments(self, corner: int) -> list[int]:
        """The segments bounding a region, counter-clockwise."""
        return [self.map.edge_id(d) for d in self.map.outgoing(corner)]

    def loops_by_axis(self) -> dict[Axis, list[int]]:
        """The loop ids of each axis."""
        out: dict[Axis, list[int]] = {a: [] for a in Axis}
        for i, a in enumerate(self.axes):
            out[a].append(i)
        return out

    # -- labels of darts ----------------------------------------------------------------
    def axis_of_dart(self, d: int) -> Axis:
        """The axis label of the loop that crosses dart ``d``'s edge."""
        return self.axes[self.map.loop_system.loop_of_dart[d]]

    def direction(self, d: int) -> Direction:
        """The direction of dart ``d`` (oriented structures only)."""
        return self._directions[d]

    @cached_property
    def direction_codes(self):
        """``int(direction)`` of every dart as a numpy array, for an oriented structure; for a
        labelled one, each dart's axis (the array kernels' label of a dart)."""
        import numpy as np

        system = self.map.loop_system
        axes = np.asarray(self.axes, dtype=np.int64)[system.loop_array]
        if self.signs is None:
            return axes
        sign = np.asarray(self.signs, dtype=np.int64)[system.loop_array] * system.side_array
        return 2 * axes + (sign < 0)

    @cached_property
    def _directions(self) -> tuple[Direction, ...]:
        if self.signs is None:
            raise ValueError("a labelled loop structure has no directions; orient it first")
        members = tuple(Direction)
        codes = self.direction_codes.tolist() if use_arrays(self.map.num_darts) else self.direction_code_list
        return tuple(members[c] for c in codes)

    @cached_property
    def direction_code_list(self) -> tuple[int, ...]:
        """``int(direction)`` of every dart (``2 * axis + 1`` on the ``-`` side), as a tuple; for
        a labelled structure, each dart's axis."""
        system = self.map.loop_system
        if self.signs is None:
            return tuple(int(self.axes[loop]) for loop in system.loop_of_dart)
        # A loop's darts point to its + side (code 2 * axis) or to its - side (2 * axis + 1).
        plus = [2 * int(a) + (s < 0) for a, s in zip(self.axes, self.signs, strict=True)]
        return tuple(plus[loop] ^ (side < 0) for loop, side in zip(system.loop_of_dart, system.side_of_dart,
                                                                     strict=True))

    def corner_directions(self, corner: int) -> tuple[Direction, ...]:
        """Directions of the edges at a corner, counter-clockwise seen from outside."""
        return tuple(self._directions[d] for d in self.map.outgoing(corner))

    def edge_labels(self) -> list[tuple[int, int, str]]:
        """One ``(u, v, label)`` per edge, as in the JSON format."""
        out = []
        for d in self.map.edge_darts:
            lab = str(self.direction(d)) if self.oriented else str(self.axis_of_dart(d))
            out.append((self.map.origin(d), self.map.target(d), lab))
        return out

    # -- zones and level graphs ---------------------------------------------------------
    def zones(self, axis: Axis) -> Zones:
        """The ``axis``-zones: corners joined by edges whose label is not ``axis``."""
        return self._zones[axis]

    @cached_property
    def _zones(self) -> tuple[Zones, ...]:
        from polyloops.core.zones import compute_zones

        return tuple(compute_zones(self, a) for a in Axis)

    def level_graph(self, axis: Axis) -> nx.MultiDiGraph:
        """A node per ``axis``-zone, an arc per ``axis``-loop from its - side to its + side."""
        from polyloops.core.zones import level_graph

        return level_graph(self, axis)

    # -- derived structures -------------------------------------------------------------
    def with_signs(self, signs: Sequence[int] | None) -> LoopStructure:
        """The same loops with these sides (one sign per loop)."""
        return LoopStructure(self.map, self.axes, None if signs is None else tuple(signs))

    def forget_orientation(self) -> LoopStructure:
        """The labelled structure: the same loops and labels, without sides."""
        return self.with_signs(None)

    def flipped(self, loop: int) -> LoopStructure:
        """The same structure with the sides of one loop exchanged."""
        if self.signs is None:
            raise ValueError("a labelled loop structure has no sides to flip")
        signs = list(self.signs)
        signs[loop] = -signs[loop]
        return self.with_signs(signs)

    def relabelled(self, loop: int, axis: Axis) -> LoopStructure:
        """The same structure with one loop's axis label changed."""
        axes = list(self.axes)
        axes[loop] = axis
        return LoopStructure(self.map, tuple(axes), self.signs)

    def primalize(self) -> Polycube:
        """The polycube of Theorem 2; see :func:`polyloops.core.duality.primalize`."""
        from polyloops.core.duality import primalize

        return primalize(self)

    # -- value semantics ----------------------------------------------------------------
    def __eq__(self, other: object) -> bool:
        return (isinstance(other, LoopStructure) and self.map == other.map
                and self.axes == other.axes and self.signs == other.signs)

    def __hash__(self) -> int:
        return hash((self.map, self.axes, self.signs))

    def __repr__(self) -> str:
        counts = {a.name: self.axes.count(a) for a in Axis}
        kind = "oriented" if self.oriented else "labelled"
        return (f"LoopStructure({kind}, regions={self.map.num_corners}, "
                f"loops={counts}, genus={self.genus})")
