"""Peak memory of a whole command: its process tree's resident memory, sampled five times a
second (the largest total, and the largest single process), as a Markdown row.

    python benchmarks/memory.py -- polyloops catalog --max-corners 28 --workers 2 -o /tmp/c28

Reads /proc (Linux).  The catalog's workers are processes, so the total is what the machine
needs; the largest process is what one worker or the parent needs.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time


def tree(pid: int) -> list[int]:
    """``pid`` and every descendant, from /proc."""
    children: dict[int, list[int]] = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/stat") as fh:
                    parent = int(fh.read().rsplit(")", 1)[1].split()[1])
            except (OSError, IndexError, ValueError):
                continue
            children.setdefault(parent, []).append(int(name))
    out, stack = [], [pid]
    while stack:
        p = stack.pop()
        out.append(p)
        stack.extend(children.get(p, []))
    return out


def rss_mb(pid: int) -> float:
    try:
        with open(f"/proc/{pid}/status") as fh:
            for line in fh:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return 0.0


def main() -> None:
    argv = sys.argv[1:]
    if argv[:1] == ["--"]:
        argv = argv[1:]
    if not argv:
        sys.exit(__doc__)
    start = time.monotonic()
    proc = subprocess.Popen(argv)
    peak_total = peak_one = 0.0
    while proc.poll() is None:
        sizes = [rss_mb(p) for p in tree(proc.pid)]
        peak_total = max(peak_total, sum(sizes))
        peak_one = max(peak_one, max(sizes, default=0.0))
        time.sleep(0.2)
    print("| command | exit | wall s | peak total MB | peak one process MB |")
    print("|---|---:|---:|---:|---:|")
    print(f"| `{' '.join(argv)}` | {proc.returncode} | {time.monotonic() - start:.0f} | {peak_total:.0f} | "
          f"{peak_one:.0f} |")


if __name__ == "__main__":
    main()
