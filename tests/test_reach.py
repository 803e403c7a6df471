"""Reachability: the breadth-first search equals a brute force, its counts equal the catalog's,
it resumes and splits work without changing its answer; paths and certificates are checked
by code that does not trust the search."""

import itertools
import json
import sqlite3
from functools import cache
from pathlib import Path

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.core.canonical import from_signature, signature
from polyloops.core.directions import Axis
from polyloops.core.moves import Addition, add_loop, canonical_cycle, try_remove
from polyloops.io.examples import load_example
from polyloops.reach.conjecture import (
    ConjectureError,
    certificate_lines,
    check_certificate,
    read_records,
    settle_catalog,
)
from polyloops.reach.search import MoveKind, check_path, explore, neighbours, path_steps, shortest_path
from polyloops.verify import check_polycube_loop_structure
from shipped import small_catalog  # the shipped catalog cut short: the certificate tests settle through 26

ROOT = Path(__file__).resolve().parent.parent
CATALOG = ROOT / "catalogs" / "genus0"
CUBE = load_example("cube").dualize()


def brute_neighbours(ls, max_corners, kinds):
    """Every loop through every simple cycle of corners (both directions, every label, avoiding
    edges of its own label) and every loop removal, each checked by the Definition-4 checker."""
    n = ls.map.num_corners
    m = ls.map
    if MoveKind.ADD in kinds:
        for axis in Axis:
            g = nx.Graph((m.origin(d), m.target(d)) for d in range(m.num_darts) if ls.axis_of_dart(d) != axis)
            for cycle in nx.simple_cycles(g, length_bound=max_corners - n):
                if len(cycle) < 3:
                    continue
                for walk in (cycle, cycle[::-1]):
                    child = add_loop(ls, Addition(axis, canonical_cycle(walk)))
                    if check_polycube_loop_structure(child).valid:
                        yield child
    if MoveKind.REMOVE in kinds:
        for lp in ls.loops:
            child = try_remove(ls, lp.id)
            if child is not None and check_polycube_loop_structure(child).valid:
                yield child


def brute_reach(start, max_corners, kinds):
    seen = {signature(start, "labelled"): 0}
    level, d = [start], 0
    while level:
        d += 1
        nxt = []
        for ls in level:
            for child in brute_neighbours(ls, max_corners, kinds):
                s = signature(child, "labelled")
                if s not in seen:
                    seen[s] = d
                    nxt.append(child)
        level = nxt
    return seen


@pytest.mark.parametrize("kinds", [(MoveKind.ADD,), (MoveKind.ADD, MoveKind.REMOVE)])
def test_reach_equals_brute_force(kinds):
    brute = brute_reach(CUBE, 18, kinds)
    result = explore(CUBE, 18, kinds=kinds)
    assert result.states == len(brute) > 10
    by_distance = {}
    for d in brute.values():
        by_distance[d] = by_distance.get(d, 0) + 1
    assert result.by_distance == by_distance


def test_neighbours_equal_brute_force_on_a_larger_state():
    ls = load_example("l-shape").dualize()
    fast = sorted(signature(c, "labelled") for _, c in neighbours(ls, 26))
    brute = sorted(signature(c, "labelled") for c in brute_neighbours(ls, 26, list(MoveKind)))
    assert fast == brute


@cache
def catalog_counts():
    return json.loads((CATALOG / "summary.json").read_text())["counts"]


def test_counts_equal_the_catalog():
    """Every labelled class through 22 corners is reached within 22 corners."""
    result = explore(CUBE, 22)
    for n in range(8, 23):
        assert result.by_corners.get(n, 0) == catalog_counts()[str(n)]["labelled"], n


