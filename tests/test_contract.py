"""The command line's contract on the inputs users and hostile corpora give: bounded numbers,
no crash of a compiled part, one-line errors (one JSON object under --json), verdicts kept
through a closed pipe, and answers from invariants where a search would be blind."""

from __future__ import annotations

import json
import os
import struct
import subprocess
import sys
import time

import pytest

from cli_run import run

ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}


@pytest.mark.parametrize("argv", [
    ["catalog", "--max-corners", "1000000000", "-o", "big"],
    ["catalog", "--generator", "loops", "--max-corners", "1000000", "-o", "big"],
    ["catalog", "--max-corners", "1" + "0" * 30, "-o", "big"],
    ["catalog", "--genus", "1", "--max-corners", "1" + "0" * 30, "-o", "big"],
    ["catalog", "--max-corners", "20", "--workers", "1" + "0" * 12, "-o", "big"],
])
def test_huge_sizes_are_usage_errors(tmp_path, capsys, argv, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, _, err = run(capsys, *argv)
    assert status == 2 and "out of range" in err and err.count("\n") == 1
    assert not (tmp_path / "big").exists()


def test_the_compiled_searches_check_their_bound():
    from polyloops.core import compiled

    if not all(compiled.built(name) for name in ("arrangements", "torus")):
        pytest.skip("the compiled searches were not built")
    from polyloops.generate.loops import _arrangements
    from polyloops.generate.torus import _torus

    for call in (lambda: _arrangements.children(b"", bytes(8), 10**6),
                 lambda: _torus.children(bytes(8), bytes(4), 10**6),
                 lambda: _torus.first_children(b"", 0, 10**6, 0)):
        with pytest.raises(ValueError, match="compiled search holds"):
            call()


def test_the_library_refuses_a_huge_catalog(tmp_path):
    from polyloops.catalog.run import CatalogRunError, build_catalog

    with pytest.raises(CatalogRunError, match="at most 96"):
        build_catalog(tmp_path / "c", 10**9)


def test_path_answers_from_the_invariants_at_once(capsys):
    started = time.perf_counter()
    status, _, err = run(capsys, "path", "example:cube", "example:ring")
    assert status == 1 and "no path at any size" in err and "genus" in err
    status, _, err = run(capsys, "path", "example:ring", "example:ring-x", "--max-corners", "44")
    assert status == 1 and "hole orientation" in err
    assert time.perf_counter() - started < 10  # a second each on a quiet machine
    status, _, err = run(capsys, "path", "example:cube", "example:l-shape")
    assert status == 2 and "--max-corners M is needed" in err


def test_the_invariant_is_one_a_search_confirms():
    """Where the invariants agree a path can exist; where they differ the bounded search finds
    none (a check that no_path_reason does not refuse a reachable pair)."""
    from polyloops.io.examples import load_example
    from polyloops.reach.search import no_path_reason, shortest_path

    cube, l_shape = load_example("cube").dualize(), load_example("l-shape").dualize()
    assert no_path_reason(cube, l_shape) is None and shortest_path(cube, l_shape, 16) is not None
    ring, ring_y = load_example("ring").dualize(), load_example("ring-y").dualize()
    assert (no_path_reason(ring, ring_y) is None) == (shortest_path(ring, ring_y, 36) is not None)


@pytest.mark.parametrize("example,status", [("torus-cycle", 1), ("ring", 0)])
def test_a_verdict_survives_a_closed_pipe(example, status):
    for _ in range(3):
        proc = subprocess.Popen([sys.executable, "-m", "polyloops", "verify", f"example:{example}"],
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=ENV)
        assert proc.stdout is not None
        proc.stdout.readline()
        proc.stdout.close()  # the reader goes away, as head -1 does
        assert proc.wait(timeout=60) == status


def test_json_errors_are_one_object(capsys, tmp_path):
    status, out, _ = run(capsys, "verify", str(tmp_path / "missing.json"), "--json")
    assert status == 2 and json.loads(out)["status"] == 2 and "missing.json" in json.loads(out)["error"]
    status, out, _ = run(capsys, "verify", "--json")
    assert status == 2 and json.loads(out)["status"] == 2
    status, out, _ = run(capsys, "orient", "example:torus-cycle", "--json")
    data = json.loads(out)
    assert status == 1 and data["status"] == 1 and data["found"] is False


def test_orient_all_json_is_one_object(capsys):
    status, out, _ = run(capsys, "orient", "example:ring", "--all", "--json")
    data = json.loads(out)
    assert status == 0 and data["count"] == len(data["orientations"]) > 1


def test_an_estimate_without_walks_says_so(capsys):
    status, out, _ = run(capsys, "moves", "example:l-shape", "--count", "--estimate", "--time-limit", "1e-9",
                         "--json")
    data = json.loads(out)  # strict JSON: no Infinity
    assert status == 0 and data["estimates"]["X"] == {"estimate": None, "low": None, "high": None, "walks": 0}
    status, out, _ = run(capsys, "moves", "example:l-shape", "--count", "--estimate", "--time-limit", "1e-9")
    assert "no estimate" in out and "about 0" not in out


def test_a_query_that_is_not_utf8_is_bad_input(capsys):
    status, _, err = run(capsys, "catalog", "query", "corners = 8 \udcff")
    assert status == 2 and "not UTF-8" in err


def test_a_huge_npy_header_is_one_line(tmp_path, capsys):
    header = b"{'descr': '|b1', 'fortran_order': False, 'shape': (2, 2, 2), }"
    header += b" " * (65536 - len(header) - 11) + b"\n"
    path = tmp_path / "big.npy"
    path.write_bytes(b"\x93NUMPY\x02\x00" + struct.pack("<I", len(header)) + header + b"\x01" * 8)
    status, _, err = run(capsys, "from-voxels", str(path))
    assert status == 2 and err.count("\n") == 1 and "big.npy" in err


MESH = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"


@pytest.mark.parametrize("faces,expect", [
    ("f 1 1 2\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n", "repeats a vertex"),
    ("f 1 3 99999999999999999999\nf 1 2 4\nf 2 3 4\nf 1 4 3\n", "does not exist"),
])
def test_bad_triangles_are_one_line(tmp_path, capsys, faces, expect):
    (tmp_path / "m.obj").write_text(MESH + faces)
    (tmp_path / "m.labels").write_text("0\n" * faces.count("f "))
    status, _, err = run(capsys, "segmentation", str(tmp_path / "m.obj"), str(tmp_path / "m.labels"))
    assert status == 2 and expect in err and err.count("\n") == 1


def test_an_unused_vertex_in_the_middle_is_left_out(tmp_path, capsys):
    (tmp_path / "m.obj").write_text("v 0 0 0\nv 1 0 0\nv 5 5 5\nv 0 1 0\nv 0 0 1\n"
                                    "f 1 4 2\nf 1 2 5\nf 2 4 5\nf 1 5 4\n")
    (tmp_path / "m.labels").write_text("0\n" * 4)
    status, _, err = run(capsys, "segmentation", str(tmp_path / "m.obj"), str(tmp_path / "m.labels"))
    assert status in (0, 1) and "internal error" not in err


def test_reach_into_a_directory_it_cannot_write_is_bad_input(tmp_path, capsys, monkeypatch):
    """A store that cannot be written (a read-only directory; here sqlite refusing, since root
    may write anywhere) is exit 2 in one line."""
    import sqlite3

    import polyloops.reach.search as reach

    def refuse(path):
        raise sqlite3.OperationalError("attempt to write a readonly database")

    monkeypatch.setattr(reach, "_open_store", refuse)
    status, _, err = run(capsys, "reach", "--max-corners", "12", "-o", str(tmp_path / "r"))
    assert status == 2 and "cannot write" in err and err.count("\n") == 1


def test_a_catalog_run_into_a_directory_it_cannot_write_is_bad_input(tmp_path, capsys, monkeypatch):
    import polyloops.catalog.run as catalog_run

    def refuse(*args, **kw):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(catalog_run, "write_atomic", refuse)
    status, _, err = run(capsys, "catalog", "--max-corners", "12", "-o", str(tmp_path / "c"))
    problems = [line for line in err.splitlines() if ": note: " not in line]  # notes: a twin runs
    assert status == 2 and "Permission denied" in err and len(problems) == 1
