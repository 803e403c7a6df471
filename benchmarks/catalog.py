"""The catalog's two generators, per corner count: plantri's maps filtered, and arrangements
of loops built one loop at a time.

For each even corner count n, runs each in a fresh process:

- plantri alone: ``plantri -qc2 n`` split into the same slices as the catalog, output discarded
  (the floor for any method that reads every quadrangulation);
- ``polyloops catalog --min-corners n --max-corners n --generator plantri`` (compiled filter);
- the same with ``--generator loops``;
- optionally (``--numpy-up-to N``) the plantri generator with the numpy filter.

Each catalog run uses ``--workers K`` (default 2, this machine's cores); its CPU time adds up
all its processes (workers and plantri), so CPU columns compare like with like.  Objects
visited: the maps plantri writes (the filter reads all of them), the arrangements the loops
search builds (all of those with at most n corners that can still grow into a candidate), and
the candidates each passes to the per-map work (the loops search's are fewer: its cuts 4 and
5 drop maps that carry no polycube).  The script checks that the records are the same bytes
and the counts in all three symmetry modes the same.

Usage: python benchmarks/catalog.py [--min N] [--max N] [--workers K] [--numpy-up-to N]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table

from polyloops.generate.plantri import slices
from polyloops.generate.plantri.quadrangulations import find_plantri


def children_cpu() -> float:
    t = os.times()
    return t.children_user + t.children_system


def measure(cmd: list[str]) -> tuple[float, float]:
    """Wall and CPU seconds of a command and everything it waited for."""
    start, cpu = time.perf_counter(), children_cpu()
    subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    return time.perf_counter() - start, children_cpu() - cpu


def plantri_alone(plantri: str, n: int, workers: int) -> tuple[float, float]:
    """plantri's slices, ``workers`` at a time, output discarded."""
    parts = slices(n, workers)
    args = [[plantri, "-qc2", str(n)] + ([f"{r}/{parts}"] if parts > 1 else []) for r in range(parts)]
    start, cpu = time.perf_counter(), children_cpu()
    running: list[subprocess.Popen] = []
    for a in args:
        if len(running) == workers:
            running.pop(0).wait()
        running.append(subprocess.Popen(a, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    for p in running:
        p.wait()
    return time.perf_counter() - start, children_cpu() - cpu


def catalog(n: int, workers: int, generator: str, method: str = "compiled") -> tuple[float, float, dict]:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "c"
        options = ["--method", method] if generator == "plantri" else []  # the strip filter's
        wall, cpu = measure([sys.executable, "-m", "polyloops", "catalog", "--min-corners", str(n),
                             "--max-corners", str(n), "--workers", str(workers), *options,
                             "--generator", generator, "-o", str(out)])
        summary = json.loads((out / "summary.json").read_text())
        parts = [json.loads(p.read_text()) for p in (out / "parts").glob("*.json")]
        # the candidate maps each generator hands to the per-map work (the loops search's are
        # fewer: cuts 4 and 5 drop maps that carry no polycube)
        candidates = sum(p["corners"][str(n)]["candidates"] for p in parts if str(n) in p["corners"])
        visited = (summary["search"]["arrangements"] if generator == "loops"
                   else summary["quadrangulations"][str(n)])
        return wall, cpu, {"visited": visited, "candidates": candidates, "counts": summary["counts"],
                           "records": (out / "catalog.jsonl").read_bytes()}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--min", type=int, default=20)
    ap.add_argument("--max", type=int, default=26)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--numpy-up-to", type=int, default=0, metavar="N",
                    help="also time the numpy strip filter up to N corners (17 minutes at 28)")
    args = ap.parse_args()
    plantri = find_plantri()
    rows = []
    for n in range(args.min + args.min % 2, args.max + 1, 2):
        _, p_cpu = plantri_alone(plantri, n, args.workers)
        f_wall, f_cpu, filt = catalog(n, args.workers, "plantri")
        l_wall, l_cpu, loops = catalog(n, args.workers, "loops")
        if any(loops[k] != filt[k] for k in ("records", "counts")):
            raise SystemExit(f"{n} corners: the two generators disagree")
        row = [n, filt["visited"], loops["visited"], filt["candidates"], loops["candidates"], p_cpu,
               f_wall, f_cpu, l_wall, l_cpu, f_cpu / l_cpu]
        if n <= args.numpy_up_to:
            _, n_cpu, slow = catalog(n, args.workers, "plantri", "numpy")
            if slow["records"] != filt["records"]:
                raise SystemExit(f"{n} corners: the two strip filters disagree")
            row += [n_cpu]
        else:
            row += ["-"]
        rows.append(row)
        print(f"{n} corners done", file=sys.stderr)
    print(markdown_table(["corners", "maps visited (plantri)", "arrangements visited (loops)",
                          "candidates (plantri)", "candidates (loops)", "plantri alone CPU s",
                          "plantri wall s", "plantri CPU s",
                          "loops wall s", "loops CPU s", "plantri/loops CPU", "numpy filter CPU s"],
                         rows))


if __name__ == "__main__":
    main()
