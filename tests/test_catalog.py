"""The genus-0 catalog: plantri's maps, two independent methods that agree, storage, resuming."""

import itertools
import json
import os
import re
import shutil
import subprocess
from functools import cache
from pathlib import Path

import pytest

from polyloops.catalog.classes import MODES
from polyloops.cli import main
from polyloops.core.canonical import canonical_form
from polyloops.core.directions import Axis
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.structure import LoopStructure
from polyloops.generate.base import Generator, Job, generators, register
from polyloops.generate.plantri.quadrangulations import find_plantri, plantri_batches, plantri_count
from polyloops.io.examples import load_example
from polyloops.solvers import OrientationProblem, make_solver
from polyloops.verify import check_polycube_loop_structure
from switch import needs

ROOT = Path(__file__).resolve().parent.parent
SHIPPED = ROOT / "catalogs" / "genus0"


@cache
def plantri():
    return find_plantri()


def test_batches_hold_every_map():
    for n in range(8, 17):
        read = sum(len(b) for b in plantri_batches(n, plantri(), batch=7))
        assert read == plantri_count(n, plantri())


def test_counts_of_quadrangulations_match_the_notes():
    # The numbers of quadrangulations of the sphere with minimum degree 3 (what plantri -qc2
    # generates), by vertices, 8..18.
    notes = [1, 0, 1, 1, 3, 3, 12, 19, 64, 155, 510]
    assert [plantri_count(n, plantri()) for n in range(8, 19)] == notes


