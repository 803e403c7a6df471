"""Helpers shared by the benchmark scripts: timing, Markdown tables, and the runs over a folder
of meshes."""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any


def timed(fn: Callable[[], Any], repeat: int = 1,
          clock: Callable[[], float] = time.perf_counter) -> tuple[float, Any]:
    """Best time of ``repeat`` runs on ``clock`` (wall time unless told), and the last result."""
    best, result = float("inf"), None
    for _ in range(repeat):
        t = clock()
        result = fn()
        best = min(best, clock() - t)
    return best, result


def timed_cpu(fn: Callable[[], Any], repeat: int = 1) -> tuple[float, Any]:
    """Best CPU time of ``repeat`` runs (this process only), and the last result."""
    return timed(fn, repeat, time.process_time)


def markdown_table(header: list[str], rows: list[list[Any]]) -> str:
    def cell(x: Any) -> str:
        return f"{x:.4g}" if isinstance(x, float) else str(x)

    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell(x) for x in row) + " |" for row in rows]
    return "\n".join(lines)


def _folder(text: str) -> Path:
    """A folder that exists (argparse reports any other as a usage error, exit 2)."""
    if not Path(text).is_dir():
        raise argparse.ArgumentTypeError(f"{text}: no such folder")
    return Path(text)


def mesh_benchmark_parser(description: str) -> argparse.ArgumentParser:
    """The options of the benchmarks over a folder of meshes: FOLDER, --budget, --seed, --only,
    --workers."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("folder", type=_folder)
    parser.add_argument("--budget", type=float, default=20.0)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--only", nargs="*", help="mesh names (stems) to run")
    parser.add_argument("--workers", type=int, default=1, help="as segment --workers (default 1)")
    return parser


def print_tables_by_folder(folder: Path, only: list[str] | None, header: list[str],
                           rows_of: Callable[[Path], list[list[Any]]]) -> None:
    """One Markdown table per subfolder of ``folder``: the rows of each mesh (``.stl``,
    ``.obj``, ``.mesh``) in it, or of those named in ``only``, printed as each folder ends."""
    meshes = sorted(p for p in folder.rglob("*") if p.suffix.lower() in (".stl", ".obj", ".mesh"))
    for sub in sorted({p.parent for p in meshes}):
        table = [r for p in meshes if p.parent == sub and (not only or p.stem in only) for r in rows_of(p)]
        if table:
            print(f"\n### {sub.name}\n")
            print(markdown_table(header, table), flush=True)
