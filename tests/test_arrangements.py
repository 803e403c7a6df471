"""The arrangement search (generate/loops/arrangements.py and its compiled core) against its slow
twin, against plantri's filter, and its own properties."""

from __future__ import annotations

import contextlib
import json
import random
from collections import Counter

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.catalog.run import CatalogRunError, build_catalog
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.generate.loops.arrangements import (
    ALL_CUTS,
    Arrangement,
    ArrangementError,
    Cuts,
    SearchStats,
    candidate_arrangements,
    children,
    compiled_generator_available,
    frontier,
)
from polyloops.generate.plantri.quadrangulations import candidate_maps, find_plantri
from reference.arrangement_reference import (
    canonical_code,
    meeting_bound,
    meets_each_loop_once,
    reference_arrangements,
    three_colourable,
)
from strategies import arrangements

# Like the strip filter's tests: without a C compiler at install time there is nothing to test
# (the install says so, and --generator loops stops with a one-line message).
pytestmark = pytest.mark.skipif(not compiled_generator_available(),
                                reason="the compiled arrangement search was not built (no C compiler)")


def whole_tree(max_corners: int, cuts: Cuts = ALL_CUTS) -> list[Arrangement]:
    out, stack = [], [None]
    while stack:
        node = stack.pop()
        if node is not None:
            out.append(node)
        stack.extend(children(node, max_corners, cuts)[0])
    return out


def reference_code(a: Arrangement) -> tuple[int, ...]:
    return canonical_code(list(a.rot), list(a.twin))


CUTS = [(False, False), (True, False), (True, True)]  # (cut 4, cut 5)


def expected_under(cuts: tuple[bool, bool], max_corners: int,
                   found: dict[tuple[int, ...], bool]) -> dict[tuple[int, ...], bool]:
    """The slow twin's arrangements (code -> candidate) that the search visits with the cuts:
    cut 4 keeps the 3-colourable ones, cut 5 those within its bound, whose candidates meet
    each loop once in each region."""
    colour_cut, meet_cut = cuts
    out = {}
    for code, candidate in found.items():
        if colour_cut and not three_colourable(code):
            continue
        if meet_cut:
            if meeting_bound(code) > max_corners - 2:
                continue
            candidate = candidate and meets_each_loop_once(code)
        out[code] = candidate
    return out


@pytest.mark.parametrize("cuts", CUTS)
@pytest.mark.parametrize("max_corners", [12, pytest.param(14, marks=pytest.mark.slow),
                                         pytest.param(16, marks=pytest.mark.slow)])
def test_search_visits_exactly_what_the_slow_twin_finds(max_corners, cuts):
    """The compiled search (canonical construction, every cut) visits each connected
    arrangement of simple loops that passes the counting bound once: the slow twin's list,
    made with no canonical construction, another canonical code and only the final bound; with
    cut 4, those of them whose crossing graph is 3-colourable (the twin tries every colouring);
    with cut 5 too, those within its bound (the twin counts each region's sides per loop)."""
    tree = whole_tree(max_corners, Cuts(*cuts))
    codes = [reference_code(a) for a in tree]
    assert len(set(codes)) == len(codes)  # no arrangement twice
    expected = expected_under(cuts, max_corners, reference_arrangements(max_corners))
    assert set(codes) == set(expected)
    assert {c: a.candidate for c, a in zip(codes, tree, strict=True)} == expected


