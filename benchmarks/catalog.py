"""The catalog's two strip filters, and plantri alone, per corner count.

For each even corner count n, three runs, each a fresh process:

- plantri alone: ``plantri -qc2 n`` split into the same slices as the catalog, output discarded
  (the floor for any method that reads every quadrangulation);
- ``polyloops catalog --min-corners n --max-corners n --method numpy`` (the reference filter);
- the same with ``--method compiled``.

Each catalog run uses ``--workers K`` (default 2, this machine's cores); its CPU time adds up
all its processes (workers and plantri), so CPU columns compare like with like.  Objects
visited: the maps plantri writes (both filters read all of them) and the candidates that pass
the filter to the per-map work.

Usage: python benchmarks/catalog.py [--min N] [--max N] [--workers K] [--skip-numpy-above N]
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

from polyloops.enumerate.catalog_run import slices
from polyloops.enumerate.quadrangulations import find_plantri


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


def catalog(n: int, workers: int, method: str) -> tuple[float, float, dict]:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "c"
        wall, cpu = measure([sys.executable, "-m", "polyloops", "catalog", "--min-corners", str(n),
                             "--max-corners", str(n), "--workers", str(workers), "--method", method,
                             "-o", str(out)])
        parts = [json.loads(p.read_text()) for p in (out / "parts").iterdir()]
        visited = {"maps": sum(p["quadrangulations"] for p in parts),
                   "candidates": sum(p["candidates"] for p in parts),
                   "records": (out / "catalog.jsonl").read_bytes()}
        return wall, cpu, visited


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--min", type=int, default=20)
    ap.add_argument("--max", type=int, default=26)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--skip-numpy-above", type=int, default=26, metavar="N",
                    help="the numpy filter takes about 17 minutes at 28 corners")
    args = ap.parse_args()
    plantri = find_plantri()
    rows = []
    for n in range(args.min + args.min % 2, args.max + 1, 2):
        p_wall, p_cpu = plantri_alone(plantri, n, args.workers)
        c_wall, c_cpu, fast = catalog(n, args.workers, "compiled")
        row = [n, fast["maps"], fast["candidates"], p_wall, p_cpu, c_wall, c_cpu]
        if n <= args.skip_numpy_above:
            n_wall, n_cpu, slow = catalog(n, args.workers, "numpy")
            if slow["records"] != fast["records"] or slow["maps"] != fast["maps"]:
                raise SystemExit(f"{n} corners: the two methods disagree")
            row += [n_wall, n_cpu, n_cpu / c_cpu]
        else:
            row += ["-", "-", "-"]
        rows.append([*row, c_cpu / p_cpu])
        print(f"{n} corners done", file=sys.stderr)
    print(markdown_table(["corners", "maps visited", "candidates", "plantri wall s", "plantri CPU s",
                          "compiled wall s", "compiled CPU s", "numpy wall s", "numpy CPU s",
                          "numpy/compiled CPU", "compiled/plantri CPU"], rows))


if __name__ == "__main__":
    main()
