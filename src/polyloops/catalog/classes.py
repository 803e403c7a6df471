"""The catalog of genus-0 polycubes, up to order-equivalence, by number of corners.

For each quadrangulation from plantri that survives the batch filter (no self-crossing
loop), :func:`polycube_structures` finds every labelling and orientation that makes it a
polycube loop structure: crossing loops get different axes (a proper 3-colouring of the
crossing graph), and Condition 3 holds at every corner (a 2-colouring of the side graph of
each axis; each component is a free choice).  Condition 5 holds at genus 0 and Conditions 1,
2 and 4 hold for every simple quadrangulation with minimum degree 3.

Structures are then identified by signature in each symmetry mode.  plantri lists each map
once, mirror images identified, and signatures identify mirror images too, so structures on
different maps never coincide: classes are counted map by map.

>>> from polyloops.io.examples import load_example
>>> cube = load_example("cube").map
>>> classes = map_classes(cube)
>>> {str(mode): len(v) for mode, v in classes.items()}
{'labelled': 1, 'rotation': 1, 'full': 1}
"""

from __future__ import annotations

from typing import Any

from polyloops.catalog.records import CatalogRecord
from polyloops.core.canonical import CanonicalForm, canonical_form
from polyloops.core.corners import CATEGORIES, corner_histogram
from polyloops.core.directions import Axis
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.holes import hole_orientation
from polyloops.core.labellings import (  # re-exported: the catalog's step 3 lives in the kernel
    MapStructureError,
    only_structure_on,
    polycube_classes_on,
    polycube_structures,
)
from polyloops.core.moves import removals
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import Symmetry

__all__ = ["MODES", "CatalogRecord", "MapStructureError", "map_classes", "only_structure_on",
           "polycube_classes_on", "polycube_structures"]

MODES = tuple(Symmetry)  # labelled, rotation, full


def map_classes(m: HalfEdgeMap) -> dict[str, list[CatalogRecord]]:
    """The polycube classes on one map, in every symmetry mode."""
    labelled: dict[str, tuple[LoopStructure, CanonicalForm]] = {}
    for ls in polycube_structures(m):
        form = canonical_form(ls, "labelled")
        labelled.setdefault(form.signature, (ls, form))
    out: dict[str, dict[str, CatalogRecord]] = {mode: {} for mode in MODES}
    # The corner categories and the removable loops are the same for every image of a class
    # under a symmetry: worked out once a full class, not once a labelled one.
    invariants: dict[str, tuple[Any, int]] = {}
    positive_genus = m.genus > 0
    for ls, form in labelled.values():
        full = canonical_form(ls, "full")
        chiral = not full.achiral
        forms = {"labelled": form, "rotation": canonical_form(ls, "rotation"), "full": full}
        if full.signature not in invariants:
            invariants[full.signature] = (corner_histogram(ls)[1], len(removals(ls)))
        categories, removable = invariants[full.signature]
        for mode, form in forms.items():
            key = form.signature
            if key not in out[mode]:
                # Symmetries permute the axes: count loops on the class's own representative,
                # the structure its signature names, not on the one met first.
                rep = ls if mode == "labelled" else form.structure
                holes = str(hole_orientation(rep)) if positive_genus else None
                out[mode][key] = CatalogRecord(
                    key, m.num_corners, m.num_faces, {a.name: rep.axes.count(a) for a in Axis},
                    {c: categories[c] for c in CATEGORIES}, form.automorphisms, chiral, removable, holes)
    return {mode: list(v.values()) for mode, v in out.items()}