def mirror_and_renumber(a: Arrangement, rng: random.Random) -> tuple[list[int], list[int]]:
    """The same arrangement with darts renumbered at random, mirrored half the time."""
    n = len(a.twin)
    rot = list(a.rot)
    if rng.random() < 0.5:
        rot = [4 * (d // 4) + (d + 3) % 4 for d in range(n)]
    perm = list(range(n))
    rng.shuffle(perm)
    new_rot, new_twin = [0] * n, [0] * n
    for d in range(n):
        new_rot[perm[d]] = perm[rot[d]]
        new_twin[perm[d]] = perm[a.twin[d]]
    return new_rot, new_twin


@settings(max_examples=60, deadline=None)
@given(arrangements(), st.randoms(use_true_random=False))
def test_canonical_form_ignores_numbering_and_mirror(a, rng):
    from polyloops.generate.loops import _arrangements

    rot, twin = mirror_and_renumber(a, rng)
    code, candidate = _arrangements.canonical(bytes_of(rot), bytes_of(twin))
    assert Arrangement(code, bool(candidate)) == a
    assert bool(candidate) == a.candidate
    assert canonical_code(rot, twin) == reference_code(a)


def bytes_of(values: list[int]) -> bytes:
    import array

    return array.array("H", values).tobytes()


@settings(max_examples=40, deadline=None)
@given(arrangements(max_corners=20))
def test_children_give_back_their_parent(a):
    """McKay's property: each child has one loop more, and deleting one of its loops with the
    fewest crossings among those whose deletion keeps it connected gives back the parent."""
    kids, stats = children(a, 20)
    assert stats.arrangements == len(kids) == len(set(kids))
    for kid in kids:
        loops = kid.loops()
        assert len(loops) == len(a.loops()) + 1
        deletable = {}
        for i in range(len(loops)):
            with contextlib.suppress(ArrangementError):
                deletable[i] = kid.without_loop(i)
        fewest = min(len(loops[i]) for i in deletable)
        assert a in [p for i, p in deletable.items() if len(loops[i]) == fewest]


@pytest.mark.parametrize("n", [*range(8, 23, 2), pytest.param(24, marks=pytest.mark.slow),
                               pytest.param(26, marks=pytest.mark.slow)])
def test_candidates_are_plantris(n):
    """The candidate maps with n corners are those plantri's filter keeps, map for map; with
    cut 4, those of them whose crossing graph is 3-colourable (every colouring tried); with cut
    5 too, those of these where no region has two sides on one loop."""
    theirs = {Arrangement.of(m) for m in candidate_maps(n, find_plantri())}
    found = {}
    for cuts in CUTS:
        found[cuts] = [a for a in candidate_arrangements(n, cuts=Cuts(*cuts)) if a.corners == n]
        assert len(set(found[cuts])) == len(found[cuts])
    assert set(found[False, False]) == theirs
    colourable = {a for a in theirs if three_colourable(reference_code(a))}
    assert set(found[True, False]) == colourable
    assert set(found[True, True]) == {a for a in colourable if meets_each_loop_once(reference_code(a))}


def test_quad_mesh_round_trip():
    none = Cuts(colour=False, meet=False)  # every candidate map
    found = list(candidate_arrangements(20, cuts=none))
    maps = sum(1 for _ in candidate_maps(20, find_plantri()))  # what plantri's filter keeps
    assert Counter(a.corners for a in found)[20] == maps == 60
    for a in found:
        m = a.quad_mesh()
        assert isinstance(m, HalfEdgeMap)
        assert (m.num_corners, m.num_faces) == (a.corners, a.crossings)
        assert sorted(len(f) for f in m.faces) == [4] * a.crossings
        assert Arrangement.of(m, none) == a and Arrangement.of(m, none).candidate
        assert all(3 <= s <= 6 for s in a.region_sizes())


def test_shares_partition_the_search():
    one: list[Arrangement] = []
    total = [SearchStats()]

    def add(s: SearchStats) -> None:
        total[0] = total[0] + s

    whole = list(candidate_arrangements(26, on_stats=add))
    parts, split = [], [SearchStats()]

    def add_split(s: SearchStats) -> None:
        split[0] = split[0] + s

    top = frontier(26)
    for res in range(3):
        parts.append(list(candidate_arrangements(26, res, 3, on_stats=add_split)))
        one.extend(parts[-1])
    assert sorted(one, key=lambda a: a.twin) == sorted(whole, key=lambda a: a.twin)
    assert len(one) == len(set(one))
    assert split[0] == total[0]
    assert len(top.roots) > 3 and all(len(r.loops()) == top.loops for r in top.roots)
    with pytest.raises(ArrangementError):
        next(candidate_arrangements(26, 3, 3))


def test_bad_arrays_are_refused():
    from polyloops.generate.loops import _arrangements

    for rot, twin in [([0, 0], [1, 0]), ([1, 0], [0, 1]), ([1, 2, 0], [1, 0, 2]), ([], [])]:
        with pytest.raises(ValueError):
            _arrangements.children(bytes_of(rot), bytes_of(twin), 10)
    with pytest.raises(ValueError, match="degree 3"):
        _arrangements.children(bytes_of([1, 2, 0, 3]), bytes_of([3, 2, 1, 0]), 10)


def test_bad_maps_are_refused():
    tetrahedron = HalfEdgeMap.from_faces([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])
    with pytest.raises(ArrangementError, match="not a quad"):
        Arrangement.of(tetrahedron)
    # plantri's only map with 10 corners has a loop that crosses itself
    (rows,) = [m for m in _all_maps(10)]
    with pytest.raises(ArrangementError, match="crosses itself"):
        Arrangement.of(rows)
    cube = next(candidate_arrangements(8))
    with pytest.raises(ArrangementError, match="no loop 3"):
        cube.without_loop(3)
    two = cube.without_loop(0)
    with pytest.raises(ArrangementError, match="single loop"):
        two.without_loop(0)


def _all_maps(n: int):
    from polyloops.generate.plantri.quadrangulations import Batch, plantri_batches

    for rows in plantri_batches(n, find_plantri()):
        batch = Batch(rows)
        for i in range(len(batch)):
            yield batch.map(i)


def _files(path):
    return (path / "catalog.jsonl").read_bytes(), (path / "catalog.sqlite").read_bytes()


def test_catalog_from_loops_is_plantris(tmp_path):
    """Record for record, byte for byte: the catalog through 20 corners from either
    generator, with one worker or two, whole or in shares."""
    plantri = build_catalog(tmp_path / "p", 20, generator="plantri")
    loops = build_catalog(tmp_path / "l", 20, generator="loops")
    assert _files(tmp_path / "p") == _files(tmp_path / "l")
    assert loops.summary["counts"] == plantri.summary["counts"]
    assert loops.summary["generator"] == "loops"
    assert loops.summary["search"]["candidates"] == sum(1 for _ in candidate_arrangements(20))
    assert set(loops.summary["quadrangulations"].values()) == {None}
    two = build_catalog(tmp_path / "w", 20, generator="loops", workers=2)
    assert _files(tmp_path / "w") == _files(tmp_path / "p")
    assert two.summary == loops.summary
    # shares on "different machines": together they hold every record once
    records = []
    for res in range(2):
        part = build_catalog(tmp_path / f"s{res}", 20, generator="loops", res=res, mod=2)
        assert "partial" in part.summary
        records += (tmp_path / f"s{res}" / "catalog.jsonl").read_text().splitlines()
    whole = (tmp_path / "p" / "catalog.jsonl").read_text().splitlines()
    key = [json.loads(r)["signature"] for r in whole]
    assert sorted(json.loads(r)["signature"] for r in records) == sorted(key)


@pytest.mark.parametrize("mode", ["labelled", "rotation"])
def test_catalog_from_loops_is_plantris_in_every_mode(tmp_path, mode):
    build_catalog(tmp_path / "p", 20, symmetry=mode, generator="plantri")
    build_catalog(tmp_path / "l", 20, symmetry=mode, generator="loops")
    assert _files(tmp_path / "p") == _files(tmp_path / "l")


def test_catalog_resumes_loops_shares(tmp_path):
    built = build_catalog(tmp_path / "c", 18, generator="loops", workers=2)
    parts = sorted((tmp_path / "c" / "parts").glob("loops-*.json"))
    assert parts
    parts[0].unlink()
    again = build_catalog(tmp_path / "c", 18, generator="loops", workers=2)
    assert again.summary == built.summary


def test_loops_generator_needs_its_compiled_search(tmp_path, monkeypatch):

    monkeypatch.setenv("POLYLOOPS_PURE_PYTHON", "arrangements")
    with pytest.raises(CatalogRunError, match="use the plantri generator"):
        build_catalog(tmp_path / "c", 12, generator="loops")
    with pytest.raises(CatalogRunError, match="unknown generator"):
        build_catalog(tmp_path / "c", 12, generator="nope")


@pytest.mark.slow
def test_catalog_from_loops_through_28_is_the_shipped_one(tmp_path):
    from polyloops.catalog.census import default_catalog

    built = build_catalog(tmp_path / "c", 28, generator="loops", workers=2)
    shipped = [line for line in (default_catalog() / "catalog.jsonl").read_text().splitlines()
               if json.loads(line)["corners"] <= 28]
    assert (tmp_path / "c" / "catalog.jsonl").read_text().splitlines() == shipped
    counts = json.loads((default_catalog() / "summary.json").read_text())["counts"]
    assert built.summary["counts"] == {n: c for n, c in counts.items() if int(n) <= 28}


def test_cli_generator_flag(tmp_path, capsys):
    from polyloops.cli.main import main

    assert main(["catalog", "--max-corners", "16", "--generator", "loops", "-o", str(tmp_path / "c"),
                 "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["generator"] == "loops" and summary["counts"]["16"]["full"] == 2
    with pytest.raises(SystemExit) as exit_info:  # argparse's usage error
        main(["catalog", "--max-corners", "16", "--generator", "nope", "-o", str(tmp_path / "d")])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'nope'" in err and len(err.strip().splitlines()) == 1


def test_a_spilled_top_gives_each_share_its_part(tmp_path):
    """The top of the search written to a file and read back share by share holds the same
    roots, in the same order, and the same shallow candidates, as the top in memory; a second
    run reads the file instead of computing the top again."""
    from polyloops.generate.loops import loops_frontier, read_frontier_share, share_of, spill_frontier

    top, search = loops_frontier(20)
    path = spill_frontier(20, 1, None, tmp_path)
    stamp = path.stat().st_mtime_ns
    for res in range(3):
        mine, mine_search = read_frontier_share(str(path), 20, res, 3, res == 0)
        theirs = share_of(top, res, 3)
        assert mine == theirs and [a.candidate for a in mine.roots] == [a.candidate for a in theirs.roots]
        assert mine_search == (search if res == 0 else None)
    assert spill_frontier(20, 1, None, tmp_path) == path and path.stat().st_mtime_ns == stamp


@pytest.mark.parametrize("slice_size", [1, 7, 1000])
def test_the_streamed_top_is_the_top_level_by_level(slice_size):
    """Walked depth first a slice at a time, the top hands out the roots the level-by-level
    top holds, in the same order, and the same shallow candidates and statistics."""
    from polyloops.generate.loops.arrangements import SearchStats

    stats: list[SearchStats] = []
    whole = frontier(26, on_stats=stats.append)
    roots: list = []
    streamed_stats: list[SearchStats] = []
    streamed = frontier(26, on_stats=streamed_stats.append, roots_to=roots.extend, slice_size=slice_size)
    assert len(whole.roots) > 300 and streamed.roots == ()
    assert [a.code for a in roots] == [a.code for a in whole.roots]
    assert [a.code for a in streamed.shallow] == [a.code for a in whole.shallow]
    assert sum(streamed_stats, SearchStats()) == sum(stats, SearchStats())
