"""Bad input gets a one-line error with the right exit status, and every command gives the same
verdict on the same file: the cases of the trust issue, each failing before its fix."""

import io
import json
import time

import numpy as np
import pytest

import polyloops as pl
from polyloops.cli import main
from polyloops.io.examples import load_example
from polyloops.io.planar_code import planar_code
from polyloops.io.registry import FORMATS, FormatChoiceError


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def one_line(err: str) -> bool:
    return err.count("\n") == 1 and "Traceback" not in err and "internal error" not in err


@pytest.mark.parametrize("corners", ["100000000", "1000000000000"])
def test_a_huge_dualcube_header_is_refused_at_once(tmp_path, capsys, corners):
    path = tmp_path / "big.graph"
    path.write_text(f"1 1 {corners}\n0 1 2 3\n0 1 X\n")
    began = time.process_time()
    status, _, err = run(capsys, "verify", str(path))
    assert status == 2 and one_line(err) and "announces" in err
    assert time.process_time() - began < 5  # nothing sized by the header alone


def test_every_command_gives_the_same_verdict_on_a_dualcube_file(tmp_path, capsys):
    path = tmp_path / "c.graph"
    assert main(["convert", "example:cube", str(path)]) == 0
    lines = path.read_text().splitlines()
    i = next(k for k, line in enumerate(lines) if not line.startswith("/"))
    f, e, v = lines[i].split()
    lines[i] = f"{f} {e} {int(v) + 3}"  # more corners than the faces use
    path.write_text("\n".join(lines) + "\n")
    capsys.readouterr()
    verdicts = set()
    for argv in (["verify", str(path)], ["info", str(path)], ["convert", str(path), str(tmp_path / "x.json")],
                 ["signature", str(path)]):
        status, _, err = run(capsys, *argv)
        verdicts.add((status, err.split(": ", 2)[-1]))
    assert len(verdicts) == 1 and next(iter(verdicts))[0] == 2


def test_planar_code_of_a_triangulation_is_invalid_not_a_bug(tmp_path, capsys):
    # the octahedron: six vertices, each of degree four (plantri's default output is triangulations)
    octahedron = pl.HalfEdgeMap.from_faces([[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1],
                                            [5, 2, 1], [5, 3, 2], [5, 4, 3], [5, 1, 4]])
    path = tmp_path / "tri.pc"
    path.write_bytes(planar_code([octahedron]))
    status, _, err = run(capsys, "verify", str(path))
    assert status == 1 and one_line(err) and "not a quadrangulation" in err


def test_picture_extensions_are_checked_before_the_work(capsys, tmp_path):
    for argv in (["segmentation", "example:sokolov-ramp", "--png", str(tmp_path / "out.jpg")],
                 ["render", "example:cube", "-o", str(tmp_path / "out.jpg")],
                 ["view", "example:cube", "-o", str(tmp_path / "out.png")]):
        status, _, err = run(capsys, *argv)
        assert status == 2 and one_line(err), argv
    assert list(tmp_path.iterdir()) == []


def test_sample_and_count_are_bounded(capsys):
    began = time.monotonic()
    status, out, _ = run(capsys, "moves", "example:cube", "--sample", "1000000")
    assert status == 0 and time.monotonic() - began < 20 and out.count("add ") > 0


def test_the_time_limit_is_shared_across_axes(capsys):
    """On a structure whose X-additions take long to list, Y and Z still get their share."""
    from polyloops.reach.listing import count_additions_within

    ls = pl.polycube_from_voxels([(0, y, z) for y in range(6) for z in range(6)]).dualize()
    counted = count_additions_within(ls, seconds=0.6)  # X alone would take minutes
    assert not counted.complete["X"] and counted.complete["Y"] and counted.complete["Z"], counted
    assert counted.counts["Y"] == count_additions_within(ls, [pl.Axis.Y]).counts["Y"] > 0


def test_obj_reading_is_scale_free_and_bom_safe(tmp_path, capsys):
    text = pl.to_obj(load_example("l-shape"))

    def scaled(factor: float, offset: float = 0.0) -> str:
        out = []
        for line in text.splitlines():
            if line.startswith("v "):
                out.append("v " + " ".join(repr(float(w) * factor + offset) for w in line.split()[1:]))
            else:
                out.append(line)
        return "\n".join(out) + "\n"

    for name, body in (("tiny", scaled(1e-10)), ("huge", scaled(1e103)), ("moved", scaled(3.5, -1e6)),
                       ("bom", "\ufeff" + text)):
        path = tmp_path / f"{name}.obj"
        path.write_text(body, encoding="utf-8")
        status, out, err = run(capsys, "identify", str(path))
        assert status == 0 and out.strip().endswith("P16.2"), (name, err)


