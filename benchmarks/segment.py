"""``polyloops segment`` over a folder of meshes, beside the naive and graph-cut labellings.

For each mesh (``.stl``, ``.obj``, ``.mesh`` in DIR and its subfolders): the per-triangle
(naive) labelling, the graph-cut labelling (:mod:`polyloops.segment.labellings`, compactness 1)
and ``segment`` (the given budget, seed, price and floor), each judged by the checker: its verdict (``valid``,
``INVALID``, ``undecided``), its fidelity (area-weighted mean of n . label), the charts, and the
wall time.  The naive fidelity is the bound no labelling exceeds; "gap" is the bound less the
fidelity; "backwards" the share of segment's boundary length that runs against its polycube
edge's direction; "converged" says whether segment's search ended with no improving move (else the
budget stopped it); "start" how its search began (the cube, a grid of sections, or a start given
by ``--start MESH=START``, which is what ``segment --start START`` takes).  One Markdown table per
subfolder, then a summary per subfolder (``--summarize FILE`` prints only the summary of an
earlier run's output, to set runs side by side).

Usage: python benchmarks/segment.py DIR [--budget SECONDS] [--seed N] [--only NAME ...]
       [--start MESH=START ...] [--price P] [--floor valid|repaired]
       python benchmarks/segment.py DIR --summarize FILE
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table, mesh_benchmark_parser, print_tables_by_folder

from polyloops.cli.segment import read_start
from polyloops.io.labelled_mesh import read_triangle_mesh
from polyloops.segment import PRICE, Floor
from polyloops.segment.labellings import fidelity, graphcut_labels, naive_labels
from polyloops.segment.run import segment_surface
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.segmentation.quality import backwards_fraction
from polyloops.surface.mesh import LabelledMesh

VERDICT = {True: "valid", False: "INVALID", None: "undecided"}


def judged(s, labels) -> tuple[str, float, int]:
    mesh = LabelledMesh(tuple(map(tuple, s.points.tolist())), tuple(map(tuple, s.triangles.tolist())), labels)
    report = check_segmentation(mesh)
    return VERDICT[report.valid], fidelity(s, labels), len(report.segmentation.charts)


def share(x: float | None) -> str:
    return "" if x is None else f"{x:.4f}"


def row(path: Path, budget: float, seed: int, start_arg: str | None, workers: int = 1,
        price: float = PRICE, floor: Floor = Floor.REPAIRED, merge: bool = False) -> list[object]:
    s = surface_of(*read_triangle_mesh(path))
    naive = judged(s, naive_labels(s))
    start = time.perf_counter()
    cut = judged(s, graphcut_labels(s))
    cut_time = time.perf_counter() - start
    bound = naive[1]  # the naive fidelity: no labelling is more faithful
    out: list[object] = [path.stem, len(s.triangles), s.genus, f"{bound:.4f}", naive[0], naive[2],
                         cut[0], f"{cut[1]:.4f}", cut[2], f"{cut_time:.1f}"]
    start = time.perf_counter()
    try:
        done = segment_surface(s, budget=budget, seed=seed, price=price, bound=floor,
                               start=read_start(start_arg) if start_arg else None, workers=workers,
                               merge=merge)
    except Exception as err:  # a benchmark reports every failure in its row
        took = time.perf_counter() - start
        return [*out, f"none ({type(err).__name__})", "", "", "", "", "", "", f"{took:.1f}",
                f"given {start_arg}" if start_arg else ""]
    took = time.perf_counter() - start
    gap = bound - done.fidelity
    return [*out, "certified", f"{done.fidelity:.4f}", f"{gap:.4f}", done.charts, done.loops,
            share(backwards_fraction(done.report)), "yes" if done.converged else "no", f"{took:.1f}",
            done.start.replace("the given start", f"given {start_arg}")]


HEADER = ["mesh", "triangles", "genus", "naive fidelity (bound)", "naive", "naive charts", "graph-cut",
          "graph-cut fidelity", "graph-cut charts", "graph-cut s", "segment", "fidelity", "gap", "charts",
          "loops", "backwards", "converged", "segment s", "start"]


def read_rows(text: str) -> list[tuple[str, dict[str, str]]]:
    """The rows of an earlier output of this script, each with its subfolder."""
    out, folder = [], ""
    for line in text.splitlines():
        if line.startswith("### "):
            folder = line[4:].strip()
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.startswith("| ") and len(cells) == len(HEADER) and cells[0] != "mesh":
            out.append((folder, dict(zip(HEADER, cells, strict=True))))
    return out


def _medians(rows: list[dict[str, str]], cut_rows: list[dict[str, str]] | None = None) -> str:
    """Median charts: segment's over ``rows``, the graph-cut labelling's over ``cut_rows``
    (``rows`` unless given); empty without rows."""
    cut_rows = rows if cut_rows is None else cut_rows
    if not rows or not cut_rows:
        return ""
    return (f"{statistics.median(int(r['charts']) for r in rows):g} / "
            f"{statistics.median(int(r['graph-cut charts']) for r in cut_rows):g}")


def summary(rows: list[tuple[str, dict[str, str]]]) -> str:
    """Per subfolder: meshes, certified, mean gap, median charts (segment / graph-cut; over all
    the meshes, and over those whose graph-cut labelling is valid), how many
    graph-cut labellings are valid and on how many of those segment is at least as faithful,
    how often the mesh's own labelling is the output, mean backwards share, longest run; then
    the mean gap of the genus-0 meshes."""
    table = []
    for folder in sorted({f for f, _ in rows}):
        mine = [r for f, r in rows if f == folder]
        done = [r for r in mine if r["segment"] == "certified"]
        valid_cut = [r for r in done if r["graph-cut"] == "valid"]
        at_least = sum(float(r["fidelity"]) >= float(r["graph-cut fidelity"]) - 5e-5 for r in valid_cut)
        kept = ("the per-triangle labelling", "the graph-cut labelling")
        own = sum(r["start"].startswith(kept) for r in done)
        gaps = [float(r["gap"]) for r in done]
        table.append([folder, len(mine), len(done), f"{statistics.mean(gaps):.4f}" if gaps else "",
                      _medians(done, mine), _medians(valid_cut), len(valid_cut),
                      f"{at_least} of {len(valid_cut)}", own,
                      f"{statistics.mean(float(r['backwards']) for r in done):.3f}" if done else "",
                      f"{max(float(r['segment s']) for r in mine):.1f} s"])
    valid = [r for _, r in rows if r["segment"] == "certified" and r["graph-cut"] == "valid"]
    genus0 = [float(r["gap"]) for _, r in rows if r["segment"] == "certified" and r["genus"] == "0"]
    tail = ""
    if genus0:
        tail = f"\n\nMean gap over the {len(genus0)} genus-0 meshes: {statistics.mean(genus0):.4f}"
    if valid:
        tail += (f"\n\nMedian charts over the {len(valid)} meshes whose graph-cut labelling is valid "
                 f"(segment / graph-cut): {_medians(valid)}")
    return markdown_table(["folder", "meshes", "certified", "mean gap", "median charts (segment / graph-cut)",
                           "the same where graph-cut is valid", "graph-cut valid",
                           "segment at least graph-cut where valid", "mesh's own labelling kept",
                           "mean backwards", "longest run"], table) + tail


def main() -> None:
    parser = mesh_benchmark_parser(__doc__.split("\n\n")[0])
    parser.add_argument("--start", action="append", default=[], metavar="MESH=START",
                        help="begin segment on mesh MESH (its stem) from START, as segment --start")
    parser.add_argument("--price", type=float, default=PRICE, help=f"as segment --price (default {PRICE:g})")
    parser.add_argument("--floor", choices=[f.value for f in Floor], default=Floor.REPAIRED.value,
                        help="as segment --floor (default repaired)")
    parser.add_argument("--merge", action="store_true", help="as segment --merge")
    parser.add_argument("--summarize", type=Path, metavar="FILE",
                        help="print only the summary of FILE, an earlier output of this script")
    args = parser.parse_args()
    if args.summarize is not None:
        try:
            text = args.summarize.read_text()
        except (OSError, UnicodeDecodeError) as err:
            parser.error(f"{args.summarize}: cannot read: {getattr(err, 'strerror', None) or err}")
        rows_read = read_rows(text)
        if not rows_read:
            parser.error(f"{args.summarize}: no table of this script in it")
        print(summary(rows_read))
        return
    starts = dict(item.split("=", 1) for item in args.start)
    rows: list[tuple[str, dict[str, str]]] = []

    def measured(p: Path) -> list[list[object]]:
        found = row(p, args.budget, args.seed, starts.get(p.stem), args.workers, args.price,
                    Floor(args.floor), args.merge)
        rows.append((p.parent.name, dict(zip(HEADER, map(str, found), strict=True))))
        return [found]

    print_tables_by_folder(args.folder, args.only, HEADER, measured)
    print("\n### Summary\n")
    print(summary(rows))

if __name__ == "__main__":
    main()
