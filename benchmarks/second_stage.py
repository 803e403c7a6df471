"""The second stage by budget: the CPU the region search spends on a two-axis arrangement B,
for a sample of the B of each number of crossings, at several corner budgets.

    python benchmarks/second_stage.py --crossings 10 12 14 --budgets 44 47
    python benchmarks/second_stage.py --genus 2 --crossings 12 14 16 --budgets 42 47 48 --sample 60 --thin 500
    python benchmarks/second_stage.py --genus 2 --share 1000/1024 --budgets 47 48

The B (of ``--genus``, 1 unless given) come from the first stage (seconds through 14
crossings, about 2 minutes for the 2.6 million of 16 at genus 1), a sample of ``--sample`` of
each size drawn with ``--seed``; with ``--thin K`` each B of the sample is drawn from a share of the
listing cut into K, the share drawn at random (13.9 million B of 16 crossings at genus 2 need
not all be held; B in small shares are drawn more often than in a uniform sample).  Every B of
the sample is searched at every budget (in corners: a map of genus g with N corners has
N + 2g - 2 crossings), one process.  Prints a Markdown table: per size and budget, the mean CPU
per B, the regions whose chords were chosen, and the third axes found
(:func:`~polyloops.generate.torus.regions.third_axis_systems`).

With ``--share RES/MOD`` every ``B`` of that share of a catalog run is searched instead (the
share a run's worker takes: the first stage through a third of the largest budget's crossings,
:func:`~polyloops.generate.torus.stages.share_of_first_stage`), and the table adds what samples
miss: the median ``B`` and the share of the time its slowest 1% take.
"""

from __future__ import annotations

import argparse
import random
import time
from collections import defaultdict

from _common import markdown_table

from polyloops.generate.torus.arrangement import arrangement_of_twin
from polyloops.generate.torus.cuts import base_bound
from polyloops.generate.torus.regions import third_axis_systems
from polyloops.generate.torus.squares import square_bases
from polyloops.generate.torus.stages import TorusSearchStats, share_of_first_stage


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--crossings", type=int, nargs="+", default=[10, 12, 14])
    parser.add_argument("--budgets", type=int, nargs="+", default=[44, 47])
    parser.add_argument("--sample", type=int, default=40)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--genus", type=int, default=1)
    parser.add_argument("--thin", type=int, default=1, metavar="K",
                        help="draw each B from a random share of the listing cut into K")
    parser.add_argument("--share", metavar="RES/MOD",
                        help="search every B of this share of a run instead of samples")
    args = parser.parse_args()
    if args.genus < 1 or args.thin < 1:
        parser.error("--genus and --thin must be 1 or more")
    extra = 2 * (args.genus - 1)  # crossings beyond the corners
    if args.share:
        try:
            res, mod = (int(x) for x in args.share.split("/"))
        except ValueError:
            parser.error(f"--share {args.share}: give RES/MOD, such as 1000/1024")
        if not 0 <= res < mod:
            parser.error(f"--share {args.share}: RES must be 0 to MOD - 1")
        print(whole_share(args.genus, res, mod, args.budgets, extra))
        return
    by_size: dict[int, list[bytes]] = defaultdict(list)
    if args.thin == 1:
        for c in args.crossings:
            by_size[c] = square_bases(c, args.genus)[0]
    rng = random.Random(args.seed)
    rows: list[list[object]] = []
    for c in args.crossings:
        if by_size[c] or args.thin == 1:
            pick = rng.sample(by_size[c], min(args.sample, len(by_size[c])))
        else:
            pick = _thinned(c, args.genus, args.sample, args.thin, rng)
        for budget in args.budgets:
            if 3 * c > budget + extra:
                continue
            stats, found = TorusSearchStats(), 0
            start = time.process_time()
            for raw in pick:
                found += sum(1 for _ in third_axis_systems(arrangement_of_twin(raw), budget + extra, stats))
            cpu = time.process_time() - start
            rows.append([c, budget, len(pick), f"{1000 * cpu / max(len(pick), 1):.1f}",
                         stats.region_choices // max(len(pick), 1), found])
    print(markdown_table(["B crossings", "corners budget", "B sampled", "ms a B", "regions cut a B",
                          "third axes"], rows))


def whole_share(genus: int, res: int, mod: int, budgets: list[int], extra: int) -> str:
    """A table of every ``B`` of share ``res`` of ``mod``, by crossings, at each budget."""
    listed, _ = share_of_first_stage(base_bound(max(budgets) + extra), genus, res, mod)
    rows: list[list[object]] = []
    for budget in budgets:
        costs: dict[int, list[float]] = defaultdict(list)
        for raw in listed:
            base = arrangement_of_twin(raw)  # anew at each budget: it caches what a search derives
            start = time.process_time()
            for _ in third_axis_systems(base, budget + extra, TorusSearchStats()):
                pass
            costs[len(base.twin) // 4].append(time.process_time() - start)
        for c in sorted(costs):
            if 3 * c > budget + extra:
                continue
            ms = sorted((1000 * x for x in costs[c]), reverse=True)
            total = sum(ms)
            slowest = sum(ms[:max(1, len(ms) // 100)]) / max(total, 1e-9)
            rows.append([c, budget, len(ms), f"{total / 1000:.1f}", f"{total / len(ms):.1f}",
                         f"{ms[len(ms) // 2]:.1f}", f"{slowest:.2f}", f"{ms[0] / 1000:.2f}"])
    return markdown_table(["B crossings", "corners budget", "B in the share", "CPU s", "ms a B",
                           "median ms", "slowest 1% of the time", "slowest B s"], rows)


def _thinned(crossings: int, genus: int, sample: int, thin: int, rng: random.Random) -> list[bytes]:
    """``sample`` B, each from a share of the listing drawn at random (empty shares drawn again,
    at most ``20 * sample`` draws)."""
    pick: list[bytes] = []
    for _ in range(20 * sample):
        if len(pick) == sample:
            break
        share = square_bases(crossings, genus, rng.randrange(thin), thin)[0]
        if share:
            pick.append(rng.choice(share))
    return pick


if __name__ == "__main__":
    main()
