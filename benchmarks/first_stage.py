"""The genus-1 first stage by its bound: the two-axis arrangements B with each number of
crossings, the states and curves the marked search made, its CPU time and peak memory.

    python benchmarks/first_stage.py 15           # one search through 15 crossings

A catalog through N corners lists the B with at most N // 3 crossings, so 15 serves 45 to 47
corners.  One search, one process; the table has a row per number of crossings (the B with
exactly that many) and a last row for the whole search.  Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import resource
import time
from collections import Counter

from _common import markdown_table

from polyloops.generate.torus.stages import TorusSearchStats, two_axis_bases


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("crossings", type=int, help="the bound on the crossings of B")
    args = parser.parse_args()
    stats = TorusSearchStats()
    start = time.process_time()
    by_crossings = Counter(a.crossings for a in two_axis_bases(args.crossings, on_stats=stats.add))
    cpu = time.process_time() - start
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024  # kB on Linux
    rows: list[list[object]] = [[c, by_crossings[c], "", "", "", ""] for c in sorted(by_crossings)]
    rows.append([f"through {args.crossings}", sum(by_crossings.values()), stats.states, stats.closed,
                 f"{cpu:.1f}", peak])
    print(markdown_table(["crossings", "B", "states", "curves closed", "CPU s", "peak MB"], rows))


if __name__ == "__main__":
    main()
