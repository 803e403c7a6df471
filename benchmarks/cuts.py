"""The effect of each cut of the loops search that can be switched off: arrangements built,
candidate maps classified, and CPU seconds, per corner budget, one process, no workers.

    python benchmarks/cuts.py --min 22 --max 28
    python benchmarks/cuts.py --min 28 --max 32 --only both

Cuts 4 (crossing graphs must be 3-colourable) and 5 (no region with two sides on one loop,
a bound like cut 1's) are in docs/catalog.md.  Each row is one setting: neither, cut 4 alone,
both.  The records of the catalog are the same in every setting (the tests check it, and the
last column counts the full classes found), so the saving is the arrangements not built and
the candidate maps not classified.  Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import time

from polyloops.catalog.classes import map_classes
from polyloops.generate.loops.arrangements import Cuts, SearchStats, candidate_arrangements

SETTINGS = {"neither": (False, False), "cut 4": (True, False), "both": (True, True)}


def run(n: int, colour_cut: bool, meet_cut: bool) -> tuple[SearchStats, float, float, int]:
    stats: list[SearchStats] = []
    start = time.process_time()
    found = list(candidate_arrangements(n, on_stats=stats.append, cuts=Cuts(colour_cut, meet_cut)))
    search = time.process_time() - start
    start = time.process_time()
    records = sum(len(map_classes(a.quad_mesh())["full"]) for a in found)
    classify = time.process_time() - start
    return sum(stats, SearchStats()), search, classify, records


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--min", type=int, default=22)
    parser.add_argument("--max", type=int, default=26)
    parser.add_argument("--only", choices=sorted(SETTINGS), action="append",
                        help="measure only these settings (repeatable; default all three)")
    args = parser.parse_args()
    chosen = args.only or list(SETTINGS)
    print("| corners | cuts | arrangements built | curves drawn | candidates | search CPU s | "
          "classification CPU s | total CPU s | full classes |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for n in range(args.min, args.max + 1, 2):
        totals = {}
        for name in chosen:
            stats, search, classify, records = run(n, *SETTINGS[name])
            totals[name] = search + classify
            print(f"| {n} | {name} | {stats.arrangements:,} | {stats.curves:,} | {stats.candidates:,} | "
                  f"{search:.1f} | {classify:.1f} | {search + classify:.1f} | {records} |", flush=True)
        if len(totals) > 1:
            first, last = chosen[0], chosen[-1]
            print(f"| {n} | {first} / {last} | | | | | | {totals[first] / totals[last]:.1f} | |")


if __name__ == "__main__":
    main()
