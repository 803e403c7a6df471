"""Pictures: produced, not blank, deterministic; every bundled example renders."""

import hashlib

import matplotlib.image as mpimg
import numpy as np
import pytest
from hypothesis import given, settings

from polyloops.cli import main
from polyloops.io.examples import EXAMPLES, load_example
from polyloops.render.colours import AXIS_COLOUR, LIGHT_COLOUR
from polyloops.render.polycube import as_polycube, choose_views, face_normal
from strategies import polycubes


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
    for colours in (AXIS_COLOUR, LIGHT_COLOUR):
        for c in colours.values():
            assert has_colour(img, c), c
    plain = tmp_path / "plain.png"
    assert main(["render", "example:ring", "--no-loops", "-o", str(plain)]) == 0
    _, img2 = ink(plain)
    assert not any(has_colour(img2, c) for c in AXIS_COLOUR.values())


def test_deterministic(tmp_path):
    """The same input gives the same bytes, in each format (one view suffices: the metadata
    that could change lives in the file, not in the views)."""
    digests = set()
    for i in range(2):
        for ext in ("png", "svg"):
            out = tmp_path / f"a{i}.{ext}"
            assert main(["render", "example:cube", "-o", str(out)]) == 0
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


# -- hidden surfaces against a ray-cast oracle --------------------------------------------

def face_boxes(q):
    """Each face as (constant axis, its coordinate, low corner, high corner)."""
    out = []
    for face in q.faces:
        pts = [q.positions[c] for c in face]
        k = next(i for i in range(3) if len({p[i] for p in pts}) == 1)
        out.append((k, pts[0][k], [min(p[i] for p in pts) for i in range(3)],
                    [max(p[i] for p in pts) for i in range(3)]))
    return out


def oracle(boxes, view, u, v):
    """The nearest face a ray through view point ``(u, v)`` hits, by exact rational arithmetic
    (each float of the view read exactly), faces as axis-aligned rectangles in 3D; ``None`` for
    no hit, and ``"unsure"`` where the answer is a tie (faces that coincide) or the point lies
    within a hair of a face's border, where a pixel cannot tell.  A float test first skips the
    faces the ray misses by far."""
    from fractions import Fraction as F

    hits = []
    for f, (k, c, lo, hi) in enumerate(boxes):
        t = (c - u * view.right[k] - v * view.up[k]) / view.toward[k]
        x = [u * view.right[i] + v * view.up[i] + t * view.toward[i] for i in range(3)]
        if min(min(x[i] - lo[i], hi[i] - x[i]) for i in range(3) if i != k) < -1e-3:
            continue
        R, U, T = ([F(a) for a in vec] for vec in (view.right, view.up, view.toward))
        fu, fv = F(u), F(v)
        t = (c - fu * R[k] - fv * U[k]) / T[k]
        x = [fu * R[i] + fv * U[i] + t * T[i] for i in range(3)]
        margin = min(min(x[i] - lo[i], hi[i] - x[i]) for i in range(3) if i != k)
        if margin >= 0:
            hits.append((t, f, margin))
    if not hits:
        return None
    hits.sort(reverse=True)
    if hits[0][2] < F(1, 10**6) or (len(hits) > 1 and hits[0][0] - hits[1][0] < F(1, 10**6)):
        return "unsure"
    return hits[0][1]


def check_against_oracle(q, pixels=28, views=4, sure=0.9):
    """The buffer agrees with the oracle at every pixel the oracle is sure of, and that is
    at least a ``sure`` fraction of them (ties and borders aside)."""
    from polyloops.render.projection import View
    from polyloops.render.raster import rasterize

    chosen = [*choose_views(q, views), View(10.0, 62.0), View(250.0, -15.0)]
    boxes = face_boxes(q)
    checked = 0
    for view in chosen:
        buf = rasterize(q, view, pixels)
        for i in range(pixels):
            for j in range(pixels):
                want = oracle(boxes, view, float(buf.u[j]), float(buf.v[i]))
                if want == "unsure":
                    continue
                got = int(buf.face[i, j])
                assert got == (-1 if want is None else want), (view.toward, i, j)
                checked += 1
    assert checked > sure * len(chosen) * pixels * pixels


