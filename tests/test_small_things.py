"""What a user notices: one way to name moves, bad move names as bad input, identify of a
non-polycube, writers that say what they wrote, a limited gallery's title, the torus note
without a compiler, pictures checked before drawing, plurals."""

import json

import pytest

from polyloops.cli import main


def test_remove_takes_the_names_moves_lists(tmp_path, capsys):
    assert main(["moves", "example:l-shape", "--remove", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["removals"]
    assert [r["name"] for r in rows] == ["Y0", "Z0", "X0", "Y1", "X1"]
    removable = next(r for r in rows if r["removable"])
    by_name, by_id = tmp_path / "n.json", tmp_path / "i.json"
    assert main(["remove", "example:l-shape", removable["name"], "-o", str(by_name)]) == 0
    assert main(["remove", "example:l-shape", str(removable["loop"]), "-o", str(by_id)]) == 0
    assert by_name.read_text() == by_id.read_text()
    assert f"wrote {by_name}: a loop structure with" in capsys.readouterr().out
    stuck = next(r for r in rows if not r["removable"])
    assert main(["remove", "example:l-shape", stuck["name"]]) == 1  # checked: not removable
    assert "is not removable" in capsys.readouterr().err
    for bad in ("X9", "Q1", "-3", "99"):
        assert main(["remove", "example:l-shape", bad]) == 2
        err = capsys.readouterr().err
        assert len(err.strip().splitlines()) == 1 and "example:l-shape" in err


@pytest.mark.parametrize("move", ["Z:", "Z: ,", ":1,2"])
def test_an_addition_that_names_too_little_is_bad_input(move, capsys):
    assert main(["add", "example:l-shape", move]) == 2
    assert len(capsys.readouterr().err.strip().splitlines()) == 1


def test_identify_says_when_it_is_no_polycube(capsys):
    assert main(["identify", "example:torus-cycle"]) == 1
    assert "it is no polycube (Definition 4 condition 5" in capsys.readouterr().out
    assert main(["identify", "example:double-plus-x", "--json"]) == 1
    data = json.loads(capsys.readouterr().out)
    assert data["polycube"] is False and data["not_polycube"].startswith("Definition 4 condition 3")
    assert main(["identify", "example:l-shape", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["polycube"] is True


@pytest.mark.parametrize("argv, words", [
    (["dualize", "example:l-shape", "-o", "{out}.json"],
     "a loop structure with 16 corners, 14 faces and 5 loops"),
    (["primalize", "{dual}", "-o", "{out}.json"], "a polycube with 8 corners and 6 faces, genus 0"),
    (["convert", "example:l-shape", "{out}.graph"], "a polycube with 16 corners"),
    (["add", "example:cube", "X0", "-o", "{out}.json"], "a loop structure with 12 corners"),
    (["render", "example:ring", "-o", "{out}.png"], "drew the polycube in 1 view to"),
    (["sheet", "--limit", "1", "-o", "{out}.png"], "drew 1 polycube to"),
])
def test_every_writer_says_what_it_wrote(argv, words, tmp_path, capsys):
    out, dual = str(tmp_path / "out"), str(tmp_path / "cube-loops.json")
    assert main(["dualize", "example:cube", "-o", dual]) == 0
    capsys.readouterr()
    assert main([a.replace("{out}", out).replace("{dual}", dual) for a in argv]) == 0
    text = capsys.readouterr().out
    assert words in text and out in text, text


def test_a_limited_gallery_titles_what_it_shows(tmp_path, capsys):
    site = tmp_path / "site"
    assert main(["gallery", "-o", str(site), "--limit", "1"]) == 0
    assert "wrote 1 class to" in capsys.readouterr().out
    page = (site / "index.html").read_text()
    assert "the first 1 of" in page and "through 36 corners" not in page


def test_the_torus_search_without_its_compiled_part_says_so(monkeypatch, tmp_path, capsys):
    from polyloops.core import compiled
    from polyloops.generate.base import generators

    # As if the install had not built it: the import that failed is remembered (the other
    # parts load as usual, whichever tests ran before in this process).
    monkeypatch.setitem(compiled._modules, "torus", None)
    (note,) = generators()["torus"].notes()
    assert "compiled torus search was not built" in note
    with compiled.pure_python("torus"):  # (not built: its twin runs)
        assert main(["catalog", "--genus", "1", "--max-corners", "8", "-o", str(tmp_path / "g1")]) == 0
    assert "polyloops catalog: note: the compiled torus search" in capsys.readouterr().err


def test_corner_pictures_are_checked_before_drawing(monkeypatch, tmp_path, capsys):
    import polyloops.render.corners as corners

    def never(path):
        raise AssertionError("drew before checking where the picture goes")

    monkeypatch.setattr(corners, "corner_sheet", never)
    assert main(["corners", "--png", str(tmp_path / "missing" / "c.png")]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert main(["corners", "--svg", str(tmp_path / "c.png")]) == 2
    assert "pictures are written as NAME.svg" in capsys.readouterr().err


def test_the_file_help_lists_every_format_read():
    from polyloops.cli.args import FILE_HELP
    from polyloops.io.registry import FORMATS

    assert all(s in FILE_HELP for f in FORMATS if f.reads for s in f.suffixes[:2])


@pytest.mark.parametrize("argv", [["render", "example:ring"], ["view", "example:ring"],
                                  ["sheet", "--limit", "2"], ["corners", "--png"],
                                  ["segmentation", "example:overhang", "--png"]])
def test_pictures_go_to_dev_null_as_the_docs_say(argv, capsys):
    """docs/formats.md: a character device is written into, so -o /dev/null discards."""
    import os

    if not os.path.exists("/dev/null"):
        pytest.skip("no /dev/null here")
    flag = [] if argv[-1] == "--png" else ["-o"]
    assert main([*argv, *flag, "/dev/null"]) == 0
    assert "/dev/null" in capsys.readouterr().out
    assert os.path.exists("/dev/null") and not os.path.isfile("/dev/null")
