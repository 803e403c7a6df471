"""Kernel operations against size: 10^3 to 10^5 faces, four families, growth exponents.

Families: boxes (their surface built directly, as a box of 10^5 faces has 2 million unit
cubes), slabs (n x n x 1), random height fields (n x n columns of 1 to 4 cubes) and random
blobs of higher genus (a slab with square holes and random bumps).  For each structure every
kernel operation runs on fresh objects (no cached zones or loops), best of ``--repeat`` runs,
timed in CPU seconds (``time.process_time``: one process, so one core) and in wall seconds.
The growth exponent of each operation is the slope of log time against log faces between
the two largest sizes of a family, and over all sizes.

With ``--shuffled`` every polycube is renumbered first as another program might write it
(corners at random, faces in random order, each from a random corner), so that the kernels
run on a numbering without locality, as on files written elsewhere.

Usage: python benchmarks/scaling.py [--max-faces N] [--repeat R] [--families ...] [--shuffled]
       [--plot FILE]
"""

from __future__ import annotations

import argparse
import math
import random
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table

from polyloops.core.canonical import canonical_form
from polyloops.core.directions import Axis
from polyloops.core.duality import dualize, primalize
from polyloops.core.halfedge import HalfEdgeMap
from polyloops.core.moves import additions, removals
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.shapes.voxels import polycube_from_voxels
from polyloops.verify import check_polycube, verify


def box_surface(a: int, b: int, c: int) -> Polycube:
    """The surface of the a x b x c box as unit quads, built directly (no cubes)."""
    index: dict[tuple[int, int, int], int] = {}
    positions: list[tuple[int, int, int]] = []

    def corner(p: tuple[int, int, int]) -> int:
        if p not in index:
            index[p] = len(positions)
            positions.append(p)
        return index[p]

    size = (a, b, c)
    faces = []
    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3  # (axis, u, v) right-handed
        for side in (0, size[axis]):
            for i in range(size[u]):
                for j in range(size[v]):
                    ring = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0, 0, 0]
                        p[axis], p[u], p[v] = side, i + du, j + dv
                        ring.append(corner((p[0], p[1], p[2])))
                    faces.append(ring if side else ring[::-1])  # counter-clockwise from outside
    return Polycube.from_faces(faces, positions)


def slab(n: int) -> Polycube:
    return polycube_from_voxels([(x, y, 0) for x in range(n) for y in range(n)])


def height_field(n: int, seed: int = 1) -> Polycube:
    """Columns of height 1 + f(x) + g(y), f and g random non-decreasing steps: terraces
    without saddles (where two diagonal columns rise above the other two, the surface of the
    cubes would meet itself)."""
    rng = random.Random(seed)
    f = [0] * n
    g = [0] * n
    for i in range(1, n):
        f[i] = f[i - 1] + (rng.random() < 0.15)
        g[i] = g[i - 1] + (rng.random() < 0.15)
    cells = [(x, y, z) for x in range(n) for y in range(n) for z in range(1 + f[x] + g[y])]
    return polycube_from_voxels(cells)