@pytest.mark.slow
def test_counts_equal_the_catalog_except_the_non_incremental_classes():
    """Within 28 corners every labelled class through 28 is reached except the four of the
    non-incremental polycube (26 corners), which need a detour through 34."""
    result = explore(CUBE, 28, workers=2)
    for n in range(8, 29):
        missing = 4 if n == 26 else 0
        assert result.by_corners.get(n, 0) == catalog_counts()[str(n)]["labelled"] - missing, n


@pytest.mark.slow
def test_at_30_corners_the_missing_classes_lead_only_to_the_non_incremental_polycube():
    """Within 30 corners, the labelled classes with 30 corners that are not reached are exactly
    the labelled versions of the classes whose every removal gives the non-incremental polycube
    (about 2 minutes)."""
    from polyloops.core.canonical import canonical_form, from_signature
    from polyloops.core.moves import removals, remove_loop

    target = canonical_form(load_example("non-incremental"), "full").signature
    records = [json.loads(line) for line in (CATALOG / "catalog.jsonl").read_text().splitlines()]
    stuck = 0
    for rec in records:
        if rec["corners"] == 30:
            ls = from_signature(rec["signature"])
            after = {canonical_form(remove_loop(ls, loop), "full").signature for loop in removals(ls)}
            if after == {target}:
                stuck += 48 // rec["automorphisms"]  # labelled versions of a full class
    assert stuck > 0
    result = explore(CUBE, 30, workers=2)
    assert result.by_corners[30] == catalog_counts()["30"]["labelled"] - stuck


def rows(directory):
    con = sqlite3.connect(directory / "reach.sqlite")
    try:
        return sorted(con.execute("SELECT * FROM states"))
    finally:
        con.close()


def test_workers_and_resume_give_the_same_rows(tmp_path):
    one, two, resumed = tmp_path / "one", tmp_path / "two", tmp_path / "resumed"
    a = explore(CUBE, 20, directory=one)
    b = explore(CUBE, 20, directory=two, workers=2)
    partial = explore(CUBE, 20, max_depth=2, directory=resumed)
    assert not partial.complete and partial.max_distance == 2
    c = explore(CUBE, 20, directory=resumed)
    assert a.to_json() | {"seconds": 0} == b.to_json() | {"seconds": 0} == c.to_json() | {"seconds": 0}
    assert rows(one) == rows(two) == rows(resumed)
    with pytest.raises(ValueError, match="other parameters"):
        explore(CUBE, 22, directory=one)


def test_stored_paths_replay(tmp_path):
    from polyloops.reach.search import path_to

    explore(CUBE, 20, directory=tmp_path)
    con = sqlite3.connect(tmp_path / "reach.sqlite")
    far = [s for s, d in con.execute("SELECT signature, distance FROM states WHERE distance = 3")]
    con.close()
    for sig in far[:5]:
        states = path_to(tmp_path, sig)
        assert [s.distance for s in states] == [0, 1, 2, 3]
        for before, after in itertools.pairwise(states):
            child = after.move.apply(from_signature(before.signature))
            assert signature(child, "labelled") == after.signature


