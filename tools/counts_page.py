"""Write docs/counts.md and the b-files in docs/bfiles/ from catalogs/genus0/summary.json
(a test checks they agree).

Run from the repository root: ``python tools/counts_page.py``.
"""

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SEQUENCES = {
    "labelled": "genus-0 polycubes with n corners up to order-equivalence (axes fixed; a polycube "
                "and its inverse identified)",
    "rotation": "genus-0 polycubes with n corners up to order-equivalence and the 24 rotations",
    "full": "genus-0 polycubes with n corners up to order-equivalence and all 48 symmetries of the cube",
}
SIMPLE_STRIPS = ("simple quadrangulations of the sphere with n vertices and minimum degree 3 (mirror "
                 "images identified) all of whose strips are simple closed curves")


def bfile(summary: dict, mode: str) -> str:
    """OEIS b-file: 'n a(n)' per line, n the number of corners."""
    if mode == "simple-strips":  # counted by plantri's generator only: as far as it went
        return "".join(f"{n} {c}\n" for n, c in summary["simple_strips"].items() if c is not None)
    return "".join(f"{n} {c[mode]}\n" for n, c in summary["counts"].items())


def page(summary: dict) -> str:
    top = max(int(n) for n in summary["counts"])
    lines = [
        "# Counts of genus-0 polycubes",
        "",
        "Computed by `polyloops catalog` (see [catalog.md](catalog.md)) and regenerated from",
        "`catalogs/genus0/summary.json` by `python tools/counts_page.py`. A polycube here is a closed",
        "quad mesh with integer corners (Definition 1 of Snoep, Speckmann and Verbeek, *Polycubes via",
        "Dual Loops*), possibly self-intersecting, counted up to order-equivalence (Definition 2) with a",
        "polycube and its inverse identified. Odd numbers of corners have none (two simple loops on the",
        f"sphere cross an even number of times). Through {top} corners:",
        "",
        "| corners | labelled | up to rotation | up to rotation and reflection "
        "| quadrangulations | with simple strips |",
        "|---:|---:|---:|---:|---:|---:|",
    ]
    for n, c in summary["counts"].items():
        if int(n) % 2 == 0:
            maps, strips = summary["quadrangulations"][n], summary["simple_strips"][n]
            lines.append(f"| {n} | {c['labelled']} | {c['rotation']} | {c['full']} "
                         f"| {'-' if maps is None else maps} | {'-' if strips is None else strips} |")
    lines += ["", "As sequences (even numbers of corners from 8), for submission:", ""]
    for mode, text in SEQUENCES.items():
        values = [c[mode] for n, c in summary["counts"].items() if int(n) % 2 == 0]
        lines.append(f"- {text}: {', '.join(map(str, values))} ([b-file](bfiles/{mode}.txt))")
    strips = [c for n, c in summary["simple_strips"].items() if int(n) % 2 == 0 and c is not None]
    lines.append(f"- {SIMPLE_STRIPS}: {', '.join(map(str, strips))} ([b-file](bfiles/simple-strips.txt))")
    lines += ["", "The b-files list `n a(n)` for every number of corners `n` in range, zeros included.",
              "*Quadrangulations* are those plantri generates (`plantri -qc2 n`: simple, minimum",
              "degree 3, mirror images identified), the maps the catalog reads; *with simple strips*",
              "counts those of them whose strips (dual loops) are all simple closed curves, whatever",
              "their degrees. Odd `n` has none with simple strips (the same theorem), so that b-file",
              "lists 0 there.",
              "The up-to-rotation count equals the up-to-all-symmetries count plus the number of",
              "chiral classes, at every `n` (tested on the catalog).", ""]
    return "\n".join(lines)


def write_all(summary: dict) -> dict[Path, str]:
    files = {ROOT / "docs" / "counts.md": page(summary)}
    for mode in (*SEQUENCES, "simple-strips"):
        files[ROOT / "docs" / "bfiles" / f"{mode}.txt"] = bfile(summary, mode)
    return files


if __name__ == "__main__":
    summary = json.loads((ROOT / "catalogs" / "genus0" / "summary.json").read_text())
    for path, text in write_all(summary).items():
        path.parent.mkdir(exist_ok=True)
        path.write_text(text)
        print(f"wrote {path}")
