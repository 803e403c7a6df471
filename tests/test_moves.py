"""Loop moves: the fast addition and removal tests equal brute force, and the paper's claims."""

import json
from functools import cache

import networkx as nx
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from cli_run import run
from polyloops.cli import main
from polyloops.core.canonical import signature
from polyloops.core.directions import Axis
from polyloops.core.moves import (
    Addition,
    add_loop,
    additions,
    canonical_cycle,
    count_additions,
    is_valid_addition,
    removals,
    remove_loop,
    try_remove,
)
from polyloops.io.examples import load_example
from polyloops.io.formats import loads
from polyloops.verify import check_polycube, check_polycube_loop_structure
from polyloops.verify.loop_structure import cycle_violations
from polyloops.verify.report import ReportBuilder
from strategies import grown_structures, handle_zone_polycubes, polycubes


def corner_graph(ls, avoid=None):
    m = ls.map
    return nx.Graph((m.origin(d), m.target(d)) for d in range(m.num_darts)
                    if avoid is None or ls.axis_of_dart(d) != avoid)


def valid_after_insert(ls, move):
    try:
        new = add_loop(ls, move)
    except ValueError:
        return False
    return check_polycube_loop_structure(new).valid


def brute_additions(ls, prune=True):
    """Every simple cycle of corners, both directions, every label, inserted and checked with the
    full Definition-4 checker.  With ``prune``, only cycles avoiding edges of the new loop's axis
    are tried (an edge of that axis would make the new loop cross a loop of its own axis);
    test_pruning_loses_nothing checks that on small structures."""
    out = set()
    for axis in Axis:
        g = corner_graph(ls, axis if prune else None)
        for cycle in nx.simple_cycles(g):
            if len(cycle) < 3:
                continue
            for walk in (cycle, cycle[::-1]):
                move = Addition(axis, canonical_cycle(walk))
                if valid_after_insert(ls, move):
                    out.add(move)
    return out


def brute_removals(ls):
    out = []
    for lp in ls.loops:
        new = try_remove(ls, lp.id)
        if new is not None and check_polycube_loop_structure(new).valid:
            out.append(lp.id)
    return out


@cache
def within_three_moves():
    """Every structure within three moves of the cube, one per class under all 48 symmetries."""
    cube = load_example("cube").dualize()
    seen = {signature(cube): cube}
    level = [cube]
    for _ in range(3):
        nxt = []
        for ls in level:
            for x in [add_loop(ls, mv) for mv in additions(ls)] + [remove_loop(ls, i) for i in removals(ls)]:
                s = signature(x)
                if s not in seen:
                    seen[s] = x
                    nxt.append(x)
        level = nxt
    return list(seen.values())


def test_three_moves_set_is_nontrivial():
    structures = within_three_moves()
    assert len(structures) > 10
    assert all(check_polycube_loop_structure(x).valid for x in structures)


@pytest.mark.parametrize("i", range(17))
def test_fast_equals_brute_within_three_moves(i):
    structures = within_three_moves()
    if i >= len(structures):
        pytest.skip("fewer structures")
    ls = structures[i]
    fast = list(additions(ls))
    assert len(fast) == len(set(fast))
    assert set(fast) == brute_additions(ls)
    assert sum(count_additions(ls).values()) == len(fast)
    assert removals(ls) == brute_removals(ls)


@pytest.mark.parametrize("name", ["cube", "box-2x1x1", pytest.param("l-shape", marks=pytest.mark.slow)])
def test_pruning_loses_nothing(name):
    ls = load_example(name).dualize()
    assert brute_additions(ls, prune=False) == brute_additions(ls, prune=True)


@settings(max_examples=25)
@given(polycubes(kinds=("blob",), max_size=3))
def test_fast_equals_brute_on_random_polycubes(q):
    ls = q.dualize()
    assert set(additions(ls)) == brute_additions(ls)
    assert removals(ls) == brute_removals(ls)


@given(polycubes())
def test_fast_removal_equals_brute_on_larger_polycubes(q):
    ls = q.dualize()
    assert removals(ls) == brute_removals(ls)


@settings(max_examples=30)
@given(polycubes(), st.integers(0, 10**6))
def test_additions_never_create_a_level_graph_cycle(q, pick):
    ls = q.dualize()
    moves = list(additions(ls, limit=60))
    for move in moves[pick % max(1, len(moves)):][:8]:
        new = add_loop(ls, move)
        assert not cycle_violations(ReportBuilder("loop-structure", "Definition 4"), new), (q.genus, move)
        assert check_polycube_loop_structure(new).valid


