"""Definition 1: is a quad mesh with integer corner positions a polycube?

The conditions on positions are checked on the raw faces, so they are reported
even when the faces do not form a closed surface.

>>> from polyloops.io.examples import load_example
>>> check_polycube(load_example("l-shape")).valid
True
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Sequence
from itertools import chain

from polyloops.core.arrays import use_arrays
from polyloops.core.directions import Direction
from polyloops.core.halfedge import FaceListError, HalfEdgeMap, MapError
from polyloops.core.polycube import Polycube, quad_volume, signed_volume
from polyloops.verify.report import Report, ReportBuilder
from polyloops.verify.surface import add_surface_checks

DEF1 = "Definition 1"
POLYGONS = "faces are polygons over the corner ids 0..n-1, each visiting distinct corners"
CONVENTION = "file convention"
OUTWARD = "faces are counter-clockwise seen from outside (positive signed volume)"


def _is_int(x: object) -> bool:
    return isinstance(x, int) and not isinstance(x, bool)


def check_polycube_faces(faces: Sequence[Sequence[int]], positions: Sequence[Sequence[int]],
                         built: HalfEdgeMap | None = None) -> Report:
    """Check raw faces and positions against Definition 1, collecting every violation, even when
    the faces do not make a surface at all.

    Parameters
    ----------
    faces:
        Corner lists, counter-clockwise seen from outside.
    positions:
        Integer coordinates of the corners.
    built:
        The map of these faces, when it exists already (saves building it again).

    Returns
    -------
    Report

    Notes
    -----
    Nothing is raised for faces over corners ``0..len(positions)-1``; other ids are reported.

    >>> report = check_polycube_faces([[0, 1, 2, 3]], [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
    >>> report.valid, "closed" in {str(v.condition) for v in report.violations}
    (False, True)
    """
    rb = ReportBuilder("polycube", DEF1)
    rb.condition("quad", "every face is a quadrilateral", [] if set(map(len, faces)) == {4} else [
        rb.violation("quad", f"face {f} has {len(face)} corners", face=f)
        for f, face in enumerate(faces) if len(face) != 4])
    problems = None
    if built is None:
        try:
            built = HalfEdgeMap.from_faces(faces)
        except MapError as err:
            problems = err.problems
        except FaceListError as err:
            rb.condition("polygons", POLYGONS, [rb.violation("polygons", str(err))])
            return rb.build()
    add_surface_checks(rb, problems)
    points = None
    if built is not None and use_arrays(built.num_darts):
        points = _positions_fine(built, positions)
    if points is not None:
        for cond, statement in (("1", "each corner has a position in Z^3"),
                                ("2", "each corner has degree at least 3"),
                                ("3", "positions of adjacent corners differ in exactly one coordinate"),
                                ("4", "edges incident to the same corner do not overlap")):
            rb.condition(cond, statement, [])
        assert built is not None
        volume = quad_volume(built.arrays.origin.reshape(-1, 4), points)
        return rb.build() + _check_outward(faces, positions, surface_ok=True, volume=volume)

    rb.condition("1", "each corner has a position in Z^3", [
        rb.violation("1", f"corner {c} has position {list(p)}, not three integers", corner=c)
        for c, p in enumerate(positions) if len(p) != 3 or not all(_is_int(x) for x in p)])

    neighbours: dict[int, set[int]] = defaultdict(set)
    for face in faces:
        for i, u in enumerate(face):
            v = face[(i + 1) % len(face)]
            neighbours[u].add(v)
            neighbours[v].add(u)
    rb.condition("2", "each corner has degree at least 3", [
        rb.violation("2", f"corner {c} has degree {len(nb)}", corner=c, degree=len(nb))
        for c, nb in sorted(neighbours.items()) if len(nb) < 3])

    bad_edges = []
    overlaps = []
    for u, nb in sorted(neighbours.items()):
        by_direction: dict[Direction, list[int]] = defaultdict(list)
        for v in sorted(nb):
            d = Direction.between(tuple(positions[u]), tuple(positions[v]))
            if d is None:
                if u < v:
                    bad_edges.append(rb.violation(
                        "3", f"edge ({u}, {v}) joins {list(positions[u])} and {list(positions[v])}, "
                        "which do not differ in exactly one coordinate", edge=[u, v]))
            else:
                by_direction[d].append(v)
        for d, vs in sorted(by_direction.items()):
            if len(vs) > 1:
                overlaps.append(rb.violation(
                    "4", f"corner {u} has {len(vs)} edges in direction {d} (to corners {vs})",
                    corner=u, direction=str(d), neighbours=vs))
    rb.condition("3", "positions of adjacent corners differ in exactly one coordinate", bad_edges)
    rb.condition("4", "edges incident to the same corner do not overlap", overlaps)
    return rb.build() + _check_outward(faces, positions, surface_ok=problems is None)


def _positions_fine(m: HalfEdgeMap, positions: Sequence[Sequence[int]]):
    """Conditions 1 to 4 on arrays, for a map that exists: the positions as an array when
    they hold, ``None`` (the corner-by-corner code then names each violation) when not."""
    import numpy as np

    from polyloops.core.arrays import all_distinct, points_array

    if len(positions) != m.num_corners or set(map(len, positions)) != {3} \
            or set(map(type, chain.from_iterable(positions))) != {int}:
        return None
    a = m.arrays
    p = points_array(positions)
    step = p[a.target] - p[a.origin]
    if np.any(np.count_nonzero(step, axis=1) != 1) or \
            np.any(np.bincount(a.origin, minlength=m.num_corners) < 3):
        return None
    # One coordinate moved: its axis and sign give the direction code 2 * axis + (step < 0).
    axis = np.abs(step).argmax(axis=1)
    negative = step.sum(axis=1) < 0
    return p if all_distinct(a.origin * 6 + 2 * axis + negative) else None


def _check_outward(faces: Sequence[Sequence[int]], positions: Sequence[Sequence[int]],
                   surface_ok: bool, volume: float | None = None) -> Report:
    """The file convention: an inside-out polycube (negative signed volume) is reported, with
    the way to repair it.  Definition 1 itself does not see orientation: a polycube and its
    inverse are order-equivalent."""
    rb = ReportBuilder("polycube", CONVENTION)
    numeric = volume is not None or (set(map(len, positions)) <= {3}
                                     and set(map(type, chain.from_iterable(positions))) <= {int})
    if not (surface_ok and numeric):
        rb.given("outward", OUTWARD, "not checked: needs a closed surface with integer positions",
                 status="not checked")
        return rb.build()
    if volume is None:
        volume = signed_volume(faces, positions)
    found = []
    if volume < 0:
        found.append(rb.violation(
            "outward", f"the polycube is inside out: its faces are clockwise seen from outside "
            f"(signed volume {volume:g}); reverse every face (Polycube.outward() does)",
            signed_volume=volume))
    rb.condition("outward", OUTWARD, found)
    return rb.build()


def check_polycube(q: Polycube) -> Report:
    """Check a :class:`~polyloops.core.polycube.Polycube` against Definition 1 (on the map it
    already has).

    Parameters
    ----------
    q:
        A polycube.

    Returns
    -------
    Report

    Raises
    ------
    AttributeError
        When ``q`` is a loop structure (use :func:`polyloops.verify.verify`, which dispatches).

    >>> from polyloops.io.examples import load_example
    >>> check_polycube(load_example("self-intersecting")).valid
    True
    """
    return check_polycube_faces(q.faces, q.positions, q.map)
