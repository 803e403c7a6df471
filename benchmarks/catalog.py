"""The genus-0 catalog against plantri: total time through N corners, for N = 20, 22, 24, 26.

plantri's time is that of writing the same quadrangulations (``plantri -qc2 n`` for every n
through N, output discarded).  The catalog's time is a fresh ``polyloops catalog`` run through
N with ``--workers 2`` (this machine has 2 cores).

Usage: python benchmarks/catalog.py [--max N] [--workers K]
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from _common import markdown_table

from polyloops.enumerate.quadrangulations import find_plantri


def plantri_seconds(plantri: str, max_n: int) -> float:
    start = time.perf_counter()
    for n in range(8, max_n + 1):
        subprocess.run([plantri, "-qc2", str(n)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       check=True)
    return time.perf_counter() - start


def catalog_seconds(max_n: int, workers: int) -> float:
    with tempfile.TemporaryDirectory() as tmp:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "polyloops", "catalog", "--max-corners", str(max_n),
                        "--workers", str(workers), "-o", str(Path(tmp) / "c")],
                       stdout=subprocess.DEVNULL, check=True)
        return time.perf_counter() - start


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max", type=int, default=26)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    plantri = find_plantri()
    rows = []
    for n in range(20, args.max + 1, 2):
        p = plantri_seconds(plantri, n)
        c = catalog_seconds(n, args.workers)
        rows.append([n, p, c, c / p])
        print(f"through {n} done", file=sys.stderr)
    print(markdown_table(["through N corners", "plantri s", "catalog s", "ratio"], rows))


if __name__ == "__main__":
    main()
