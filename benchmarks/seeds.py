"""Seeds of ``polyloops segment``: a valid graph-cut labelling's loops, recovered and laid out.

For each mesh of a folder whose graph-cut labelling the checker finds valid: the loops of its
realising polycube, drawn through the surface's map onto it (``polyloops.segment.seeds``), read
off the surface and compared with the polycube's own structure (``same``: isomorphic); then
the layout of those loops (the one that follows the labels), polished as every finalist is,
beside the graph-cut labelling: the fidelity of each, and the shortfall of the layout.  This
measures the layout alone, on a structure known to carry a labelling as good as the graph-cut
one.  One Markdown table per subfolder, then the summary.

Usage: python benchmarks/seeds.py FOLDER [--only NAME ...]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import _folder, print_tables_by_folder

from polyloops.core.canonical import is_isomorphic
from polyloops.core.duality import dualize
from polyloops.io.labelled_mesh import read_triangle_mesh
from polyloops.segment.embedded import read_structure
from polyloops.segment.labellings import fidelity, graphcut_labels
from polyloops.segment.layout import lay_out
from polyloops.segment.polish import polish_layout
from polyloops.segment.seeds import seed_start
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation

HEADER = ["mesh", "triangles", "genus", "loops", "same", "graph-cut", "laid out", "polished", "shortfall",
          "s"]
SHORTFALLS: list[tuple[str, float]] = []


def rows(path: Path) -> list[list[object]]:
    s = surface_of(*read_triangle_mesh(path))
    labels = graphcut_labels(s)
    report = check_segmentation(s.labelled(labels))
    if report.valid is not True or report.polycube is None:
        return []
    began = time.perf_counter()
    r, loops, chosen, _ = seed_start(s, labels, "graph-cut", report)
    chosen_loops = [loops[i] for i in chosen]
    same = is_isomorphic(read_structure(r, chosen_loops).structure, dualize(report.polycube))
    lay = lay_out(r, chosen_loops)
    polished = polish_layout(lay)
    took = time.perf_counter() - began
    own = fidelity(s, labels)
    laid = fidelity(lay.embedded.refined.surface, lay.labels)
    shine = fidelity(polished.embedded.refined.surface, polished.labels)
    SHORTFALLS.append((path.stem, own - shine))
    return [[path.stem, len(s.triangles), s.genus, len(chosen), "yes" if same else "NO", f"{own:.4f}",
             f"{laid:.4f}", f"{shine:.4f}", f"{own - shine:.4f}", f"{took:.1f}"]]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", type=_folder)
    parser.add_argument("--only", nargs="*", help="mesh names (stems) to run")
    args = parser.parse_args()
    print_tables_by_folder(args.folder, args.only, HEADER, rows)
    if SHORTFALLS:
        values = [v for _, v in SHORTFALLS]
        worst = max(SHORTFALLS, key=lambda nv: nv[1])
        print(f"\n{len(values)} meshes with a valid graph-cut labelling; shortfall of the polished layout: "
              f"mean {sum(values) / len(values):.4f}, within 0.005 on {sum(v <= 0.005 for v in values)}, "
              f"most {worst[1]:.4f} ({worst[0]})")


if __name__ == "__main__":
    main()
