"""The effect of each cut of the loops search that can be switched off: arrangements built,
candidate maps classified, and CPU seconds, per corner budget, one process, no workers.

    python benchmarks/cuts.py --min 22 --max 28

Cut 4 (crossing graphs must be 3-colourable, docs/catalog.md) is measured against the search
without it; the records of the catalog are the same either way (the tests check it), so the
saving is the arrangements not built and the candidate maps not classified.  Prints a
Markdown table.
"""

from __future__ import annotations

import argparse
import time

import polyloops.enumerate.arrangements as arrangements
from polyloops.enumerate.arrangements import SearchStats, candidate_arrangements
from polyloops.enumerate.catalog import map_classes


def run(n: int, colour_cut: bool) -> tuple[SearchStats, float, float, int]:
    arrangements.COLOUR_CUT = colour_cut
    stats: list[SearchStats] = []
    start = time.process_time()
    found = list(candidate_arrangements(n, on_stats=stats.append))
    search = time.process_time() - start
    start = time.process_time()
    records = sum(len(map_classes(a.quad_mesh())["full"]) for a in found)
    classify = time.process_time() - start
    return sum(stats, SearchStats()), search, classify, records


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--min", type=int, default=22)
    parser.add_argument("--max", type=int, default=26)
    args = parser.parse_args()
    print("| corners | cut 4 | arrangements built | candidates | search CPU s | classification CPU s | "
          "total CPU s | full classes |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|")
    for n in range(args.min, args.max + 1, 2):
        rows = {}
        for cut in (False, True):
            stats, search, classify, records = run(n, cut)
            rows[cut] = search + classify
            print(f"| {n} | {'on' if cut else 'off'} | {stats.arrangements} | {stats.candidates} | "
                  f"{search:.1f} | {classify:.1f} | {search + classify:.1f} | {records} |")
        print(f"| {n} | ratio | | | | | {rows[False] / rows[True]:.2f} | |")


if __name__ == "__main__":
    main()
