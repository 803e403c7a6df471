"""A summary of a structure: sizes, loops, genus, zones, level graphs, corner degrees.

>>> from polyloops.io.examples import load_example
>>> s = describe(load_example("ring"))
>>> s["corners"], s["faces"], s["loops"], s["genus"]
(32, 32, {'X': 4, 'Y': 4, 'Z': 2}, 1)
"""

from __future__ import annotations

from collections import Counter
from typing import Any

from polyloops.core.corners import corner_histogram
from polyloops.core.directions import Axis
from polyloops.core.duality import DualityError, dualize
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.io.formats import Structure
from polyloops.verify.loop_structure import genus_balance


def _loop_part(ls: LoopStructure) -> dict[str, Any]:
    out: dict[str, Any] = {
        "oriented": ls.oriented,
        "loops": {a.name: ls.axes.count(a) for a in Axis},
        "self_crossing_loops": [lp.id for lp in ls.loops if lp.self_crossings],
        "zones": {a.name: {"count": ls.zones(a).count, "genera": list(ls.zones(a).genera)} for a in Axis},
        "theorem3": {b.axis.name: b.to_json() for b in genus_balance(ls)},
    }
    if ls.oriented:
        import networkx as nx

        graphs = {}
        for a in Axis:
            g = ls.level_graph(a)
            graphs[a.name] = {"vertices": g.number_of_nodes(), "arcs": g.number_of_edges(),
                              "acyclic": nx.is_directed_acyclic_graph(g),
                              "arc_list": [[u, v, k] for u, v, k in sorted(g.edges(keys=True))]}
        out["level_graphs"] = graphs
        from polyloops.core.holes import hole_orientation

        out["hole_orientation"] = hole_orientation(ls).to_json()
    return out


def describe(obj: Structure) -> dict[str, Any]:
    """A JSON-ready summary of a polycube or loop structure: sizes, corner degrees and categories,
    genus, and for a loop structure (a polycube is dualized first when it can be) its loops,
    zones, level graphs, Theorem 3 and hole orientation.

    Parameters
    ----------
    obj:
        A :class:`~polyloops.core.polycube.Polycube` or
        :class:`~polyloops.core.structure.LoopStructure`, valid or not.

    Returns
    -------
    dict
        Plain JSON types; ``polyloops info --json`` prints it.

    Notes
    -----
    Nothing is raised for a built structure; what cannot be computed is reported in the
    summary.

    >>> from polyloops.io.examples import load_example
    >>> s = describe(load_example("ring"))
    >>> s["corners"], s["faces"], s["loops"], s["genus"]
    (32, 32, {'X': 4, 'Y': 4, 'Z': 2}, 1)
    """
    m = obj.map
    out: dict[str, Any] = {
        "kind": "polycube" if isinstance(obj, Polycube) else "loop-structure",
        "corners": m.num_corners,
        "edges": m.num_edges,
        "faces": m.num_faces,
        "genus": m.genus,
        "corner_degrees": dict(sorted(Counter(m.degree(c) for c in range(m.num_corners)).items())),
    }
    ids, categories, unclassified = corner_histogram(obj)
    out["corner_categories"] = categories
    out["corner_configurations"] = ids
    out["unclassified_corners"] = unclassified
    ls: LoopStructure | None = None
    if isinstance(obj, Polycube):
        lo, hi = obj.bounding_box()
        out["bounding_box"] = [list(lo), list(hi)]
        try:
            ls = dualize(obj)
        except DualityError as err:
            out["dual"] = f"none: {err}"
            out["loops"] = None
    else:
        ls = obj
    if ls is not None:
        out.update(_loop_part(ls))
    return out
