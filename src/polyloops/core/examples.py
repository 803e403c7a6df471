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

from polyloops.core import builders
from polyloops.core.formats import Structure, loads
from polyloops.core.voxels import polycube_from_voxels


@dataclass(frozen=True)
class Example:
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
    Example("ring", "a square ring of eight unit cubes (genus 1)", True, lambda: builders.ring(3)),
    Example("non-incremental", "six cubes of a 2x2x2 block (two opposite cubes missing): a polycube "
            "none of whose loops can be removed, so additions alone cannot build it", True,
            lambda: polycube_from_voxels(NON_INCREMENTAL_CUBES)),
    Example("bridged-ring", "a ring of ten cubes with a bridge (genus 1) whose Z-zone at z = 1 has "
            "a handle: a Z-loop around it is locally valid but closes a level-graph cycle", True,
            lambda: polycube_from_voxels(BRIDGED_RING_CUBES)),
    Example("two-axis-holes", "two square rings sharing a bar (genus 2), one hole along Z and one "
            "along Y: loop moves keep each hole's orientation", True,
            lambda: polycube_from_voxels(TWO_AXIS_HOLES_CUBES)),
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


def example_text(name: str) -> str:
    """The shipped JSON text of an example; ``KeyError`` for an unknown name."""
    if name not in EXAMPLES:
        raise KeyError(name)
    return resources.files("polyloops.examples").joinpath(f"{name}.json").read_text(encoding="utf-8")


def load_example(name: str) -> Structure:
    return loads(example_text(name))
