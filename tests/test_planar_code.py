"""plantri's planar code, in and out: agreement with plantri and the batch decoder, round
trips in both widths, and clear errors."""

import subprocess

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.core.canonical import signature
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.generate.plantri.quadrangulations import Batch, find_plantri, plantri_batches
from polyloops.io.examples import load_example
from polyloops.io.planar_code import HEADER_BE, PlanarCodeError, planar_code, read_planar_code
from polyloops.shapes.builders import box
from strategies import polycubes


def face_cycles(m: HalfEdgeMap) -> list[tuple[int, ...]]:
    """The faces as cycles, independent of where each face's list starts and of face order."""
    return sorted(min(f[i:] + f[:i] for i in range(len(f))) for f in (tuple(face) for face in m.faces))


@pytest.mark.parametrize("n", [12, 14, 16])
def test_reading_plantri_agrees_with_the_batch_decoder(n):
    plantri = find_plantri()
    data = subprocess.run([plantri, "-qc2m3", str(n)], capture_output=True, check=True).stdout
    maps = read_planar_code(data)
    batched = [Batch(rows).map(i) for rows in plantri_batches(n, plantri) for i in range(len(rows))]
    assert len(maps) == len(batched) > 0
    assert [m.faces for m in maps] == [m.faces for m in batched]


@settings(max_examples=25, deadline=None)
@given(polycubes(kinds=("blob",), max_size=8))
def test_round_trip_in_both_widths(q):
    for two_byte in (False, True):
        back = read_planar_code(planar_code([q.map], two_byte=two_byte))
        assert len(back) == 1
        assert face_cycles(back[0]) == face_cycles(q.map)


def test_large_maps_use_two_bytes_and_come_back():
    m = box(9, 9, 9).map
    assert m.num_corners > 255
    data = planar_code([load_example("cube").map, m])
    assert data.startswith(b">>planar_code le<<")
    back = read_planar_code(data)
    assert face_cycles(back[1]) == face_cycles(m)
    # The same numbers big-endian under the other header read the same.
    body = bytearray()
    small, large = load_example("cube").map, m
    for mm in (small, large):
        body += b"\x00" + mm.num_corners.to_bytes(2, "big")
        for c in range(mm.num_corners):
            for d in reversed(mm.outgoing(c)):
                body += (mm.target(d) + 1).to_bytes(2, "big")
            body += b"\x00\x00"
    again = read_planar_code(HEADER_BE + bytes(body))
    assert [face_cycles(x) for x in again] == [face_cycles(small), face_cycles(large)]


@pytest.mark.parametrize("data, words", [
    (b">>planar_code<<\x04\x02\x03", "ends inside"),
    (b"\x03\x02\x09\x00\x01\x03\x00\x01\x02\x00", "vertex 9 does not exist"),
    (b"\x03\x02\x03\x00\x03\x00\x01\x02\x00", "not the other way round"),
    (b"\x03\x01\x02\x00\x01\x03\x00\x01\x02\x00", "lists itself"),
    (b"\x02\x02\x00\x01\x00", "needs 3 or more"),
    (bytes([6, 2, 3, 0, 3, 1, 0, 1, 2, 0, 5, 6, 0, 6, 4, 0, 4, 5, 0]), "2 components"),
])
def test_bad_bytes_are_named(data, words):
    with pytest.raises(PlanarCodeError, match=words):
        read_planar_code(data)


def test_writer_refuses_what_planar_code_cannot_hold():
    with pytest.raises(ValueError, match="genus 1"):
        planar_code([load_example("ring").map])


@pytest.mark.parametrize("name", ["cube", "l-shape", "non-incremental"])
def test_cli_round_trip_keeps_the_polycube(name, tmp_path, capsys):
    out = tmp_path / f"{name}.pc"
    assert main(["convert", f"example:{name}", str(out)]) == 0
    assert main(["convert", str(out), str(tmp_path / "back.json")]) == 0
    assert "no axis labels" in capsys.readouterr().err
    back = main(["signature", str(tmp_path / "back.json"), "--symmetry", "full"])
    first = capsys.readouterr().out
    assert back == 0
    main(["signature", f"example:{name}", "--symmetry", "full"])
    assert capsys.readouterr().out == first
    assert signature(load_example(name), "full") in first


def test_cli_errors_name_the_file(tmp_path, capsys):
    many = tmp_path / "many.pc"
    many.write_bytes(planar_code([load_example("cube").map] * 2))
    bad = tmp_path / "bad.pc"
    bad.write_bytes(b">>planar_code<<\x08\x02")
    for path, words in ((many, "holds 2 maps"), (bad, "ends inside")):
        assert main(["info", str(path)]) == 2
        err = capsys.readouterr().err.strip()
        assert str(path) in err and words in err and "\n" not in err
    assert main(["convert", "example:ring", str(tmp_path / "ring.pc")]) == 2
    assert "genus-0" in capsys.readouterr().err


@settings(max_examples=200, deadline=None)
@given(st.binary(max_size=64), st.booleans())
def test_any_bytes_read_or_fail_cleanly(data, with_header):
    """Random bytes, and damaged real maps, give maps or a PlanarCodeError, nothing else."""
    cube = planar_code([load_example("cube").map])
    for blob in ((b">>planar_code<<" if with_header else b"") + data, cube[: len(data) % len(cube)] + data):
        try:
            maps = read_planar_code(blob)
        except PlanarCodeError:
            continue
        assert all(isinstance(m, HalfEdgeMap) for m in maps)
