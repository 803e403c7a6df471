"""polyloops: polycubes via their dual loops.

The kernel is :mod:`polyloops.core` (one half-edge map; polycubes and loop
structures are views of it).  Checkers live in :mod:`polyloops.verify`.

>>> import polyloops as pl
>>> q = pl.load_example("l-shape")
>>> ls = pl.dualize(q)
>>> pl.verify(ls).valid, pl.is_order_equivalent(pl.primalize(ls), q) is not None
(True, True)
"""

__version__ = "0.1.0"

from polyloops.core.directions import Axis, Direction
from polyloops.core.duality import DualityError, dualize, is_order_equivalent, primalize
from polyloops.core.examples import EXAMPLES, load_example
from polyloops.core.formats import dumps, loads, to_obj
from polyloops.core.halfedge import HalfEdgeMap, MapError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.core.voxels import polycube_from_voxels
from polyloops.render.jupyter import register as _register_pictures
from polyloops.verify import verify

_register_pictures()

__all__ = [
    "EXAMPLES", "Axis", "Direction", "DualityError", "HalfEdgeMap", "LoopStructure", "MapError",
    "Polycube", "__version__", "dualize", "dumps", "is_order_equivalent", "load_example", "loads",
    "polycube_from_voxels", "primalize", "to_obj", "verify",
]
