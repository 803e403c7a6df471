"""Orientation solvers: time against k (free choices) and genus.

Instances are two slabs joined by p pillars (genus p - 1): every pillar's Z-loop is a free
choice, and acyclicity leaves only 2 of the 2^p choices, so exhaustive search has to try
them all.  A second series adds unit-cube bumps to a genus-0 block: free choices that
acyclicity never restricts.

Times are the best of three runs, after the problem's cached structure check has been computed
(so that no solver pays for it); SAT is also timed on a randomly renumbered copy, since the
builders number corners in a regular order that suits it.

Usage: python benchmarks/orient.py [--max-k K] [--brute-max K] [--plot FILE]
Prints a Markdown table; --plot draws time against k.
"""

from __future__ import annotations

import argparse
import random
import sys
from functools import partial
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table, timed

from polyloops.core.directions import Axis
from polyloops.shapes.voxels import polycube_from_voxels
from polyloops.solvers import OrientationProblem, make_solver
from polyloops.solvers.base import count, solve
from strategies import pillar_cells, renumbered


def solved(name: str, problem: OrientationProblem) -> object:
    """One orientation by solver ``name`` (its construction timed too)."""
    return solve(make_solver(name), problem)


def counted(name: str, problem: OrientationProblem) -> int:
    """The orientations counted by solver ``name`` (its construction timed too)."""
    return count(make_solver(name), problem)


def bumpy_slab(bumps: int):
    """A genus-0 slab with unit cubes on top, two apart: each bump's loop is a free choice."""
    side = 1
    while ((side - 1) // 2) ** 2 < bumps:
        side += 2
    cells = {(x, y, 0) for x in range(side) for y in range(side)}
    spots = [(x, y) for x in range(1, side - 1, 2) for y in range(1, side - 1, 2)][:bumps]
    return polycube_from_voxels(cells | {(x, y, 1) for x, y in spots})


def instances(max_k: int):
    for p in range(2, max_k):
        yield "pillars", polycube_from_voxels(pillar_cells(0, 0, p))
    for bumps in range(2, max_k, 3):
        yield "bumps", bumpy_slab(bumps)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-k", type=int, default=34)
    ap.add_argument("--brute-max", type=int, default=20, help="skip exhaustive search above this k per axis")
    ap.add_argument("--plot", help="write a PNG of time against k")
    args = ap.parse_args()
    rows = []
    rng = random.Random(0)
    for family, q in instances(args.max_k):
        problem = OrientationProblem(q.dualize().forget_orientation())
        k = problem.k
        kmax = max(len(problem.components_of(a)) for a in Axis)
        if k > args.max_k:
            continue
        # The problem caches a Definition-4 check of the structure; computing it here keeps
        # its cost out of whichever solver happens to be timed first.
        _ = problem.local_violations
        row = [family, q.genus, q.map.num_corners, k]
        for name in ("brute", "sat", "smt"):
            if name == "brute" and kmax > args.brute_max:
                row += ["-", "-"]
                continue
            t_solve, _ = timed(partial(solved, name, problem), repeat=3)
            t_count, n_count = timed(partial(counted, name, problem), repeat=3)
            row += [t_solve, t_count]
        # The builder numbers corners in a regular order; a random numbering is the usual case.
        shuffled = OrientationProblem(renumbered(q, rng).dualize().forget_orientation())
        _ = shuffled.local_violations
        t_shuffled, _ = timed(partial(solved, "sat", shuffled), repeat=3)
        row += [t_shuffled, n_count]
        rows.append(row)
        print(f"{family} k={k} genus={q.genus} done", file=sys.stderr)
    header = ["family", "genus", "corners", "k", "brute solve s", "brute count s", "sat solve s",
              "sat count s", "smt solve s", "smt count s", "sat solve s, renumbered", "count"]
    print(markdown_table(header, rows))
    if args.plot:
        plot(rows, args.plot)


def plot(rows: list[list], path: str) -> None:
    """Time to find one orientation against k, per solver and family (log scale)."""
    from polyloops.render.figure import new_figure, save_figure

    fig = new_figure(7, 4.5)
    ax = fig.add_subplot(1, 1, 1)
    series = [("brute", 4, "o-"), ("sat", 6, "s-"), ("smt", 8, "^-"), ("sat, renumbered corners", 10, "d:")]
    for name, col, style in series:
        for family, marker_fill in (("pillars", "full"), ("bumps", "none")):
            pts = [(r[3], r[col]) for r in rows if r[0] == family and isinstance(r[col], float)]
            if pts:
                ax.semilogy(*zip(*pts, strict=True), style, fillstyle=marker_fill, label=f"{name} ({family})")
    ax.set_xlabel("k (free choices)")
    ax.set_ylabel("time to find one orientation (s)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    save_figure(fig, path)


if __name__ == "__main__":
    main()
