"""A catalog as a static web site: every class with its picture, name and columns, filters by
those columns, a button that copies the signature, a viewer page per class, and the move
graph: a page per class with its moves and its way down to the cube (at genus 1, to the base of
its hole orientation), and an overview.

The site is a directory: ``index.html`` (the list, with the data inside it), ``img/NAME.png``
(one picture per class, drawn by :func:`polyloops.render.polycube.write_thumbnail`),
``view/NAME.html`` (one interactive viewer per class, sharing ``view/plotly.min.js``), and for a
catalog in full symmetry ``class/NAME.html`` and ``moves.html``
(:mod:`polyloops.render.class_pages`).  It
needs no server and no network: open ``index.html``.  Pictures and viewer pages already there
are kept, so an interrupted run resumes; every file is written through a temporary file.

>>> import tempfile, pathlib
>>> from polyloops.catalog.census import read_catalog
>>> census = read_catalog()
>>> with tempfile.TemporaryDirectory() as tmp:
...     built = build_gallery(census, pathlib.Path(tmp) / "site", limit=2)
...     names = sorted(p.name for p in (pathlib.Path(tmp) / "site" / "img").iterdir())
>>> built.classes, names
(2, ['P12.1.png', 'P8.1.png'])
"""

from __future__ import annotations

import html
import json
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from polyloops.catalog.census import CatalogEntry, Census
from polyloops.core.corners import CATEGORIES
from polyloops.core.symmetry import Symmetry
from polyloops.io.files import check_within, write_atomic


@dataclass(frozen=True)
class GalleryBuild:
    """What :func:`build_gallery` wrote: the site's directory and how many classes it lists."""

    directory: Path
    classes: int


def _row(entry: CatalogEntry) -> dict[str, object]:
    r = entry.record
    return {"name": entry.name, "signature": r.signature, "corners": r.corners, "faces": r.faces,
            "loops": r.loops, "categories": {str(c): r.categories[c] for c in CATEGORIES},
            "chiral": r.chiral, "irreducible": r.irreducible, "automorphisms": r.automorphisms}


def build_gallery(census: Census, out: str | Path, limit: int | None = None,
                  progress: Callable[[str], None] | None = None, workers: int = 1) -> GalleryBuild:
    """Write the gallery of a catalog into directory ``out``.

    Parameters
    ----------
    census:
        A catalog, as :func:`polyloops.catalog.census.read_catalog` reads it.
    out:
        The site's directory (made if missing; its parent must exist).
    limit:
        List only the first ``limit`` classes.
    progress:
        Called with each class's name once its picture and viewer page exist.
    workers:
        Local worker processes drawing the classes' pictures and pages.

    Returns
    -------
    GalleryBuild

    Raises
    ------
    OSError
        When a file cannot be written.
    ValueError
        When a record's signature does not decode.
    """
    from polyloops.catalog.census import NAME
    from polyloops.parallel import run_jobs
    from polyloops.render.viewer import write_plotly_js

    out = Path(out)
    entries = list(census.entries[:limit] if limit is not None else census.entries)
    for entry in entries:  # names become file names: only class names, never a path
        if not NAME.fullmatch(entry.name):
            raise ValueError(f"record {entry.name[:60]!r} is not named as a class (P16.2, T32.1); "
                             "its picture and page would not stay in the site")
    for sub in ("img", "view", "class", "img/steps"):
        check_within(out / sub / "x", out)
    (out / "img").mkdir(parents=True, exist_ok=True)
    (out / "view").mkdir(exist_ok=True)
    if not (out / "view" / "plotly.min.js").exists():
        write_plotly_js(out / "view")
    tasks = []
    for entry in entries:
        picture, page = out / "img" / f"{entry.name}.png", out / "view" / f"{entry.name}.html"
        check_within(picture, out)
        check_within(page, out)
        if picture.exists() and page.exists():
            if progress is not None:
                progress(entry.name)
        else:
            tasks.append((entry.signature, entry.name, entry.corners, str(picture), str(page)))
    batch = max(1, min(16, len(tasks) // (4 * max(1, workers))))
    for name in run_jobs(_draw_class, tasks, workers, ordered=False, batch=batch):
        if progress is not None:
            progress(name)
    if limit is None or len(entries) == len(census.entries):
        span = f"through {census.max_corners} corners"
    else:  # a limited gallery says what it shows, not the catalog's whole range
        low, high = (entries[0].corners, entries[-1].corners) if entries else (0, 0)
        span = f"the first {len(entries)} of {len(census.entries)} classes ({low} to {high} corners)"
    title = f"Genus-{census.genus} polycubes, {span}, up to {Symmetry.parse(census.symmetry).up_to}"
    full = str(census.symmetry) == "full"  # the move graph names classes by full signature
    if full:
        from polyloops.reach.move_graph import move_graph
        from polyloops.render.class_pages import write_class_pages

        listed = Census(census.directory, tuple(entries), census.summary)
        write_class_pages(out, entries, move_graph(listed, workers=workers), title)
    write_atomic(out / "index.html", gallery_html([_row(e) for e in entries], title, class_pages=full,
                                                  genus=census.genus), within=out)
    return GalleryBuild(out, len(entries))


def _draw_class(task: tuple[str, str, int, str, str]) -> str:
    """One class's picture and viewer page, each only if missing (a job for a worker)."""
    from polyloops.core.canonical import from_signature
    from polyloops.render.polycube import write_thumbnail
    from polyloops.render.viewer import write_viewer

    signature, name, corners, picture, page = task
    ls = from_signature(signature)
    if not Path(picture).exists():
        write_thumbnail(ls, picture)
    if not Path(page).exists():
        write_viewer(ls, page, title=f"{name}: {corners} corners", plotly_js="directory")
    return name


def gallery_html(rows: list[dict[str, object]], title: str, class_pages: bool = True, genus: int = 0) -> str:
    """The gallery's index page: the rows as data inside it, filters and cards drawn by a
    small script (no library, nothing loaded from elsewhere); each card leads to its class's
    page (``class_pages``) or else to its viewer."""
    from importlib.resources import files

    page = files("polyloops.render").joinpath("gallery.html").read_text(encoding="utf-8")
    data = json.dumps(rows, separators=(",", ":")).replace("</", "<\\/")
    moves = ('<p><a href="moves.html">The move graph</a>: every class by corners, loop removals as '
             "edges; each class's page shows its moves and its way down to "
             + ("the base of its hole orientation (one class of each orientation type with fewest "
                "corners: moves never change it)" if genus else "the cube") + ".</p>"
             if class_pages else "")
    return (page.replace("@TITLE@", html.escape(title))
            .replace("@MOVES@", moves)
            .replace("@PAGE@", "class/" if class_pages else "view/")
            .replace("@CATEGORIES@", json.dumps([str(c) for c in CATEGORIES]))
            .replace("@DATA@", data))
