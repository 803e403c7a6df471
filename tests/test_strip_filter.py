"""The compiled strip filter against its numpy twin and a per-map count; bad input is refused."""

import os
from functools import cache

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.generate.plantri import quadrangulations as quads
from polyloops.generate.plantri.quadrangulations import (
    MAX_DEGREE,
    Batch,
    compiled_filter_available,
    filtered_batches,
    find_plantri,
    plantri_batches,
    record_size,
    resolve_method,
)

needs_compiled = pytest.mark.skipif(not compiled_filter_available(),
                                    reason="the compiled strip filter was not built (no C compiler)")


@cache
def plantri():
    return find_plantri()


@cache
def all_rows(n):
    return np.concatenate(list(plantri_batches(n, plantri())))


def collect(n, method):
    batches = list(filtered_batches(n, plantri(), method=method))
    rows = np.concatenate([b.rows for b in batches])
    return rows, sum(b.maps for b in batches), sum(b.simple_strips for b in batches)


def test_ci_builds_the_compiled_filter():
    if os.environ.get("CI") != "true":
        pytest.skip("only CI promises a C compiler")
    assert compiled_filter_available()


@needs_compiled
@pytest.mark.parametrize("n", [8, 12, 16, 18, 20, 22])
def test_compiled_and_numpy_filters_keep_the_same_maps(n):
    fast, slow = collect(n, "compiled"), collect(n, "numpy")
    assert np.array_equal(fast[0], slow[0])
    assert fast[1:] == slow[1:]


@pytest.mark.parametrize("n", [12, 14, 16, 18])
def test_filter_equals_a_per_map_count(n):
    """Decode every map on its own and ask the half-edge map: the slow obvious twin."""
    rows = all_rows(n)
    batch = Batch(rows)
    simple = kept = 0
    for i in range(len(batch)):
        m = batch.map(i)
        ok = not any(lp.self_crossings for lp in m.loop_system.loops)
        simple += ok
        kept += ok and max(m.degree(c) for c in range(m.num_corners)) <= MAX_DEGREE
    for method in ("numpy", "compiled") if compiled_filter_available() else ("numpy",):
        got = collect(n, method)
        assert (len(got[0]), got[1], got[2]) == (kept, len(rows), simple), method


@needs_compiled
@given(st.data())
def test_compiled_filter_refuses_damaged_records(data):
    from polyloops.generate.plantri._strips import filter_maps

    n = data.draw(st.sampled_from([12, 16, 18]))
    rows = all_rows(n)
    record = bytearray(rows[data.draw(st.integers(0, len(rows) - 1))].tobytes())
    for _ in range(data.draw(st.integers(1, 4))):
        record[data.draw(st.integers(0, len(record) - 1))] = data.draw(st.integers(0, 255))
    try:
        kept, simple = filter_maps(bytes(record), n, MAX_DEGREE)
    except ValueError as err:
        assert "planar code" in str(err)
    else:  # still a quadrangulation: then it agrees with the numpy twin
        row = np.frombuffer(bytes(record), dtype=np.uint8).reshape(1, -1)
        twin = quads._filter_numpy(row)
        assert (kept, simple) == (twin.rows.tobytes(), twin.simple_strips)


@needs_compiled
def test_compiled_filter_refuses_partial_records():
    from polyloops.generate.plantri._strips import filter_maps

    record = all_rows(12)[0].tobytes()
    with pytest.raises(ValueError, match="whole planar-code records"):
        filter_maps(record[:-1], 12, MAX_DEGREE)
    with pytest.raises(ValueError):
        filter_maps(record, 300, MAX_DEGREE)
    assert filter_maps(b"", 12, MAX_DEGREE) == (b"", 0)
    assert len(record) == record_size(12)


def test_method_names(monkeypatch):
    assert resolve_method("auto") == ("compiled" if compiled_filter_available() else "numpy")
    assert resolve_method("numpy") == "numpy"
    with pytest.raises(ValueError, match="unknown filter method"):
        resolve_method("fast")
    monkeypatch.setenv("POLYLOOPS_PURE_PYTHON", "strips")
    assert resolve_method("auto") == "numpy"
    with pytest.raises(quads.PlantriError, match="use the numpy filter"):
        resolve_method("compiled")


def test_cli_says_when_the_compiled_filter_is_missing(monkeypatch, tmp_path, capsys):
    monkeypatch.setenv("POLYLOOPS_PURE_PYTHON", "strips")
    code = main(["catalog", "--max-corners", "12", "--method", "compiled", "-o", str(tmp_path / "c")])
    err = capsys.readouterr().err
    assert code == 2
    assert "--method numpy" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_the_fallback_filter_is_announced(monkeypatch, capsys, tmp_path):
    """Without the compiled filter, plantri's generator says once that the numpy twin runs."""

    monkeypatch.setenv("POLYLOOPS_PURE_PYTHON", "strips")
    assert main(["catalog", "--max-corners", "12", "--generator", "plantri", "-o", str(tmp_path / "c")]) == 0
    err = capsys.readouterr().err
    assert err.count("numpy filter") == 1 and "note:" in err
