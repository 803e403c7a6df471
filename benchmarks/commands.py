"""Whole commands where users wait: CPU seconds (user + system of the command's process tree)
and peak memory of `polyloops ...` runs, best of --repeat, against the targets in
docs/performance.md.

Inputs are written here, not by polyloops' writers: a 130 x 130 x 130 box's loop structure
(101,400 faces) as JSON in polyloops' own numbering and shuffled (corners renumbered at random,
faces and edges in random order, each face from a random corner), labelled meshes of a random
polycube cut into s x s squares (about 23,000 and 52,000 triangles) as OBJ with a labels
file, and a 5 x 5 x 1 slab whose 2,445,152 Z-additions are the cycles of a 6 x 6 grid, and a
6 x 5 x 1 slab with 36,879,956 (the size of a DualCube fandisk layout's 39.8 million).

With --pictures, also the gallery (one run: a second would resume) and the sheet of the whole
shipped catalog with two workers, whose target is wall time.

Usage: python benchmarks/commands.py [--repeat 3] [--quick] [--pictures]
"""

from __future__ import annotations

import argparse
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from _common import markdown_table
from scaling import box_surface
from segmentation import subdivided

from polyloops.io.formats import dumps
from polyloops.shapes.builders import box
from strategies import random_polycube

CATALOG = Path(__file__).resolve().parent.parent / "src" / "polyloops" / "catalogs" / "genus0"


def run(args: list[str], repeat: int) -> tuple[float, float, int]:
    """Best CPU seconds, its wall seconds and the peak resident memory (MB) of a command (each
    run's own figures, from ``wait4``; inputs are written in other processes, see ``main``)."""
    import time

    best = (float("inf"), 0.0, 0)
    for _ in range(repeat):
        wall = time.perf_counter()
        proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(proc.pid, 0)  # this process's own figures, not all children's
        proc.returncode = os.waitstatus_to_exitcode(status)
        wall = time.perf_counter() - wall
        if proc.returncode not in (0, 1):
            sys.exit(f"{' '.join(args)}: exit {proc.returncode}")
        cpu = usage.ru_utime + usage.ru_stime
        if cpu < best[0]:
            best = (cpu, wall, usage.ru_maxrss // 1024)
    return best


def structure_json(faces, edges) -> str:
    return json.dumps({"polyloops": 1, "kind": "loop-structure", "faces": faces, "edges": edges})


def write_structures(tmp: Path) -> tuple[Path, Path]:
    """The box's loop structure in its own numbering and shuffled."""
    ls = box_surface(130, 130, 130).dualize()
    faces = [list(f) for f in ls.map.faces]
    edges = list(ls.edge_labels())  # (u, v, label): JSON writes each as a list
    own = tmp / "box.json"
    own.write_text(structure_json(faces, edges))
    rng = random.Random(5)
    perm = list(range(ls.map.num_corners))
    rng.shuffle(perm)
    shuffled_faces = []
    for f in faces:
        k = rng.randrange(len(f))
        shuffled_faces.append([perm[c] for c in f[k:] + f[:k]])
    rng.shuffle(shuffled_faces)
    shuffled_edges = [[perm[u], perm[v], lab] for u, v, lab in edges]
    rng.shuffle(shuffled_edges)
    shuffled = tmp / "box-shuffled.json"
    shuffled.write_text(structure_json(shuffled_faces, shuffled_edges))
    return own, shuffled


def write_mesh(tmp: Path, s: int) -> tuple[Path, Path, int]:
    mesh = subdivided(random_polycube(3, "frame1", 30), s)
    obj, labels = tmp / f"mesh{s}.obj", tmp / f"mesh{s}.labels"
    obj.write_text("".join(f"v {x} {y} {z}\n" for x, y, z in mesh.points)
                   + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in mesh.triangles))
    labels.write_text("".join(f"{int(d)}\n" for d in mesh.labels))
    return obj, labels, len(mesh.triangles)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="skip the 10^5-face structures")
    parser.add_argument("--pictures", action="store_true",
                        help="also the gallery and the sheet of the whole shipped catalog, two workers "
                             "(about a minute each a run; the target is wall time)")
    args = parser.parse_args()
    exe = [sys.executable, "-m", "polyloops"]
    rows = []
    with tempfile.TemporaryDirectory() as name:
        tmp = Path(name)
        cases: list[tuple[str, list[str], float | None]] = []
        if not args.quick:
            # Written in another process: a child forked from a process holding the box would
            # report that process's memory as its own peak.
            with ProcessPoolExecutor(1) as pool:
                own, shuffled = pool.submit(write_structures, tmp).result()
            for label, path in (("own numbering", own), ("shuffled", shuffled)):
                cases += [(f"verify, box 10^5 faces, {label}", ["verify", str(path)], 2.0),
                          (f"signature (labelled), {label}",
                           ["signature", str(path), "--symmetry", "labelled"], 2.0),
                          (f"signature (full), {label}", ["signature", str(path)], None),
                          (f"moves --remove --count, {label}",
                           ["moves", str(path), "--remove", "--count"], 2.0)]
        for s in (10, 15):
            with ProcessPoolExecutor(1) as pool:
                obj, labels, triangles = pool.submit(write_mesh, tmp, s).result()
            cases += [(f"segmentation, {triangles} triangles",
                       ["segmentation", str(obj), str(labels)], 0.5),
                      (f"segmentation --png, {triangles} triangles",
                       ["segmentation", str(obj), str(labels), "--png", str(tmp / "s.png")], 3.0)]
        slab, large = tmp / "slab.json", tmp / "slab-6x5x1.json"
        slab.write_text(dumps(box(5, 5, 1)))
        large.write_text(dumps(box(6, 5, 1)))
        # 36.9 million Z-loops, the size of the fandisk layout's 39.8 million (issue 26's 30 s).
        cases += [("moves --count --add Z, 5x5x1 slab (2.4 million)",
                   ["moves", str(slab), "--count", "--add", "Z"], None),
                  ("moves --count --add Z, 6x5x1 slab (36.9 million)",
                   ["moves", str(large), "--count", "--add", "Z"], 30.0),
                  ("moves --count --estimate, 5x5x1 slab",
                   ["moves", str(slab), "--count", "--estimate"], None)]
        if args.pictures:
            cases += [("gallery, whole catalog, --workers 2 (wall)",
                       ["gallery", "-o", str(tmp / "site"), "--workers", "2"], 60.0),
                      ("sheet, whole catalog, --workers 2 (wall)",
                       ["sheet", str(CATALOG), "-o", str(tmp / "sheet.png"), "--workers", "2"], 60.0)]
        for label, cmd, target in cases:
            if cmd[0] == "gallery":
                shutil.rmtree(tmp / "site", ignore_errors=True)  # the gallery resumes: start afresh
            cpu, wall, mb = run([*exe, *cmd], 1 if cmd[0] == "gallery" else args.repeat)  # a rerun resumes
            spent = wall if "(wall)" in label else cpu
            rows.append([label, round(cpu, 2), round(wall, 2), mb, "-" if target is None else target,
                         "-" if target is None else round(spent / target, 2)])
            print(f"{label}: {cpu:.2f} s", file=sys.stderr)
    print(f"load average at the end: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    print(markdown_table(["command", "CPU s", "wall s", "peak MB", "target s", "CPU (wall) / target"], rows))


if __name__ == "__main__":
    main()