def ascii_maps(n):
    """A second reader: plantri's ASCII output (-a), neighbours clockwise, faces traced here."""
    out = subprocess.run([plantri(), "-qc2a", str(n)], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        if not line.strip():
            continue
        _, spec = line.split()
        rot = [[ord(ch) - ord("a") for ch in part] for part in spec.split(",")]
        seen, faces = set(), []
        for u in range(len(rot)):
            for v in rot[u]:
                if (u, v) in seen:
                    continue
                face, a, b = [], u, v
                while (a, b) not in seen:
                    seen.add((a, b))
                    face.append(a)
                    i = rot[b].index(a)
                    a, b = b, rot[b][(i - 1) % len(rot[b])]
                faces.append(face)
        yield HalfEdgeMap.from_faces(faces)


def brute_counts(n):
    """The slow twin: every labelling of the loops by axes (skipping those where two crossing
    loops share an axis), every orientation the SAT solver lists, each checked with the
    Definition-4 checker, deduplicated by signature."""
    classes = {mode: set() for mode in MODES}
    for m in ascii_maps(n):
        loops = m.loop_system.loops
        if any(lp.self_crossings for lp in loops):
            continue
        pairs = {tuple(sorted(m.loop_system.loops_of_face(m, f))) for f in range(m.num_faces)}
        for axes in itertools.product(Axis, repeat=len(loops)):
            if any(axes[a] == axes[b] for a, b in pairs):
                continue
            ls = LoopStructure(m, axes)
            for signs in make_solver("sat").solutions(OrientationProblem(ls)):
                oriented = ls.with_signs(signs)
                assert check_polycube_loop_structure(oriented).valid
                for mode in MODES:
                    classes[mode].add(canonical_form(oriented, mode).signature)
    return {mode: len(v) for mode, v in classes.items()}


@pytest.fixture(scope="module")
def small_catalog(tmp_path_factory):
    out = tmp_path_factory.mktemp("cat") / "c"
    assert main(["catalog", "--min-corners", "8", "--max-corners", "20", "-o", str(out), "--symmetry",
                 "rotation", "--generator", "plantri"]) == 0
    return out


def test_two_methods_agree_through_20(small_catalog):
    summary = json.loads((small_catalog / "summary.json").read_text())
    for n in range(8, 21):
        assert summary["counts"][str(n)] == brute_counts(n), n


def test_summary_form_and_records(small_catalog):
    summary = json.loads((small_catalog / "summary.json").read_text())
    assert summary["genus"] == 0
    assert set(summary["counts"]) == {str(n) for n in range(8, 21)}
    assert summary["quadrangulations"]["16"] == plantri_count(16, plantri())
    lines = (small_catalog / "catalog.jsonl").read_text().splitlines()
    assert len(lines) == sum(c["rotation"] for c in summary["counts"].values())
    for line in lines:
        rec = json.loads(line)
        assert sum(rec["corner_categories"].values()) == rec["corners"]
        assert rec["faces"] == rec["corners"] - 2
        assert rec["symmetry"] == "rotation"


def test_query(capsys, small_catalog):
    assert main(["catalog", "query", str(small_catalog), "corners = 16", "--json"]) == 0
    answer = json.loads(capsys.readouterr().out)
    rows = answer["rows"]
    summary = json.loads((small_catalog / "summary.json").read_text())
    assert len(rows) == answer["count"] == summary["counts"]["16"]["rotation"]
    assert answer["where"] == "corners = 16" and answer["catalog"] == str(small_catalog)
    assert main(["catalog", "query", str(small_catalog), "nonsense ((("]) == 2
    assert "bad query" in capsys.readouterr().err


def test_query_without_the_database_reads_the_records(tmp_path, capsys, small_catalog):
    """A catalog without ``catalog.sqlite`` (as shipped) answers queries and exports from
    ``catalog.jsonl`` with the same rows and columns as its database."""
    bare = tmp_path / "bare"
    shutil.copytree(small_catalog, bare, ignore=shutil.ignore_patterns("catalog.sqlite", "parts"))
    assert not (SHIPPED / "catalog.sqlite").exists()
    for where in ("corners = 16", "1", "chiral OR irreducible"):
        answers = []
        for directory in (small_catalog, bare):
            assert main(["catalog", "query", str(directory), where, "--json"]) == 0
            answers.append(json.loads(capsys.readouterr().out)["rows"])
        assert answers[0] == answers[1] and answers[0]
    csvs = [main(["catalog", "export", str(d), "--csv", "-o", str(tmp_path / f"{d.name}.csv")]) for d in
            (small_catalog, bare)]
    assert csvs == [0, 0]
    assert (tmp_path / "bare.csv").read_bytes() == (tmp_path / f"{small_catalog.name}.csv").read_bytes()
    assert main(["catalog", "query", str(bare), "nonsense ((("]) == 2
    assert "bad query" in capsys.readouterr().err


def test_resume_and_no_half_written_files(tmp_path, capsys):
    out = tmp_path / "c"
    assert main(["catalog", "--max-corners", "18", "-o", str(out)]) == 0
    first = (out / "summary.json").read_text()
    parts = sorted((out / "parts").iterdir())
    stamp = {p.name: p.stat().st_mtime_ns for p in parts}
    parts[0].unlink()  # as if interrupted before that job finished
    assert main(["catalog", "--max-corners", "18", "-o", str(out)]) == 0
    assert (out / "summary.json").read_text() == first
    again = {p.name: p.stat().st_mtime_ns for p in (out / "parts").iterdir()}
    assert [k for k in again if again[k] != stamp.get(k)] == [parts[0].name]
    assert not list(out.rglob("*.tmp"))


def test_slices_and_workers_agree(tmp_path):
    whole, a, b, w = (tmp_path / x for x in ("whole", "a", "b", "w"))
    assert main(["catalog", "--min-corners", "20", "--max-corners", "20", "--generator", "plantri",
                 "-o", str(whole)]) == 0
    assert main(["catalog", "--min-corners", "20", "--max-corners", "20", "--res", "0", "--mod", "2",
                 "--generator", "plantri", "-o", str(a)]) == 0
    assert main(["catalog", "--min-corners", "20", "--max-corners", "20", "--res", "1", "--mod", "2",
                 "--generator", "plantri", "-o", str(b)]) == 0
    assert main(["catalog", "--min-corners", "20", "--max-corners", "20", "--workers", "2",
                 "--generator", "plantri", "-o", str(w)]) == 0
    total = json.loads((whole / "summary.json").read_text())["counts"]["20"]
    halves = [json.loads((x / "summary.json").read_text())["counts"]["20"] for x in (a, b)]
    assert {m: halves[0][m] + halves[1][m] for m in MODES} == total
    assert json.loads((w / "summary.json").read_text())["counts"]["20"] == total
    assert (whole / "catalog.jsonl").read_text() == (w / "catalog.jsonl").read_text()


@pytest.mark.parametrize("generator", ["plantri", pytest.param("loops", marks=pytest.mark.slow)])
def test_dask_local(tmp_path, generator):
    pytest.importorskip("distributed")
    if generator == "loops":
        pytest.importorskip("polyloops.generate.loops._arrangements")
    out, ref = tmp_path / "d", tmp_path / "r"
    assert main(["catalog", "--max-corners", "16", "--dask", "local", "--generator", generator,
                 "-o", str(out)]) == 0
    assert main(["catalog", "--max-corners", "16", "--generator", "plantri", "-o", str(ref)]) == 0
    assert (out / "catalog.jsonl").read_text() == (ref / "catalog.jsonl").read_text()


def test_shipped_catalog_regenerates(tmp_path):
    shipped = json.loads((SHIPPED / "summary.json").read_text())
    out = tmp_path / "c"
    assert main(["catalog", "--max-corners", "20", "--generator", "plantri", "-o", str(out)]) == 0
    mine = json.loads((out / "summary.json").read_text())
    for n in range(8, 21):
        assert mine["counts"][str(n)] == shipped["counts"][str(n)]
        assert mine["quadrangulations"][str(n)] == shipped["quadrangulations"][str(n)]
        assert mine["simple_strips"][str(n)] == shipped["simple_strips"][str(n)]
    ours = (out / "catalog.jsonl").read_text().splitlines()
    theirs = [line for line in (SHIPPED / "catalog.jsonl").read_text().splitlines()
              if json.loads(line)["corners"] <= 20]
    assert ours == theirs


def test_bad_arguments(capsys, tmp_path):
    assert main(["catalog", "--max-corners", "6", "--min-corners", "8", "-o", str(tmp_path / "x")]) == 2
    assert main(["catalog", "--max-corners", "10", "--res", "1", "-o", str(tmp_path / "x")]) == 2
    assert main(["catalog", "--max-corners", "10", "--plantri", "/nonexistent",
                 "-o", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    problems = [line for line in err.splitlines() if ": note: " not in line]  # notes: a twin runs
    assert "Traceback" not in err and len(problems) == 3


def test_plantri_is_found_without_help():
    """The plantri found with no option set is an executable that answers: it counts the one
    quadrangulation with 8 vertices (the cube) as plantri's own summary states it."""
    import subprocess

    binary = find_plantri()
    assert Path(binary).is_file() and os.access(binary, os.X_OK)
    done = subprocess.run([binary, "-qc2m3u", "8"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and re.search(r"\b1 quadrangulations? generated", done.stderr), done.stderr


def test_catalog_readme_table_is_the_summary():
    import importlib.util

    spec = importlib.util.spec_from_file_location("catalog_readme", ROOT / "tools" / "catalog_readme.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    summary = json.loads((SHIPPED / "summary.json").read_text())
    readme = (ROOT / "catalogs" / "README.md").read_text()
    rows = mod.certificate_rows(SHIPPED / "reachability-certificate.jsonl")
    genus1 = mod.genus1()
    assert genus1 is not None and genus1[1]  # the genus-1 catalog ships, with its certificate
    assert mod.render(readme, summary, rows, genus1) == readme, "run: python tools/catalog_readme.py"
    page = (ROOT / "docs" / "reachability.md").read_text()
    assert mod._replace(page, mod.REACH_BEGIN, mod.REACH_END, mod.reach_table(rows)) == page
    assert mod._replace(page, mod.G1_REACH_BEGIN, mod.G1_REACH_END, mod.reach_table(genus1[1])) == page
    assert mod.G1_REACH_BEGIN in page and mod.G1_BEGIN in readme
    rows = len((SHIPPED / "catalog.jsonl").read_text().splitlines())
    assert rows == sum(c["full"] for c in summary["counts"].values())


def shipped_records():
    return [json.loads(line) for line in (SHIPPED / "catalog.jsonl").read_text().splitlines()]


@pytest.mark.parametrize("every", [pytest.param(1, marks=pytest.mark.slow), 37])
def test_shipped_records_describe_their_own_signature(every):
    """Every column is recomputed from the structure that ``sig:SIGNATURE`` loads (every 37th
    record in the default run, all of them in the slow one)."""
    from polyloops.core.canonical import from_signature
    from polyloops.core.corners import corner_histogram
    from polyloops.core.moves import removals

    for rec in shipped_records()[::every]:
        ls = from_signature(rec["signature"])
        form = canonical_form(ls, rec["symmetry"])
        assert form.signature == rec["signature"]
        assert rec["loops"] == {a.name: ls.axes.count(a) for a in Axis}, rec["signature"]
        assert rec["corners"] == ls.map.num_corners and rec["faces"] == ls.map.num_faces
        _, categories, _ = corner_histogram(ls)
        assert rec["corner_categories"] == {c: categories[c] for c in rec["corner_categories"]}
        assert rec["automorphisms"] == form.automorphisms
        assert rec["chiral"] == (not form.achiral)
        assert rec["removable_loops"] == len(removals(ls))
        assert rec["irreducible"] == (rec["removable_loops"] == 0)


def chiral_identity_holds(summary, records):
    """A class up to all 48 symmetries is one class up to rotation when it is achiral and two
    when it is chiral (the rotations are a subgroup of index 2)."""
    chiral = {n: 0 for n in summary["counts"]}
    for rec in records:
        chiral[str(rec["corners"])] += rec["chiral"]
    return all(c["rotation"] == c["full"] + chiral[n] for n, c in summary["counts"].items())


def test_chirality_ties_the_columns_together():
    assert chiral_identity_holds(json.loads((SHIPPED / "summary.json").read_text()), shipped_records())
    assert any(rec["chiral"] for rec in shipped_records())


def test_chiral_query_in_the_readme(capsys):
    """The README's example query returns every chiral class with 24 corners."""
    assert "corners = 24 AND chiral" in (ROOT / "catalogs" / "README.md").read_text()
    assert main(["catalog", "query", str(SHIPPED), "corners = 24 AND chiral", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    counts = json.loads((SHIPPED / "summary.json").read_text())["counts"]["24"]
    assert len(rows) == counts["rotation"] - counts["full"] > 0


def test_irreducible_records_include_the_non_incremental_polycube(capsys):
    from polyloops.core.canonical import signature
    from polyloops.io.examples import load_example

    assert main(["catalog", "query", str(SHIPPED), "irreducible", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert signature(load_example("non-incremental"), "full") in {r["signature"] for r in rows}
    assert {r["signature"] for r in rows} == {r["signature"] for r in shipped_records() if r["irreducible"]}


def test_degree_filter_equals_decoded_degrees():
    from polyloops.generate.plantri.quadrangulations import Batch, max_degrees

    for n in (12, 14, 16):
        for rows in plantri_batches(n, plantri(), batch=50):
            batch = Batch(rows)
            for i, top in enumerate(max_degrees(rows)):
                m = batch.map(i)
                assert top == max(m.degree(c) for c in range(m.num_corners))


def test_no_quadrangulation_with_odd_corners_has_only_simple_loops():
    """The theorem behind skipping odd corner counts, checked where plantri is quick."""
    from polyloops.generate.plantri.quadrangulations import Batch, odd_corners_have_no_polycube

    for n in (9, 11, 13, 15, 17, 19, 21):
        assert odd_corners_have_no_polycube(n)
        for rows in plantri_batches(n, plantri()):
            assert not Batch(rows).without_self_crossing().any(), n


def test_odd_counts_are_not_generated(tmp_path):
    from polyloops.generate.base import generators

    assert {j.n for j in generators()["plantri"].plan(8, 21, None, 2)} == {8, 10, 12, 14, 16, 18, 20}
    assert main(["catalog", "--min-corners", "9", "--max-corners", "11", "--generator", "plantri",
                 "-o", str(tmp_path / "c")]) == 0
    summary = json.loads((tmp_path / "c" / "summary.json").read_text())
    assert summary["quadrangulations"] == {"9": None, "10": 1, "11": None}
    assert summary["simple_strips"] == {"9": 0, "10": 0, "11": 0}
    assert summary["counts"]["9"] == {"labelled": 0, "rotation": 0, "full": 0}


@pytest.mark.parametrize("every", [pytest.param(1, marks=pytest.mark.slow), 211])
def test_names_and_identify_every_shipped_record(tmp_path, capsys, every):
    """Every record (every 211th in the default run, all of them in the slow one) is found by
    its name from a renumbered, mirrored, moved copy."""
    import random

    from polyloops.catalog.census import identify, read_catalog
    from polyloops.core.canonical import from_signature, transformed
    from polyloops.core.symmetry import SIGNED_PERMUTATIONS
    from polyloops.io.formats import dumps
    from test_canonical import mirror, renumber

    rng = random.Random(7)
    census = read_catalog(SHIPPED)
    records = shipped_records()
    assert len({r["name"] for r in records}) == len(records)
    for r in records[::every]:
        assert r["name"][0] == "P" and int(r["name"][1:].split(".")[0]) == r["corners"]
        moved = transformed(from_signature(r["signature"]), rng.choice(SIGNED_PERMUTATIONS))
        copy = renumber(mirror(moved), rng)
        assert identify(copy, census).name == r["name"]
    ranks = {}
    for r in records:  # ranks count up from 1 within a corner count, in signature order
        ranks.setdefault(r["corners"], []).append((r["signature"], int(r["name"].split(".")[1])))
    for rows in ranks.values():
        assert [k for _, k in sorted(rows)] == list(range(1, len(rows) + 1))
    path = tmp_path / "q.json"
    path.write_text(dumps(from_signature(records[-1]["signature"]).primalize().outward()))
    assert main(["identify", str(path), "--catalog", str(SHIPPED)]) == 0
    assert records[-1]["name"] in capsys.readouterr().out
    assert main(["identify", "example:ring", "--catalog", str(SHIPPED)]) == 1
    assert "genus 1" in capsys.readouterr().out


def test_csv_export(tmp_path):
    import csv

    from shipped import small_catalog

    out, cut = tmp_path / "c.csv", small_catalog(26)  # every row of a real catalog, a short one
    assert main(["catalog", "export", str(cut), "--csv", "-o", str(out)]) == 0
    rows = list(csv.DictReader(out.read_text().splitlines()))
    assert [r["signature"] for r in rows] == [json.loads(line)["signature"]
                                             for line in (cut / "catalog.jsonl").read_text().splitlines()]
    assert main(["catalog", "export", str(tmp_path), "--csv"]) == 2


# OEIS A078666 (simple quadrangulations of the sphere with minimum degree 3, mirror images
# identified), offset 6, indexed by faces: an outside count to compare plantri's with.
A078666 = [1, 0, 1, 1, 3, 3, 12, 19, 64, 155, 510, 1514, 5146, 16966, 58782, 203269, 716607, 2536201,
           9062402, 32533568, 117498072, 426212952, 1553048548]


def test_quadrangulation_counts_are_oeis_a078666():
    """The shipped counts of quadrangulations (plantri -qc2, by corners = vertices) are
    A078666(n - 2) wherever they are known, and docs/counts.md cites that range."""
    summary = json.loads((ROOT / "catalogs" / "genus0" / "summary.json").read_text())
    known = {int(n): c for n, c in summary["quadrangulations"].items() if c is not None}
    assert known and max(known) == 30
    for n, c in known.items():
        assert c == A078666[n - 2 - 6], n
    page = (ROOT / "docs" / "counts.md").read_text()
    assert "A078666](https://oeis.org/A078666)`(n - 2)`" in page
    assert f"from {min(known)} to {max(known)}" in page
@needs("arrangements")  # the loops generator: its compiled search
@pytest.mark.parametrize("through", [pytest.param(None, marks=pytest.mark.slow), 34])
def test_maps_by_classes_agree_with_the_records(through):
    """summary.json's count of maps by the classes they carry, made per map while the catalog
    was built, equals a count from the records alone: each record's map found again from its
    signature (its quad mesh's canonical arrangement), records grouped by map (through 34
    corners in the default run, every size in the slow one)."""
    from collections import Counter

    from polyloops.core.canonical import from_signature
    from polyloops.generate.loops.arrangements import Arrangement

    summary = json.loads((ROOT / "catalogs" / "genus0" / "summary.json").read_text())
    sizes = [n for n in summary["counts"] if through is None or int(n) <= through]
    per_map: Counter[tuple[int, bytes]] = Counter()
    for line in (ROOT / "catalogs" / "genus0" / "catalog.jsonl").read_text().splitlines():
        record = json.loads(line)
        if str(record["corners"]) in sizes:
            per_map[record["corners"], Arrangement.of(from_signature(record["signature"]).map).code] += 1
    derived: dict[str, Counter[str]] = {n: Counter() for n in sizes}
    for (n, _), k in per_map.items():
        derived[str(n)][str(k)] += 1
    assert {n: summary["maps_by_classes"][n] for n in sizes} == {
        n: dict(sorted(c.items(), key=lambda kv: int(kv[0]))) for n, c in derived.items()}


def test_counts_page_and_bfiles_are_the_summary():
    import importlib.util

    spec = importlib.util.spec_from_file_location("counts_page", ROOT / "tools" / "counts_page.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    files = mod.write_all()
    assert ROOT / "docs" / "bfiles" / "genus1-full.txt" in files  # the genus-1 catalog ships
    for path, text in files.items():
        assert path.read_text() == text, "run: python tools/counts_page.py"


def test_long_corner_counts_are_sliced():
    from polyloops.generate.base import Job, generators

    plantri = generators()["plantri"]
    jobs = plantri.plan(24, 26, None, 2)
    assert set(jobs) == ({Job("plantri", 24, 24, r, 4) for r in range(4)}
                         | {Job("plantri", 26, 26, r, 8) for r in range(8)})
    assert all(j.mod == 1 for j in plantri.plan(8, 30, None, 1))


@pytest.mark.slow
@pytest.mark.parametrize("n", [24, 26, 28])
def test_compiled_and_numpy_filters_agree_on_large_counts(n):
    """The two strip filters keep the same maps, in order (28 corners: about 30 minutes)."""
    from polyloops.generate.plantri.quadrangulations import compiled_filter_available, filtered_batches

    if not compiled_filter_available():
        pytest.skip("the compiled strip filter was not built")
    import numpy as np

    def run(method):
        batches = list(filtered_batches(n, plantri(), method=method))
        return (np.concatenate([b.rows for b in batches]), sum(b.maps for b in batches),
                sum(b.simple_strips for b in batches))

    fast, slow = run("compiled"), run("numpy")
    assert np.array_equal(fast[0], slow[0]) and fast[1:] == slow[1:]


@pytest.mark.slow
def test_shipped_catalog_regenerates_through_28(tmp_path):
    """About 4 minutes with two workers."""
    out = tmp_path / "c"
    assert main(["catalog", "--max-corners", "28", "--workers", "2", "--generator", "plantri",
                 "-o", str(out)]) == 0
    shipped = json.loads((SHIPPED / "summary.json").read_text())
    mine = json.loads((out / "summary.json").read_text())
    for table in ("counts", "quadrangulations", "simple_strips"):
        assert mine[table] == {k: v for k, v in shipped[table].items() if int(k) <= 28}
    theirs = [line for line in (SHIPPED / "catalog.jsonl").read_text().splitlines()
              if json.loads(line)["corners"] <= 28]
    assert (out / "catalog.jsonl").read_text().splitlines() == theirs


@pytest.mark.slow  # the census module's doctest checks the same counts through 20 corners in the default run
def test_orbit_stabiliser_ties_the_three_columns_of_the_shipped_catalog():
    """From the full classes alone (their automorphism groups in the three modes and the group
    orders 48 and 24), the orbit-stabiliser theorem predicts the labelled and rotation counts
    that summary.json states from separate canonical forms; and a class is chiral exactly when
    it splits into two rotation classes."""
    from polyloops.catalog.census import orbit_counts, read_catalog

    census = read_catalog(SHIPPED)
    derived = orbit_counts(census)
    for n, row in census.summary["counts"].items():
        if row["full"]:
            got = derived[int(n)]
            assert (got.labelled, got.rotation, got.full) == (row["labelled"], row["rotation"], row["full"])
    for entry in census.entries:
        aut_r = canonical_form(entry.structure(), "rotation").automorphisms
        assert entry.record.chiral == (aut_r == entry.record.automorphisms)


# -- nothing is overwritten with less ------------------------------------------------------------

def test_a_smaller_build_refuses_to_replace_a_larger_catalog(tmp_path, capsys):
    out = tmp_path / "c"
    assert main(["catalog", "--max-corners", "18", "--generator", "plantri", "-o", str(out)]) == 0
    before = {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()}
    capsys.readouterr()
    for extra in (["--max-corners", "14"], ["--max-corners", "18", "--min-corners", "12"],
                  ["--max-corners", "18", "--symmetry", "rotation"],
                  ["--max-corners", "18", "--res", "0", "--mod", "2"]):
        assert main(["catalog", *extra, "--generator", "plantri", "-o", str(out)]) == 2
        err = capsys.readouterr().err
        assert "--overwrite" in err and "8 to 18 corners" in err and err.count("\n") == 1
        assert {p.name: p.read_bytes() for p in out.iterdir() if p.is_file()} == before
    # a larger build extends it; --overwrite replaces it with less when asked
    assert main(["catalog", "--max-corners", "20", "--generator", "plantri", "-o", str(out)]) == 0
    assert "20" in json.loads((out / "summary.json").read_text())["counts"]
    assert main(["catalog", "--max-corners", "14", "--generator", "plantri", "--overwrite",
                 "-o", str(out)]) == 0
    assert max(map(int, json.loads((out / "summary.json").read_text())["counts"])) == 14


def test_a_share_and_an_unreadable_catalog(tmp_path, capsys):
    out = tmp_path / "c"
    assert main(["catalog", "--max-corners", "16", "--res", "0", "--mod", "2", "--generator", "plantri",
                 "-o", str(out)]) == 0
    assert json.loads((out / "summary.json").read_text())["share"] == [0, 2]
    assert main(["catalog", "--max-corners", "16", "--res", "0", "--mod", "2", "--generator", "plantri",
                 "-o", str(out)]) == 0  # the same share resumes
    assert main(["catalog", "--max-corners", "16", "--res", "1", "--mod", "2", "--generator", "plantri",
                 "-o", str(out)]) == 2  # another share would replace it
    # the whole search covers the share
    assert main(["catalog", "--max-corners", "16", "--generator", "plantri", "-o", str(out)]) == 0
    (out / "summary.json").write_text("{not json")
    capsys.readouterr()
    assert main(["catalog", "--max-corners", "20", "--generator", "plantri", "-o", str(out)]) == 2
    assert "summary.json" in capsys.readouterr().err


def test_generator_default_and_plantri_options(capsys, tmp_path):
    from polyloops.catalog.run import choose_generator
    from polyloops.generate.loops.arrangements import compiled_generator_available

    assert choose_generator(None) == ("loops", None) if compiled_generator_available() else \
        choose_generator(None)[0] == "plantri"
    assert choose_generator(None, plantri="/usr/bin/plantri") == ("plantri", None)
    assert main(["catalog", "--max-corners", "12", "--generator", "loops", "--method", "numpy",
                 "-o", str(tmp_path / "x")]) == 2
    assert "plantri generator" in capsys.readouterr().err and not (tmp_path / "x").exists()


def test_catalog_readers_refuse_fifos_and_odd_summaries(tmp_path, capsys):
    import os

    cat = tmp_path / "cat"
    shutil.copytree(SHIPPED, cat)
    (cat / "catalog.jsonl").unlink()
    os.mkfifo(cat / "catalog.jsonl")
    cert = str(SHIPPED / "reachability-certificate.jsonl")
    for argv in (["identify", "example:l-shape", "--catalog", str(cat)],
                 ["gallery", str(cat), "-o", str(tmp_path / "site")],
                 ["conjecture", "check", cert, "--catalog", str(cat)]):
        assert main(argv) == 2, argv  # refused at once, not read (a FIFO would block)
        assert "not a regular file" in capsys.readouterr().err
    (cat / "catalog.jsonl").unlink()
    shutil.copy(SHIPPED / "catalog.jsonl", cat / "catalog.jsonl")
    summary = json.loads((cat / "summary.json").read_text())
    summary["counts"]["x"] = summary["counts"]["8"]
    (cat / "summary.json").write_text(json.dumps(summary))
    assert main(["conjecture", "check", cert, "--catalog", str(cat)]) == 2
    assert "not an integer" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["a#b", "100%", "what?", "x y"])
def test_catalog_query_in_strange_directory_names(tmp_path, capsys, name):

    from shipped import small_catalog

    cat = tmp_path / name
    shutil.copytree(small_catalog(20), cat)
    assert main(["catalog", "query", str(cat), "corners = 16", "--json"]) == 0
    assert [r["name"] for r in json.loads(capsys.readouterr().out)["rows"]] == ["P16.1", "P16.2"]
    empty = tmp_path / f"empty-{name}"
    empty.mkdir()
    assert main(["catalog", "query", str(empty), "corners = 16"]) == 2
    assert list(empty.iterdir()) == []  # no stray database left behind


# -- a generator plugs in by the interface alone -------------------------------------------------

class ToyGenerator(Generator):
    """A toy generator: the quad maps of a few bundled examples, one job a corner count."""

    name = "toy"
    visits = "examples"
    statistics_key = "toy"

    def plan(self, low, high, share, workers):
        res, mod = share or (0, 1)
        return [Job(self.name, n, n, res, mod) for n in range(low, high + 1) if n % 2 == 0]

    def candidates(self, job, context, tally):
        for name in ("cube", "box-2x1x1", "l-shape"):
            m = load_example(name).map
            if m.num_corners == job.n and job.res == 0:
                tally.visited += 1
                tally.statistics["examples"] = tally.statistics.get("examples", 0) + 1
                yield m


def test_a_toy_generator_builds_a_catalog_through_the_pipeline(tmp_path):
    """Implementing the interface is all a generator needs: the pipeline plans, runs, keeps
    parts, names and stores the records, and sums the generator's statistics."""
    from polyloops.catalog.run import build_catalog

    register(ToyGenerator())
    try:
        built = build_catalog(tmp_path / "toy", 16, generator="toy")
        again = build_catalog(tmp_path / "toy", 16, generator="toy")  # resumed from its parts
    finally:
        generators().pop("toy")
    reference = build_catalog(tmp_path / "ref", 16, generator="plantri")
    known = {json.loads(line)["signature"]: json.loads(line)["name"]
             for line in (tmp_path / "ref" / "catalog.jsonl").read_text().splitlines()}
    mine = [json.loads(line) for line in (tmp_path / "toy" / "catalog.jsonl").read_text().splitlines()]
    # the cube, the 2x1x1 box and the L: each named as the full catalog names it, where its
    # corner count holds no other class of the toy's
    assert [r["name"] for r in mine] == ["P8.1", "P12.1", "P16.1"]
    assert [known[r["signature"]] for r in mine] == ["P8.1", "P12.1", "P16.2"]
    assert built.summary["generator"] == "toy" and built.summary["toy"] == {"examples": 3}
    assert set(built.summary["quadrangulations"].values()) == {None}  # the toy counts no maps
    assert reference.summary["counts"]["12"] == built.summary["counts"]["12"]  # the 2x1x1 boxes
    assert again.summary == built.summary and sorted(p.name for p in (tmp_path / "toy" / "parts").iterdir()) \
        == [f"toy-{n}to{n}-0of1.json" for n in (10, 12, 14, 16, 8)]


def test_crosschecks_agree_with_the_shipped_catalog_and_catch_a_gap(tmp_path):
    """The sampled plantri comparison and the reachability comparison find nothing missing in
    the shipped catalog, and both notice a class taken out of a copy of it."""

    from polyloops.reach.crosscheck import plantri_sample, reach_agreement
    from shipped import small_catalog

    shipped = small_catalog(26)  # the comparisons look at 20 corners: the rest is not read
    assert plantri_sample(shipped, 20, mod=4, k=4, seed=7).agrees
    reach = reach_agreement(shipped, 20)
    assert reach.agrees and sum(reach.reached.values()) == sum(
        json.loads((SHIPPED / "summary.json").read_text())["counts"][str(n)]["full"] for n in range(8, 21))
    # A copy without P20.3 that is consistent in itself (renamed, recounted, digested again):
    # no reader's check can see the gap; the two independent methods do.
    from polyloops.catalog.census import Census, read_catalog
    from polyloops.catalog.records import CatalogEntry, class_names
    from polyloops.catalog.run import write_census

    census = read_catalog(shipped)
    gone = census["P20.3"]
    kept = [e for e in census.entries if e.name != "P20.3"]
    names = class_names([e.record for e in kept], "full")
    counts = {**census.summary["counts"], "20": {**census.summary["counts"]["20"], "full": 5}}
    renamed = tuple(CatalogEntry(n, e.symmetry, e.record) for n, e in zip(names, kept, strict=True))
    cut = write_census(Census(SHIPPED, renamed, {**census.summary, "counts": counts}), tmp_path / "cut")
    assert len(read_catalog(cut)) == len(census) - 1
    assert plantri_sample(cut, 20, mod=4, k=4, seed=7).missing == (gone.signature,)
    assert reach_agreement(cut, 20).missing == (gone.signature,)


@needs("arrangements")  # the loops generator: its compiled search
def test_shipping_a_larger_run_keeps_the_old_counts_and_checks_everything(tmp_path):
    """tools/ship_catalog.py: a run that extends the shipped catalog replaces it only after
    agreeing with it record for record, keeps the numbers of plantri's maps it cannot count,
    and writes a certificate that checks; a run that disagrees is refused."""
    import importlib.util
    import shutil

    from polyloops.catalog.run import build_catalog
    from polyloops.reach.conjecture import check_certificate

    spec = importlib.util.spec_from_file_location("ship_catalog", ROOT / "tools" / "ship_catalog.py")
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    into = tmp_path / "shipped"
    shutil.copytree(SHIPPED, into)
    lines = [line for line in (into / "catalog.jsonl").read_text().splitlines()
             if json.loads(line)["corners"] <= 20]
    (into / "catalog.jsonl").write_text("\n".join(lines) + "\n")
    old = json.loads((into / "summary.json").read_text())
    cut = {table: {n: v for n, v in old[table].items() if int(n) <= 20}
           for table in ("counts", "quadrangulations", "simple_strips")}
    (into / "summary.json").write_text(json.dumps({**old, **cut}))
    run = tmp_path / "run"
    build_catalog(run, 24, generator="loops")
    report = tool.ship(run, into, slack=10)
    summary = json.loads((into / "summary.json").read_text())
    assert report["max_corners"] == 24 and report["unsettled"] == {}
    assert summary["quadrangulations"]["20"] == old["quadrangulations"]["20"]
    assert summary["quadrangulations"]["24"] is None
    assert summary["counts"]["24"] == old["counts"]["24"]
    assert (into / "catalog.jsonl").read_text() == (run / "catalog.jsonl").read_text()
    lines = (into / "reachability-certificate.jsonl").read_text().splitlines()
    assert check_certificate(lines, into).valid
    bad = tmp_path / "bad"
    shutil.copytree(run, bad)
    records = (bad / "catalog.jsonl").read_text().splitlines()
    (bad / "catalog.jsonl").write_text("\n".join(records[1:]) + "\n")
    with pytest.raises(tool.ShipError):
        tool.ship(bad, into)


def test_the_catalog_readme_counts_what_ships():
    """The README's count of the shipped genus-0 classes is the summary's."""
    summary = json.loads((SHIPPED / "summary.json").read_text())
    readme = (ROOT / "catalogs" / "README.md").read_text()
    found = re.search(r"with at most (\d+) corners.*?identified: ([\d,]+) classes \(([\d,]+) of them with "
                      r"(\d+) corners\)", readme, re.S)
    assert found is not None
    top, total, at_top, top_again = found.groups()
    counts = summary["counts"]
    assert int(top) == int(top_again) == max(int(n) for n in counts)
    assert int(total.replace(",", "")) == sum(row["full"] for row in counts.values())
    assert int(at_top.replace(",", "")) == counts[top]["full"]


class ToyGenus2(Generator):
    """A toy genus-2 generator: the quad map of the bundled two-hole example, nothing else. A
    genus-2 search would be a folder of polyloops.generate with a class like this one."""

    name = "toy-genus2"
    genus = 2
    visits = "examples"
    statistics_key = "toy"

    def plan(self, low, high, share, workers):
        res, mod = share or (0, 1)
        return [Job(self.name, high, low, res, mod)]

    def candidates(self, job, context, tally):
        m = load_example("two-axis-holes").map
        if job.low <= m.num_corners <= job.n and job.res == 0:
            tally.visited += 1
            yield m


def test_a_genus_two_generator_plugs_in_by_registering_itself(tmp_path, capsys):
    """Genus is data: a generator of genus 2 registers itself, and the pipeline, the names, the
    readers and the command line's --genus take it without any other file edited."""
    from polyloops.catalog.census import read_catalog
    from polyloops.catalog.run import build_catalog

    register(ToyGenus2())
    try:
        top = load_example("two-axis-holes").map.num_corners
        built = build_catalog(tmp_path / "g2", top, generator="toy-genus2", genus=2)  # beside handles
        census = read_catalog(tmp_path / "g2")
        assert built.summary["genus"] == 2 and census.genus == 2
        assert [e.name for e in census.entries] == [f"G2-{top}.1"]
        from polyloops.catalog.census import identify

        assert identify(load_example("two-axis-holes"), census).name == f"G2-{top}.1"
        from polyloops.cli.main import build_parser

        assert build_parser().parse_args(["catalog", "--genus", "2", "--max-corners", "9"]).genus == 2
    finally:
        generators().pop("toy-genus2")


@needs("arrangements")
@needs("torus")  # the Python loop-by-loop second stage takes minutes
def test_generator_options_change_the_work_not_the_records(tmp_path):
    """The search variants that were module flags are generator options: the loops search with
    its cuts off and the torus search with its loop-by-loop second stage write the records of
    the defaults byte for byte, do other work, say so in the summary, and keep their parts apart
    (a default run over a variant's directory recomputes every job instead of reusing them).
    The torus run stops below the smallest genus-1 polycube (32 corners: the loop-by-loop stage
    takes two minutes there); test_torus compares the two stages' maps."""
    from polyloops.catalog.run import CatalogRunError, build_catalog
    from polyloops.generate.loops.arrangements import Cuts

    runs = [("loops", 0, 18, {"cuts": Cuts(colour=False, meet=False)}, "no-colour-no-meet"),
            ("torus", 1, 26, {"stage": "loops"}, "stage-loops")]
    for name, genus, top, options, variant in runs:
        plain = build_catalog(tmp_path / f"{name}-plain", top, generator=name, genus=genus)
        other = build_catalog(tmp_path / f"{name}-variant", top, generator=name, genus=genus, options=options)
        assert (tmp_path / f"{name}-variant" / "catalog.jsonl").read_bytes() \
            == (tmp_path / f"{name}-plain" / "catalog.jsonl").read_bytes()
        assert other.summary["counts"] == plain.summary["counts"]
        assert other.summary["variant"] == variant and "variant" not in plain.summary
        assert other.summary["search"] != plain.summary["search"]
        parts = sorted(p.name for p in (tmp_path / f"{name}-variant" / "parts").glob("*.json"))
        assert parts and all(p.startswith(f"{name}-{variant}-") for p in parts)
        again = build_catalog(tmp_path / f"{name}-variant", top, generator=name, genus=genus, overwrite=True)
        assert again.summary["search"] == plain.summary["search"] and "variant" not in again.summary
    with pytest.raises(CatalogRunError, match="stage is regions or loops"):
        build_catalog(tmp_path / "bad", 32, generator="torus", genus=1, options={"stage": "rows"})
    with pytest.raises(CatalogRunError, match="takes no option cuts"):
        build_catalog(tmp_path / "bad", 16, generator="plantri", options={"cuts": Cuts()})


def test_a_ship_takes_the_records_of_its_earlier_passes(tmp_path):
    """tools/ship_catalog.py keeps one settle journal a slack in the run's parts; a later pass
    takes every journal of the same catalog and range (the open class with the slack its pass
    searched to), and none of another range."""
    import importlib.util

    from polyloops.catalog.run import file_digest
    from polyloops.reach.conjecture import settle_catalog
    from shipped import small_catalog

    spec = importlib.util.spec_from_file_location("ship_catalog", ROOT / "tools" / "ship_catalog.py")
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    catalog, parts = small_catalog(26), tmp_path / "parts"
    parts.mkdir()
    settle_catalog(catalog, 26, 6, journal=parts / "settle-journal-6.jsonl")
    digest = file_digest(catalog / "catalog.jsonl")
    records = tool.journal_records(parts, digest, 26)
    assert len(records) == 55 and [r.searched for r in records if not r.settled] == [6]
    assert tool.journal_records(parts, digest, 24) == [] == tool.journal_records(parts, "0" * 64, 26)
