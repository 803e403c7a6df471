"""Peers' formats: DualCube's Abstract Polycube Graph and OBJ quad meshes, in and out."""

import random
from pathlib import Path

import pytest
from hypothesis import given, settings

from polyloops.cli import main
from polyloops.core.canonical import signature
from polyloops.core.polycube import Polycube
from polyloops.io.examples import load_example
from polyloops.io.exchange import ExchangeError, apg_text, parse_apg, parse_obj
from polyloops.io.formats import to_obj
from strategies import polycubes, random_polycube

FIXTURES = Path(__file__).parent / "fixtures"
EXAMPLES = ["cube", "l-shape", "ring", "non-incremental", "bridged-ring"]


def translated(q: Polycube) -> list[tuple[int, int, int]]:
    """Positions with corner 0 at the origin (the reader of lengths puts it there)."""
    x0, y0, z0 = q.positions[0]
    return [(x - x0, y - y0, z - z0) for x, y, z in q.positions]


def order_type(q: Polycube) -> list[list[int]]:
    """Per axis, the rank of each corner's coordinate among the distinct values."""
    out = []
    for k in range(3):
        values = sorted({p[k] for p in q.positions})
        out.append([values.index(p[k]) for p in q.positions])
    return out


def check_apg_round_trip(q: Polycube) -> None:
    back = parse_apg(apg_text(q)).build()
    assert isinstance(back, Polycube)
    assert [list(f) for f in back.faces] == [list(f) for f in q.faces]
    assert list(back.positions) == translated(q)
    assert signature(back) == signature(q)


def check_obj_round_trip(q: Polycube) -> None:
    back = parse_obj(to_obj(q)).build()
    assert [list(f) for f in back.faces] == [list(f) for f in q.faces]
    assert order_type(back) == order_type(q)
    assert signature(back) == signature(q)


@pytest.mark.parametrize("name", EXAMPLES)
def test_examples_round_trip(name):
    q = load_example(name)
    check_apg_round_trip(q)
    check_obj_round_trip(q)


@settings(max_examples=25)
@given(polycubes())
def test_random_polycubes_round_trip(q):
    check_apg_round_trip(q)
    check_obj_round_trip(q)


def test_a_polycube_of_more_than_100_corners_round_trips():
    q = random_polycube(4, "blob", 48)
    assert q.map.num_corners > 100
    check_apg_round_trip(q)
    check_obj_round_trip(q)


def test_loop_structures_round_trip_without_lengths():
    ls = load_example("ring").dualize()
    doc = parse_apg(apg_text(ls))
    assert doc.kind == "loop-structure" and "not every edge has a length" in doc.notes[0]
    assert doc.build() == ls


def test_hand_written_cube():
    q = parse_apg((FIXTURES / "cube.graph").read_text()).build()
    assert signature(q, "full") == signature(load_example("cube"), "full")
    assert q.signed_volume() > 0  # clockwise there is counter-clockwise here


def test_obj_keeps_the_order_type_of_real_coordinates():
    q = load_example("l-shape")
    rng = random.Random(3)
    scale = [rng.uniform(0.1, 3) for _ in range(3)]
    shift = [rng.uniform(-10, 10) for _ in range(3)]
    lines = ["# moved and stretched"]
    lines += [f"v {x * scale[0] + shift[0]} {y * scale[1] + shift[1]} {z * scale[2] + shift[2]}"
              for x, y, z in q.positions]
    lines += ["f " + " ".join(f"{c + 1}/{c + 1}" for c in face) for face in q.faces]
    back = parse_obj("\n".join(lines)).build()
    assert order_type(back) == order_type(q) and signature(back) == signature(q)


def test_conflicting_lengths_give_a_loop_structure_and_say_so(tmp_path, capsys):
    text = (FIXTURES / "cube.graph").read_text().replace("0 1 X 1", "0 1 X 2")
    (tmp_path / "c.graph").write_text(text)
    assert main(["verify", str(tmp_path / "c.graph")]) == 0
    captured = capsys.readouterr()
    assert "lengths conflict" in captured.err and "loop-structure: valid" in captured.out


def test_convert_between_all_formats(tmp_path):
    q = load_example("non-incremental")
    steps = ["a.graph", "b.obj", "c.apg", "d.json"]
    source = "example:non-incremental"
    for name in steps:
        assert main(["convert", source, str(tmp_path / name)]) == 0
        source = str(tmp_path / name)
    from polyloops.io.formats import loads

    assert signature(loads((tmp_path / "d.json").read_text())) == signature(q)
    assert main(["convert", str(tmp_path / "a.graph"), str(tmp_path / "e.txt"), "--to", "obj"]) == 0
    assert main(["convert", str(tmp_path / "e.txt"), str(tmp_path / "f.json"), "--from", "obj"]) == 0
    with pytest.raises(SystemExit) as stop:  # argparse's own check
        main(["convert", "example:cube", str(tmp_path / "g.obj"), "--to", "nope"])
    assert stop.value.code == 2
    # A loop structure has no coordinates for OBJ: a one-line refusal.
    assert main(["convert", "sig:" + signature(q), str(tmp_path / "h.obj")]) == 2


