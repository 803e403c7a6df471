"""Inside-out input: a polycube whose faces are clockwise seen from outside is reported by
``verify``, refused by every other command with the same hint, and repaired by ``convert``."""

import json

import pytest
from hypothesis import given

from polyloops.cli import main
from polyloops.core.canonical import from_signature, signature
from polyloops.io.examples import load_example
from polyloops.io.formats import dumps, loads
from polyloops.verify import check_polycube
from strategies import polycubes


@given(polycubes())
def test_volume_sign_tells_inside_out(q):
    assert q.signed_volume() > 0
    assert q.inverse().signed_volume() == -q.signed_volume()
    assert check_polycube(q).valid
    report = check_polycube(q.inverse())
    assert [(v.definition, v.condition) for v in report.violations] == [("file convention", "outward")]


@pytest.fixture
def inside_out(tmp_path):
    path = tmp_path / "l.json"
    path.write_text(dumps(load_example("l-shape").inverse()))
    return path


def test_verify_names_the_convention(capsys, inside_out):
    assert main(["verify", str(inside_out), "--json"]) == 1
    data = json.loads(capsys.readouterr().out)
    (v,) = data["violations"]
    assert v["condition"] == "outward" and "inside out" in v["message"]


@pytest.mark.parametrize("command", ["dualize", "info", "signature", "orient", "moves", "render"])
def test_other_commands_refuse_with_the_repair(capsys, inside_out, tmp_path, command):
    extra = ["-o", str(tmp_path / "x.png")] if command == "render" else []
    assert main([command, str(inside_out), *extra]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "inside out" in err and "--fix-orientation" in err


def test_convert_repairs(inside_out, tmp_path):
    out = tmp_path / "fixed.json"
    assert main(["convert", str(inside_out), str(out)]) == 1
    assert main(["convert", str(inside_out), str(out), "--fix-orientation"]) == 0
    fixed = loads(out.read_text())
    assert fixed.signed_volume() > 0 and check_polycube(fixed).valid
    assert signature(fixed) == signature(load_example("l-shape"))
    assert main(["convert", str(out), str(tmp_path / "fixed.obj")]) == 0


def test_primalize_writes_outward(tmp_path):
    """Catalog signatures often name the mirror of a polycube's own structure; its polycube is
    still written counter-clockwise."""
    catalog = (__import__("pathlib").Path(__file__).parent.parent / "catalogs" / "genus0" / "catalog.jsonl")
    for line in catalog.read_text().splitlines()[:6]:
        sig = json.loads(line)["signature"]
        out = tmp_path / "p.json"
        assert main(["primalize", f"sig:{sig}", "-o", str(out)]) == 0
        q = loads(out.read_text())
        assert check_polycube(q).valid
        assert signature(q, "full") == signature(from_signature(sig), "full")
