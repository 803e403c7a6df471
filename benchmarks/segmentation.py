"""Labelled segmentations: time each stage against the number of triangles.

A random polycube's quads are each cut into s x s squares of two triangles and labelled by
their normals, so the charts stay the same while the mesh grows as s^2; a second series grows
the polycube instead (more charts at two triangles per quad).  Times are CPU seconds, best of
three, for segmenting (charts, boundaries, corners), the local criteria, the global test with
the solver alone (the mesh's own directions are not tried first) and with them tried first (as
``check_segmentation`` does), and the realisation from the solver's directions.

Usage: python benchmarks/segmentation.py [--max-s S]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table, timed_cpu

from polyloops.core.polycube import Polycube
from polyloops.segmentation import check_global, check_local, realise, segment
from polyloops.surface.mesh import LabelledMesh
from strategies import random_polycube


def subdivided(q: Polycube, s: int) -> LabelledMesh:
    """Each quad as an s x s grid of squares, two triangles each, labelled by its normal."""
    points: list[tuple[float, float, float]] = []
    index: dict[tuple[float, float, float], int] = {}

    def point(p) -> int:
        key = tuple(round(x, 9) for x in p)
        if key not in index:
            index[key] = len(points)
            points.append(key)
        return index[key]

    triangles, labels = [], []
    for f, (a, b, _, d) in enumerate(q.faces):
        pa, pb, pd = (q.positions[i] for i in (a, b, d))
        label = q.face_normal(f)
        assert label is not None  # a polycube's faces are axis-parallel

        def at(i: int, j: int, pa=pa, pb=pb, pd=pd):
            return tuple(pa[k] + i / s * (pb[k] - pa[k]) + j / s * (pd[k] - pa[k]) for k in range(3))

        for i in range(s):
            for j in range(s):
                p00, p10, p11, p01 = (point(at(i, j)), point(at(i + 1, j)), point(at(i + 1, j + 1)),
                                      point(at(i, j + 1)))
                triangles += [(p00, p10, p11), (p00, p11, p01)]
                labels += [label, label]
    return LabelledMesh(tuple(points), tuple(triangles), tuple(labels))


def row(q: Polycube, s: int) -> list:
    mesh = subdivided(q, s)
    t_seg, seg = timed_cpu(lambda: segment(mesh), 3)
    t_local, _ = timed_cpu(lambda: check_local(seg), 3)
    t_global, result = timed_cpu(lambda: check_global(seg, try_mesh_first=False), 3)
    t_real, real = timed_cpu(lambda: realise(seg, result), 3)
    t_mesh, _ = timed_cpu(lambda: check_global(seg), 3)
    return [q.map.num_corners, s, len(mesh.triangles), len(seg.charts), t_seg, t_local, t_global, t_mesh,
            t_real, "yes" if real.polycube is not None else "undecided"]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-s", type=int, default=16)
    args = parser.parse_args()
    header = ["corners", "s", "triangles", "charts", "segment s", "local s", "global s (solver)",
              "global s (mesh first)", "realise s", "realised"]
    q = random_polycube(3, "frame1", 30)
    rows = [row(q, s) for s in (1, 2, 4, 8, 16, 32) if s <= args.max_s]
    rows += [row(random_polycube(5, "smooth", size), 1) for size in (20, 80, 320)]
    print(markdown_table(header, rows))


if __name__ == "__main__":
    main()