APG_ERRORS = [
    ("", "header"),
    ("6 12\n", "header"),
    ("6 12 8\n0 1 3 2\n", "lines follow"),
    ("1 1 4\n0 1 2\n0 1 X\n", "4 corners"),
    ("1 1 4\n0 1 2 9\n0 1 X\n", "corner ids"),
    ("1 1 4\n0 1 2 3\n0 1 W\n", "unknown axis"),
    ("1 2 4\n0 1 2 3\n0 1 X\n1 0 Y\n", "listed twice"),
    ("1 1 4\n0 1 2 3\n0 1 X long\n", "not a number"),
    ("1 1 4\n0 1 2 x\n0 1 X\n", "integers"),
]


OBJ_ERRORS = [
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 4: a face must be a quad"),
    ("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 1 2 3 4\n",
     "line 5: the edge from vertex 3 to 4 is not parallel"),
    ("v 0 0 0\nf 1 2 3 4\n", "line 2: vertex 2 does not exist"),
    ("v 0 0\n", "line 1: a vertex"),
    ("v 0 0 x\n", "numbers"),
    ("# nothing\n", "no faces"),
]


@pytest.mark.parametrize(("suffix", "text", "words"), [(".graph", t, w) for t, w in APG_ERRORS]
                         + [(".obj", t, w) for t, w in OBJ_ERRORS])
def test_bad_files_name_the_problem(suffix, text, words, tmp_path, capsys):
    parse = parse_apg if suffix == ".graph" else parse_obj
    with pytest.raises(ExchangeError, match=words):
        parse(text)
    path = tmp_path / f"bad{suffix}"
    path.write_text(text)
    assert main(["verify", str(path)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and str(path) in err and "Traceback" not in err
    if suffix == ".obj":  # OBJ problems name their line
        assert "line" in err or "no faces" in err


# -- voxels ------------------------------------------------------------------------------------

def test_from_voxels_text_and_npy(tmp_path, capsys):
    import numpy as np

    from polyloops.io.formats import loads
    from polyloops.shapes.voxels import polycube_from_voxels

    cells = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (2, 1, 0), (0, 2, 0), (1, 2, 0), (2, 2, 0)]
    lines = "".join(f"{x} {y} {z}\n" for x, y, z in cells)
    (tmp_path / "ring.txt").write_text("# a ring of eight cubes\n" + lines)
    grid = np.zeros((3, 3, 1), dtype=bool)
    for c in cells:
        grid[c] = True
    np.save(tmp_path / "ring.npy", grid)
    want = polycube_from_voxels(cells)
    for name in ("ring.txt", "ring.npy"):
        assert main(["from-voxels", str(tmp_path / name), "-o", str(tmp_path / f"{name}.json")]) == 0
        got = loads((tmp_path / f"{name}.json").read_text())
        assert got == want and got.genus == 1
    capsys.readouterr()
    assert main(["from-voxels", str(tmp_path / "ring.txt")]) == 0
    assert loads(capsys.readouterr().out) == want


@pytest.mark.parametrize(("content", "code", "words"), [
    ("0 0 0\n0 0\n", 2, "line 2"),
    ("0 0 x\n", 2, "line 1"),
    ("# nothing\n", 2, "no cubes"),
    ("0 0 0\n1 1 0\n", 1, "2 pieces"),  # touching only along an edge: two surfaces
    # a hollow 3x3x3 block: a cavity, not two pieces
    ("".join(f"{x} {y} {z}\n" for x in range(3) for y in range(3) for z in range(3)
             if (x, y, z) != (1, 1, 1)), 1, "a cavity of 1 empty cell, (1, 1, 1)"),
    # a chain of five cubes whose two ends touch at a corner only: the split cannot mend it
    ("0 0 0\n0 1 0\n1 1 0\n1 1 1\n1 0 1\n", 1, "meets itself at the position (1, 1, 1)"),
])
def test_from_voxels_bad_input(content, code, words, tmp_path, capsys):
    path = tmp_path / "cubes.txt"
    path.write_text(content)
    assert main(["from-voxels", str(path)]) == code
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and words in err and str(path) in err


def test_from_voxels_refuses_other_npy(tmp_path, capsys):
    import numpy as np

    np.save(tmp_path / "flat.npy", np.ones((2, 2), dtype=bool))
    (tmp_path / "junk.npy").write_bytes(b"not numpy")
    for name in ("flat.npy", "junk.npy"):
        assert main(["from-voxels", str(tmp_path / name)]) == 2
        err = capsys.readouterr().err
        assert len(err.strip().splitlines()) == 1 and name in err
