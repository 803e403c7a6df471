"""Check a catalog against plantri's slices and against reachability, and print what was
compared (the rows of docs/catalog.md's table of checks).

    python tools/crosscheck.py catalogs/genus0 32 --mod 64 --slices 1 --seed 2026 [--reach]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from polyloops.reach.crosscheck import plantri_sample, reach_agreement


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("catalog", type=Path)
    parser.add_argument("corners", type=int)
    parser.add_argument("--mod", type=int, default=64)
    parser.add_argument("--slices", type=int, default=1, help="how many of the mod slices")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--reach", action="store_true", help="also compare the classes reached from the cube")
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    start = time.process_time()
    sample = plantri_sample(args.catalog, args.corners, args.mod, args.slices, args.seed)
    print(f"| {args.corners} | plantri slices {', '.join(map(str, sample.slices))} of {sample.mod} "
          f"(seed {sample.seed}) | {sample.maps} maps, {sample.found} classes | "
          f"{'agrees' if sample.agrees else 'MISSING ' + ', '.join(sample.missing)} | "
          f"{time.process_time() - start:.0f} s |")
    if args.reach:
        start = time.process_time()
        reach = reach_agreement(args.catalog, args.corners, args.workers)
        print(f"| {args.corners} | reached from the cube | {sum(reach.reached.values())} classes | "
              f"{'agrees' if reach.agrees else 'MISSING ' + ', '.join(reach.missing)} | "
              f"{time.process_time() - start:.0f} s |")


if __name__ == "__main__":
    main()
