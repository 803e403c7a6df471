"""The region search of the torus's second stage (``polyloops.generate.torus.regions``): its
compiled and Python forms agree, without its level-graph cut it lists what the loop-by-loop
search lists (both cut by Condition 3), and with the cut it still builds every genus-1 polycube
at hand from the decomposition through its axis of fewest crossings."""

from __future__ import annotations

import pytest

import polyloops.generate.torus.regions as regions
from polyloops.core.directions import Axis
from polyloops.core.disjoint_sets import ParitySets
from polyloops.core.labellings import admits_polycube, polycube_structures, proper_colourings, sign_components
from polyloops.generate.torus.arrangement import (
    TorusArrangement,
    axis_classes,
    labelled_mesh,
    layered_code,
    walk_forward,
    with_layer,
)
from polyloops.generate.torus.candidates import SecondStage, candidate_torus_arrangements
from polyloops.generate.torus.cuts import base_bound
from polyloops.generate.torus.decompositions import carries_polycube, decomposes
from polyloops.generate.torus.stages import TorusSearchStats, second_stage, two_axis_bases
from polyloops.io.examples import load_example
from switch import needs, running
from test_torus import genus_one_polycubes

needs_compiled = needs("regions")


def _systems(n: int, cut: bool, compiled: bool, monkeypatch) -> tuple[list, TorusSearchStats]:
    stats = TorusSearchStats()
    out = []
    with running("regions", compiled):
        for rank, base in enumerate(two_axis_bases(base_bound(n))):
            for twin, layer in regions.third_axis_systems(base, n, stats, cut_one_way=cut):
                out.append((rank, twin, layer))
    return sorted(out), stats


@needs_compiled
@pytest.mark.parametrize(("n", "cut"), [(16, False), (24, True),
                                        pytest.param(20, False, marks=pytest.mark.slow),
                                        pytest.param(28, True, marks=pytest.mark.slow)])
def test_the_compiled_region_search_lists_what_the_python_one_lists(n, cut, monkeypatch):
    """The same third axes, array for array and as often, and the same regions cut."""
    fast, fast_stats = _systems(n, cut, True, monkeypatch)
    slow, slow_stats = _systems(n, cut, False, monkeypatch)
    assert fast == slow
    assert fast_stats.region_choices == slow_stats.region_choices > 0
    assert fast_stats.third_axes == slow_stats.third_axes == len(fast)
    if cut:
        assert fast_stats.one_way > 0  # the cut acts


def _condition_three(a: TorusArrangement) -> bool:
    m, axes = labelled_mesh(a)
    return sign_components(m, axes) is not None


@needs("torus")  # the loop-by-loop search in Python takes minutes
@pytest.mark.parametrize("n", [20, *(pytest.param(n, marks=pytest.mark.slow) for n in (24, 26))])
def test_without_its_cut_the_region_search_lists_what_the_loop_search_lists(n):
    """For every B, the decompositions (:func:`decomposes`) whose labelling meets
    Condition 3: the same from the region search (level-graph cut off) and from the
    loop-by-loop search, which shares none of its code (by canonical code)."""
    total = 0
    for base in two_axis_bases(base_bound(n)):
        by_loops = second_stage(base, n, TorusSearchStats())
        loops = {layered_code(kid) for kid in by_loops if _condition_three(kid)}
        found = set()
        for twin, layer in regions.third_axis_systems(base, n, cut_one_way=False):
            kid = TorusArrangement(twin, (), layer)
            chosen = frozenset(kid.third_loops())
            if decomposes(TorusArrangement(twin), chosen, n) and _condition_three(kid):
                found.add(layered_code(kid))
        assert found == loops
        total += len(found)
    assert total > 0


def _known_decompositions(max_corners: int):
    """Each genus-1 polycube at hand with each axis whose deletion leaves fewest crossings:
    (the arrangement with that axis's loops as its layer, B)."""
    for ls in genus_one_polycubes(max_corners):
        a = TorusArrangement.of_quad_mesh(ls.map)
        axis_of_loop = {a.loop_of[d]: ls.axis_of_dart(d) for d in range(ls.map.num_darts)}
        by_axis = {axis: frozenset(lp for lp, ax in axis_of_loop.items() if ax == axis) for axis in Axis}
        left = {axis: a.without_loops(set(chosen)) for axis, chosen in by_axis.items()}
        least = min(b.crossings for b in left.values())
        for axis, chosen in by_axis.items():
            if left[axis].crossings == least:
                yield with_layer(a, chosen), left[axis]


