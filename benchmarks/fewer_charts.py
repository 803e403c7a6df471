"""What fewer charts cost: per mesh, the certified labellings `segment` makes (every start's
result, default settings) and those its output's charts merged give (`polyloops.segment.merge`,
every step, whatever the price), and the least fidelity each number of charts costs among them.

    python benchmarks/fewer_charts.py ../shared/meshes --only B13 B30 B35 B38 --workers 2 --charts 12

One table: per mesh and number of charts, the most faithful certified labelling found with that
many charts or fewer, its gap to the per-triangle bound, loops and where it came from; then,
per mesh, the least gap at ``--charts`` charts or fewer (what a median of charts asks of it).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from _common import markdown_table, mesh_benchmark_parser, print_tables_by_folder

from polyloops.core.duality import dualize
from polyloops.io.labelled_mesh import read_triangle_mesh
from polyloops.segment.labellings import label_indices, naive_fidelity
from polyloops.segment.merge import merges
from polyloops.segment.run import segment_surface
from polyloops.segment.surface import Surface, surface_of

Found = tuple[int, float, int, str]  # charts, fidelity, loops, where it came from
HEADER = ["mesh", "charts (at most)", "fidelity", "gap", "loops", "from"]


def labellings(path: Path, budget: float, seed: int, workers: int) -> tuple[float, list[Found]]:
    """The per-triangle bound, and ``(charts, fidelity, loops, from)`` of every certified
    labelling found: each start's result, the output, and the output's merges."""
    s = surface_of(*read_triangle_mesh(path))
    done = segment_surface(s, budget=budget, seed=seed, workers=workers)
    found: list[Found] = [(c.charts, c.fidelity, c.loops, c.start) for c in done.candidates
             if c.certified and c.charts is not None and c.fidelity is not None and c.loops is not None]
    mesh = done.mesh
    own = Surface(np.asarray(mesh.points, dtype=float), np.asarray(mesh.triangles, dtype=np.int64))
    for k, step in enumerate(merges(own, label_indices(mesh.labels), least=-1.0, steps=40), start=1):
        assert step.report.polycube is not None  # a merge is returned only with its polycube
        found.append((step.charts, step.fidelity, len(dualize(step.report.polycube).loops),
                      f"the output, merged ({k} chart{'s' if k > 1 else ''} relabelled)"))
    return naive_fidelity(s), found


def main() -> None:
    parser = mesh_benchmark_parser(__doc__.split("\n\n")[0])
    parser.add_argument("--charts", type=int, default=12, help="the chart count asked for (default 12)")
    args = parser.parse_args()
    asked: list[list[object]] = []

    def rows_of(p: Path) -> list[list[object]]:
        bound, found = labellings(p, args.budget, args.seed, args.workers)
        out: list[list[object]] = []
        best_gap = None
        for charts in sorted({c for c, _, _, _ in found}):
            fewest = max((f for f in found if f[0] <= charts), key=lambda f: f[1])
            if out and out[-1][2] == f"{fewest[1]:.4f}":
                continue  # no more faithful than with fewer charts
            out.append([p.stem, charts, f"{fewest[1]:.4f}", f"{bound - fewest[1]:.4f}", fewest[2], fewest[3]])
            if charts <= args.charts:
                best_gap = bound - fewest[1]
        asked.append([p.stem, "" if best_gap is None else f"{best_gap:.4f}"])
        return out

    print_tables_by_folder(args.folder, args.only, HEADER, rows_of)
    print(f"\n### The least gap at {args.charts} charts or fewer\n")
    print(markdown_table(["mesh", "gap"], asked))


if __name__ == "__main__":
    main()
