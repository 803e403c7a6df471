"""Pictures: produced, not blank, deterministic; every bundled example renders."""

import hashlib
import json
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.io.examples import EXAMPLES, load_example
from polyloops.render.colours import AXIS_COLOUR, LIGHT_COLOUR
from polyloops.render.polycube import as_polycube, choose_views, face_normal
from strategies import polycubes
from switch import needs


def ink(path):
    img = mpimg.imread(path)[..., :3]
    return np.any(np.abs(img - 1.0) > 0.05, axis=-1).mean(), img


def has_colour(img, hex_colour, tol=0.06):
    rgb = np.array([int(hex_colour[i:i + 2], 16) / 255 for i in (1, 3, 5)])
    return bool((np.abs(img - rgb).max(axis=-1) < tol).any())


@pytest.mark.parametrize("name", sorted(EXAMPLES))
def test_every_example_renders(tmp_path, capsys, name):
    """Every example draws; one without a polycube (a cyclic level graph) draws its level
    graphs and exits 1, as 'view' does."""
    out = tmp_path / f"{name}.png"
    assert main(["render", f"example:{name}", "-o", str(out)]) == (0 if drawable(name) is not None else 1)
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


def test_sheet_cells_are_the_pictures_and_workers_change_nothing(tmp_path, capsys):
    """A PNG sheet pastes each class's thumbnail under its caption; two workers write the
    same bytes as one."""
    from PIL import Image

    from polyloops.render.polycube import thumbnail_pixels
    from polyloops.render.sheet import CAPTION

    sources = ["example:cube", "example:l-shape", "example:ring", "example:non-incremental"]
    files = {}
    for workers in (1, 2):
        files[workers] = tmp_path / f"sheet{workers}.png"
        assert main(["sheet", *sources, "--columns", "3", "--workers", str(workers),
                     "-o", str(files[workers])]) == 0
    assert files[1].read_bytes() == files[2].read_bytes()
    sheet = np.asarray(Image.open(files[1]).convert("RGB"))
    assert sheet.shape == (2 * (220 + CAPTION), 3 * 220, 3)
    for i, name in enumerate(sources):
        r, c = divmod(i, 3)
        top = r * (220 + CAPTION) + CAPTION
        cell = sheet[top:top + 220, c * 220:(c + 1) * 220]
        assert np.array_equal(cell, thumbnail_pixels(load_example(name.split(":")[1]), 220)), name
        band = sheet[top - CAPTION:top, c * 220:(c + 1) * 220]
        assert (band < 128).any(), f"{name}: no caption"
    assert (sheet[255 + CAPTION:, 440:] == 255).all()  # the empty cell stays blank


def test_sheet_captions_are_catalog_names(tmp_path, monkeypatch):
    """Captions name classes as the census does (never a cut-off signature)."""
    import json
    from pathlib import Path

    import polyloops.render.sheet as sheet
    from polyloops.core.canonical import canonical_form

    seen = []
    monkeypatch.setattr(sheet, "render_sheet", lambda items, out, **options: seen.extend(items))
    catalog = Path(__file__).resolve().parent.parent / "catalogs" / "genus0"
    records = [json.loads(line) for line in (catalog / "catalog.jsonl").read_text().splitlines()[:5]]
    l_shape = load_example("l-shape")
    sig = canonical_form(l_shape, "labelled").signature
    assert main(["sheet", str(catalog), "--limit", "5", "-o", str(tmp_path / "s.png")]) == 0
    assert [c for c, _ in seen] == [r["name"] for r in records]
    seen.clear()
    sources = ["example:l-shape", f"sig:{sig}", "example:ring", "example:bridged-ring",
               "example:two-axis-holes"]
    assert main(["sheet", *sources, "-o", str(tmp_path / "s.png")]) == 0
    full = canonical_form(l_shape, "full").signature
    name = next(r["name"] for r in map(json.loads, (catalog / "catalog.jsonl").read_text().splitlines())
                if r["signature"] == full)
    holes = load_example("two-axis-holes").map.num_corners  # genus 2: no catalog names it
    assert [c for c, _ in seen] == [name, name, "T32.1", "T40.58",
                                    f"example:two-axis-holes ({holes} corners)"]


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