@pytest.mark.parametrize("corners", [36, pytest.param(40, marks=pytest.mark.slow)])
def test_the_cut_keeps_every_polycube_at_hand(corners):
    """The ring, the rings along X and Y, the bridged ring (another hole orientation: no loop
    runs round its hole) and every class the moves reach from the ring within ``corners``
    corners: the region search, with every cut, builds each from B."""
    count = 0
    for layered, base in _known_decompositions(corners):
        want = layered_code(layered)
        got = {layered_code(TorusArrangement(twin, (), layer))
               for twin, layer in regions.third_axis_systems(base, layered.crossings)}
        assert want in got
        assert carries_polycube(layered)
        count += 1
    assert count >= 10


def test_the_cycles_of_b_run_both_ways_in_real_polycubes():
    """The bookkeeping of the level-graph cut on real orientations: in every polycube at hand,
    each cycle of a level graph of B has arcs both ways round (the constraints of the true
    signs do not force it one way), and reversing the arcs that run backwards would."""
    checked = 0
    for ls in genus_one_polycubes(36):
        a = TorusArrangement.of_quad_mesh(ls.map)
        system = ls.map.loop_system
        for third in Axis:
            chosen = {a.loop_of[d] for d in range(ls.map.num_darts) if ls.axis_of_dart(d) == third}
            base = a.without_loops(chosen)
            keep = [v for v in range(a.crossings) if not {a.loop_of[4 * v], a.loop_of[4 * v + 1]} & chosen]
            forward = walk_forward(base)
            sign = {}  # per loop of B, +1 when its + side is on the right of B's reference walk
            for d in range(len(base.twin)):
                if forward[d] == 1:
                    # the same dart of the quad mesh: its edge runs from the right of the walk
                    # to its left, and points to the + side when sign * side > 0
                    mesh_dart = 4 * keep[d // 4] + d % 4
                    loop = system.loop_of_dart[mesh_dart]
                    sign[base.loop_of[d]] = -ls.signs[loop] * system.side_of_dart[mesh_dart]
            for cycle in regions.axis_cycles(base, axis_classes(base)):
                first = cycle.loops[0][0]
                true = ParitySets(range(base.num_loops))
                for lp, _ in cycle.loops:
                    assert true.relate(first, lp, sign[first] * sign[lp])
                assert not regions.forced_one_way(cycle, true)
                coherent = ParitySets(range(base.num_loops))
                for lp, rho in cycle.loops:
                    assert coherent.relate(first, lp, cycle.loops[0][1] * rho)
                assert regions.forced_one_way(cycle, coherent)
                checked += 1
    assert checked > 10


def test_admits_polycube_agrees_with_the_structures_a_map_carries(monkeypatch):
    """``admits_polycube`` decides each labelling by axes one at a time; the structures of a
    map enumerate every labelling and every choice of sides together.  On the examples (every
    labelling of the ring carries one) and the candidate maps of 20 crossings (none does)."""
    maps = [load_example(name).map for name in ("ring", "ring-x", "bridged-ring", "l-shape")]
    listed = candidate_torus_arrangements(20, polycubes=False, stage=SecondStage.LOOPS)
    maps += [a.quad_mesh() for a in listed]
    seen = set()
    for m in maps:
        carried = {ls.axes for ls in polycube_structures(m)}
        adjacency: list[set[int]] = [set() for _ in m.loop_system.loops]
        for f in range(m.num_faces):
            a, b = m.loop_system.loops_of_face(m, f)
            adjacency[a].add(b)
            adjacency[b].add(a)
        for colouring in proper_colourings(adjacency):
            admitted = admits_polycube(m, colouring)
            assert admitted == (tuple(Axis(c) for c in colouring) in carried)
            seen.add(admitted)
    assert seen == {True, False}


@needs_compiled
@pytest.mark.parametrize(("genus", "n"), [(1, 32), pytest.param(2, 27, marks=pytest.mark.slow)])
def test_listed_options_and_direct_walks_give_the_same_search(genus, n, monkeypatch):
    """The compiled search lists a region's options once for each numbering of its sides and
    reuses them (``_regions.c``); walking every region directly instead (no option listed), or
    listing only short lists, gives the same third axes in the same order and the same regions
    cut (only the counts of options cut by the signs may differ)."""
    from polyloops.core import compiled

    module = compiled.require("regions")
    systems = module.systems
    bases = list(two_axis_bases(base_bound(n), genus=genus))
    seen = []
    for most in (regions.LISTED_OPTIONS, 0, 3):
        monkeypatch.setattr(module, "systems", lambda spec, _=0, most=most: systems(spec, most))
        stats = TorusSearchStats()
        out = [(rank, *found) for rank, base in enumerate(bases)
               for found in regions.third_axis_systems(base, n, stats)]
        seen.append((out, stats.region_choices, stats.over_bound, stats.third_axes))
    assert seen[0] == seen[1] == seen[2]
    assert seen[0][1] > 0 and (genus == 2 or seen[0][0])  # regions chosen; genus-1 polycubes found
