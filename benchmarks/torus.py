"""The genus-1 search by corner budget: the first stage (two-axis arrangements B with at most a
third of the crossings), the second (the third axis, region by region or loop by loop), the
maps that carry a polycube and the polycube classes on them, in CPU seconds of one process.

    python benchmarks/torus.py --min 20 --max 30
    python benchmarks/torus.py --min 24 --max 30 --stage loops   # the loop-by-loop second stage
    python benchmarks/torus.py --min 16 --max 22 --python        # the Python searches, the twins

The first stage's arrangements do not depend on the budget beyond ``N // 3`` and a catalog's
worker lists them once for all its shares; here each row lists them afresh.  Prints a Markdown
table.
"""

from __future__ import annotations

import argparse
import os
import time

from polyloops.catalog.classes import map_classes
from polyloops.core import compiled
from polyloops.generate.torus.candidates import SecondStage, candidate_torus_arrangements
from polyloops.generate.torus.cuts import base_bound
from polyloops.generate.torus.stages import TorusSearchStats, first_stage, forget_first_stage


def row(n: int, stage: SecondStage) -> list[object]:
    forget_first_stage()
    start = time.process_time()
    bases, _ = first_stage(base_bound(n))
    first = time.process_time() - start
    stats: list[TorusSearchStats] = []
    start = time.process_time()
    maps = list(candidate_torus_arrangements(n, on_stats=stats.append, stage=stage))
    second = time.process_time() - start  # the bases are cached: the second stage alone
    start = time.process_time()
    classes = sum(len(map_classes(a.quad_mesh())["full"]) for a in maps)
    classify = time.process_time() - start
    s = stats[0]
    work = s.region_choices if stage is SecondStage.REGIONS else s.states - stats_first(n)
    return [n, len(bases), f"{first:.1f}", work, f"{second:.1f}", len(maps), f"{classify:.1f}", classes]


def stats_first(n: int) -> int:
    """The states of the first stage (the second stage's statistics include them)."""
    return first_stage(base_bound(n))[1].states


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--min", type=int, default=20)
    parser.add_argument("--max", type=int, default=28)
    parser.add_argument("--step", type=int, default=2)
    parser.add_argument("--stage", choices=["regions", "loops"], default="regions",
                        help="the second stage: region by region (the generator's) or loop by loop")
    parser.add_argument("--python", action="store_true",
                        help="the Python searches instead of the compiled ones")
    args = parser.parse_args()
    if args.python:  # the switchboard's twins, for the rest of the run
        os.environ[compiled.ENV] = "torus,regions"
    work = "regions cut" if args.stage == "regions" else "second-stage states"
    header = ["corners N", "B (<= N/3 crossings)", "first stage s", work, "second stage s",
              "maps with a polycube", "classify s", "classes (all symmetries)"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---:|" * len(header))
    for n in range(args.min, args.max + 1, args.step):
        print("| " + " | ".join(map(str, row(n, SecondStage(args.stage)))) + " |", flush=True)


if __name__ == "__main__":
    main()