def test_integer_positions_beyond_floats(tmp_path, capsys):
    data = json.loads(pl.dumps(load_example("l-shape")))
    data["positions"] = [[c * 10**103 for c in p] for p in data["positions"]]
    path = tmp_path / "huge.json"
    path.write_text(json.dumps(data))
    for command in ("verify", "info", "signature"):
        status, _, err = run(capsys, command, str(path))
        assert status == 0, err


def test_a_npy_declaring_a_huge_shape(tmp_path, capsys):
    buf = io.BytesIO()
    np.save(buf, np.zeros((2, 2, 2), dtype=bool))
    data = buf.getvalue().replace(b"(2, 2, 2), }", b"(100000, 100000, 100000), }")
    path = tmp_path / "huge.npy"
    path.write_bytes(data)
    status, _, err = run(capsys, "from-voxels", str(path), "-o", str(tmp_path / "q.json"))
    assert status == 2 and one_line(err) and "declares" in err
    assert err.startswith("polyloops from-voxels: ")


def test_an_addition_past_a_corner_that_does_not_exist(capsys):
    status, _, err = run(capsys, "add", "example:cube", "X:0,99,3")
    assert status == 2 and "no corner 99" in err and one_line(err)


# -- formats that do what their names say ---------------------------------------------------------

def test_unsupported_output_extensions_are_refused(tmp_path, capsys):
    for name in ("ring.xyz", "ring"):
        status, _, err = run(capsys, "convert", "example:ring", str(tmp_path / name))
        assert status == 2 and one_line(err) and ".json" in err and ".ply" in err
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(FormatChoiceError):
        pl.write(load_example("ring"), tmp_path / "ring.xyz")


MESH_FORMATS = [f for f in FORMATS if f.mesh]


@pytest.mark.parametrize("fmt", MESH_FORMATS, ids=[f.name for f in MESH_FORMATS])
def test_polycube_meshes_round_trip(tmp_path, fmt):
    """Written by polyloops, read back by meshio (an independent reader): the same corners and
    faces (quads, or two triangles a quad for STL); and polyloops reads back those it reads."""
    import meshio

    for name in ("ring", "l-shape"):
        q = load_example(name)
        path = tmp_path / f"{name}{fmt.suffixes[0]}"
        pl.write(q, path)
        if fmt.name != "off":  # meshio reads only triangles from OFF
            mesh = meshio.read(path)
            points = {tuple(round(float(c)) for c in p) for p in mesh.points}
            assert points == {tuple(p) for p in q.positions}
            cells = sum(len(block.data) for block in mesh.cells)
            assert cells == (2 if fmt.name == "stl" else 1) * len(q.faces)
        if fmt.reads:
            assert pl.identify(pl.read(path)).name == pl.identify(q).name
            assert pl.is_order_equivalent(pl.read(path), q) is not None


def test_a_loop_structure_is_not_written_as_a_mesh(tmp_path, capsys):
    status, _, err = run(capsys, "convert", "example:l-shape", str(tmp_path / "l.json"))
    status, _, err = run(capsys, "dualize", "example:l-shape", "-o", str(tmp_path / "ls.json"))
    status, _, err = run(capsys, "convert", str(tmp_path / "ls.json"), str(tmp_path / "ls.ply"))
    assert status == 2 and "only a polycube" in err and not (tmp_path / "ls.ply").exists()


def test_read_by_content_without_extension(tmp_path):
    for fmt in ("json", "apg", "obj", "planar", "ply"):
        path = tmp_path / f"x.{fmt}"
        pl.write(load_example("l-shape"), path, fmt)
        bare = tmp_path / f"bare-{fmt}"
        bare.write_bytes(path.read_bytes())
        assert pl.identify(pl.read(bare)).name == "P16.2", fmt


def test_labelled_meshes_with_a_bom_and_from_stdin(tmp_path):
    import subprocess
    import sys

    from polyloops.io.labelled_mesh import labels_text, triangle_obj_text
    from polyloops.surface.construct import labelled_mesh_from_polycube

    mesh = labelled_mesh_from_polycube(load_example("l-shape"))
    obj, labels = tmp_path / "m.obj", tmp_path / "m.labels"
    obj.write_text("\ufeff" + triangle_obj_text(mesh), encoding="utf-8")
    labels.write_text(labels_text(mesh))
    command = [sys.executable, "-m", "polyloops", "segmentation"]
    plain = subprocess.run([*command, str(obj), str(labels), "--json"], capture_output=True, text=True)
    piped = subprocess.run([*command, "-", str(labels), "--json"],
                           input=obj.read_text(encoding="utf-8"), capture_output=True, text=True)
    assert plain.returncode == piped.returncode == 0, plain.stderr + piped.stderr
    assert json.loads(plain.stdout)["valid"] and json.loads(plain.stdout) == json.loads(piped.stdout)