def pixel_by_pixel(x, y, d, triangles, shape):
    """The slow twin of ``triangle_buffer``: every pixel centre against every triangle."""
    h, w = shape
    seen = [[-1] * w for _ in range(h)]
    best = [[float("-inf")] * w for _ in range(h)]
    for t, (a, b, c) in enumerate(triangles):
        area = (x[b] - x[a]) * (y[c] - y[a]) - (x[c] - x[a]) * (y[b] - y[a])
        if abs(area) < 1e-12:
            continue
        for i in range(h):
            for j in range(w):
                px, py = j + 0.5, i + 0.5
                wa = ((x[b] - px) * (y[c] - py) - (x[c] - px) * (y[b] - py)) / area
                wb = ((x[c] - px) * (y[a] - py) - (x[a] - px) * (y[c] - py)) / area
                wc = 1.0 - wa - wb
                if min(wa, wb, wc) < -1e-9:
                    continue
                depth = wa * d[a] + wb * d[b] + wc * d[c]
                if depth > best[i][j]:  # equal depth: the earlier (lower) id stays
                    best[i][j], seen[i][j] = depth, t
    return seen


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_triangle_buffer_agrees_with_its_pixel_by_pixel_twin(data):
    """All triangles at once, in chunks of any size, against every pixel and every triangle
    one by one: triangles partly or wholly off the picture, slivers and overlaps."""
    from polyloops.render.raster import triangle_buffer

    n = data.draw(st.integers(3, 12))
    coord = st.floats(-4, 16, allow_nan=False).map(lambda v: round(v, 3))
    x = np.array(data.draw(st.lists(coord, min_size=n, max_size=n)))
    y = np.array(data.draw(st.lists(coord, min_size=n, max_size=n)))
    d = np.array(data.draw(st.lists(st.floats(-5, 5, allow_nan=False), min_size=n, max_size=n)))
    triangles = data.draw(st.lists(st.tuples(*[st.integers(0, n - 1)] * 3), min_size=1, max_size=8))
    chunk = data.draw(st.sampled_from([1, 7, 50, 1 << 21]))
    seen, depth = triangle_buffer(x, y, d, np.array(triangles), (9, 11), chunk=chunk)
    assert seen.tolist() == pixel_by_pixel(x, y, d, triangles, (9, 11))
    assert np.all((seen >= 0) == np.isfinite(depth))


@settings(max_examples=6, deadline=None)
@given(polycubes(kinds=("blob", "frame1", "frame2"), max_size=6))
def test_triangle_buffer_shows_the_nearest_face_of_polycubes(q):
    """The buffer of a polycube's triangles (front-facing, as segmentations are drawn)
    agrees with the exact ray oracle at every pixel the oracle is sure of."""
    from polyloops.render.projection import View
    from polyloops.render.raster import triangle_buffer

    boxes = face_boxes(q)
    pos = np.asarray(q.positions, dtype=float)
    tris = np.array([t for a, b, c, e in q.faces for t in ((a, b, c), (a, c, e))])
    checked = 0
    for view in (*choose_views(q, 2), View(250.0, -15.0)):
        right, up, toward = (np.asarray(v) for v in (view.right, view.up, view.toward))
        pu, pv, pd = pos @ right, pos @ up, pos @ toward
        front = np.flatnonzero(np.cross(pos[tris[:, 1]] - pos[tris[:, 0]], pos[tris[:, 2]] - pos[tris[:, 0]])
                               @ toward > 0)
        left, top, step, pixels = pu.min() - 0.3, pv.max() + 0.3, (pu.max() - pu.min() + 0.6) / 24, 24
        seen, _ = triangle_buffer((pu - left) / step, (top - pv) / step, pd, tris[front], (pixels, pixels))
        for i in range(pixels):
            for j in range(pixels):
                want = oracle(boxes, view, left + (j + 0.5) * step, top - (i + 0.5) * step)
                if want == "unsure":
                    continue
                got = -1 if seen[i, j] < 0 else int(front[seen[i, j]]) // 2
                assert got == (-1 if want is None else want), (view.toward, i, j)
                checked += 1
    assert checked > 0.9 * 3 * 24 * 24


