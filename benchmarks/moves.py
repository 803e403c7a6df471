"""Loop moves: time to enumerate all additions and all removals against structure size, and
the time of one addition or removal.

Families: boxes n x 1 x 1 (the number of additions grows quadratically), random face-connected
blobs of n unit cubes (well-composed, so nothing is split), and square slabs n x n x 1 (the
number of additions grows exponentially: every cycle of the top grid can carry a loop).

Usage: python benchmarks/moves.py [--quick]
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Iterable
from functools import partial
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table, timed

from polyloops.core.moves import add_loop, additions, count_additions, removals, remove_loop
from polyloops.shapes.builders import box
from polyloops.shapes.voxels import polycube_from_voxels
from strategies import well_composed_blob


def each(fn: Callable[[Any, Any], object], ls: Any, items: Iterable[Any]) -> list[object]:
    """``fn(ls, item)`` for every item (timed as one)."""
    return [fn(ls, item) for item in items]


def structures(quick: bool):
    for n in (1, 2, 4, 8, 16, 32) + (() if quick else (64, 128)):
        yield f"box {n}x1x1", box(n, 1, 1)
    for n in (2, 5, 10, 20) + (() if quick else (40, 80)):
        yield f"blob {n}", polycube_from_voxels(well_composed_blob(7, n - 1))
    for n in (2, 3) + (() if quick else (4, 5)):
        yield f"slab {n}x{n}x1", box(n, n, 1)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="small sizes only")
    args = ap.parse_args()
    rows = []
    for name, q in structures(args.quick):
        ls = q.dualize()
        t_count, counts = timed(partial(count_additions, ls))
        total = sum(counts.values())
        t_rem, removable = timed(partial(removals, ls))
        sample = list(additions(ls, limit=20))
        t_add, _ = timed(partial(each, add_loop, ls, sample))
        t_one_rem, _ = timed(partial(each, remove_loop, ls, removable[:20]))
        rows.append([name, ls.map.num_corners, len(ls.loops), total, t_count,
                     total / t_count if t_count else float("nan"), len(removable), t_rem,
                     t_add / max(1, len(sample)), t_one_rem / max(1, len(removable[:20]))])
        print(f"{name} done", file=sys.stderr)
    print(markdown_table(["structure", "corners", "loops", "additions", "enumerate all s", "additions/s",
                          "removable", "test all removals s", "one addition s", "one removal s"], rows))


if __name__ == "__main__":
    main()
