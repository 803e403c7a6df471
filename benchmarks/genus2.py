"""Genus 2 with a sparse pair of axes: every genus-2 polycube with at most ``--corners`` corners
whose sparsest pair of axes crosses at most ``--bases`` times, and what finding them costs.

    python benchmarks/genus2.py --bases 10 --corners 48

Lists the two-axis arrangements B of genus 2 through ``--bases`` crossings (the first stage of
the ``handles`` generator), then the third axis of each within ``--corners + 2`` crossings (the
second stage), keeping the maps that carry a polycube from their canonical decomposition: the
candidates of ``polyloops catalog --genus 2`` restricted to those B.  So the list is complete
for polycubes whose sparsest pair crosses at most ``--bases`` times; it is the whole catalog
only through ``3 * bases`` corners.  One process; prints a Markdown table per size of B (how
many, the CPU of each stage, the maps found) and the maps found, each named when it is one of
the bundled genus-2 examples.
"""

from __future__ import annotations

import argparse
import sys
import time
from collections import Counter

from _common import markdown_table

from polyloops.generate.torus.arrangement import TorusArrangement, arrangement_of_twin, canonical
from polyloops.generate.torus.candidates import SecondStage, _third_axes
from polyloops.generate.torus.decompositions import canonical_decomposition, carries_polycube
from polyloops.generate.torus.stages import TorusSearchStats, first_stage
from polyloops.io.examples import load_example

EXAMPLES = ("slab-2-holes", "two-axis-holes")  # the bundled genus-2 polycubes


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--bases", type=int, default=10, help="the most crossings of B (default 10)")
    parser.add_argument("--corners", type=int, default=48, help="the most corners (default 48)")
    args = parser.parse_args()
    if not 3 <= args.bases <= 14 or args.corners < 1:
        parser.error("--bases takes 3 to 14 and --corners a positive number")
    start = time.process_time()
    bases, _ = first_stage(args.bases, genus=2)
    first_cpu = time.process_time() - start
    known = {}
    for name in EXAMPLES:
        structure = load_example(name).dualize()  # type: ignore[union-attr]
        known[canonical(TorusArrangement(tuple(structure.map.twin)))[0]] = name
    rows, found = [], []
    sizes = Counter(len(raw) // 8 for raw in bases)  # four darts a crossing, two bytes a dart
    for c in sorted(sizes):
        stats, kept = TorusSearchStats(), 0
        start = time.process_time()
        for raw in bases:
            if len(raw) // 8 != c:
                continue
            for kid in _third_axes(arrangement_of_twin(raw), args.corners + 2, stats, SecondStage.REGIONS):
                if carries_polycube(kid) and canonical_decomposition(kid):
                    plain = TorusArrangement(kid.twin)
                    found.append((plain.crossings - 2, c, known.get(canonical(plain)[0], "-")))
                    kept += 1
        rows.append([c, sizes[c], f"{time.process_time() - start:.1f}", kept])
    print(f"first stage through {args.bases} crossings: {len(bases)} B, {first_cpu:.1f} s of CPU\n")
    header = ["B crossings", "B", "second stage CPU s", f"polycubes with <= {args.corners} corners"]
    print(markdown_table(header, rows))
    if found:
        print()
        print(markdown_table(["corners", "B crossings", "bundled example"], [list(f) for f in sorted(found)]))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
