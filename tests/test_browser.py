"""The viewer and the gallery, opened in headless Chromium: no console errors, a picture that
is not blank, loop axes that toggle, filters that change the list, a signature that copies."""

import io

import matplotlib.image as mpimg
import numpy as np
import pytest

from polyloops.cli import main


def open_page(chromium, url):
    page = chromium.new_page(viewport={"width": 1000, "height": 760})
    errors = []
    # Software WebGL reports "GL Driver Message ... Performance" notices (a stall on reading
    # pixels back for a screenshot) through the console: they are the driver's, not the page's.
    page.on("console", lambda m: errors.append(m.text)
            if m.type == "error" and "GL Driver Message" not in m.text else None)
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url)
    return page, errors


def follow(page, link) -> str:
    """Click a link and wait for the page it opens (a click returns once dispatched, before the
    browser has navigated); returns the new URL."""
    with page.expect_navigation():
        link.click()
    return page.url


def ink(png: bytes) -> float:
    img = mpimg.imread(io.BytesIO(png), format="png")[..., :3]
    return float(np.any(np.abs(img - 1.0) > 0.05, axis=-1).mean())


def viewer_page(chromium, path):
    page, errors = open_page(chromium, path.as_uri())
    page.wait_for_selector(".js-plotly-plot canvas")
    page.wait_for_timeout(600)
    return page, errors


@pytest.mark.browser
def test_viewer_turns_toggles_and_stays_quiet(chromium, tmp_path, capsys):
    out = tmp_path / "ring.html"
    assert main(["view", "example:bridged-ring", "-o", str(out)]) == 0
    page, errors = viewer_page(chromium, out)
    before = page.screenshot()
    assert ink(before) > 0.1  # the canvas is not blank
    for axis in "XYZ":
        page.locator(".legend .traces", has_text=f"{axis}-loops").locator(".legendtoggle").click()
        page.wait_for_timeout(700)  # past plotly's double-click delay, so each click is one click
        hidden = page.evaluate(f"document.querySelector('.js-plotly-plot').data"
                               f".filter(t => t.legendgroup === '{axis}-loops').map(t => t.visible)")
        assert hidden and set(hidden) == {"legendonly"}
    after = page.screenshot()
    assert after != before  # hiding the loops changed the picture
    # Turning the camera (as a drag does) changes the picture too.
    page.evaluate("Plotly.relayout(document.querySelector('.js-plotly-plot'), "
                  "{'scene.camera.eye': {x: -1.5, y: 1.2, z: 0.6}})")
    page.wait_for_timeout(400)
    assert page.screenshot() != after
    assert errors == []
    page.close()


@pytest.mark.browser
@pytest.mark.slow
def test_gallery_filters_copy_and_links(chromium, tmp_path, capsys):
    site = tmp_path / "site"
    assert main(["gallery", "-o", str(site), "--limit", "12"]) == 0
    page, errors = open_page(chromium, (site / "index.html").as_uri())
    cards = page.locator(".card")
    assert cards.count() == 12
    assert "showing 12 of 12" in page.inner_text("#count")
    page.select_option("#f-corners", "16")
    assert cards.count() == 2 and "showing 2 of 12" in page.inner_text("#count")
    assert set(page.locator(".card .name a:not(.view3d)").all_inner_texts()) == {"P16.1", "P16.2"}
    page.select_option("#f-corners", "")
    page.select_option("#f-irreducible", "1")
    irreducible = cards.count()
    assert 1 <= irreducible < 12
    page.select_option("#f-irreducible", "")
    page.select_option("#f-Z", "1")
    assert 0 < cards.count() < 12
    first = cards.first
    assert first.get_attribute("title").startswith("1o")  # the full signature on hover
    first.locator("button").click()
    # The copy answers asynchronously (the clipboard's promise, or the fallback).
    first.locator("button", has_text="copied").wait_for(timeout=5000)
    assert ink(page.screenshot()) > 0.05
    follow(page, first.locator(".name a.view3d"))
    page.wait_for_selector(".js-plotly-plot canvas")
    assert page.url.endswith(".html") and "/view/" in page.url
    assert errors == []
    page.close()