def drawable(name):
    from polyloops.core.duality import DualityError

    try:
        return as_polycube(load_example(name))[0]
    except DualityError:  # a loop structure with a cyclic level graph: no polycube to draw
        return None


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_every_pixel_shows_the_nearest_face_on_the_examples(name):
    """Every bundled example that has a polycube (the invalid ones too, drawn as they are)."""
    q = drawable(name)
    if q is None:
        pytest.skip(f"{name} has no polycube to draw")
    # An invalid structure's polycube may fold onto itself: many ties, each left out.
    check_against_oracle(q, sure=0.9 if EXAMPLES[name].valid else 0.5)


@settings(max_examples=8, deadline=None)
@given(polycubes(kinds=("blob", "frame1", "frame2"), max_size=7))
def test_every_pixel_shows_the_nearest_face_on_random_polycubes(q):
    """Concave blobs and frames of genus 1 and 2, several views each."""
    check_against_oracle(q, pixels=20, views=2)


def test_the_picture_is_drawn_from_the_buffer_it_checks(tmp_path):
    """draw_polycube returns the depth buffer its picture was shaded from, so the oracle tests
    check what is drawn; and a surface that meets itself shows its outside where two faces
    coincide (the self-intersecting example seen from below)."""
    from matplotlib.figure import Figure

    from polyloops.render.polycube import draw_polycube
    from polyloops.render.projection import View

    q, ls = as_polycube(load_example("self-intersecting"))
    ax = Figure().add_subplot()
    buf = draw_polycube(ax, q, View(35.0, -28.0), ls, pixels=40)
    assert buf.face.shape == (120, 120) and len(ax.images) == 1
    seen = buf.face[buf.face >= 0]
    facing = {f for f in set(seen.tolist()) if View(35.0, -28.0).facing(q.face_normal(f).vector) > 0}
    assert facing == set(seen.tolist())  # no inside face wins a tie with the outside


def test_zones_and_grid(tmp_path):
    out = tmp_path / "zones.png"
    assert main(["render", "example:bridged-ring", "--zones", "Z", "--level-graphs", "-o", str(out)]) == 0
    _, img = ink(out)
    from polyloops.render.polycube import ZONE_SHADES

    assert has_colour(img, ZONE_SHADES[0], 0.03) and has_colour(img, ZONE_SHADES[1], 0.03)
    assert main(["render", "example:l-shape", "--grid", "-o", str(tmp_path / "grid.png")]) == 0


def test_view_writes_one_self_contained_page(tmp_path, capsys):
    out = tmp_path / "ring.html"
    assert main(["view", "example:ring", "-o", str(out)]) == 0
    page = out.read_text(encoding="utf-8")
    assert "<script" in page and '<script src="http' not in page  # plotly.js is inside, not fetched
    for group in ("X-loops", "Y-loops", "Z-loops", "corners"):
        assert group in page
    assert main(["view", "example:ring", "-o", str(tmp_path / "ring.png")]) == 2
    assert main(["view", "example:torus-cycle", "-o", str(tmp_path / "t.html")]) == 1
    assert not (tmp_path / "t.html").exists()


def test_jupyter_shows_the_viewer_with_the_picture_as_fallback():
    import polyloops  # noqa: F401  (registers the representations)

    cube = load_example("cube")
    html = cube._repr_html_()
    assert "plotly" in html.lower() and "X-loops" in html and not html.lstrip().startswith("<html")
    assert cube._repr_png_().startswith(b"\x89PNG")
    assert load_example("torus-cycle")._repr_html_() is None  # no polycube: text instead