def test_cli_reach_json(capsys, tmp_path):
    assert main(["reach", "--max-corners", "16", "--json", "-o", str(tmp_path / "r")]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["states"] == 19 and data["by_corners"] == {"8": 1, "12": 3, "16": 15}
    assert data["max_distance"] == 2 and data["seconds"] >= 0
    assert json.loads((tmp_path / "r" / "summary.json").read_text())["states"] == 19
    assert main(["reach", "--max-corners", "16", "--moves", "jump"]) == 2
    assert main(["reach", "example:torus-cycle", "--max-corners", "40"]) == 1


def test_path_and_its_check(tmp_path, capsys):
    out = tmp_path / "p.json"
    assert main(["path", "example:cube", "example:l-shape", "--max-corners", "20", "-o", str(out)]) == 0
    doc = json.loads(out.read_text())
    assert doc["kind"] == "path" and len(doc["steps"]) >= 3
    assert main(["verify", str(out)]) == 0
    # Corrupt the path: skip a step (a shortest path's ends are not one move apart).
    bad = {**doc, "steps": [doc["steps"][0], *doc["steps"][2:]], "moves": doc["moves"][1:]}
    (tmp_path / "bad.json").write_text(json.dumps(bad))
    capsys.readouterr()
    assert main(["verify", str(tmp_path / "bad.json"), "--json"]) == 1
    assert json.loads(capsys.readouterr().out)["bad_step"] == 1
    broken = {**doc, "steps": [doc["steps"][0], {"polyloops": 1, "kind": "loop-structure"}]}
    (tmp_path / "broken.json").write_text(json.dumps(broken))
    assert main(["verify", str(tmp_path / "broken.json")]) == 2
    assert "step 1" in capsys.readouterr().err
    # The non-incremental polycube has no move that stays within its own 26 corners.
    assert main(["path", "example:cube", "example:non-incremental", "--max-corners", "26"]) == 1
    assert "no path within 26 corners" in capsys.readouterr().err
    assert main(["path", "example:cube", "example:l-shape", "--max-corners", "12"]) == 2


def test_path_tells_its_moves_and_the_file_replays_them(tmp_path, capsys):
    """``path`` prints each move; the path file stores the moves beside the steps, in the
    certificate's move format, and replaying them from the first step gives every stored step
    exactly; ``verify`` checks the moves, and still reads a path file without them."""
    from polyloops.io.formats import to_data
    from polyloops.reach.search import Move

    out = tmp_path / "p.json"
    assert main(["path", "example:cube", "example:non-incremental", "--max-corners", "34",
                 "-o", str(out), "--json"]) == 0
    told = json.loads(capsys.readouterr().out)
    doc = json.loads(out.read_text())
    assert [s["move"] for s in told["steps"]] == doc["moves"] and len(doc["moves"]) == told["moves"]
    steps = path_steps(doc)
    ls = steps[0]
    for i, move in enumerate(doc["moves"]):
        ls = Move.from_json(move).apply(ls)
        assert to_data(ls) == doc["steps"][i + 1]
        assert told["steps"][i]["corners"] == ls.map.num_corners
        assert told["steps"][i]["text"].startswith("add " if "add" in move else "remove loop ")
    assert signature(ls, "labelled") == signature(load_example("non-incremental").dualize(), "labelled")
    assert any("remove" in m for m in doc["moves"])  # the way to the non-incremental polycube
    assert main(["path", "example:cube", "example:l-shape", "--max-corners", "20"]) == 0
    text = capsys.readouterr().out
    assert "2 moves" in text and " 1. add a" in text and " 2. add a" in text
    assert main(["verify", str(out)]) == 0
    older = {k: v for k, v in doc.items() if k != "moves"}
    (tmp_path / "older.json").write_text(json.dumps(older))
    assert main(["verify", str(tmp_path / "older.json")]) == 0
    wrong = {**doc, "moves": [{"remove": 0}, *doc["moves"][1:]]}
    (tmp_path / "wrong.json").write_text(json.dumps(wrong))
    capsys.readouterr()
    assert main(["verify", str(tmp_path / "wrong.json"), "--json"]) == 1
    assert json.loads(capsys.readouterr().out)["bad_step"] == 1
    short = {**doc, "moves": doc["moves"][1:]}
    (tmp_path / "short.json").write_text(json.dumps(short))
    assert main(["verify", str(tmp_path / "short.json")]) == 1
    assert "moves for" in capsys.readouterr().out
    (tmp_path / "junk.json").write_text(json.dumps({**doc, "moves": [{"jump": 1}]}))
    assert main(["verify", str(tmp_path / "junk.json")]) == 2
    assert "move 0" in capsys.readouterr().err


def test_check_path_names_the_first_bad_step():
    steps = shortest_path(CUBE, load_example("l-shape").dualize(), 20)
    assert check_path(steps).valid
    skipped = [steps[0], *steps[2:]]
    result = check_path(skipped)
    assert not result.valid and result.bad_step == 1
    assert not check_path([steps[0], steps[0]]).valid


def test_shortest_path_is_shortest():
    target = load_example("l-shape").dualize()
    steps = shortest_path(CUBE, target, 20)
    distances = brute_reach(CUBE, 20, (MoveKind.ADD, MoveKind.REMOVE))
    assert len(steps) - 1 == distances[signature(target, "labelled")]


@cache
def certificate():
    return list(certificate_lines(settle_catalog(small_catalog(26), 26, 10)))


def test_conjecture_settled_through_26_and_checked():
    lines = certificate()
    check = check_certificate(lines, small_catalog(26))
    assert check.header["max_corners"] == check.checked_corners == 26 and check.problems == ()
    records = [json.loads(line) for line in lines[1:]]
    detours = [r for r in records if "detour" in r]
    non_incremental = signature(load_example("non-incremental"), "full")
    assert [r["signature"] for r in detours] == [non_incremental]


def test_corrupted_certificates_are_rejected():
    lines = certificate()
    records = [json.loads(line) for line in lines[1:]]
    i = next(k for k, r in enumerate(records) if "detour" in r)
    bad = json.loads(json.dumps(records[i]))
    bad["detour"]["moves"] = bad["detour"]["moves"][1:]  # drop the first move
    corrupted = [lines[0], *lines[1:i + 1], json.dumps(bad), *lines[i + 2:]]
    problems = check_certificate(corrupted, small_catalog(26)).problems
    assert len(problems) == 1 and problems[0].line == i + 2 and "step" in problems[0].message
    j = next(k for k, r in enumerate(records) if "removable" in r)
    ls = from_signature(records[j]["signature"])
    wrong = next(lp.id for lp in ls.loops if try_remove(ls, lp.id) is None
                 or not check_polycube_loop_structure(try_remove(ls, lp.id)).valid)
    bad = {**records[j], "removable": wrong}
    corrupted = [lines[0], *lines[1:j + 1], json.dumps(bad), *lines[j + 2:]]
    problems = check_certificate(corrupted, small_catalog(26)).problems
    assert [p.line for p in problems] == [j + 2]
    problems = check_certificate(lines[:-1], small_catalog(26)).problems
    assert [p.name for p in problems if "missing" in p.message] == ["P26.20"]  # the last class


def _open(lines: list[str], signatures: set[str]) -> list[str]:
    """The certificate with the records of ``signatures`` made unsettled, the header saying so."""
    records = [json.loads(line) for line in lines[1:]]
    for r in records:
        if r["signature"] in signatures:
            for kind in ("removable", "detour"):
                r.pop(kind, None)
            r["unsettled"] = True
    header = {**json.loads(lines[0]), "unsettled": len(signatures)}
    return [json.dumps(header), *map(json.dumps, records)]


def test_open_classes_bound_what_a_certificate_proves():
    """Every class below the smallest open one is reachable, and every other class of its size;
    a header that states fewer (or more) open classes than the records, or a record that states
    no way of being settled, is refused."""
    lines, catalog = certificate(), small_catalog(26)
    records = [json.loads(line) for line in lines[1:]]
    at = {n: [r["signature"] for r in records if r["corners"] == n and "removable" in r] for n in (22, 26)}
    check = check_certificate(_open(lines, {at[26][0]}), catalog)
    assert check.valid and not check.complete and check.proven_corners == 25
    assert [c.signature for c in check.open] == [at[26][0]]
    assert check.statement() == ("every genus-0 class through 25 corners is reachable from the cube; "
                                 "with 26, every class but 1 (recorded as open, no detour within +10: "
                                 f"{check.open[0].name})")
    check = check_certificate(_open(lines, {at[22][0], at[26][0]}), catalog)
    assert check.valid and check.proven_corners == 21 and "1 more open" in check.statement()
    full = check_certificate(lines, catalog)
    assert full.complete and full.proven_corners == 26 and "but" not in full.statement()
    understated = [json.dumps({**json.loads(lines[0]), "unsettled": 0}), *_open(lines, {at[22][0]})[1:]]
    check = check_certificate(understated, catalog)
    assert not check.valid and check.proven_corners is None and check.statement() == ""
    assert "the header states 0 unsettled classes; the certificate has 1" in str(check.problems[0])
    overstated = [json.dumps({**json.loads(lines[0]), "unsettled": 1}), *lines[1:]]
    assert not check_certificate(overstated, catalog).valid
    bare = {k: v for k, v in records[-1].items() if k in ("signature", "corners")}
    check = check_certificate([*lines[:-1], json.dumps(bare)], catalog)
    assert "states no way of being settled" in str(check.problems[0])


def test_an_open_class_is_searched_again_from_where_it_stopped(monkeypatch):
    """A run at slack 6 leaves the non-incremental class open, searched to +6; a run at slack 8
    from its records searches that class alone, from +8 on, takes every other record as it is,
    and writes the certificate a run at slack 8 from nothing writes. Its open record's search is
    checked for form and bound."""
    from polyloops.reach import conjecture

    catalog = small_catalog(26)
    low = settle_catalog(catalog, 26, 6)
    [open_] = low.unsettled
    assert open_.searched == 6 and json.loads(list(certificate_lines(low))[-1]).get("searched") in (None, 6)
    lines = list(certificate_lines(low))
    records = read_records(lines)
    assert [r for r in records if not r.settled] == [open_]
    calls = []
    real = conjecture.find_detour

    def counted(ls, bound, target=None):
        calls.append(bound - ls.map.num_corners)
        return real(ls, bound, target)

    monkeypatch.setattr(conjecture, "find_detour", counted)
    again = settle_catalog(catalog, 26, 8, earlier=records)
    assert calls == [8] and again.slack == 8 and not again.unsettled
    assert list(certificate_lines(again)) == list(certificate_lines(settle_catalog(catalog, 26, 8)))
    # an open record searched no further than asked is taken as it is
    calls.clear()
    assert settle_catalog(catalog, 26, 6, earlier=records).unsettled == [open_] and calls == []
    check = check_certificate(lines, catalog)
    assert check.valid and check.open[0].searched == 6
    at = next(i for i, line in enumerate(lines) if i and "unsettled" in line)
    for searched, why in ((7, "searched 7 is not a slack from 0 to the header's 6"),
                          ("6", "searched '6' is not a slack")):
        bad = [*lines[:at], json.dumps({**json.loads(lines[at]), "searched": searched}), *lines[at + 1:]]
        assert why in str(check_certificate(bad, catalog).problems[0])
    settled = next(i for i, line in enumerate(lines) if "removable" in line)
    bad = [*lines[:settled], json.dumps({**json.loads(lines[settled]), "searched": 2}), *lines[settled + 1:]]
    assert "is neither open nor settled by a detour" in str(check_certificate(bad, catalog).problems[0])
    with pytest.raises(ConjectureError, match="line 3 is not a certificate record"):
        read_records([lines[0], lines[1], "[]"])


def test_cli_conjecture(tmp_path, capsys):
    cert = tmp_path / "c.jsonl"
    assert main(["conjecture", "genus0", "--catalog", str(small_catalog(26)), "--max-corners", "26", "--json",
                 "-o", str(cert)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["settled"] == data["classes"] == 55 and data["unsettled"] == []
    assert main(["conjecture", "check", str(cert), "--catalog", str(small_catalog(26))]) == 0
    assert main(["conjecture", "genus0", "--catalog", str(small_catalog(26)), "--max-corners", "26",
                 "--slack", "6", "-o", str(cert)]) == 1  # the non-incremental class stays open
    capsys.readouterr()
    # The certificate states its open class, so it holds, and proves the range below it.
    assert main(["conjecture", "check", str(cert), "--catalog", str(small_catalog(26)), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["valid"] and not data["complete"] and data["proven_corners"] == 25 and len(data["open"]) == 1
    assert data["searched"] == {data["open"][0]: 6}
    # deepened from it: the open class is searched again at +8 and settled
    deeper = tmp_path / "deeper.jsonl"
    assert main(["conjecture", "genus0", "--catalog", str(small_catalog(26)), "--max-corners", "26",
                 "--slack", "8", "--from", str(cert), "-o", str(deeper), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["unsettled"] == []
    (tmp_path / "not.jsonl").write_text('{"polyloops": 1}\n')
    assert main(["conjecture", "genus0", "--catalog", str(small_catalog(26)), "--max-corners", "26",
                 "--from", str(tmp_path / "not.jsonl"), "-o", str(deeper)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "not.jsonl: not a reachability certificate" in err
    lines = cert.read_text().splitlines()
    cert.write_text("\n".join([json.dumps({**json.loads(lines[0]), "unsettled": 0}), *lines[1:]]) + "\n")
    assert main(["conjecture", "check", str(cert), "--catalog", str(small_catalog(26))]) == 1
    assert main(["conjecture", "check", str(cert), "--catalog", str(tmp_path)]) == 2


def test_reach_from_a_zone_with_a_handle_stays_valid():
    ls = load_example("bridged-ring").dualize()
    for _, child in neighbours(ls, ls.map.num_corners + 6):
        assert check_polycube_loop_structure(child).valid


@pytest.mark.slow  # test_certificates.py checks the whole shipped certificate in the default run
def test_shipped_certificate_checks():
    lines = (CATALOG / "reachability-certificate.jsonl").read_text().splitlines()
    check = check_certificate(lines, CATALOG)
    top = max(int(n) for n in json.loads((CATALOG / "summary.json").read_text())["counts"])
    assert check.problems == () and check.header["max_corners"] == check.checked_corners == top


@pytest.mark.slow  # test_dask_cluster.py runs a catalog on a local cluster in the default run
def test_dask_gives_the_same_rows(tmp_path):
    pytest.importorskip("distributed")
    a, b = tmp_path / "a", tmp_path / "b"
    explore(CUBE, 18, directory=a)
    explore(CUBE, 18, directory=b, dask="local")
    assert rows(a) == rows(b)


def test_not_a_certificate_is_bad_input(tmp_path, capsys):
    (tmp_path / "g.jsonl").write_text("garbage\n")
    assert main(["conjecture", "check", str(tmp_path / "g.jsonl"), "--catalog", str(small_catalog(26))]) == 2
    assert "not a reachability certificate" in capsys.readouterr().err


# -- reach directories: nothing replaced without --overwrite, nothing foreign read ---------------

def test_reach_refuses_another_search_without_overwrite(tmp_path, capsys):
    out = tmp_path / "r"
    assert main(["reach", "--max-corners", "16", "-o", str(out)]) == 0
    before = rows(out)
    capsys.readouterr()
    assert main(["reach", "--max-corners", "12", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--overwrite" in err and err.count("\n") == 1 and rows(out) == before
    assert main(["reach", "--max-corners", "16", "-o", str(out)]) == 0  # the same search resumes
    assert rows(out) == before
    assert main(["reach", "--max-corners", "12", "--overwrite", "-o", str(out)]) == 0
    assert json.loads((out / "summary.json").read_text())["max_corners"] == 12


@pytest.mark.parametrize("content", ["fifo", "garbage", "foreign", "catalog"])
def test_reach_refuses_what_is_not_a_search(tmp_path, capsys, content):
    import os
    import shutil
    import sqlite3

    out = tmp_path / "r"
    out.mkdir()
    db = out / "reach.sqlite"
    if content == "fifo":
        os.mkfifo(db)
    elif content == "garbage":
        db.write_bytes(b"SQLite format 3\x00" + bytes(range(256)) * 8)
    elif content == "foreign":
        con = sqlite3.connect(db)
        con.execute("CREATE TABLE other (x)")
        con.commit()
        con.close()
    else:
        out.rmdir()
        shutil.copytree(small_catalog(26), out)
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()}
    for overwrite in ([], ["--overwrite"]):
        assert main(["reach", "--max-corners", "12", "-o", str(out), *overwrite]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "internal error" not in err
    assert {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()} == before


def test_the_search_finds_what_the_naive_reference_finds():
    """The benchmark's naive search (every cycle of the corner graph tried as a new loop, every
    loop tried for removal, every child checked from scratch against Definition 4) reaches the
    same states from the cube, corner count by corner count; and with every child re-checked
    (``VERIFY_CHILDREN``) the search itself finds the same states."""
    import sys

    from polyloops.core import moves

    sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "benchmarks"))
    from naive_reach import naive_explore

    cube = load_example("cube").dualize()
    found = explore(cube, 18).by_corners
    assert naive_explore(cube, 18) == found
    fast = explore(cube, 20)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(moves, "VERIFY_CHILDREN", True)
        checked = explore(cube, 20)
    assert checked.by_corners == fast.by_corners and checked.by_distance == fast.by_distance


@cache
def _detour_cases() -> list[tuple[str, str | None]]:
    """Classes to search detours from: the genus-0 classes through 22 corners and the genus-1
    classes through 36, each with no target and with another class of its size as target."""
    from polyloops.catalog.census import default_catalog, read_catalog

    entries = [e for e in read_catalog().entries if e.corners <= 22]
    entries += [e for e in read_catalog(default_catalog(1)).entries if e.corners <= 36]
    out: list[tuple[str, str | None]] = []
    for e in entries:
        out.append((e.signature, None))
        other = next((f.signature for f in entries if f.corners == e.corners and f is not e), None)
        out.append((e.signature, other))
    return out


@settings(max_examples=25)
@given(st.data())
def test_the_detour_search_meets_the_plain_searchs_first_detour(data):
    """Trying each level's removals before its additions (and the array test of removals)
    returns the very detour the plain breadth-first search returns, target or not, found or
    not; the irreducible classes of the certificate are always among the cases."""
    from polyloops.reach.conjecture import find_detour
    from reference.detour_reference import plain_detour

    cases = _detour_cases()
    sig, target = data.draw(st.sampled_from(cases))
    slack = data.draw(st.sampled_from([2, 4, 6]))
    ls = from_signature(sig)
    bound = ls.map.num_corners + slack
    assert find_detour(ls, bound, target) == plain_detour(ls, bound, target)


def test_the_detour_search_agrees_on_the_irreducible_classes():
    """The irreducible classes the shipped certificates settle by short detours (the
    non-incremental genus-0 class at +8, the genus-1 classes through 44 corners at +4): at
    their detour's slack and just below it, where the search is exhaustive."""
    from polyloops.catalog.census import default_catalog
    from polyloops.reach.conjecture import find_detour
    from reference.detour_reference import plain_detour

    lines = (default_catalog(1) / "reachability-certificate.jsonl").read_text().splitlines()[1:]
    records = [r for r in map(json.loads, lines) if "detour" in r and r["corners"] <= 44
               and r["detour"]["slack"] <= 4]
    cases = [(signature(load_example("non-incremental"), "full"), 8),
             *((r["signature"], r["detour"]["slack"]) for r in records)]
    assert len(cases) >= 6
    for sig, slack in cases:
        ls = from_signature(sig)
        for bound in (ls.map.num_corners + slack - 2, ls.map.num_corners + slack):
            assert find_detour(ls, bound) == plain_detour(ls, bound)
        assert find_detour(ls, bound) is not None