@pytest.mark.browser
@pytest.mark.slow
def test_the_gallery_walks_the_move_graph(chromium, tmp_path, capsys):
    """From the non-incremental polycube's page a user reaches the cube by clicks: along its
    detour and then removals; from a class to the class a removal leaves and back by the
    additions above; the overview links every class; a removable loop opens highlighted."""
    site = tmp_path / "site"
    assert main(["gallery", "-o", str(site), "--limit", "60"]) == 0
    page, errors = open_page(chromium, (site / "index.html").as_uri())
    follow(page, page.locator(".card", has_text="P26.20").locator(".name a").first)
    assert page.url.endswith("/class/P26.20.html") and "irreducible" in page.inner_text("body")
    # Within the gallery's classes (through 26 corners here) nothing leads to P26.20.
    assert page.locator(".shortest").count() == 0 and "Not reachable" in page.inner_text("body")
    visited = ["P26.20"]
    while visited[-1] != "P8.1":
        strip = page.locator(".strip .cell")
        assert strip.count() >= 2
        assert strip.first.inner_text().strip().startswith(visited[-1])
        nxt = strip.locator("a")  # the way down's next class with a page
        assert nxt.count() >= 2, page.url
        follow(page, nxt.nth(1))
        visited.append(page.url.rsplit("/", 1)[1].removesuffix(".html"))
        assert len(visited) < 10
    assert visited[1] != "P26.20" and page.locator("h1").inner_text() == "P8.1"
    # Up by an addition, and down again by its removal.
    follow(page, page.locator(".above a", has_text="P12.1").first)
    assert page.url.endswith("/class/P12.1.html")
    follow(page, page.locator(".removals a", has_text="P8.1").first)
    assert page.url.endswith("/class/P8.1.html")
    page.go_back()
    link = page.locator(".removals a", has_text="see it").first
    target = link.get_attribute("href")
    assert "#loop-" in target
    follow(page, link)
    page.wait_for_selector(".js-plotly-plot canvas")
    page.wait_for_timeout(500)
    widths = page.evaluate("document.querySelector('.js-plotly-plot').data"
                           ".filter(t => t.mode === 'lines' && typeof t.hovertext === 'string'"
                           " && /-loop \\d+,/.test(t.hovertext)).map(t => t.line.width)")
    assert max(widths) > min(widths)  # the removable loop stands out
    page.goto((site / "class" / "P18.1.html").as_uri())
    shortest = page.locator(".shortest .cell a")  # from the cube, a shortest path
    assert shortest.first.get_attribute("href") == "P8.1.html"
    assert shortest.last.get_attribute("href") == "P18.1.html"
    assert "From the cube: " in page.inner_text("body")
    page.goto((site / "moves.html").as_uri())
    assert page.locator("#graph a").count() == 60
    follow(page, page.locator('#graph a[href="class/P12.1.html"]'))
    assert page.url.endswith("/class/P12.1.html")
    assert errors == []
    page.close()


@pytest.mark.browser
@pytest.mark.parametrize("dims", [pytest.param((1, 1, 6), marks=pytest.mark.slow),
                                  pytest.param((6, 2, 1), marks=pytest.mark.slow),
                                  pytest.param((3, 3, 3), marks=pytest.mark.slow)])
def test_the_first_view_shows_the_whole_shape(chromium, tmp_path, dims):
    """The first camera is fitted to the bounding box: nothing of a tall tower, a flat slab or
    a cube touches the plot's edges (the scene's ink stays inside, with a margin)."""
    from polyloops.render.viewer import write_viewer
    from polyloops.shapes.builders import box

    out = tmp_path / "shape.html"
    write_viewer(box(*dims), out)
    page, errors = viewer_page(chromium, out)
    scene_box = page.locator(".js-plotly-plot canvas").first.bounding_box()  # the 3D scene
    assert scene_box is not None
    png = page.screenshot()
    img = mpimg.imread(io.BytesIO(png), format="png")[..., :3]
    top, left = int(scene_box["y"]), int(scene_box["x"])
    bottom, right = int(top + scene_box["height"]), int(left + scene_box["width"])
    scene = np.any(np.abs(img[top:bottom, left:right] - 1.0) > 0.05, axis=-1)
    rows = np.flatnonzero(scene.any(axis=1))
    cols = np.flatnonzero(scene.any(axis=0))
    assert len(rows) and len(cols)
    margin = 10
    assert rows[0] > margin and rows[-1] < scene.shape[0] - margin, (rows[0], rows[-1], scene.shape)
    assert cols[0] > margin and cols[-1] < scene.shape[1] - margin, (cols[0], cols[-1], scene.shape)
    assert errors == []
    page.close()


@pytest.mark.browser
@pytest.mark.slow  # the size is pinned by test_render's test in the default run; this draws them
def test_notebook_viewers_share_one_plotly(chromium, tmp_path):
    """Viewer fragments as a notebook shows them, one after another in one page: only the
    first carries plotly.js, and every one draws."""
    import subprocess
    import sys

    code = ("import polyloops as pl\n"
            "shown = [pl.load_example(n)._repr_html_() for n in ['cube', 'l-shape', 'ring']]\n"
            "print('<!-- next -->'.join(shown))\n")
    body = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    page_file = tmp_path / "notebook.html"
    page_file.write_text(f"<html><body>{body}</body></html>", encoding="utf-8")
    page, errors = open_page(chromium, page_file.as_uri())
    page.wait_for_function("document.querySelectorAll('.js-plotly-plot canvas').length >= 3")
    first, *others = body.split("<!-- next -->")
    assert len(others) == 2 and "plotly.js v" in first and not any("plotly.js v" in o for o in others)
    assert errors == []
    page.close()


@pytest.mark.browser
@pytest.mark.slow  # a segmentation run and a page of 50,000 triangles: several seconds
def test_the_segmentation_page_shows_mesh_and_polycube_and_toggles_loops_on_both(chromium, tmp_path, capsys):
    out = tmp_path / "egg.html"
    assert main(["segment", "example:egg", "--budget", "2", "--search-only", "--html", str(out)]) == 0
    page, errors = viewer_page(chromium, out)
    assert len(page.query_selector_all(".js-plotly-plot canvas")) >= 1 and ink(page.screenshot()) > 0.1
    scenes = page.evaluate("[...new Set(document.querySelector('.js-plotly-plot').data.map(t => t.scene))]")
    assert sorted(scenes) == ["scene", "scene2"]
    page.locator(".legend .traces", has_text="X-loops").first.locator(".legendtoggle").click()
    page.wait_for_timeout(700)
    hidden = page.evaluate("document.querySelector('.js-plotly-plot').data"
                           ".filter(t => t.legendgroup === 'X-loops').map(t => [t.scene, t.visible])")
    assert {s for s, _ in hidden} == {"scene", "scene2"} and {v for _, v in hidden} == {"legendonly"}
    assert not errors, errors
