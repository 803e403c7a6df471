"""``polyloops segment --guide`` over a folder of meshes, guided by their naive and graph-cut
labellings.

For each mesh (``.stl``, ``.obj``, ``.mesh`` in DIR and its subfolders) and each guide (the
per-triangle labelling and the graph-cut one, :mod:`polyloops.segment.labellings`): the
checker's verdict on the guide, then ``segment`` with that guide (the given budget and seed):
whether its output is certified, the share of the area it labels otherwise than the guide
("changed"; 0 when a valid guide is kept), its fidelity, charts, and wall time.  One Markdown
table per subfolder.

Usage: python benchmarks/guide.py DIR [--budget SECONDS] [--seed N] [--only NAME ...] [--workers K]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import mesh_benchmark_parser, print_tables_by_folder

from polyloops.io.labelled_mesh import read_triangle_mesh
from polyloops.segment.labellings import graphcut_labels, naive_labels
from polyloops.segment.run import segment_surface
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.surface.mesh import LabelledMesh

VERDICT = {True: "valid", False: "INVALID", None: "undecided"}


def rows(path: Path, budget: float, seed: int, workers: int = 1) -> list[list[object]]:
    s = surface_of(*read_triangle_mesh(path))
    out: list[list[object]] = []
    points, triangles = tuple(map(tuple, s.points.tolist())), tuple(map(tuple, s.triangles.tolist()))
    for name, labels in (("naive", naive_labels(s)), ("graph-cut", graphcut_labels(s))):
        mesh = LabelledMesh(points, triangles, labels)
        verdict = VERDICT[check_segmentation(mesh).valid]
        start = time.perf_counter()
        try:
            done = segment_surface(s, budget=budget, seed=seed, guide=labels, workers=workers)
        except Exception as err:  # a benchmark reports every failure in its row
            out.append([path.stem, len(s.triangles), s.genus, name, verdict, f"none ({type(err).__name__})",
                        "", "", "", f"{time.perf_counter() - start:.1f}"])
            continue
        out.append([path.stem, len(s.triangles), s.genus, name, verdict, "certified",
                    f"{done.guide_changed:.4f}", f"{done.fidelity:.4f}", done.charts,
                    f"{time.perf_counter() - start:.1f}"])
    return out


def main() -> None:
    args = mesh_benchmark_parser(__doc__.split("\n\n")[0]).parse_args()
    header = ["mesh", "triangles", "genus", "guide", "guide verdict", "segment --guide", "changed",
              "fidelity", "charts", "s"]
    print_tables_by_folder(args.folder, args.only, header,
                           lambda p: rows(p, args.budget, args.seed, args.workers))

if __name__ == "__main__":
    main()
