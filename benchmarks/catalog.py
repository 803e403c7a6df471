"""The genus-0 catalog against plantri: total time through N corners, for N = 20, 22, 24, 26.

plantri's time is that of writing the quadrangulations the catalog reads (``plantri -qc2 n``
for every even n through N, output discarded; odd counts carry no polycube and are skipped by
both).  The catalog's time is a fresh ``polyloops catalog`` run through N with ``--workers 2``
(this machine has 2 cores), as wall time and as CPU time of all its processes, so that the CPU
ratio compares like with like (plantri runs in one process).

Usage: python benchmarks/catalog.py [--max N] [--workers K]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table

from polyloops.enumerate.quadrangulations import find_plantri


def children_cpu() -> float:
    t = os.times()
    return t.children_user + t.children_system


def plantri_seconds(plantri: str, max_n: int) -> float:
    start = time.perf_counter()
    for n in range(8, max_n + 1, 2):
        subprocess.run([plantri, "-qc2", str(n)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       check=True)
    return time.perf_counter() - start


def catalog_seconds(max_n: int, workers: int) -> tuple[float, float]:
    """Wall and CPU seconds (the command and its workers and plantri processes)."""
    with tempfile.TemporaryDirectory() as tmp:
        start, cpu = time.perf_counter(), children_cpu()
        subprocess.run([sys.executable, "-m", "polyloops", "catalog", "--max-corners", str(max_n),
                        "--workers", str(workers), "-o", str(Path(tmp) / "c")],
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        return time.perf_counter() - start, children_cpu() - cpu


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=26)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    plantri = find_plantri()
    rows = []
    for n in range(20, args.max + 1, 2):
        p = plantri_seconds(plantri, n)
        wall, cpu = catalog_seconds(n, args.workers)
        rows.append([n, p, wall, cpu, wall / p, cpu / p])
        print(f"through {n} done", file=sys.stderr)
    print(markdown_table(["through N corners", "plantri s", "catalog wall s", "catalog CPU s",
                          "wall ratio", "CPU ratio"], rows))


if __name__ == "__main__":
    main()
