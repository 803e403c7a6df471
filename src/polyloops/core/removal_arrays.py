"""The removal test of every loop at once, on arrays: the twin of
:func:`polyloops.core.moves.check_removal` for large structures.

Removing loop ``L`` contracts the edges it crosses (its *rungs*); the corners each group of
rungs joins become one corner.  The tuple kernel walks one loop at a time through Python
objects, so its cost follows the memory layout of the input (a file numbered at random made it
2.4 times slower than the same structure in polyloops' own numbering).  Here every loop is
tested at once with sorts, gathers and scipy's connected components, whatever the numbering:

- a *node* is a pair (corner, loop) of a corner on one of the loop's rungs; the merged groups
  are the connected components of the rung graph over nodes, and each must be a tree;
- a face outside the loop's strip must not meet one group at two of its corners;
- the edges that survive at a group, keyed by the group or corner at their far end, must not
  return to the group, must come in at most pairs (and a pair must be the two sides of a strip
  face, with one direction), and the group must keep three or more directions, all distinct;
- the level graph must stay acyclic (:func:`~polyloops.core.moves.closes_cycle`, shared with
  the tuple kernel).

Each condition is the tuple kernel's, in the same words; ``tests/test_kernels.py`` compares the
two verdicts on random structures, valid and not.

>>> from polyloops.io.examples import load_example
>>> removable_loops(load_example("box-2x1x1").dualize()).tolist()
[False, False, True, True]
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from polyloops.core.arrays import components
from polyloops.core.zones import closes_cycle, level_arcs_of

if TYPE_CHECKING:
    from polyloops.core.structure import LoopStructure


def applies(ls: LoopStructure) -> bool:
    """Whether the array test covers ``ls``: an oriented structure whose faces are all quads."""
    return ls.oriented and all(len(face) == 4 for face in ls.map.faces)


def removable_loops(ls: LoopStructure) -> np.ndarray:
    """One verdict per loop: whether removing it leaves a polycube loop structure (the same
    verdicts as :func:`~polyloops.core.moves.check_removal`, for a structure :func:`applies`
    covers).

    Raises
    ------
    ValueError
        When the structure has no sides or a face that is not a quad.
    """
    if not applies(ls):
        raise ValueError("the array removal test needs an oriented structure of quads")
    m, a = ls.map, ls.map.arrays
    loop_of = m.loop_system.loop_array
    loops = len(ls.loops)
    ok = np.ones(loops, dtype=bool)
    # A loop through a face twice crosses itself.
    first = loop_of[a.face_start]
    second = loop_of[a.face_start + 1]
    ok[first[first == second]] = False
    # Nodes: (corner, loop) for the ends of every rung; groups: components of the rungs.
    rung = a.edge_darts
    rung_loop = loop_of[rung]
    ends = np.concatenate([a.origin[rung], a.target[rung]]) * loops + np.concatenate([rung_loop, rung_loop])
    keys, node_of = np.unique(ends, return_inverse=True)
    node_corner, node_loop = keys // loops, keys % loops
    half = len(rung)
    count, group_of_node = components(len(keys), node_of[:half], node_of[half:])
    group_loop = np.empty(count, dtype=np.int64)
    group_loop[group_of_node] = node_loop
    members = np.bincount(group_of_node, minlength=count)
    rungs = np.bincount(group_of_node[node_of[:half]], minlength=count)
    ok[group_loop[members != rungs + 1]] = False  # "would merge around a cycle"
    # Every dart leaving a node's corner, paired with that node.
    dart, node = _darts_at_nodes(a.origin, node_corner, m.num_darts)
    group = group_of_node[node]
    loop = node_loop[node]
    face = a.face_of[dart]
    in_strip = (first[face] == loop) | (second[face] == loop)
    # A surviving face that meets one group at two corners.
    outside = ~in_strip
    _mark_repeats(ok, group_loop, group[outside], face[outside])
    # Surviving edges at each group, keyed by what is at their far end.
    keep = loop_of[dart] != loop
    dart, group, loop = dart[keep], group[keep], loop[keep]
    far_key = a.target[dart] * loops + loop
    at = np.minimum(np.searchsorted(keys, far_key), len(keys) - 1)
    far = np.where(keys[at] == far_key, group_of_node[at], count + a.target[dart])
    ok[group_loop[group[far == group]]] = False  # "an edge would join merged corner c to itself"
    # One integer key per (group, far end); a stable sort keeps each pair's darts in order.
    order = np.argsort(group * (count + m.num_corners) + far, kind="stable")
    dart, group, far = dart[order], group[order], far[order]
    starts = np.flatnonzero(np.r_[True, (group[1:] != group[:-1]) | (far[1:] != far[:-1])][:len(dart)])
    sizes = np.diff(np.r_[starts, len(dart)])
    ok[group_loop[group[starts[sizes > 2]]]] = False  # "edges would join ... twice"
    pairs = starts[sizes == 2]
    d1, d2 = dart[pairs], dart[pairs + 1]
    pair_loop = group_loop[group[pairs]]
    codes = ls.direction_codes

    def strip_face(f: np.ndarray) -> np.ndarray:
        return (first[f] == pair_loop) | (second[f] == pair_loop)

    f1, f2 = a.face_of[a.twin[d2]], a.face_of[a.twin[d1]]
    paired = ((a.face_of[d1] == f1) & strip_face(f1)) | ((a.face_of[d2] == f2) & strip_face(f2))
    ok[pair_loop[~paired | (codes[d1] != codes[d2])]] = False  # "two edges would join ..."
    # Each group keeps three or more segments, in distinct directions.
    kept = group[starts]
    ok[group_loop[np.flatnonzero(np.bincount(kept, minlength=count) < 3)]] = False
    _mark_repeats(ok, group_loop, kept, codes[dart[starts]])
    # The level graph stays acyclic (searched loop by loop where it has a cycle already).
    arcs = level_arcs_of(ls)
    for axis in set(ls.axes):
        bypassed = arcs.bypassed(axis)
        if bypassed is not None:
            ok[list(bypassed)] = False
    for i in np.flatnonzero(ok).tolist():
        if arcs.bypassed(ls.axes[i]) is None and closes_cycle(ls, i, arcs):
            ok[i] = False
    return ok


def _darts_at_nodes(origin: np.ndarray, node_corner: np.ndarray, darts: int) -> tuple[np.ndarray, np.ndarray]:
    """Every pair (dart, node) where the dart leaves the node's corner (nodes sorted by corner)."""
    corners = int(max(origin.max(initial=-1), node_corner.max(initial=-1))) + 1
    per_corner = np.bincount(node_corner, minlength=corners)
    first_node = np.cumsum(per_corner) - per_corner
    repeat = per_corner[origin]
    dart = np.repeat(np.arange(darts), repeat)
    offset = np.arange(len(dart)) - np.repeat(np.cumsum(repeat) - repeat, repeat)
    return dart, first_node[origin[dart]] + offset


def _mark_repeats(ok: np.ndarray, group_loop: np.ndarray, group: np.ndarray, value: np.ndarray) -> None:
    """Mark invalid the loop of every group in which some value occurs twice."""
    if not len(group):
        return
    span = int(value.max()) + 1  # values are non-negative: one integer key per (group, value)
    keys = np.sort(group * span + value)
    twice = keys[1:] == keys[:-1]
    ok[group_loop[keys[1:][twice] // span]] = False
