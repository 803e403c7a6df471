"""The command line: exit statuses, one-line errors, JSON output."""

import json
import subprocess
import sys

import pytest

from polyloops.cli import main
from polyloops.io.examples import EXAMPLES, load_example
from polyloops.io.formats import dumps, loads
from shipped import small_catalog

ROOT = __import__("pathlib").Path(__file__).resolve().parent.parent

COMMANDS = ["examples", "verify", "primalize", "dualize", "info", "corners", "orient", "moves", "add",
            "remove", "signature", "catalog", "catalog-query", "render", "sheet", "convert", "reach", "path",
            "conjecture", "identify", "catalog-export", "from-voxels", "segmentation", "segment", "view",
            "gallery"]


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


@pytest.mark.parametrize("command", [None, *COMMANDS])
def test_help(capsys, command):
    with pytest.raises(SystemExit) as exit_:
        main([command, "--help"] if command else ["--help"])
    assert exit_.value.code == 0
    assert "usage" in capsys.readouterr().out


def test_usage_errors(capsys):
    for argv in ([], ["nope"], ["verify"], ["verify", "example:cube", "--bogus"]):
        with pytest.raises(SystemExit) as exit_:
            main(argv)
        assert exit_.value.code == 2
        err = capsys.readouterr().err
        assert "Traceback" not in err


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_verify_examples(capsys, name):
    status, out, _ = run(capsys, "verify", f"example:{name}", "--json")
    data = json.loads(out)
    assert set(data) >= {"valid", "kind", "checks", "violations"}
    assert data["valid"] == EXAMPLES[name].valid
    assert status == (0 if EXAMPLES[name].valid else 1)
    for v in data["violations"]:
        assert v["definition"] and v["condition"]


def test_verify_text(capsys):
    status, out, _ = run(capsys, "verify", "example:double-plus-x")
    assert status == 1
    assert "Definition 4 condition 3" in out


def test_info_json(capsys):
    status, out, _ = run(capsys, "info", "example:ring", "--json")
    data = json.loads(out)
    assert status == 0
    assert data["genus"] == 1
    assert set(data["loops"]) == {"X", "Y", "Z"}
    ring = load_example("ring")
    assert data["corners"] == ring.map.num_corners and data["faces"] == ring.map.num_faces
    assert all(data["theorem3"][a]["holds"] for a in "XYZ")


def test_info_text_for_loop_structure(capsys):
    status, out, _ = run(capsys, "info", "example:torus-cycle")
    assert status == 0 and "HAS A CYCLE" in out


def test_dualize_primalize_files(capsys, tmp_path):
    ls_path = tmp_path / "l.json"
    assert run(capsys, "dualize", "example:l-shape", "-o", str(ls_path))[0] == 0
    assert loads(ls_path.read_text()) == load_example("l-shape").dualize()
    q_path = tmp_path / "q.json"
    assert run(capsys, "primalize", str(ls_path), "-o", str(q_path))[0] == 0
    assert loads(q_path.read_text()).dualize() == loads(ls_path.read_text())
    obj = tmp_path / "q.obj"
    assert run(capsys, "primalize", str(ls_path), "-o", str(obj))[0] == 0
    assert obj.read_text().startswith("# polyloops")
    status, out, _ = run(capsys, "dualize", "example:cube")
    assert status == 0 and loads(out) == load_example("cube").dualize()


def test_primalize_invalid_is_exit_1(capsys):
    status, _, err = run(capsys, "primalize", "example:torus-cycle")
    assert status == 1 and "condition 5" in err and err.count("\n") == 1


def test_wrong_kind_is_exit_2(capsys):
    status, _, err = run(capsys, "primalize", "example:cube")
    assert status == 2 and "example:cube" in err
    status, _, err = run(capsys, "dualize", "example:ring")
    assert status == 0
    status, _, err = run(capsys, "dualize", "example:torus-cycle")
    assert status == 2


def _cube():
    return json.loads(dumps(load_example("cube")))


def _ls():
    return json.loads(dumps(load_example("cube").dualize()))


def _set_label(d, label):
    d["edges"][0][2] = label
    return d


