"""The first stage by crossings: the two-axis arrangements B of a genus with each number of
crossings, listed as square-tiled surfaces, with the nodes of that search, its CPU time and
the peak memory; with ``--marked``, the marked search's time for the same B beside it.

    python benchmarks/first_stage.py 16                    # genus 1, 1 to 16 crossings
    python benchmarks/first_stage.py 14 --genus 2 --marked 12

A catalog through N corners lists the B with at most (N + 2g - 2) // 3 crossings, so at genus 1
16 serves 48 corners and at genus 2 16 serves 46 to 48.  One process; a row per number of
crossings (the B with exactly that many, listed on their own, not kept) and a last row for the
whole range.  The marked search builds every B through its bound at once (its states are not
cellular, so it cannot stop at one size): its column is the CPU through that row's crossings,
up to ``--marked``.  Prints a Markdown table.
"""

from __future__ import annotations

import argparse
import resource
import time

from _common import markdown_table

from polyloops.generate.torus.squares import square_bases
from polyloops.generate.torus.stages import TorusSearchStats, two_axis_bases


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("crossings", type=int, help="the most crossings of B (1 to 24)")
    parser.add_argument("--genus", type=int, default=1)
    parser.add_argument("--marked", type=int, default=0, metavar="K",
                        help="also time the marked search through 1, 2, ..., K crossings")
    args = parser.parse_args()
    if not 1 <= args.crossings <= 24 or args.genus < 1 or args.marked > args.crossings:
        parser.error("crossings 1 to 24, genus 1 or more, --marked at most the crossings")
    rows: list[list[object]] = []
    total_b = total_nodes = 0
    total_cpu = 0.0
    for n in range(1, args.crossings + 1):
        start = time.process_time()
        _, stats = square_bases(n, args.genus, keep=False)
        cpu = time.process_time() - start
        kept = stats.kept
        total_b, total_nodes, total_cpu = total_b + kept, total_nodes + stats.nodes, total_cpu + cpu
        marked = ""
        if n <= args.marked:
            start = time.process_time()
            sum(1 for _ in two_axis_bases(n, on_stats=TorusSearchStats().add, genus=args.genus))
            marked = f"{time.process_time() - start:.1f}"
        if kept or marked:
            rows.append([n, kept, stats.nodes, f"{cpu:.2f}", marked])
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024  # kB on Linux
    rows.append([f"through {args.crossings}", total_b, total_nodes, f"{total_cpu:.1f}", f"peak {peak} MB"])
    print(markdown_table(["crossings", "B", "nodes", "CPU s", "marked search CPU s (through)"], rows))


if __name__ == "__main__":
    main()
