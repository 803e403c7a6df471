"""The gallery's pages that walk the move graph: one page per class, and an overview.

``class/NAME.html`` shows a class with its removable loops (each linked to the class it
leaves, with its thumbnail, and to the viewer with that loop highlighted: ``view/NAME.html#loop-N``),
the classes one addition above it within the gallery, and its way down to the cube as a strip
of thumbnails, a detour of the reachability certificate step by step where no loop can be
removed (:mod:`polyloops.reach.move_graph`).  ``moves.html`` draws the whole graph in
layers by corners, removals as edges, every class a link, with a filter by corners.  All
static: no script loads anything.
"""

from __future__ import annotations

import html
from pathlib import Path

from polyloops.catalog.census import CatalogEntry
from polyloops.core.words import plural
from polyloops.io.files import write_atomic
from polyloops.reach.move_graph import Descent, MoveGraph

STYLE = """body { font-family: system-ui, sans-serif; margin: 1.2em; color: #222; max-width: 1100px; }
h1 { font-size: 1.4em; margin: 0 0 .3em; } h2 { font-size: 1.1em; margin: 1.2em 0 .4em; }
.row { display: flex; flex-wrap: wrap; gap: .6em; align-items: flex-start; }
.cell { width: 130px; font-size: .8em; text-align: center; }
.cell img { width: 130px; height: 130px; border: 1px solid #ddd; border-radius: 4px; }
.strip .cell { width: 120px; } .strip img { width: 120px; height: 120px; }
.move { font-size: .75em; color: #555; min-height: 2.4em; }
.detour img { border-color: #e66101; } .note { color: #555; font-size: .9em; }
.x { color: #7b3294; } .y { color: #e66101; } .z { color: #1a9641; }"""


def _page(title: str, body: str) -> str:
    return (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{html.escape(title)}"
            f"</title>\n<style>{STYLE}</style></head>\n<body>\n{body}\n</body></html>\n")


def _cell(name: str, caption: str = "", image: str | None = None, link: bool = True) -> str:
    img = f'<img src="{image or f"../img/{name}.png"}" alt="{html.escape(name)}" loading="lazy">'
    label = html.escape(name)
    inner = f'<a href="{name}.html">{img}<br>{label}</a>' if link else f"{img}<br>{label}"
    extra = f'<div class="move">{caption}</div>' if caption else ""
    return f'<div class="cell">{inner}{extra}</div>'


def class_page(entry: CatalogEntry, graph: MoveGraph, listed: set[str],
               step_images: dict[tuple[str, int], str]) -> str:
    """The page of one class (links only to classes in ``listed``; ``step_images`` holds the
    pictures of detour steps outside the gallery, by class and step)."""
    r = entry.record
    name = entry.name
    loops = " ".join(f'<span class="{a.lower()}">{a}:{n}</span>' for a, n in r.loops.items())
    parts = ['<p><a href="../index.html">all classes</a> · <a href="../moves.html">the move graph</a></p>',
             f"<h1>{html.escape(name)}</h1>",
             f"<p>{r.corners} corners, {r.faces} faces; loops {loops}; "
             f"{'chiral' if r.chiral else 'achiral'}; |Aut| {r.automorphisms}"
             f"{'; <b>irreducible</b> (no loop can be removed)' if r.irreducible else ''}</p>",
             f'<div class="row"><a href="../view/{name}.html"><img src="../img/{name}.png" alt="{name}" '
             f'width="240" height="240"></a><p class="note">Turn it in the <a href="../view/{name}.html">'
             f"3D viewer</a>.</p></div>"]
    removals = graph.removals.get(name, ())
    parts.append(f"<h2>Removable loops ({len(removals)})</h2>")
    if removals:
        cells = []
        for rm in removals:
            caption = (f'remove <span class="{rm.axis.lower()}">{rm.axis}-loop {rm.loop}</span> '
                       f'(<a href="../view/{name}.html#loop-{rm.loop}">see it</a>)')
            if rm.leaves is not None and rm.leaves in listed:
                cells.append(_cell(rm.leaves, caption))
            else:
                cells.append(f'<div class="cell">{caption}<br>leaves a class outside the gallery</div>')
        parts.append(f'<div class="row removals">{"".join(cells)}</div>')
    else:
        parts.append('<p class="note">None: every loop is needed.</p>')
    above = [a for a in graph.above.get(name, ()) if a in listed]
    parts.append(f"<h2>One addition above, within the gallery ({len(above)})</h2>")
    parts.append(f'<div class="row above">{"".join(_cell(a) for a in above)}</div>' if above
                 else '<p class="note">None within the gallery.</p>')
    start = _start(name, graph)
    parts.append(_shortest_html(name, graph, listed, start))
    descent = graph.descents.get(name)
    parts.append(_descent_html(name, descent, listed, step_images, start))
    return _page(f"{name}: {r.corners} corners", "\n".join(parts))