BAD_FILES = {
    "bad-json": ("{ nope", "not valid JSON"),
    "float": ({**_cube(), "positions": [[0.5, 0, 0], *_cube()["positions"][1:]]}, "non-integer"),
    "hexagon": ({**_cube(), "faces": [[0, 1, 2, 3, 4, 5], *_cube()["faces"][1:]]}, "quads"),
    "unknown-label": (_set_label(_ls(), "+Q"), "unknown label"),
    "missing-edge": ({**_ls(), "edges": _ls()["edges"][1:]}, "missing"),
    "disagree": (_set_label(_ls(), "+Z" if _ls()["edges"][0][2][1] != "Z" else "+X"), "disagree"),
    "open-surface": ({**_ls(), "faces": _ls()["faces"][:-1]}, "not a closed oriented surface"),
}


@pytest.mark.parametrize("case", sorted(BAD_FILES))
@pytest.mark.parametrize("command", ["verify", "info", "dualize", "primalize"])
def test_bad_files_exit_2_with_one_line(capsys, tmp_path, case, command):
    content, words = BAD_FILES[case]
    path = tmp_path / f"{case}.json"
    path.write_text(content if isinstance(content, str) else json.dumps(content))
    status, _, err = run(capsys, command, str(path))
    if case == "open-surface" and command == "verify":
        assert status == 1  # a well-formed file that fails the surface conditions
        return
    assert status == 2
    assert str(path) in err and words in err
    assert err.count("\n") == 1 and "Traceback" not in err


def test_missing_file_and_unknown_example(capsys, tmp_path):
    status, _, err = run(capsys, "verify", str(tmp_path / "nothing.json"))
    assert status == 2 and "cannot read" in err
    status, _, err = run(capsys, "verify", "example:nothing")
    assert status == 2 and "unknown example" in err


def test_unwritable_output(capsys, tmp_path):
    status, _, err = run(capsys, "dualize", "example:cube", "-o", str(tmp_path / "no" / "such" / "x.json"))
    assert status == 2 and "cannot write" in err
    assert not list(tmp_path.rglob("*.tmp"))


def test_every_command_is_listed():
    from polyloops.cli.main import build_parser

    sub = next(a for a in build_parser()._actions if a.dest == "command")
    assert set(sub.choices) == set(COMMANDS)


def test_module_entry_point():
    res = subprocess.run([sys.executable, "-m", "polyloops", "verify", "example:torus-cycle", "--json"],
                         capture_output=True, text=True, check=False)
    assert res.returncode == 1
    assert json.loads(res.stdout)["valid"] is False


def test_examples_listing(capsys):
    status, out, _ = run(capsys, "examples", "--json")
    assert status == 0
    assert {row["name"] for row in json.loads(out)["examples"]} == set(EXAMPLES)


@pytest.mark.parametrize("which", ["genus0", "check"])
def test_conjecture_subcommand_help(capsys, which):
    with pytest.raises(SystemExit) as exit_:
        main(["conjecture", which, "--help"])
    assert exit_.value.code == 0
    assert "--catalog" in capsys.readouterr().out


def _leaf_commands():
    import argparse

    from polyloops.cli.main import build_parser

    def walk(parser, words):
        subs = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
        if not subs:
            yield words, parser
        for action in subs:
            for name, sub in action.choices.items():
                yield from walk(sub, [*words, name])

    return list(walk(build_parser(), []))


def test_every_leaf_command_has_json():
    missing = [" ".join(words) for words, parser in _leaf_commands()
               if "--json" not in {o for a in parser._actions for o in a.option_strings}]
    assert len(_leaf_commands()) >= 26 and not missing


