"""Coarsening: remove the loops that only subdivide flat faces.

A polycube made of unit cubes has a loop for every layer of cubes, so a shape sampled finely has
many more loops than its features need: the 3x3x2 ring of cubes has 48 corners, the square ring
it samples (T32.1) has 32.  A loop *lies in a flat band* when, on one of its two sides, every
face of its strip continues flat into the next face across that side (both faces have the same
normal).  Removing such a loop collapses its strip onto the flat neighbouring strip: every bend
of the surface (an edge between faces of different normals) is kept, only the subdivision
between parallel layers goes.

:func:`coarsen` removes such loops one at a time, in loop order, as long as the result stays a
polycube loop structure (Definition 4, checked by the removal test of Section 4.2), until no
such loop is left.  The result is a coarsening, not necessarily the coarsest one: which loops
can go may depend on the order (two parallel loops in one band, for instance, cannot both go).

>>> from polyloops.shapes.voxels import polycube_from_voxels
>>> ring = [(x, y, z) for x in range(3) for y in range(3) for z in range(2) if (x, y) != (1, 1)]
>>> q = polycube_from_voxels(ring)
>>> q.map.num_corners, coarsen(q.dualize()).structure.map.num_corners
(48, 32)
"""

from __future__ import annotations

from dataclasses import dataclass

from polyloops.core.directions import Direction
from polyloops.core.duality import primalize
from polyloops.core.moves import check_removal, remove_loop
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure


@dataclass(frozen=True)
class Coarsening:
    """The result of :func:`coarsen`: the coarser structure and how many loops went."""

    structure: LoopStructure
    removed: int  # loops removed, each one lying in a flat band when it went

    @property
    def polycube(self) -> Polycube:
        """The coarser structure's polycube, in compact coordinates (Theorem 2)."""
        return primalize(self.structure)


def _cross(a: Direction, b: Direction) -> Direction:
    u, v = a.vector, b.vector
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    (k,) = [i for i in range(3) if n[i]]
    return Direction.of(k, 1 if n[k] > 0 else -1)


def face_normals(ls: LoopStructure) -> list[Direction]:
    """The outward normal of every face, from the directions of its edges (no embedding needed).

    >>> from polyloops.io.examples import load_example
    >>> sorted(str(n) for n in face_normals(load_example("cube").dualize()))
    ['+X', '+Y', '+Z', '-X', '-Y', '-Z']
    """
    m = ls.map
    out = []
    for f in range(m.num_faces):
        d = m.face_darts(f)[0]
        out.append(_cross(ls.direction(d), ls.direction(m.next[d])))
    return out


def in_flat_band(ls: LoopStructure, loop: int, normals: list[Direction] | None = None) -> bool:
    """Whether every face of ``loop``'s strip has the same normal as its neighbour across one
    and the same side of the loop.

    >>> from polyloops.io.examples import load_example
    >>> box = load_example("box-2x1x1").dualize()
    >>> [in_flat_band(box, lp.id) for lp in box.loops]
    [False, False, True, True]
    """
    m = ls.map
    normals = face_normals(ls) if normals is None else normals
    flat = [True, True]  # the left and the right side of the walk
    lp = ls.loops[loop]
    for dart, f in zip(lp.darts, lp.faces, strict=True):
        # The dart points from the walk's left to its right; find its copy in face f.
        entry = dart if m.face_of[dart] == f else m.twin[dart]
        after, before = m.next[entry], m.prev[entry]
        left, right = (before, after) if entry == dart else (after, before)
        for side, d in enumerate((left, right)):
            if flat[side] and normals[m.face_of[m.twin[d]]] != normals[f]:
                flat[side] = False
        if not any(flat):
            return False
    return True


def coarsen(ls: LoopStructure) -> Coarsening:
    """Remove loops lying in flat bands while the structure stays a polycube loop structure
    (see the module docstring).

    Parameters
    ----------
    ls:
        An oriented polycube loop structure.

    Returns
    -------
    Coarsening
        The coarser structure (``ls`` itself when no loop can go) and the number removed.

    >>> from polyloops.io.examples import load_example
    >>> c = coarsen(load_example("box-2x1x1").dualize())
    >>> c.removed, c.structure.map.num_corners
    (1, 8)
    """
    removed = 0
    while True:
        normals = face_normals(ls)
        for lp in ls.loops:
            if in_flat_band(ls, lp.id, normals) and check_removal(ls, lp.id).valid:
                ls = remove_loop(ls, lp.id)
                removed += 1
                break
        else:
            return Coarsening(ls, removed)


def coarsen_polycube(q: Polycube) -> Coarsening:
    """:func:`coarsen` on a polycube's loop structure (Theorem 1), its polycube in
    :attr:`Coarsening.polycube`.

    >>> from polyloops.shapes.voxels import polycube_from_voxels
    >>> c = coarsen_polycube(polycube_from_voxels([(x, 0, 0) for x in range(5)]))
    >>> c.removed, c.polycube.map.num_corners
    (4, 8)
    """
    return coarsen(q.dualize())
