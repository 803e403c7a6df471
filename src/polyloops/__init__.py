"""polyloops: polycubes via their dual loops.

The kernel is :mod:`polyloops.core` (one half-edge map; polycubes and loop structures are
views of it).  Checkers live in :mod:`polyloops.verify`, orientation solvers in
:mod:`polyloops.solvers`, generators in :mod:`polyloops.generate`, catalogs in
:mod:`polyloops.catalog` and reachability in :mod:`polyloops.reach`.  The names
below are the public API; the heavier ones (solvers, catalogs, reachability) load on first use.

>>> import polyloops as pl
>>> q = pl.load_example("l-shape")
>>> ls = pl.dualize(q)
>>> pl.verify(ls).valid, pl.is_order_equivalent(pl.primalize(ls), q) is not None
(True, True)
>>> pl.identify(q).name, pl.orient(ls.forget_orientation()).found
('P16.2', True)
"""

from __future__ import annotations

import importlib
from typing import Any

import polyloops._startup  # noqa: F401  (first: before numpy loads, the command pins BLAS threads)

__version__ = "0.1.0"

from polyloops.core.canonical import canonical_form, from_signature, is_isomorphic, signature
from polyloops.core.corners import classify, corner_configurations
from polyloops.core.directions import Axis, Direction
from polyloops.core.duality import DualityError, dualize, is_order_equivalent, primalize
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import HalfEdgeMap, MapError
from polyloops.core.moves import add_loop, additions, removals, remove_loop
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import Symmetry
from polyloops.io.examples import EXAMPLES, load_example
from polyloops.io.formats import dumps, loads, to_obj
from polyloops.render.jupyter import register as _register_pictures
from polyloops.shapes.coarsen import coarsen
from polyloops.shapes.voxels import polycube_from_voxels
from polyloops.verify import as_loop_structure, verify
from polyloops.verify.describe import describe

_register_pictures()

# Loaded on first use, to keep ``import polyloops`` light (pysat, z3, sqlite, dask).
_LAZY = {
    "orient": "polyloops.solvers",
    "count_orientations": "polyloops.solvers",
    "identify": "polyloops.catalog.census",
    "read_catalog": "polyloops.catalog.census",
    "read_certificate": "polyloops.reach.conjecture",
    "build_catalog": "polyloops.catalog.run",
    "explore": "polyloops.reach.search",
    "shortest_path": "polyloops.reach.search",
    "read": "polyloops.io.registry",
    "write": "polyloops.io.registry",
    "segment_mesh": "polyloops.segment.run",  # (``polyloops.segment`` is the constructors' package)
}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'polyloops' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "EXAMPLES",
    "Axis",
    "Direction",
    "DualityError",
    "HalfEdgeMap",
    "LoopStructure",
    "MapError",
    "Polycube",
    "PolyloopsError",
    "Symmetry",
    "__version__",
    "add_loop",
    "additions",
    "as_loop_structure",
    "build_catalog",
    "canonical_form",
    "classify",
    "coarsen",
    "corner_configurations",
    "count_orientations",
    "describe",
    "dualize",
    "dumps",
    "explore",
    "from_signature",
    "identify",
    "is_isomorphic",
    "is_order_equivalent",
    "load_example",
    "loads",
    "orient",
    "polycube_from_voxels",
    "primalize",
    "read",
    "read_catalog",
    "read_certificate",
    "removals",
    "remove_loop",
    "shortest_path",
    "signature",
    "to_obj",
    "verify",
    "write",
]