def _start(name: str, graph: MoveGraph) -> str:
    """What the ways start from: the cube, or at genus 1 the base of the class's orientation
    type (named when its way is known)."""
    if graph.genus:
        path = graph.path_from_cube(name)
        base = path[0] if path else None
        return (f"the base of its hole orientation ({html.escape(base)})" if base
                else "the base of its hole orientation")
    return "the cube"


def _shortest_html(name: str, graph: MoveGraph, listed: set[str], start: str = "the cube") -> str:
    path = graph.path_from_cube(name)
    if not path:
        return (f'<h2>From {start}</h2><p class="note">Not reachable by moves that stay among the '
                "gallery's classes: every way to it passes through larger structures (see its way "
                "down below).</p>")
    cells = []
    for before, here in zip((None, *path), path, strict=False):
        if before is None:
            caption = start.split(" (")[0]
        else:
            down = next((r for r in graph.removals[before] if r.leaves == here), None)
            up = next((r for r in graph.removals[here] if r.leaves == before), None)
            caption = (f"remove {down.axis}-loop {down.loop}" if down is not None
                       else f"add its {up.axis}-loop {up.loop}" if up is not None else "")
        cells.append(_cell(here, caption))
    return (f'<h2>From {start}: {plural(len(path) - 1, "move")}</h2><p class="note">A shortest path of loop '
            f"moves among the gallery's classes (breadth first; so within their range of corners: a "
            f"path through larger structures could be shorter).</p><div class=\"row shortest\">"
            f"{''.join(cells)}</div>")


def _descent_html(name: str, descent: Descent | None, listed: set[str],
                  step_images: dict[tuple[str, int], str], start: str = "the cube") -> str:
    if descent is None:
        return (f'<h2>To {start}</h2><p class="note">No way down is known here (no removable loop, '
                "and no certificate detour in this catalog).</p>")
    cells = []
    for k, step in enumerate(descent.steps):
        caption = "" if step.move is None else html.escape(str(step.move))
        corners = step.structure.map.num_corners
        caption = f"{caption}<br>{corners} corners" if caption else f"{corners} corners"
        if step.name is not None and step.name in listed:
            cells.append(_cell(step.name, caption))
        else:
            image = step_images.get((name, k))
            img = f'<img src="{image}" alt="step {k}">' if image else ""
            cells.append(f'<div class="cell detour">{img}<br>step {k}<div class="move">{caption}</div></div>')
    climbs = any(s.move is not None and s.move.kind.value == "add" for s in descent.steps)
    note = (" It climbs first: the detour of the reachability certificate, through larger structures "
            "to a smaller class, then removals." if climbs else " Each step removes a loop.")
    return (f"<h2>To {start}: {plural(descent.moves, 'move')}</h2><p class=\"note\">A way down with the "
            f"fewest moves among removals and the certificate's detours (not necessarily a shortest path of "
            f"the move graph).{note}</p><div class=\"row strip\">{''.join(cells)}</div>")


