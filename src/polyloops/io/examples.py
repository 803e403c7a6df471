"""Bundled examples, shipped as JSON files and named ``example:NAME`` on the command line.

>>> sorted(EXAMPLES)[:3]
['box-2x1x1', 'bridged-ring', 'cube']
>>> load_example("cube")
Polycube(corners=8, faces=6, genus=0)
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources

from polyloops.core.directions import Axis, Direction
from polyloops.core.polycube import Polycube
from polyloops.io.formats import Structure, loads
from polyloops.shapes import builders
from polyloops.shapes.voxels import polycube_from_voxels
from polyloops.surface.construct import labelled_mesh_from_polycube
from polyloops.surface.mesh import LabelledMesh


def slab_cubes(holes: int) -> list[tuple[int, int, int]]:
    """A slab one cube thick, ``2 * holes + 1`` long and 3 wide, with ``holes`` holes along Z."""
    return [(x, y, 0) for x in range(2 * holes + 1) for y in range(3) if not (y == 1 and x % 2 == 1)]


@dataclass(frozen=True)
class Example:
    """A bundled example: its name, whether it is valid, what it shows, and its file."""

    name: str
    description: str
    valid: bool
    build: Callable[[], Structure]


# Found by searching random unions of unit cubes for polycubes with no removable loop.
NON_INCREMENTAL_CUBES = [(0, 0, 0), (0, 0, 1), (0, 1, 1), (1, 0, 0), (1, 1, 0), (1, 1, 1)]

# A genus-1 ring whose x = 0 side is a bridge at z = 1: one Z-zone runs around the hole and
# under the bridge, so it has a handle, and a Z-loop around it would not separate the zone.
BRIDGED_RING_CUBES = [(0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 2, 0), (0, 2, 1), (1, 0, 0), (1, 2, 0),
                      (2, 0, 0), (2, 1, 0), (2, 2, 0)]

# Two square rings sharing a bar: one in the plane z = 0 (hole along Z), one in y = 0 (hole
# along Y); genus 2.
TWO_AXIS_HOLES_CUBES = sorted({(x, y, 0) for x in range(3) for y in range(3) if (x, y) != (1, 1)}
                              | {(x, 0, z) for x in range(3) for z in range(3) if (x, z) != (1, 1)})

_ALL = [
    Example("cube", "the unit cube", True, lambda: builders.box(1, 1, 1)),
    Example("box-2x1x1", "two unit cubes in a row: two X-loops", True, lambda: builders.box(2, 1, 1)),
    Example("l-shape", "three unit cubes in an L", True,
            lambda: polycube_from_voxels([(0, 0, 0), (1, 0, 0), (0, 1, 0)])),
    Example("ring", "a square ring of eight unit cubes (genus 1), its hole along Z", True,
            lambda: builders.ring(3)),
    Example("ring-x", "the square ring with its hole along X: no loop moves join it to the ring "
            "(the hole orientation differs)", True, lambda: builders.ring(3, hole=Axis.X)),
    Example("ring-y", "the square ring with its hole along Y", True, lambda: builders.ring(3, hole=Axis.Y)),
    Example("non-incremental", "six cubes of a 2x2x2 block (two opposite cubes missing): a polycube "
            "none of whose loops can be removed, so additions alone cannot build it", True,
            lambda: polycube_from_voxels(NON_INCREMENTAL_CUBES)),
    Example("bridged-ring", "a ring of ten cubes with a bridge (genus 1) whose Z-zone at z = 1 has "
            "a handle: a Z-loop around it is locally valid but closes a level-graph cycle", True,
            lambda: polycube_from_voxels(BRIDGED_RING_CUBES)),
    Example("two-axis-holes", "two square rings sharing a bar (genus 2), one hole along Z and one "
            "along Y: loop moves keep each hole's orientation", True,
            lambda: polycube_from_voxels(TWO_AXIS_HOLES_CUBES)),
    Example("slab-2-holes", "a slab of 5 x 3 unit cubes with two holes along Z (genus 2): a start for "
            "segment on shapes with two holes side by side", True,
            lambda: polycube_from_voxels(slab_cubes(2))),
    Example("slab-3-holes", "a slab of 7 x 3 unit cubes with three holes along Z (genus 3)", True,
            lambda: polycube_from_voxels(slab_cubes(3))),
    Example("self-intersecting", "a slab whose dent reaches down to its own bottom face: a valid "
            "polycube whose surface meets itself", True, builders.dented_slab),
    Example("torus-cycle", "a flat 3x3 torus grid: its X- and Y-graphs are cycles (Condition 5)",
            False, lambda: builders.torus_grid(3, 3)),
    Example("degree-two", "two quads glued along their boundary: regions bounded by two segments "
            "(Condition 2)", False, builders.pillow),
    Example("double-plus-x", "box-2x1x1 with one X-loop flipped: two +X edges at a corner (Condition 3)",
            False, builders.double_plus_x),
    Example("self-crossing", "a loop that crosses itself (Condition 3)", False, builders.self_crossing),
]
EXAMPLES: dict[str, Example] = {e.name: e for e in _ALL}
"""The bundled polycubes and loop structures by name, each an :class:`Example` with its
description and whether it is valid (the labelled meshes are :data:`LABELLED_EXAMPLES`)."""


# -- labelled triangle meshes ------------------------------------------------------------

@dataclass(frozen=True)
class LabelledExample:
    """A bundled labelled triangle mesh: its name, expected verdict and description."""

    name: str
    description: str
    valid: bool
    build: Callable[[], LabelledMesh]


def _relabelled(cells: list[tuple[int, int, int]], old: Direction, new: Direction, level: int,
                span: tuple[int, int]) -> LabelledMesh:
    """The polycube of ``cells``, labelled by its normals except the quads of normal ``old``
    at height ``z = level`` with ``x`` in ``span``, which get ``new``."""
    q = polycube_from_voxels(cells)
    labels = []
    for f, face in enumerate(q.faces):
        label = q.face_normal(f)
        assert label is not None
        xs = [q.positions[c][0] for c in face]
        if label == old and all(q.positions[c][2] == level for c in face) and \
                span[0] <= min(xs) and max(xs) <= span[1]:
            label = new
        labels.append(label)
    return labelled_mesh_from_polycube(q, labels)


# A block with two pillars (Z up): the charts of the polyhedron with three faces up and one
# down.  Labelling the floor between the pillars -Z (the underside of a ramp) gives two up
# and two down: every local criterion holds, but no polycube has these labels.
U_CUBES = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 0, 1), (2, 0, 1)]
# Three steps; the middle step's top labelled -Z is an overhang, which a polycube has.
STAIR_CUBES = [(x, 0, z) for x in range(3) for z in range(3 - x)]

_LABELLED = [
    LabelledExample("sokolov-ramp", "a block with two pillars whose floor between them is labelled "
                    "facing down: two charts up and two down, every local criterion holds, yet no "
                    "polycube has these labels (in the manner of Sokolov's ramp)", False,
                    lambda: _relabelled(U_CUBES, Direction.PZ, Direction.NZ, 1, (1, 2))),
    LabelledExample("overhang", "three steps whose middle step is labelled facing down: not the "
                    "mesh's own normals, but a polycube with an overhang has these labels", True,
                    lambda: _relabelled(STAIR_CUBES, Direction.PZ, Direction.NZ, 2, (1, 2))),
]
LABELLED_EXAMPLES: dict[str, LabelledExample] = {e.name: e for e in _LABELLED}


def example_text(name: str) -> str:
    """The shipped JSON text of an example; ``KeyError`` for an unknown name."""
    if name not in EXAMPLES:
        raise KeyError(name)
    return resources.files("polyloops.examples").joinpath(f"{name}.json").read_text(encoding="utf-8")


def load_example(name: str) -> Structure:
    """A bundled example, built (``polyloops examples`` lists them, :data:`EXAMPLES` holds them).

    Parameters
    ----------
    name:
        The example's name, such as ``"l-shape"`` or ``"torus-cycle"``.

    Returns
    -------
    Polycube or LoopStructure
        As the example's file describes it (some examples are invalid on purpose).

    Raises
    ------
    KeyError
        For an unknown name.

    >>> load_example("ring").genus, type(load_example("torus-cycle")).__name__
    (1, 'LoopStructure')
    """
    return loads(example_text(name))


def labelled_mesh_example(name: str) -> LabelledMesh:
    """A bundled labelled mesh (shipped as ``NAME.obj`` and ``NAME.labels``), or a bundled
    polycube's quads cut into triangles and labelled by their normals."""
    from polyloops.io.labelled_mesh import parse_labels, read_triangle_mesh

    if name in LABELLED_EXAMPLES:
        folder = resources.files("polyloops.examples")
        with resources.as_file(folder.joinpath(f"{name}.obj")) as path:
            points, triangles = read_triangle_mesh(path)
        labels = parse_labels(folder.joinpath(f"{name}.labels").read_text(encoding="utf-8"), len(triangles))
        return LabelledMesh(points, triangles, labels)
    if name in EXAMPLES and EXAMPLES[name].valid:
        q = load_example(name)
        if isinstance(q, Polycube):
            return labelled_mesh_from_polycube(q)
    raise KeyError(f"no labelled mesh of that name (bundled: {', '.join(LABELLED_EXAMPLES)}, or a valid "
                   "bundled polycube example)")
