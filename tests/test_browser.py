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
def test_gallery_filters_copy_and_links(chromium, tmp_path, capsys):
    site = tmp_path / "site"
    assert main(["gallery", "-o", str(site), "--limit", "12"]) == 0
    page, errors = open_page(chromium, (site / "index.html").as_uri())
    cards = page.locator(".card")
    assert cards.count() == 12
    assert "showing 12 of 12" in page.inner_text("#count")
    page.select_option("#f-corners", "16")
    assert cards.count() == 2 and "showing 2 of 12" in page.inner_text("#count")
    assert set(page.locator(".card .name").all_inner_texts()) == {"P16.1", "P16.2"}
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
    first.locator(".name a").click()
    page.wait_for_selector(".js-plotly-plot canvas")
    assert page.url.endswith(".html") and "/view/" in page.url
    assert errors == []
    page.close()