@settings(max_examples=20)
@given(polycubes(kinds=("blob", "frame1"), max_size=3),
       st.lists(st.integers(0, 10**6), min_size=1, max_size=5))
def test_any_sequence_of_moves_keeps_a_polycube(q, picks):
    """A drawn sequence of moves (each a drawn index into the valid additions and removals):
    hypothesis shrinks a failure to the shortest sequence on the smallest shape."""
    ls = q.dualize()
    for p in picks:
        options = [("add", mv) for mv in additions(ls, limit=40)] + [("remove", i) for i in removals(ls)]
        kind_, arg = options[p % len(options)]
        ls = add_loop(ls, arg) if kind_ == "add" else remove_loop(ls, arg)
        assert check_polycube_loop_structure(ls).valid
        assert check_polycube(ls.primalize()).valid


def test_paper_addition_sequence():
    """The paper's figure: from the cube a Z-loop, then a Y-loop placed between existing loops
    (through corners that the Z-loop created), then an X-loop."""
    ls = load_example("cube").dualize()
    z = next(additions(ls, Axis.Z))
    ls = add_loop(ls, z)
    n = 8
    y = next(mv for mv in additions(ls, Axis.Y) if any(c >= n for c in mv.cycle)
             and any(c < n for c in mv.cycle))
    ls = add_loop(ls, y)
    x = next(additions(ls, Axis.X))
    ls = add_loop(ls, x)
    assert [ls.axes.count(a) for a in Axis] == [2, 2, 2]
    assert check_polycube(ls.primalize()).valid


@pytest.mark.parametrize("name", ["cube", "box-2x1x1"])
def test_counts_for_cube_and_box(name):
    ls = load_example(name).dualize()
    counts = count_additions(ls)
    brute = brute_additions(ls)
    assert counts == {a.name: sum(1 for mv in brute if mv.axis == a) for a in Axis}
    assert len(removals(ls)) == len(brute_removals(ls))


def test_non_incremental():
    q = load_example("non-incremental")
    ls = q.dualize()
    assert check_polycube(q).valid and check_polycube_loop_structure(ls).valid
    assert signature(ls) != signature(load_example("cube"))
    assert removals(ls) == brute_removals(ls) == []


def test_numbering_after_addition():
    ls = load_example("cube").dualize()
    move = next(additions(ls))
    new = add_loop(ls, move)
    n, k = ls.map.num_corners, len(move.cycle)
    assert new.map.num_corners == n + k
    assert new.map.faces[ls.map.num_faces:] == tuple(
        (move.cycle[(i + 1) % k], move.cycle[i], n + i, n + (i + 1) % k) for i in range(k))


def test_is_valid_addition_matches_listing():
    ls = load_example("box-2x1x1").dualize()
    for mv in additions(ls):
        assert is_valid_addition(ls, mv)
        assert not is_valid_addition(ls, Addition(mv.axis, mv.cycle[::-1]))