def test_writing_commands_summarise_what_they_wrote_in_json(tmp_path, capsys):
    """Each command that writes a file prints one JSON object with --json: the file and its
    counts; without -o the written document is inside it."""
    cube = tmp_path / "cube.json"
    cube.write_text(dumps(load_example("cube").dualize()))
    voxels = tmp_path / "v.txt"
    voxels.write_text("0 0 0\n0 0 0\n1 0 0\n")  # a cube listed twice is one cube
    cases = [
        (["primalize", str(cube), "-o", str(tmp_path / "p.json")], {"kind": "polycube", "corners": 8}),
        (["primalize", str(cube)], {"kind": "polycube", "corners": 8}),
        (["dualize", "example:l-shape", "-o", str(tmp_path / "d.json")],
         {"kind": "loop-structure", "corners": 16, "loops": len(load_example("l-shape").dualize().loops)}),
        (["convert", "example:cube", str(tmp_path / "c.obj")], {"kind": "polycube", "faces": 6}),
        (["from-voxels", str(voxels), "-o", str(tmp_path / "f.json")], {"cubes": 2, "corners": 12}),
        (["add", str(cube), "X0", "-o", str(tmp_path / "a.json")],
         {"move": {"add": "X", "corners": [0, 1, 3, 2]}, "loops": 4}),
        (["remove", str(tmp_path / "a.json"), "3", "-o", str(tmp_path / "r.json")],
         {"move": {"remove": 3, "axis": "X"}, "loops": 3}),
        (["render", "example:cube", "-o", str(tmp_path / "r.png")], {"drew": "polycube", "views": 1}),
        (["view", "example:cube", "-o", str(tmp_path / "v.html")], {"page": "viewer"}),
        (["sheet", "example:cube", "example:l-shape", "-o", str(tmp_path / "s.png")], {"pictures": 2}),
        (["gallery", "-o", str(tmp_path / "site"), "--limit", "2"], {"classes": 2}),
        (["catalog", "export", str(small_catalog(20)), "--csv", "-o", str(tmp_path / "e.csv")],
         {"rows": sum(1 for _ in (small_catalog(20) / "catalog.jsonl").open())}),
    ]
    for argv, expected in cases:
        status, out, _ = run(capsys, *argv, "--json")
        assert status == 0, argv
        data = json.loads(out)
        assert isinstance(data, dict) and {k: data[k] for k in expected} == expected, argv
        if "-o" in argv:
            assert data["output"] == argv[argv.index("-o") + 1] and "document" not in data
    status, out, _ = run(capsys, "primalize", str(cube), "--json")
    assert loads(json.dumps(json.loads(out)["document"])).map.num_corners == 8


def test_listing_commands_print_one_json_object(capsys):
    for argv, key in ((["examples"], "examples"), (["corners"], "configurations"),
                      (["corners", "--symmetry", "rotation"], "classes"),
                      (["catalog", "query", str(ROOT / "catalogs" / "genus0"), "corners = 16"], "rows")):
        status, out, _ = run(capsys, *argv, "--json")
        data = json.loads(out)
        assert status == 0 and isinstance(data, dict) and data[key], argv


def test_counts_in_words_and_aligned_reports(capsys):
    """One arc, one violation: singular; every condition's columns line up in verify."""
    status, out, _ = run(capsys, "info", "example:cube")
    assert status == 0 and "1 arc," in out and "1 arcs" not in out
    status, out, _ = run(capsys, "verify", "example:cube")
    rows = [line for line in out.splitlines()[1:] if line.startswith("  ") and "violation" not in line]
    starts = {line.index(" holds") for line in rows}
    assert len(rows) >= 10 and len(starts) == 1, out  # 'file convention' rows too
    import polyloops as pl

    report = pl.verify(load_example("double-plus-x"))
    text = str(report)
    assert text.startswith("loop-structure: INVALID (") and f"{len(report.violations)} violations" in text


def test_the_census_reads_like_a_census():
    """pl.read_catalog() indexes by name, signature or position, and iterates in catalog order."""
    import polyloops as pl

    census = pl.read_catalog()
    names = [entry.name for entry in census]
    assert names == [e.name for e in census.entries] and len(census) == len(names)
    assert census["P26.20"].name == "P26.20" and census[census["P26.20"].signature] is census["P26.20"]
    assert census[0].name == names[0] and "P16.2" in census and "P999.1" not in census
    with pytest.raises(KeyError, match=r"P999\.1"):
        census["P999.1"]


def test_examples_list_the_labelled_meshes_too(capsys):
    status, out, _ = run(capsys, "examples")
    assert status == 0 and "sokolov-ramp" in out and "overhang" in out
    status, out, _ = run(capsys, "examples", "--json")
    assert {m["name"] for m in json.loads(out)["labelled_meshes"]} == {"sokolov-ramp", "overhang"}