def holey_blob(n: int, seed: int = 2) -> Polycube:
    """An n x n x 2 slab with about n^2 / 40 square holes and n^2 / 20 bumps (genus > 0)."""
    rng = random.Random(seed)
    holes = set()
    for _ in range(max(1, n * n // 40)):
        x, y = rng.randrange(2, n - 3, 4), rng.randrange(2, n - 3, 4)
        holes |= {(x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1)}
    cells = {(x, y, z) for x in range(n) for y in range(n) for z in range(2) if (x, y) not in holes}
    spots = [(x, y) for x in range(0, n, 2) for y in range(0, n, 2) if (x, y) not in holes]
    for x, y in rng.sample(spots, min(len(spots), n * n // 20)):
        cells.add((x, y, 2))
    return polycube_from_voxels(cells)


# family: (builder of a size parameter, faces as a function of it, to invert)
FAMILIES: dict[str, tuple[Callable[[int], Polycube], Callable[[int], float]]] = {
    "box": (lambda n: box_surface(n, n, n), lambda n: 6 * n * n),
    "slab": (slab, lambda n: 2 * n * n + 4 * n),
    "height field": (height_field, lambda n: 2 * n * n + 0.7 * n * n),
    "holey blob": (holey_blob, lambda n: 2.6 * n * n),
}


def shuffled(q: Polycube, seed: int = 5) -> Polycube:
    """``q`` renumbered without locality: corners at random, faces in random order, each
    from a random corner (the same polycube)."""
    rng = random.Random(seed)
    perm = list(range(q.map.num_corners))
    rng.shuffle(perm)
    positions = list(q.positions)
    for c, p in enumerate(q.positions):
        positions[perm[c]] = p
    faces = []
    for f in q.faces:
        k = rng.randrange(len(f))
        faces.append([perm[c] for c in (*f[k:], *f[:k])])
    rng.shuffle(faces)
    return Polycube(HalfEdgeMap.from_faces(faces), tuple(positions))


def parameter_for(family: str, faces: float) -> int:
    estimate = FAMILIES[family][1]
    n = 2
    while estimate(n + 1) <= faces:
        n += 1
    return max(n, 4)


def fresh(ls: LoopStructure) -> LoopStructure:
    """The same structure on a new map, so no cached loops, zones or arrays carry over."""
    return LoopStructure(HalfEdgeMap.from_faces(ls.map.faces), ls.axes, ls.signs)


def fresh_polycube(q: Polycube) -> Polycube:
    return Polycube(HalfEdgeMap.from_faces(q.faces), q.positions)


Operation = tuple[Callable[[], Any], Callable[[Any], object]]


def operations(q: Polycube, ls: LoopStructure) -> dict[str, Operation]:
    """name: (set-up outside the timer, the timed operation taking the set-up's result)."""
    return {
        "from_faces": (lambda: [list(f) for f in q.faces], HalfEdgeMap.from_faces),
        "Definition 1": (lambda: fresh_polycube(q), check_polycube),
        "dualize": (lambda: fresh_polycube(q), dualize),
        "Definition 4 (verify)": (lambda: fresh(ls), verify),
        "signature labelled": (lambda: fresh(ls), lambda s: canonical_form(s, "labelled")),
        "signature full": (lambda: fresh(ls), lambda s: canonical_form(s, "full")),
        "removal test, every loop": (lambda: fresh(ls), removals),
        "first addition, Z": (lambda: fresh(ls), lambda s: next(iter(additions(s, Axis.Z, limit=1)), None)),
        "primalize": (lambda: fresh(ls), primalize),
    }


def measure(setup, op, repeat: int) -> tuple[float, float]:
    best_cpu = best_wall = math.inf
    for _ in range(repeat):
        arg = setup()
        w, c = time.perf_counter(), time.process_time()
        op(arg)
        best_cpu = min(best_cpu, time.process_time() - c)
        best_wall = min(best_wall, time.perf_counter() - w)
    return best_cpu, best_wall


def _nearest(points: list[tuple[float, float]], size: float) -> tuple[float, float]:
    """The point whose size is nearest ``size`` on a log scale."""
    return min(points, key=lambda p: abs(math.log(p[0] / size)))


def slope(points: list[tuple[float, float]]) -> float:
    """Least-squares slope of log t against log n."""
    xs = [math.log(n) for n, _ in points]
    ys = [math.log(max(t, 1e-6)) for _, t in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    den = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys, strict=True)) / den if den else float("nan")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-faces", type=float, default=1e5)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--families", nargs="+", default=list(FAMILIES), choices=list(FAMILIES))
    parser.add_argument("--skip", nargs="*", default=[], help="operations to leave out")
    parser.add_argument("--plot", metavar="FILE", help="a log-log plot of CPU time against faces")
    parser.add_argument("--shuffled", action="store_true", help="renumber every polycube at random first")
    args = parser.parse_args()
    targets = [t for t in (1e3, 3e3, 1e4, 3e4, 1e5, 3e5) if t <= args.max_faces * 1.01]
    rows = []
    series: dict[tuple[str, str], list[tuple[float, float]]] = {}
    for family in args.families:
        for target in targets:
            q = FAMILIES[family][0](parameter_for(family, target))
            if args.shuffled:
                q = shuffled(q)
            ls = dualize(q)
            faces = q.map.num_faces
            for name, (setup, op) in operations(q, ls).items():
                if name in args.skip:
                    continue
                cpu, wall = measure(setup, op, args.repeat)
                series.setdefault((family, name), []).append((faces, cpu))
                rows.append([family, faces, q.genus, name, cpu, wall])
                print(f"{family:>12} {faces:>7} {name:<26} {cpu:9.4f} s CPU {wall:9.4f} s wall",
                      file=sys.stderr, flush=True)
    print(markdown_table(["family", "faces", "genus", "operation", "CPU s", "wall s"], rows))
    print()
    growth = []
    for (family, name), pts in series.items():
        near = [_nearest(pts, t) for t in (1e4, 1e5)]
        decade = slope(near) if near[0] != near[1] else float("nan")
        growth.append([family, name, f"{slope(pts):.2f}", f"{decade:.2f}", pts[-1][0], pts[-1][1]])
    print(markdown_table(["family", "operation", "exponent (all sizes)", "exponent (10^4 to 10^5)",
                          "largest faces", "CPU s there"], growth))
    if args.plot:
        plot(series, args.plot)


def plot(series, path: str) -> None:
    from polyloops.render.figure import new_figure, save_figure

    names = sorted({name for _, name in series})
    fig = new_figure(11, 7)
    axes = fig.subplots(3, 3).ravel()
    for ax, name in zip(axes, names, strict=False):
        for (family, op), pts in sorted(series.items()):
            if op == name:
                ax.loglog([p[0] for p in pts], [max(p[1], 1e-5) for p in pts], marker="o", label=family)
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("faces", fontsize=8)
        ax.set_ylabel("CPU s", fontsize=8)
        ax.tick_params(labelsize=7)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, path)


if __name__ == "__main__":
    main()
