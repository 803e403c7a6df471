"""``polyloops segment`` beside segmentations made by another tool, on that tool's own meshes.

DIR holds pairs ``NAME.obj`` (a refined mesh) and ``NAME.flag`` (one label 0..5 per triangle,
the ``.flag`` convention), such as the DualCube outputs the paper's authors ship.  For each
pair: the per-triangle bound; the given labels judged by the checker (verdict, fidelity,
charts, and the loops of the checker's realising polycube); the graph-cut labelling judged the
same way; and ``segment`` on the same mesh (the given budget, seed and workers), with the
default floor and with ``--floor valid``: its fidelity, charts, loops, wall time and start.
One Markdown table.

Usage: python benchmarks/dualcube.py DIR [--budget SECONDS] [--seed N] [--only NAME ...] [--workers K]
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import mesh_benchmark_parser

from polyloops.core.duality import dualize
from polyloops.io.labelled_mesh import read_labels, read_triangle_mesh
from polyloops.segment import Floor
from polyloops.segment.labellings import fidelity, graphcut_labels, naive_fidelity
from polyloops.segment.run import segment_surface
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.surface.mesh import LabelledMesh

VERDICT = {True: "valid", False: "INVALID", None: "undecided"}


def judged(s, labels) -> str:
    """The checker's verdict, the fidelity, the charts and (when valid) the loops."""
    mesh = LabelledMesh(tuple(map(tuple, s.points.tolist())), tuple(map(tuple, s.triangles.tolist())), labels)
    report = check_segmentation(mesh)
    loops = "" if report.polycube is None else f", {len(dualize(report.polycube).loops)}"
    return f"{VERDICT[report.valid]}, {fidelity(s, labels):.4f}, {len(report.segmentation.charts)}{loops}"


def row(obj: Path, budget: float, seed: int, workers: int) -> list[object]:
    s = surface_of(*read_triangle_mesh(obj))
    given = read_labels(obj.with_suffix(".flag"), len(s.triangles))
    cells: list[object] = [obj.stem, len(s.triangles), f"{naive_fidelity(s):.4f}", judged(s, given),
                           judged(s, graphcut_labels(s))]
    for bound in (Floor.REPAIRED, Floor.VALID):
        began = time.perf_counter()
        done = segment_surface(s, budget=budget, seed=seed, workers=workers, bound=bound)
        took = time.perf_counter() - began
        cells.append(f"{done.fidelity:.4f}, {done.charts}, {done.loops}, {took:.1f}, {done.start}")
    return cells


def main() -> None:
    args = mesh_benchmark_parser(__doc__.split("\n\n")[0]).parse_args()
    pairs = sorted(p for p in args.folder.glob("*.obj") if p.with_suffix(".flag").exists()
                   and (not args.only or p.stem in args.only))
    print("| mesh | triangles | per-triangle bound | given: verdict, fidelity, charts, loops "
          "| graph-cut: verdict, fidelity, charts, loops | polyloops: fidelity, charts, loops, s, from "
          "| polyloops --floor valid: the same |")
    print("|---|---:|---:|---|---|---|---|")
    for obj in pairs:
        cells = row(obj, args.budget, args.seed, args.workers)
        print("| " + " | ".join(str(x) for x in cells) + " |", flush=True)


if __name__ == "__main__":
    main()