def moves_page(entries: list[CatalogEntry], graph: MoveGraph, title: str) -> str:
    """The overview: classes in layers by corners (a circle each, a link to its page),
    removals as edges, and a filter that shows the layers up to a number of corners."""
    layers: dict[int, list[str]] = {}
    for e in entries:
        layers.setdefault(e.corners, []).append(e.name)
    width, gap = 1100, 46
    pos = {}
    for row, (corners, names) in enumerate(sorted(layers.items())):
        for i, n in enumerate(names):
            pos[n] = (20 + (width - 40) * (i + 0.5) / len(names), 30 + gap * row, corners)
    height = 60 + gap * len(layers)
    edges = []
    for name, found in graph.removals.items():
        for rm in found:
            if name in pos and rm.leaves in pos:
                (x1, y1, c1), (x2, y2, _) = pos[name], pos[rm.leaves]
                edges.append(f'<line x1="{x1:.1f}" y1="{y1}" x2="{x2:.1f}" y2="{y2}" data-c="{c1}"/>')
    irreducible = {e.name for e in entries if e.record.irreducible}
    orange = ' fill="#e66101"'
    nodes = [f'<a href="class/{n}.html" data-c="{c}"><circle cx="{x:.1f}" cy="{y}" r="4"'
             f'{orange if n in irreducible else ""}><title>{n}</title></circle></a>'
             for n, (x, y, c) in pos.items()]
    labels = [f'<text x="2" y="{30 + gap * row + 4}" font-size="11">{c}</text>'
              for row, c in enumerate(sorted(layers))]
    options = "".join(f'<option value="{c}"{" selected" if c == _default(layers) else ""}>{c}</option>'
                      for c in sorted(layers))
    body = f"""<p><a href="index.html">all classes</a></p><h1>{html.escape(title)}: the move graph</h1>
<p class="note">Each circle is a class (corners downwards; hover for its name, click for its page);
each line a loop removal from a class to the class it leaves. The cube is at the top; orange
circles are irreducible (no loop can be removed: their way down is a certificate's detour).</p>
<label>show classes up to <select id="upto">{options}</select> corners</label>
<svg id="graph" viewBox="0 0 {width} {height}" width="100%">
<g stroke="#aaa" stroke-width="0.6">{''.join(edges)}</g>
<g fill="#333">{''.join(nodes)}</g><g fill="#555">{''.join(labels)}</g></svg>
<script>
function show() {{
  const upto = Number(document.getElementById("upto").value);
  for (const el of document.querySelectorAll("#graph [data-c]"))
    el.style.display = Number(el.dataset.c) <= upto ? "" : "none";
}}
document.getElementById("upto").onchange = show; show();
</script>"""
    return _page(f"{title}: the move graph", body)


def _default(layers: dict[int, list[str]]) -> int:
    """The largest corner count whose classes, with all below, stay readable (a few hundred)."""
    total, best = 0, min(layers)
    for c in sorted(layers):
        total += len(layers[c])
        if total > 400:
            break
        best = c
    return best


def write_class_pages(out: Path, entries: list[CatalogEntry], graph: MoveGraph, title: str) -> None:
    """``class/NAME.html`` for every entry, their detour steps' pictures, and ``moves.html``."""
    from polyloops.render.polycube import write_thumbnail

    (out / "class").mkdir(exist_ok=True)
    listed = {e.name for e in entries}
    step_images: dict[tuple[str, int], str] = {}
    for e in entries:
        descent = graph.descents.get(e.name)
        for k, step in enumerate(descent.steps if descent is not None else ()):
            if step.name is None or step.name not in listed:
                picture = out / "img" / "steps" / f"{e.name}-{k}.png"
                if not picture.exists():
                    picture.parent.mkdir(exist_ok=True)
                    write_thumbnail(step.structure, picture)
                step_images[(e.name, k)] = f"../img/steps/{e.name}-{k}.png"
    for e in entries:
        write_atomic(out / "class" / f"{e.name}.html", class_page(e, graph, listed, step_images), within=out)
    write_atomic(out / "moves.html", moves_page(entries, graph, title), within=out)