def test_segmentation_pictures_mark_what_is_wrong_in_red(tmp_path, capsys):
    """A chart bent over an edge of the cube breaks local rules: its boundaries are drawn in
    the witness red; a valid segmentation's picture has no red."""
    from matplotlib.colors import to_rgb

    from polyloops.core.directions import Direction
    from polyloops.render.segmentation import WITNESS_COLOUR, render_segmentation
    from polyloops.segmentation import check_segmentation
    from polyloops.surface.construct import labelled_mesh_from_polycube

    def red_pixels(labels, name):
        report = check_segmentation(labelled_mesh_from_polycube(q, labels))
        render_segmentation(report, tmp_path / name)
        image = mpimg.imread(tmp_path / name)[..., :3]
        return int((np.abs(image - np.array(to_rgb(WITNESS_COLOUR))).max(axis=2) < 0.02).sum())

    q = load_example("l-shape")
    labels = [q.face_normal(f) for f in range(q.map.num_faces)]
    assert red_pixels(labels, "valid.png") == 0
    labels[labels.index(Direction.PZ)] = Direction.PX
    assert red_pixels(labels, "bent.png") > 100


def test_gallery_workers_write_the_same_site(tmp_path, capsys):
    """Two worker processes write the same files, byte for byte, as one; a rerun keeps what
    is there (resumable) and fills in what is missing."""
    sites = {}
    for workers in (1, 2):
        site = tmp_path / f"site{workers}"
        assert main(["gallery", "-o", str(site), "--limit", "6", "--workers", str(workers)]) == 0
        sites[workers] = {p.relative_to(site): p.read_bytes() for p in site.rglob("*") if p.is_file()}
    # per class: a picture, a viewer page and a move-graph page; the index, plotly.js, the overview
    assert sites[1] == sites[2] and len(sites[1]) == 3 * 6 + 3
    site = tmp_path / "site1"
    (site / "img" / "P8.1.png").unlink()
    kept = (site / "view" / "P8.1.html").stat().st_mtime_ns
    assert main(["gallery", "-o", str(site), "--limit", "6", "--workers", "2"]) == 0
    assert (site / "img" / "P8.1.png").read_bytes() == sites[1][Path("img/P8.1.png")]
    assert (site / "view" / "P8.1.html").stat().st_mtime_ns == kept


@needs("raster")
@settings(max_examples=15, deadline=None)
@given(polycubes(kinds=("blob", "frame1", "frame2"), max_size=7), st.integers(5, 60),
       st.floats(0, 360), st.floats(-80, 80))
def test_compiled_depth_buffer_equals_the_python_loop(q, pixels, azimuth, elevation):
    """The compiled rasteriser and the triangle-at-a-time loop give the same buffers, bit for
    bit (faces, depths and the points seen), from any view, also on the self-touching
    example where ties decide."""
    from polyloops.core import compiled
    from polyloops.render import raster
    from polyloops.render.projection import View

    shapes = [q, drawable("self-intersecting")]
    for shape in shapes:
        if shape is None:
            continue
        view = View(azimuth, elevation)
        fast = raster.rasterize(shape, view, pixels)
        with compiled.pure_python("raster"):
            slow = raster.rasterize(shape, view, pixels)
        for name in ("face", "depth", "point"):
            assert np.array_equal(getattr(fast, name), getattr(slow, name)), name


def test_a_notebook_gets_plotly_once(tmp_path):
    """In a fresh process (a kernel), the first viewer carries plotly.js and the next ones do
    not: twenty polycubes cost one copy of plotly, not twenty."""
    import subprocess
    import sys

    code = ("import json, polyloops as pl\n"
            "pages = [pl.load_example(n)._repr_html_() for n in ['cube', 'l-shape'] * 10]\n"
            "print(json.dumps([len(p) for p in pages]))\n")
    sizes = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                      check=True).stdout)
    assert sizes[0] > 3_000_000 and max(sizes[1:]) < 200_000, sizes
    assert sum(sizes) < sizes[0] + 19 * 200_000


def test_the_segmentation_picture_tells_its_progress(tmp_path):
    """render_segmentation reports each of its two views and the file written (what the
    command's progress bar counts)."""
    from polyloops.io.examples import labelled_mesh_example
    from polyloops.render.segmentation import render_segmentation
    from polyloops.segmentation import check_segmentation

    told: list[str] = []
    report = check_segmentation(labelled_mesh_example("overhang"))
    render_segmentation(report, tmp_path / "o.png", told.append)
    assert told == ["view", "view", "written"] and (tmp_path / "o.png").stat().st_size > 1000
