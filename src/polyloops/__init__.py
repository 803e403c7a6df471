"""polyloops: polycubes via their dual loops.

The kernel is :mod:`polyloops.core` (one half-edge map; polycubes and loop structures are
views of it).  Checkers live in :mod:`polyloops.verify`, orientation solvers in
:mod:`polyloops.solvers`, catalogs and reachability in :mod:`polyloops.enumerate`.  The names
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
import os
from typing import Any

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
from polyloops.core.voxels import polycube_from_voxels
from polyloops.io.examples import EXAMPLES, load_example
from polyloops.io.formats import dumps, loads, to_obj
from polyloops.render.jupyter import register as _register_pictures
from polyloops.verify import as_loop_structure, verify
from polyloops.verify.describe import describe

_register_pictures()

# Loaded on first use, to keep ``import polyloops`` light (pysat, z3, sqlite, dask).
_LAZY = {
    "orient": "polyloops.solvers",
    "count_orientations": "polyloops.solvers",
    "identify": "polyloops.enumerate.census",
    "read_catalog": "polyloops.enumerate.census",
    "build_catalog": "polyloops.enumerate.catalog_run",
    "explore": "polyloops.enumerate.reach",
    "shortest_path": "polyloops.enumerate.reach",
}


def read(path: str | os.PathLike[str], format: str | None = None) -> Polycube | LoopStructure:
    """Read a polycube or loop structure from a file in any format polyloops reads
    (:mod:`polyloops.io.registry`: JSON, DualCube's ``.graph``, OBJ, planar code, PLY, OFF, VTK,
    ...), by ``format``, extension or content.  Planar code, which has no axis labels, gives
    the map's only polycube loop structure.

    Parameters
    ----------
    path:
        The file; ``-`` is standard input.
    format:
        A format name of :data:`polyloops.io.registry.FORMATS` (``json``, ``apg``, ``obj``,
        ``planar``, ``ply``, ...), when the extension does not say it.

    Returns
    -------
    Polycube or LoopStructure

    Raises
    ------
    polyloops.io.files.InputError
        When the file cannot be read.
    polyloops.io.formats.FormatError
        When its content is not in the format (the message names the file).
    polyloops.core.halfedge.MapError
        When the faces do not form a closed oriented surface.

    >>> import tempfile, os
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write(load_example("l-shape"), os.path.join(tmp, "l.ply"))
    ...     print(identify(read(os.path.join(tmp, "l.ply"))).name)
    P16.2
    """
    from polyloops.io.formats import Document, FormatError
    from polyloops.io.registry import read_document

    name = os.fspath(path)
    try:
        doc = read_document(name, format)
        if doc.kind == "map":
            from polyloops.enumerate.catalog import only_structure_on

            doc = Document.of(only_structure_on(HalfEdgeMap.from_faces(doc.faces)))
    except FormatError as err:
        raise type(err)(f"{name}: {err}") from None
    return doc.build()


def write(obj: Polycube | LoopStructure, path: str | os.PathLike[str], format: str | None = None) -> None:
    """Write a polycube or loop structure in the format ``format`` or the extension names
    (JSON, ``.graph``, OBJ, planar code, and polycube meshes through meshio: PLY, OFF, VTK,
    VTU, MEDIT, Gmsh, STL), through the shared writer: ``-`` is standard output, a link is
    followed, nothing is left half-written.

    Parameters
    ----------
    obj:
        What to write (the mesh formats and OBJ take polycubes only).
    path:
        The output; ``-`` is standard output (JSON unless ``format`` says otherwise).
    format:
        A format name, when the extension does not say it.

    Returns
    -------
    None

    Raises
    ------
    polyloops.io.registry.FormatChoiceError
        For an extension polyloops does not write, or a loop structure in a mesh format.
    polyloops.io.files.OutputError
        When the output cannot be written.

    >>> write(load_example("cube"), "-", "apg")  # doctest: +ELLIPSIS
    / written by polyloops: ...
    6 12 8
    ...
    """
    from polyloops.io.registry import write_structure

    write_structure(obj, path, format)


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
    "removals",
    "remove_loop",
    "shortest_path",
    "signature",
    "to_obj",
    "verify",
    "write",
]
