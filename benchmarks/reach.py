"""Reachability: states per second of the breadth-first search from the cube, by the corner
bound M and the number of worker processes, and its ratio to a naive search (benchmarks/
naive_reach.py: every cycle of the corner graph tried, every child re-checked from scratch)
at the bounds up to --naive-max.  Reports wall time and the CPU time of this process and its
workers, so one worker and two compare like with like.

Usage: python benchmarks/reach.py [--quick] [--bounds 26 28 30] [--workers 1 2] [--naive-max 26]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table
from naive_reach import naive_explore

from polyloops.core.polycube import Polycube
from polyloops.io.examples import load_example
from polyloops.reach.search import explore


def cpu_seconds() -> float:
    """CPU time of this process and of its finished children."""
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="bounds 20 and 24 only")
    parser.add_argument("--bounds", type=int, nargs="+", default=[26, 28, 30])
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2])
    parser.add_argument("--naive-max", type=int, default=26,
                        help="run the naive reference up to this bound (it grows about 3x per 2 corners)")
    args = parser.parse_args()
    bounds = [20, 24] if args.quick else args.bounds
    cube_polycube = load_example("cube")
    assert isinstance(cube_polycube, Polycube)
    cube = cube_polycube.dualize()
    rows = []
    for m in bounds:
        naive_cpu = None
        if m <= args.naive_max:
            cpu = cpu_seconds()
            naive = naive_explore(cube, m)
            naive_cpu = cpu_seconds() - cpu
        for k in args.workers:
            wall, cpu = time.perf_counter(), cpu_seconds()
            result = explore(cube, m, workers=k)
            wall, cpu = time.perf_counter() - wall, cpu_seconds() - cpu
            if naive_cpu is not None and naive != result.by_corners:
                sys.exit(f"M={m}: the naive search found {naive}, the search {result.by_corners}")
            rows.append([m, k, result.states, result.max_distance, round(wall, 2), round(cpu, 2),
                         round(result.states / wall), round(result.states / cpu),
                         "-" if naive_cpu is None else round(naive_cpu, 1),
                         "-" if naive_cpu is None else round(naive_cpu / cpu, 1)])
            print(f"M={m} workers={k}: {result.states} states in {wall:.1f} s", file=sys.stderr)
    print(markdown_table(["M", "workers", "states", "max distance", "wall s", "CPU s", "states/s (wall)",
                          "states/s (CPU)", "naive CPU s", "naive / search (CPU)"], rows))


if __name__ == "__main__":
    main()
