"""The torus search (genus-1 candidate maps) against its slow twin and the theorems it uses."""

import random

import pytest

from polyloops.core import compiled as compiled_parts
from polyloops.core.canonical import from_signature
from polyloops.core.directions import Axis
from polyloops.core.labellings import polycube_structures, proper_colourings
from polyloops.generate.torus import stages
from polyloops.generate.torus.arrangement import TorusArrangement, canonical
from polyloops.generate.torus.candidates import SecondStage, candidate_torus_arrangements
from polyloops.generate.torus.cuts import (
    axis_runs,
    base_bound,
    layered_need,
    orientable,
    third_sides_consistent,
    zones_split_every_loop,
)
from polyloops.generate.torus.decompositions import independent_with_bipartite_rest, two_stage_decompositions
from polyloops.generate.torus.stages import torus_arrangements, torus_children, two_axis_bases
from polyloops.io.examples import load_example
from polyloops.reach.search import explore, stored_signatures
from reference.torus_brute import _least_code, torus_maps_by_brute_force
from switch import needs, running

LOOPS = SecondStage.LOOPS  # the loop-by-loop second stage, which lists maps without a polycube too


def by_size(arrangements, n):
    return {_least_code(list(a.twin)) for a in arrangements if a.crossings == n}


@pytest.mark.parametrize("compiled", [False, True])
@pytest.mark.parametrize("n", [1, 2, 3, 4, 5, pytest.param(6, marks=pytest.mark.slow)])
def test_the_search_lists_what_brute_force_lists(n, compiled, monkeypatch):
    """Every cellular arrangement of simple loops on the torus with n crossings, once: the
    canonical construction path over marked maps, in Python and compiled, against a brute
    force over all pairings of darts (the same arrangements, compared by the twin's own
    canonical code)."""
    with running("torus", compiled):
        found = list(torus_arrangements(n))
    codes = by_size(found, n)
    assert len(codes) == sum(a.crossings == n for a in found)  # none twice
    assert codes == torus_maps_by_brute_force(n)


def renumbered(a: TorusArrangement, rng: random.Random, mirror: bool) -> TorusArrangement:
    """The same arrangement with crossings renumbered, each crossing's darts turned, and
    perhaps seen in a mirror (the darts of each crossing read clockwise)."""
    n = a.crossings
    perm = list(range(n))
    rng.shuffle(perm)
    turn = [rng.randrange(4) for _ in range(n)]

    def new(d: int) -> int:
        v, i = divmod(d, 4)
        i = (-i if mirror else i) % 4
        return 4 * perm[v] + (i + turn[v]) % 4

    twin = [0] * len(a.twin)
    for d, t in enumerate(a.twin):
        twin[new(d)] = new(t)
    marks = tuple((kind, new(_rot(d) if mirror else d)) for kind, d in a.marks)
    return TorusArrangement(tuple(twin), marks)


