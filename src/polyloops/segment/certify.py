"""The two checks on every segmentation ``polyloops segment`` writes.

1. :func:`layout_problem`: the layout is the primalized polycube's quad mesh drawn on the
   surface: each patch is a disc, carries its face's normal, and its boundary passes the
   corners of exactly its face's four regions, in the face's order.
2. The labelled-segmentation checker (:func:`polyloops.segmentation.check_segmentation`) on the
   labels alone: valid, with a realising polycube it builds itself.

The second knows nothing of the loops or the layout; the first knows nothing of the checker.
"""

from __future__ import annotations

import numpy as np

from polyloops.segment.layout import Layout

__all__ = ["layout_problem"]


def layout_problem(lay: Layout) -> str | None:
    """What is wrong with the layout as a drawing of the polycube's quad mesh (``None``: nothing)."""
    r = lay.embedded.refined
    tris = r.triangles
    faces = lay.polycube.faces
    if (lay.patch < 0).any():
        return "a triangle lies in no patch"
    corner_region = {}
    for g, c in enumerate(lay.corners):
        corner_region[c] = g
    owner = r.owner
    for f, face in enumerate(faces):
        mine = np.nonzero(lay.patch == f)[0]
        if len(mine) == 0:
            return f"face {f} has no patch"
        if any(lay.labels[t] != lay.polycube.face_normal(f) for t in mine.tolist()):
            return f"patch {f} carries another label than its face's normal"
        nxt: dict[int, int] = {}
        edges = set()
        for t in mine.tolist():
            a, b, c = tris[t].tolist()
            for u, v in ((a, b), (b, c), (c, a)):
                edges.add((min(u, v), max(u, v)))
                if lay.patch[owner[v, u]] != f:
                    if u in nxt:
                        return f"patch {f} touches itself at vertex {u}"
                    nxt[u] = v
        verts = len(np.unique(tris[mine]))
        if verts - len(edges) + len(mine) != 1:
            return f"patch {f} is not a disc"
        start = min(nxt)
        walk, v = [start], nxt[start]
        while v != start:
            walk.append(v)
            v = nxt[v]
        if len(walk) != len(nxt):
            return f"patch {f} has more than one boundary curve"
        seen = [corner_region[v] for v in walk if v in corner_region]
        want = list(face)
        if len(seen) != 4 or not any(seen[k:] + seen[:k] == want for k in range(4)):
            return f"patch {f} meets the corners of regions {seen}, not {want}"
    return None