def test_cli_moves_count(capsys):
    assert main(["moves", "example:box-2x1x1", "--count", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    ls = load_example("box-2x1x1").dualize()
    assert data["additions"] == count_additions(ls) and data["removals"] == len(removals(ls))


def test_cli_add_and_remove(capsys, tmp_path):
    out = tmp_path / "a.json"
    assert main(["add", "example:cube", "0", "-o", str(out)]) == 0
    added = loads(out.read_text())
    assert check_polycube_loop_structure(added).valid and len(added.loops) == 4
    loop = removals(added)[0]
    back = tmp_path / "b.json"
    assert main(["remove", str(out), str(loop), "-o", str(back)]) == 0
    assert signature(loads(back.read_text())) == signature(load_example("cube"))
    assert main(["remove", "example:cube", "0"]) == 1
    assert "not removable" in capsys.readouterr().err
    assert main(["add", "example:cube", "99"]) == 2
    assert main(["add", "example:cube", "Q:1,2"]) == 2
    assert main(["moves", "example:cube", "--add", "Z", "--json"]) == 0


@pytest.mark.slow
def test_non_incremental_is_five_moves_from_the_cube():
    """Breadth-first search over additions and removals (about 3 minutes): the first structure
    without a removable loop appears at distance 5, and it is the bundled example."""
    target = signature(load_example("non-incremental"))
    cube = load_example("cube").dualize()
    seen = {signature(cube)}
    level = [cube]
    for depth in range(1, 6):
        nxt = []
        for ls in level:
            for x in [add_loop(ls, mv) for mv in additions(ls)] + [remove_loop(ls, i) for i in removals(ls)]:
                s = signature(x)
                if s not in seen:
                    seen.add(s)
                    nxt.append(x)
                    if not removals(x):
                        assert depth == 5 and s == target
                        return
        level = nxt
    pytest.fail("no structure without a removable loop within five moves")


@pytest.mark.parametrize("which", [[], ["--add", "Y"], ["--add", "Z"], ["--add", "all"]])
def test_every_listed_index_adds_the_listed_loop(capsys, tmp_path, which):
    """``moves`` and ``add`` name additions the same way, whichever labels are listed."""
    ls = load_example("box-2x1x1").dualize()
    assert main(["moves", "example:box-2x1x1", *which, "--json"]) == 0
    listed = json.loads(capsys.readouterr().out)["additions"]
    assert listed and len({row["index"] for row in listed}) == len(listed)
    for row in listed:
        out = tmp_path / f"{row['index']}.json"
        assert main(["add", "example:box-2x1x1", row["index"], "-o", str(out)]) == 0
        expected = add_loop(ls, Addition(Axis.parse(row["axis"]), tuple(row["corners"])))
        assert loads(out.read_text()) == expected
    if not which:  # a plain integer counts through the full listing
        for n, row in enumerate(listed):
            out = tmp_path / f"{n}.json"
            assert main(["add", "example:box-2x1x1", str(n), "-o", str(out)]) == 0
            assert loads(out.read_text()) == loads((tmp_path / f"{row['index']}.json").read_text())


@settings(max_examples=20)
@given(polycubes(kinds=("blob",), max_size=2), st.integers(3, 8))
def test_max_length_keeps_exactly_the_short_loops(q, k):
    ls = q.dualize()
    assert list(additions(ls, max_length=k)) == [mv for mv in additions(ls) if len(mv.cycle) <= k]


def test_count_of_one_label_counts_only_that_label(capsys, monkeypatch):
    from polyloops.core import moves

    seen = []
    original = moves._AdditionGraph.__init__

    def spy(self, ls, axis):
        seen.append(axis)
        original(self, ls, axis)

    monkeypatch.setattr(moves._AdditionGraph, "__init__", spy)
    assert main(["moves", "example:box-2x1x1", "--count", "--add", "Y", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["additions"] == {"Y": 6}
    assert seen == [Axis.Y]  # no addition graph was built for X or Z


# -- moves on structures of real size: shortest, sampled, counted within a time ----------------

@settings(max_examples=20)
@given(polycubes(kinds=("blob", "smooth", "frame1"), max_size=3), st.integers(1, 12))
def test_shortest_additions_are_the_shortest(q, k):
    from polyloops.core.moves import shortest_additions

    ls = q.dualize()
    for a in Axis:
        found = shortest_additions(ls, a, k)
        if not found:
            assert next(additions(ls, a), None) is None
            continue
        # Every loop as short as the longest one found is in the listing bounded by its length.
        bounded = list(additions(ls, a, max_length=len(found[-1].cycle)))
        by_length = sorted(bounded, key=lambda mv: len(mv.cycle))  # stable: ties in listing order
        assert found == by_length[:k]


@settings(max_examples=20)
@given(polycubes(kinds=("blob", "smooth", "frame1"), max_size=3), st.integers(0, 2**16), st.integers(1, 6))
def test_sampled_additions_are_listed_valid_and_reproducible(q, seed, n):
    from polyloops.core.moves import sample_additions

    ls = q.dualize()
    for a in Axis:
        picked = sample_additions(ls, a, n, seed)
        assert len(picked) <= n and len({mv.cycle for mv in picked}) == len(picked)
        small = ls.map.num_corners <= 40
        listed = set(additions(ls, a)) if small else set()
        for mv in picked:  # a valid cycle from its lowest corner: how the listing names it
            assert is_valid_addition(ls, mv) and mv.cycle[0] == min(mv.cycle)
            assert mv in listed or not small
        assert picked == sample_additions(ls, a, n, seed)
        if next(additions(ls, a), None) is not None:
            assert picked, "some valid loop exists, so some walk should close within 200 n tries"


def test_counting_within_a_time_limit_on_a_large_slab():
    import time

    from polyloops.reach.listing import count_additions_within
    from polyloops.shapes.builders import box

    ls = box(8, 8, 1).dualize()  # 162 corners; Z-loops: every cycle of a 9x9 grid
    start = time.monotonic()
    counted = count_additions_within(ls, seconds=1.0)
    assert time.monotonic() - start < 3.0
    assert not counted.complete["Z"]
    small = load_example("l-shape").dualize()
    full = count_additions_within(small, seconds=60)
    assert all(full.complete.values()) and full.counts == count_additions(small)


@pytest.mark.slow
def test_moves_cli_on_a_large_slab(tmp_path, capsys):
    import time

    from polyloops.io.formats import dumps
    from polyloops.shapes.builders import box

    path = tmp_path / "slab.json"
    path.write_text(dumps(box(8, 8, 1)))
    start = time.monotonic()
    assert main(["moves", str(path), "--count", "--add", "Z", "--time-limit", "1", "--json"]) == 0
    assert time.monotonic() - start < 5.0
    out = json.loads(capsys.readouterr().out)
    assert out["complete"] == {"Z": False} and out["additions"]["Z"] >= 0
    assert main(["moves", str(path), "--count", "--add", "Z", "--time-limit", "1"]) == 0
    assert "(>=: Z not finished, stopped by the time limit" in capsys.readouterr().out
    # one budget for all three axes, and the line names each axis it did not finish
    start = time.monotonic()
    assert main(["moves", str(path), "--count", "--time-limit", "0.6"]) == 0
    assert time.monotonic() - start < 5.0
    text = capsys.readouterr().out
    counts = text.splitlines()[0].split()[1:]  # "additions X:6  Y:>=40  Z:>=12"
    unfinished = [c.split(":")[0] for c in counts if ":>=" in c]
    assert unfinished and f"{' and '.join(unfinished)} not finished" in text and "shared across" in text
    start = time.monotonic()
    assert main(["moves", str(path), "--add", "Z", "--time-limit", "1", "--json"]) == 0
    assert time.monotonic() - start < 5.0
    listed = json.loads(capsys.readouterr().out)
    assert listed["complete"] == {"Z": False}
    assert all(len(r["corners"]) >= 3 and r["axis"] == "Z" for r in listed["additions"])
    start = time.monotonic()
    assert main(["moves", str(path), "--shortest", "5", "--json"]) == 0
    assert time.monotonic() - start < 5.0
    rows = json.loads(capsys.readouterr().out)["additions"]
    assert len(rows) == 15 and all(len(r["corners"]) == 4 for r in rows)
    # A picked loop's index is a move that 'polyloops add' takes as it is.
    assert main(["add", str(path), rows[0]["index"], "-o", str(tmp_path / "more.json")]) == 0
    capsys.readouterr()
    assert main(["moves", str(path), "--sample", "3", "--seed", "7", "--add", "X", "--json"]) == 0
    first = capsys.readouterr().out
    assert main(["moves", str(path), "--sample", "3", "--seed", "7", "--add", "X", "--json"]) == 0
    assert capsys.readouterr().out == first and len(json.loads(first)["additions"]) == 3


@pytest.mark.parametrize("argv", [
    ["--count", "--shortest", "2"], ["--sample", "2", "--shortest", "2"], ["--seed", "3"],
    ["--shortest", "2", "--remove"], ["--time-limit", "0"], ["--time-limit", "nan"],
    ["--time-limit", "x"], ["--shortest", "0"],
])
def test_moves_options_that_do_not_go_together(argv, capsys):
    code, _, err = run(capsys, "moves", "example:cube", *argv)
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err


@settings(max_examples=30, deadline=None)
@given(st.one_of(grown_structures(max_moves=3), polycubes(max_size=7).map(lambda q: q.dualize())))
def test_children_built_without_checks_are_the_checked_ones(ls):
    """Every addition (the first few of each axis) and every valid removal builds the same
    structure without re-checking (the search's hot path) as with every check of
    ``from_edge_labels``; and each child is a polycube loop structure (Definition 4)."""
    from polyloops.core import moves
    from polyloops.verify import check_polycube_loop_structure

    trials = [(moves.add_loop, mv) for axis in Axis for mv in moves.additions(ls, axis, limit=4)]
    trials += [(moves.remove_loop, i) for i in moves.removals(ls)]
    for build, move in trials:
        fast = build(ls, move, checked=False)
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(moves, "VERIFY_CHILDREN", True)
            checked = build(ls, move, checked=False)
        assert checked == build(ls, move)
        assert fast == checked
        assert fast.map.loop_system == checked.map.loop_system
        assert check_polycube_loop_structure(fast).valid


@settings(max_examples=12, deadline=None)
@given(st.one_of(grown_structures(max_moves=3), polycubes(max_size=8).map(lambda q: q.dualize()),
                 handle_zone_polycubes().map(lambda q: q.dualize())),
       st.sampled_from(list(Axis)), st.one_of(st.none(), st.integers(0, 12)))
def test_counts_without_listing_equal_the_listing(ls, axis, limit):
    """The count of additions (compiled where zones have genus 0, listed and tested where they
    have a handle) equals the number the listing yields, with and without a limit, with the
    compiled count and with the Python search."""
    from itertools import islice

    from polyloops.core import compiled, moves

    # the listing is the slow twin: structures with more than a thousand additions are left out
    listed = sum(1 for _ in islice(moves.valid_additions(ls, axis), 1001))
    assume(listed <= 1000)
    want = (listed, True) if limit is None or listed <= limit else (limit, False)
    assert moves.count_valid_additions(ls, axis, limit) == want
    with compiled.pure_python("cycles"):
        assert moves.count_valid_additions(ls, axis, limit) == want


def test_counts_stop_at_the_deadline():
    """A deadline already past stops the count: a lower bound, said to be incomplete."""
    import time

    from polyloops.core import moves
    from polyloops.shapes.builders import box

    ls = box(4, 4, 4).dualize()
    count, complete = moves.count_valid_additions(ls, Axis.Z, deadline=time.monotonic() - 1)
    assert not complete and count <= sum(1 for _ in moves.valid_additions(ls, Axis.Z))


@pytest.mark.parametrize("name", ["l-shape", "box-2x1x1", "non-incremental", "ring", "bridged-ring"])
def test_estimates_bracket_the_exact_counts(name):
    """Knuth's estimator is unbiased: with enough seeded walks the exact count lies in the
    estimate's interval (widened to four standard errors, so that a fixed seed is no accident),
    on genus 0 and on zones with a handle."""
    from polyloops.core import moves

    x = load_example(name)
    ls = x.dualize() if hasattr(x, "dualize") else x
    for axis in Axis:
        exact, complete = moves.count_valid_additions(ls, axis)
        est = moves.estimate_additions(ls, axis, walks=4000, seed=3)
        half = (est.high - est.estimate) / 1.96 * 4
        assert complete and abs(est.estimate - exact) <= half + 1e-9, (axis, exact, est)


def test_cli_estimate(capsys):
    assert main(["moves", "example:l-shape", "--count", "--estimate", "--walks", "500", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data["estimates"]) == {"X", "Y", "Z"} and data["removals"] == 2
    estimates = data["estimates"].values()
    assert all(e["walks"] == 500 and e["low"] <= e["estimate"] <= e["high"] for e in estimates)
    for bad in (["--estimate"], ["--count", "--walks", "5"]):
        assert main(["moves", "example:l-shape", *bad]) == 2
    with pytest.raises(SystemExit) as exit_:
        main(["moves", "example:l-shape", "--count", "--estimate", "--walks", "0"])
    assert exit_.value.code == 2


def _renumbered_structure(ls, seed):
    """``ls`` with its corners renumbered and its faces reordered and rotated at random."""
    from polyloops.io.formats import loads
    from strategies import shuffled_document

    return loads(json.dumps(shuffled_document(ls, seed)))


@settings(max_examples=40, deadline=None)
@given(grown_structures(), st.integers(0, 2**16), st.sampled_from([None, 4, 6, 9]),
       st.sampled_from(list(Axis)))
def test_pruned_cycle_search_finds_the_same_cycles_in_the_same_order(ls, seed, max_length, axis):
    """The search that backs up from walks that cannot close (pruning at every step) and the
    plain depth-first search (never pruning) list the same cycles in the same order, in the
    structure's numbering and renumbered at random."""
    import polyloops.core.moves as moves_module
    from polyloops.core.moves import _AdditionGraph

    for s in (ls, _renumbered_structure(ls, seed)):
        found = {}
        for every in (1, 10**12):
            saved, moves_module.PRUNE_EVERY = moves_module.PRUNE_EVERY, every
            try:
                found[every] = list(_AdditionGraph(s, axis).cycles(max_length))
            finally:
                moves_module.PRUNE_EVERY = saved
        assert found[1] == found[10**12]


def test_a_first_addition_on_a_renumbered_box_is_found_without_wandering():
    """On a 22 x 22 x 22 box renumbered at random, the plain depth-first search walled itself
    off from its start and wandered for minutes before its first Z-loop; backing up from
    walks that cannot close finds one within a few hundred thousand steps."""
    from polyloops.core.moves import SearchStopped, additions
    from polyloops.shapes.builders import box

    ls = _renumbered_structure(box(22, 22, 22).dualize(), 7)
    asked = [0]

    def stop() -> bool:  # asked every 4096 steps of the search
        asked[0] += 1
        return asked[0] > 200

    try:
        found = list(additions(ls, Axis.Z, limit=1, stop=stop))
    except SearchStopped:
        found = []
    assert len(found) == 1 and asked[0] <= 200
