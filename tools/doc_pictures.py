"""Redraw the pictures of docs/pictures.md and README.md, and take the screenshots of the viewer
and the gallery in headless Chromium (Debian's chromium; Playwright drives it).

    python tools/doc_pictures.py            # from the repository root, with the test extras
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IMAGES = ROOT / "docs" / "images"
sys.path.insert(0, str(ROOT / "tests"))


def polyloops(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "polyloops", *args], check=True, cwd=ROOT)


def screenshots(site: Path, viewer: Path) -> None:
    from playwright.sync_api import sync_playwright

    from browser import FLAGS, find_chromium

    path, why = find_chromium()
    if path is None:
        raise SystemExit(why)
    with sync_playwright() as driver:
        browser = driver.chromium.launch(executable_path=path, args=FLAGS)
        page = browser.new_page(viewport={"width": 1100, "height": 720})
        page.goto(viewer.as_uri())
        page.wait_for_selector(".js-plotly-plot canvas")
        page.wait_for_timeout(800)
        page.mouse.move(520, 330)  # hover a face: the tooltip names it and its zones
        page.wait_for_timeout(400)
        page.screenshot(path=str(IMAGES / "viewer.png"))
        page.goto((site / "index.html").as_uri())
        page.select_option("#f-irreducible", "0")
        page.select_option("#f-corners", "24")
        page.wait_for_timeout(400)
        page.screenshot(path=str(IMAGES / "gallery.png"))
        browser.close()


def genus1_sheet() -> None:
    """The smallest class of each hole-orientation type in the genus-1 catalog (the
    certificate's bases), every irreducible genus-1 class through 46 corners (the bridged ring,
    of the type whose invariant is zero, among them) and the classes the certificate leaves
    open."""
    import json

    catalog = ROOT / "catalogs" / "genus1"
    lines = [json.loads(line) for line in
             (catalog / "reachability-certificate.jsonl").read_text().splitlines()[1:]]
    bases = {r["signature"] for r in lines if r.get("base")}
    open_ = {r["signature"] for r in lines if r.get("unsettled")}
    records = [json.loads(line) for line in (catalog / "catalog.jsonl").read_text().splitlines()]
    chosen = [f"sig:{r['signature']}" for r in records
              if r["signature"] in bases | open_ or (r["irreducible"] and r["corners"] <= 46)]
    polyloops("sheet", *chosen, "--columns", "4",
              "-o", str(IMAGES / "genus1-sheet.png"))


def main() -> None:
    genus1_sheet()
    polyloops("render", "example:ring", "-o", str(IMAGES / "ring.png"), "--views", "2")
    polyloops("render", "example:bridged-ring", "--zones", "Z", "--level-graphs",
              "-o", str(IMAGES / "bridged-ring-zones.png"))
    polyloops("render", "example:self-intersecting", "--views", "2", "--grid",
              "-o", str(IMAGES / "self-intersecting.png"))
    polyloops("sheet", "catalogs/genus0", "--columns", "8", "--limit", "32",
              "-o", str(IMAGES / "catalog-sheet.png"))
    with tempfile.TemporaryDirectory() as tmp:
        viewer = Path(tmp) / "bridged-ring.html"
        polyloops("view", "example:bridged-ring", "-o", str(viewer))
        site = Path(tmp) / "site"
        polyloops("gallery", "-o", str(site))
        screenshots(site, viewer)


if __name__ == "__main__":
    main()
