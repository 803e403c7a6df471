"""Pictures: produced, not blank, deterministic; every bundled example renders."""

import hashlib

import matplotlib.image as mpimg
import numpy as np
import pytest

from polyloops.cli import main
from polyloops.core.examples import EXAMPLES, load_example
from polyloops.render.colors import AXIS_COLOR, LIGHT_COLOR
from polyloops.render.polycube import as_polycube, choose_views, face_normal


def ink(path):
    img = mpimg.imread(path)[..., :3]
    return np.any(np.abs(img - 1.0) > 0.05, axis=-1).mean(), img


def has_colour(img, hex_colour, tol=0.06):
    rgb = np.array([int(hex_colour[i:i + 2], 16) / 255 for i in (1, 3, 5)])
    return bool((np.abs(img - rgb).max(axis=-1) < tol).any())


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_every_example_renders(tmp_path, capsys, name):
    out = tmp_path / f"{name}.png"
    assert main(["render", f"example:{name}", "-o", str(out)]) == 0
    fraction, _ = ink(out)
    assert 0.02 < fraction < 0.9


def test_loops_in_the_paper_colours_on_both_sides(tmp_path):
    out = tmp_path / "ring.png"
    assert main(["render", "example:ring", "-o", str(out)]) == 0
    _, img = ink(out)
    for colours in (AXIS_COLOR, LIGHT_COLOR):
        for c in colours.values():
            assert has_colour(img, c), c
    plain = tmp_path / "plain.png"
    assert main(["render", "example:ring", "--no-loops", "-o", str(plain)]) == 0
    _, img2 = ink(plain)
    assert not any(has_colour(img2, c) for c in AXIS_COLOR.values())


def test_deterministic(tmp_path):
    digests = set()
    for i in range(2):
        for ext in ("png", "svg"):
            out = tmp_path / f"a{i}.{ext}"
            assert main(["render", "example:l-shape", "--views", "4", "-o", str(out)]) == 0
            digests.add((ext, hashlib.sha256(out.read_bytes()).hexdigest()))
    assert len(digests) == 2


def test_views_cover_every_face():
    for name in ("l-shape", "ring", "non-incremental", "self-intersecting"):
        q, _ = as_polycube(load_example(name))
        views = choose_views(q, 4)
        for f in range(q.map.num_faces):
            n = face_normal(q, f)
            assert any(v.facing(n.vector) > 0 for v in views)


def test_outward_orientation():
    q = load_example("ring")
    assert q.signed_volume() > 0 and q.inverse().outward() == q


def test_level_graphs(tmp_path):
    out = tmp_path / "lg.png"
    assert main(["render", "example:box-2x1x1", "--level-graphs", "-o", str(out)]) == 0
    assert 0.005 < ink(out)[0] < 0.5


def test_sheet_from_files_and_catalog(tmp_path, capsys):
    out = tmp_path / "sheet.png"
    assert main(["sheet", "example:cube", "example:ring", "-o", str(out)]) == 0
    assert ink(out)[0] > 0.02
    from pathlib import Path

    catalog = Path(__file__).resolve().parent.parent / "catalogs" / "genus0"
    assert main(["sheet", str(catalog), "--limit", "4", "-o", str(out)]) == 0


def test_sheet_captions_are_catalog_names(tmp_path, monkeypatch):
    """Captions name classes as the census does (never a cut-off signature)."""
    import json
    from pathlib import Path

    import polyloops.render.sheet as sheet
    from polyloops.core.canonical import canonical_form

    seen = []
    monkeypatch.setattr(sheet, "render_sheet", lambda items, out, columns: seen.extend(items))
    catalog = Path(__file__).resolve().parent.parent / "catalogs" / "genus0"
    records = [json.loads(line) for line in (catalog / "catalog.jsonl").read_text().splitlines()[:5]]
    l_shape = load_example("l-shape")
    sig = canonical_form(l_shape, "labelled").signature
    assert main(["sheet", str(catalog), "--limit", "5", "-o", str(tmp_path / "s.png")]) == 0
    assert [c for c, _ in seen] == [r["name"] for r in records]
    seen.clear()
    sources = ["example:l-shape", f"sig:{sig}", "example:ring"]
    assert main(["sheet", *sources, "-o", str(tmp_path / "s.png")]) == 0
    full = canonical_form(l_shape, "full").signature
    name = next(r["name"] for r in map(json.loads, (catalog / "catalog.jsonl").read_text().splitlines())
                if r["signature"] == full)
    ring = load_example("ring").map.num_corners  # genus 1: not in the catalog
    assert [c for c, _ in seen] == [name, name, f"example:ring ({ring} corners)"]


def test_bad_picture_arguments(capsys, tmp_path):
    assert main(["render", "example:cube", "-o", str(tmp_path / "x.jpg")]) == 2
    assert main(["sheet", str(tmp_path), "-o", str(tmp_path / "x.png")]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_jupyter_repr():
    png = load_example("cube")._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert load_example("torus-cycle")._repr_png_() is None