def _rot(d):
    return 4 * (d // 4) + (d + 1) % 4


def test_canonical_codes_do_not_depend_on_numbering_or_mirror():
    """Renumbered and mirrored copies of arrangements, cellular or marked, get the same code;
    different arrangements get different ones."""
    rng = random.Random(7)
    states = [kid for root in (0, 1) for kid, _ in torus_children(root, 4)]
    states += [kid for s in list(states) for kid, _ in torus_children(s, 4)]
    assert any(s.marks for s in states) and any(not s.marks for s in states)
    codes = [canonical(s)[0] for s in states]
    assert len(set(codes)) == len(codes)
    for s, code in zip(states, codes, strict=True):
        for mirror in (False, True):
            assert canonical(renumbered(s, rng, mirror))[0] == code


def test_candidate_cuts_keep_every_candidate():
    """The bound and the cuts of the candidate search drop nothing: its candidate maps are
    those of the unpruned search that are candidates."""
    n = 6
    everything = list(torus_arrangements(n))
    candidates = {canonical(a)[0] for a in torus_arrangements(n, colours=3, regions=True)}
    expected = set()
    for a in everything:
        sizes_ok = all(3 <= len(f) <= 6 for f in a.faces)
        meets_once = all(len({a.loop_of[d] for d in f}) == len(f) for f in a.faces)
        sides = [(a.face_of[d], a.face_of[a.twin[d]]) for d in range(len(a.twin))]
        simple = all(f != g for f, g in sides) and len(set(sides)) == len(sides)
        colourable = next(proper_colourings(a.crossing_graph()), None) is not None
        if sizes_ok and meets_once and simple and colourable:
            expected.add(canonical(TorusArrangement(a.twin))[0])
    assert candidates == expected


def genus_one_polycubes(max_corners: int):
    """Genus-1 polycube loop structures: the examples, and every class the moves reach from
    the ring within ``max_corners`` corners."""
    import tempfile
    from pathlib import Path

    out = [load_example(name).dualize() for name in ("ring", "ring-x", "ring-y", "bridged-ring")]
    with tempfile.TemporaryDirectory() as tmp:
        explore(out[0], max_corners, directory=Path(tmp) / "reach", mode="full")
        out += [from_signature(sig) for sig in stored_signatures(Path(tmp) / "reach")]
    return out


@pytest.fixture(scope="module")
def genus_one():
    return genus_one_polycubes(40)


def test_deleting_one_axis_leaves_a_cellular_two_axis_arrangement(genus_one):
    """The two-stage theorem on every genus-1 polycube at hand: for each axis, the loops of the
    two others form a cellular arrangement whose regions are the paths of that axis's edges,
    and the deleted loops cross each region at most once; the axis leaving fewest crossings
    gives a decomposition the second stage builds."""
    assert len(genus_one) > 10
    for ls in genus_one:
        a = TorusArrangement.of_quad_mesh(ls.map)
        axis_of_loop = {a.loop_of[d]: ls.axis_of_dart(d) for d in range(ls.map.num_darts)}
        crossings = {}
        for axis in Axis:
            chosen = {lp for lp, ax in axis_of_loop.items() if ax == axis}
            base = a.without_loops(chosen)  # raises unless cellular
            crossings[axis] = base.crossings
        least = min(crossings, key=crossings.get)
        chosen = frozenset(lp for lp, ax in axis_of_loop.items() if ax == least)
        assert 3 * crossings[least] <= a.crossings
        assert chosen in two_stage_decompositions(a, a.crossings)


@pytest.mark.parametrize("slow", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_genus_one_structures_check_condition_five(slow):
    """At genus 1 the structures a map carries are those the full checker accepts among all
    labellings and sides (Condition 5 is not automatic there)."""
    from itertools import product

    from polyloops.verify.loop_structure import check_polycube_loop_structure

    ring = load_example("ring").map
    found = {(ls.axes, ls.signs) for ls in polycube_structures(ring)}
    assert found
    for ls in list(polycube_structures(ring))[:4]:
        assert check_polycube_loop_structure(ls).valid
    # a brute-force twin on small torus maps: every labelling and every choice of sides
    from polyloops.core.structure import LoopStructure

    maps = [load_example("torus-cycle").map] + [a.quad_mesh() for a in torus_arrangements(9, 3, True)]
    for torus in maps:
        if len(torus.loop_system.loops) > 4 and not slow:
            continue  # five loops: 7,776 structures to check, six: 46,656 (40 s)
        loops = len(torus.loop_system.loops)
        valid = set()
        for axes in product(tuple(Axis), repeat=loops):
            for signs in product((1, -1), repeat=loops):
                if check_polycube_loop_structure(LoopStructure(torus, axes, signs)).valid:
                    valid.add((axes, signs))
        assert {(ls.axes, ls.signs) for ls in polycube_structures(torus)} == valid


@pytest.mark.slow  # 25 s: the one-stage search at 12 crossings
def test_the_two_stages_list_what_the_direct_search_lists():
    """The second stage (every B, then third-axis loops) lists exactly the candidate maps of
    the direct search that the two-stage theorem decomposes (three at 12 crossings)."""
    n = 12
    direct = list(torus_arrangements(n, colours=3, regions=True))
    want = {canonical(TorusArrangement(a.twin))[0] for a in direct if two_stage_decompositions(a, n)}

    got = [canonical(a)[0] for a in candidate_torus_arrangements(n, polycubes=False, stage=LOOPS)]
    assert len(got) == len(set(got)) and set(got) == want and want


def test_layered_need_counts_sides_of_each_class():
    """A region of B with eight sides alternating between its two axes needs four later
    crossing points (each piece holds two sides of an axis at most); three sides of the third
    axis can never become a corner."""
    assert layered_need(8, [0, 1] * 4, False) == 4
    assert layered_need(6, [0, 1, 2, 0, 1, 2], False) == 0
    assert layered_need(5, [0, 2, 1, 2, 2], False) > 1000


def test_genus_one_records_carry_the_hole_invariant_and_torus_names():
    """The ring's map gives one class in each mode, named T32.1 up to all symmetries; each
    record carries the hole-orientation invariant of the structure its signature names."""
    from polyloops.catalog.classes import map_classes
    from polyloops.catalog.records import class_names
    from polyloops.core.canonical import canonical_form
    from polyloops.core.holes import hole_orientation

    ring = load_example("ring").dualize()
    classes = map_classes(ring.map)
    assert [len(classes[m]) for m in ("labelled", "rotation", "full")] == [3, 1, 1]
    full = classes["full"][0]
    assert full.holes == str(hole_orientation(canonical_form(ring, "full").structure))
    assert str(hole_orientation(ring)) in {r.holes for r in classes["labelled"]}
    assert class_names([full], "full", genus=1) == ["T32.1"]
    assert type(full).from_json(full.to_json()) == full


def test_catalog_command_builds_genus_one(tmp_path, capsys):
    """`catalog --genus 1` runs the torus generator; its summary says genus 1 and counts odd
    corner counts too; a genus-0 generator or a genus-0 build into it is refused."""
    import json

    from polyloops.cli import main

    out = tmp_path / "g1"
    assert main(["catalog", "--genus", "1", "--max-corners", "13", "-o", str(out), "--json"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["genus"] == 1 and summary["generator"] == "torus"
    assert set(summary["counts"]) == {str(n) for n in range(8, 14)}
    assert summary["search"]["states"] > 0
    capsys.readouterr()
    assert main(["catalog", "--genus", "1", "--generator", "loops", "--max-corners", "13", "-o",
                 str(tmp_path / "x")]) == 2
    assert "genus 0, not 1" in capsys.readouterr().err
    assert main(["catalog", "--max-corners", "12", "-o", str(out)]) == 2
    assert "genus 1" in capsys.readouterr().err


@pytest.mark.slow  # about two minutes
def test_each_map_comes_from_its_canonical_decomposition_and_none_is_lost(monkeypatch):
    """Listing each map from its canonical decomposition only (so that shares never repeat a
    map) keeps every map the second stage reaches: the same maps as the whole search with
    duplicates removed by code, at 20 crossings."""


    n = 20
    reached = set()
    for base in two_axis_bases(base_bound(n)):
        stack = [TorusArrangement(base.twin, (), (0,) * len(base.twin))]
        while stack:
            kids = torus_children(stack.pop(), n, None, True)
            for kid, facts in kids:
                if facts.target and two_stage_decompositions(TorusArrangement(kid.twin), kid.crossings):
                    reached.add(canonical(TorusArrangement(kid.twin))[0])
            stack.extend(kid for kid, _ in kids)
    listed = [canonical(a)[0] for a in candidate_torus_arrangements(n, polycubes=False, stage=LOOPS)]
    assert len(listed) == len(set(listed)) and set(listed) == reached


def test_the_second_stage_orients_the_third_axis(monkeypatch):
    """The orientation cut drops states (so it can fail), and every map listed has a
    decomposition whose third-axis loops it can orient."""

    stats = []
    listed = list(candidate_torus_arrangements(14, on_stats=stats.append, polycubes=False, stage=LOOPS))
    assert stats[0].inconsistent_sides > 0 and listed
    for a in listed:
        decompositions = two_stage_decompositions(a, a.crossings)
        assert decompositions
        for chosen in decompositions:
            layer = tuple(int(a.loop_of[d] in chosen) for d in range(len(a.twin)))
            assert third_sides_consistent(TorusArrangement(a.twin, (), layer))


def _second_stage_states(n: int, compiled: bool, monkeypatch) -> tuple[dict, set]:
    """Every state the second stage keeps up to ``n`` crossings, by Python canonical code, and
    the targets among them."""

    states, targets = {}, set()
    with running("torus", compiled):
        for base in two_axis_bases(base_bound(n)):
            stack = [TorusArrangement(base.twin, (), (0,) * len(base.twin))]
            while stack:
                kids = torus_children(stack.pop(), n, None, True)
                for kid, facts in kids:
                    code = canonical(TorusArrangement(kid.twin, (), kid.layer))[0]
                    assert code not in states  # each state once
                    states[code] = kid
                    if facts.target:
                        targets.add(code)
                stack.extend(kid for kid, _ in kids)
    return states, targets


@needs("torus")
@pytest.mark.parametrize("n", [16, *(pytest.param(n, marks=pytest.mark.slow) for n in (18, 20, 24))])
def test_the_compiled_second_stage_keeps_the_python_states(n, monkeypatch):
    """The compiled second stage keeps exactly the states of the Python search (by canonical
    code, every state once), with the same targets."""
    slow, slow_targets = _second_stage_states(n, False, monkeypatch)
    fast, fast_targets = _second_stage_states(n, True, monkeypatch)
    assert set(fast) == set(slow) and fast_targets == slow_targets and len(slow) > (100 if n >= 18 else 10)


@pytest.mark.slow  # 15 s: the Python search twice
@needs("torus")
@pytest.mark.parametrize("n", [18, 20])
def test_the_compiled_search_lists_the_python_candidate_maps(n, monkeypatch):
    """Both stages and the decomposition test, compiled and in Python: the same candidate
    maps, each once."""

    with running("torus", True):
        with_c = [canonical(a)[0] for a in candidate_torus_arrangements(n, polycubes=False, stage=LOOPS)]
    with running("torus", False):
        in_python = [canonical(a)[0] for a in candidate_torus_arrangements(n, polycubes=False, stage=LOOPS)]
    assert len(with_c) == len(set(with_c)) and set(with_c) == set(in_python) and with_c


def test_the_second_stage_never_crosses_its_start_edge_again(monkeypatch):
    """No state of the second stage has a face of two sides with a third-axis side (the cut
    that skips crossing the start edge again loses nothing: such a face never becomes a
    corner), in Python and compiled."""
    for compiled in (False, *((True,) if compiled_parts.in_use("torus") else ())):
        states, _ = _second_stage_states(14, compiled, monkeypatch)
        for kid in states.values():
            assert not any(len(f) == 2 and any(kid.layer[d] for d in f) for f in kid.faces)


@needs("torus")
@pytest.mark.parametrize(("n", "colours"), [(5, None), (6, 2), pytest.param(7, 2, marks=pytest.mark.slow)])
def test_the_compiled_first_stage_keeps_the_python_states(n, colours, monkeypatch):
    """The compiled marked search keeps exactly the states of the Python one (marked states
    included, by canonical code), each once."""

    def states(compiled: bool) -> list:
        out, stack = [], [1, 0]
        with running("torus", compiled):
            while stack:
                node = stack.pop()
                kids = torus_children(node, n, colours)
                out += [canonical(kid)[0] for kid, _ in kids]
                stack.extend(kid for kid, _ in kids)
        return out

    slow, fast = states(False), states(True)
    assert len(fast) == len(set(fast)) and set(fast) == set(slow) and any(c[2] for c in slow)


def test_decompositions_are_tried_over_every_set_of_loops():
    """The sets of loops the decompositions are chosen from (colour classes of 3-colourings)
    are exactly the nonempty proper sets, no two of which cross, whose complement has a
    bipartite crossing graph: checked against every set of loops."""
    from itertools import combinations

    arrangements = list(torus_arrangements(5)) + list(torus_arrangements(9, 3, True))
    assert len(arrangements) > 50
    for a in arrangements:
        adj = a.crossing_graph()
        want = set()
        for k in range(1, a.num_loops):
            for chosen in combinations(range(a.num_loops), k):
                rest = [v for v in range(a.num_loops) if v not in chosen]
                sub = [{rest.index(u) for u in adj[v] if u in rest} for v in rest]
                if not any(adj[v] & set(chosen) for v in chosen) and next(proper_colourings(sub, 2), None):
                    want.add(frozenset(chosen))
        assert set(independent_with_bipartite_rest(adj)) == want


def test_new_third_axis_loops_turn_at_least_four_times():
    """The rectilinear cut drops states (so it can fail), and in every state kept each loop
    of the third axis crosses the two classes of B in four runs at least; the polycube
    structures of the examples have that property on every loop and axis pair."""
    from polyloops.core.directions import Axis as A

    stats = []
    list(candidate_torus_arrangements(16, on_stats=stats.append, polycubes=False, stage=LOOPS))
    assert stats[0].not_rectilinear > 0
    states, _ = _second_stage_states(16, True, pytest.MonkeyPatch())
    assert all(axis_runs(kid, lp) >= 4 for kid in states.values() for lp in kid.third_loops())
    for name in ("ring", "bridged-ring", "l-shape", "cube"):
        ls = load_example(name).dualize()
        for third in A:
            loop_of = ls.map.loop_system.loop_of_dart
            layer = tuple(int(ls.axes[loop_of[d]] == third) for d in range(len(ls.map.twin)))
            arrangement = TorusArrangement(tuple(ls.map.twin), (), layer)
            assert all(axis_runs(arrangement, lp) >= 4 for lp in arrangement.third_loops())


@pytest.mark.parametrize("genus1_top", [44, pytest.param(99, marks=pytest.mark.slow)])
def test_every_loop_of_every_catalog_class_crosses_the_other_axes_in_four_runs(genus1_top):
    """The four-runs lemma on independent data: every loop of every genus-0 class through 32
    corners and of the genus-1 catalog through 44 (all of it, slow), the axes crossed along it
    counted in runs."""
    from polyloops.catalog.census import default_catalog, read_catalog

    checked = 0
    for genus, top in ((0, 32), (1, genus1_top)):
        for entry in read_catalog(default_catalog(genus)).entries:
            if entry.corners > top:
                continue
            ls = entry.structure()
            arrangement = TorusArrangement(tuple(ls.map.twin))
            loop_of = ls.map.loop_system.loop_of_dart
            axis = {arrangement.loop_of[d]: int(ls.axes[loop_of[d]]) for d in range(len(ls.map.twin))}
            klass = [axis[lp] for lp in range(arrangement.num_loops)]
            runs = [axis_runs(arrangement, lp, klass) for lp in range(arrangement.num_loops)]
            assert min(runs) >= 4, entry.name
            checked += 1
    assert checked > 700


@pytest.mark.parametrize("genus1_top", [44, pytest.param(99, marks=pytest.mark.slow)])
def test_real_polycubes_are_orientable_with_any_axis_third(genus1_top):
    """The orientation cut never refuses a real structure: every genus-0 class through 30
    corners and every genus-1 class through 44 (all of them, slow), with each axis taken as the
    third, passes :func:`orientable` (each of its constraints is Condition 3 at a corner of the
    polycube)."""
    from polyloops.catalog.census import default_catalog, read_catalog
    from polyloops.core.directions import Axis as A

    checked = 0
    for genus, top in ((0, 30), (1, genus1_top)):
        for entry in read_catalog(default_catalog(genus)).entries:
            if entry.corners > top:
                continue
            ls = entry.structure()
            loop_of = ls.map.loop_system.loop_of_dart
            for third in A:
                layer = tuple(int(ls.axes[loop_of[d]] == third) for d in range(len(ls.map.twin)))
                assert orientable(TorusArrangement(tuple(ls.map.twin), (), layer)), (entry.name, third)
                checked += 1
    assert checked > 700


@pytest.mark.parametrize(("n", "colours"), [(5, None), (6, 2), pytest.param(6, None, marks=pytest.mark.slow),
                                             pytest.param(7, 2, marks=pytest.mark.slow),
                                             pytest.param(8, 2, marks=pytest.mark.slow)])
def test_each_curve_drawn_from_one_start_keeps_every_state(n, colours):
    """The first stage draws a new curve from one dart of each edge, from the least edge it
    crosses only, and round a single loop with the loop's mark just before the curve's first
    point; the Python search drawing every curve from every start, the mark in every gap, keeps
    exactly the same states with the same facts, in the same order."""

    def states(every: bool) -> list:
        out, stack, stats = [], [1, 0], stages.TorusSearchStats()
        with running("torus", False):
            while stack:
                node = stack.pop()
                kids = torus_children(node, n, colours, False, stats, every_start=every)
                out += [(kid.code, facts) for kid, facts in kids]
                stack.extend(kid for kid, _ in kids)
        return [out, stats.closed]

    (every, closed_every), (once, closed_once) = states(True), states(False)
    assert once == every and any(f.target for _, f in once)
    assert closed_once < closed_every / 2  # and the shortcuts do spare work


@needs("torus")
def test_the_compiled_zones_agree_with_the_python_zones():
    """The compiled first stage's flag (the zones of each class split every loop) is
    ``zones_split_every_loop`` on every cellular two-colour arrangement through 9 crossings,
    both answers occurring."""
    seen = {True: 0, False: 0}
    for a, facts in stages._targets(9, 2, False, None):
        assert facts.split is not None and facts.split == zones_split_every_loop(a)
        seen[facts.split] += 1
    assert min(seen.values()) > 40, seen
