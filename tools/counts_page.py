"""Write docs/counts.md and the b-files in docs/bfiles/ from catalogs/genus0/summary.json and,
when the genus-1 catalog ships, catalogs/genus1 (a test checks they agree).

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
    lines += quadrangulation_note(summary) + carrying_section(summary) + drafts(summary)
    return "\n".join(lines)


def quadrangulation_note(summary: dict) -> list[str]:
    known = [int(n) for n, c in summary["quadrangulations"].items() if c is not None and int(n) % 2 == 0]
    return ["## Conventions", "",
            "- *Polycube*: Definition 1 of the paper, a closed quad mesh of genus 0 whose corners",
            "  have integer coordinates and whose edges are parallel to the axes, with pairwise",
            "  different directions at each corner; it may intersect itself. *Corners* are the",
            "  mesh's vertices (the regions of its loop structure).",
            "- *Order-equivalence* (Definition 2): two polycubes are the same when a bijection of",
            "  their meshes keeps, along each axis, the order of the corners' coordinates. A",
            "  polycube and its inverse (every face reversed) are identified.",
            "- *Labelled*: axes fixed, no symmetry; *up to rotation*: the 24 rotations of the cube",
            "  act on the axes; *up to rotation and reflection*: all 48 signed permutations.",
            "- *Quadrangulations*: the number of corners `n` is the number of vertices; the column",
            "  is OEIS [A078666](https://oeis.org/A078666)`(n - 2)` (indexed by faces) at every",
            f"  even `n` from {min(known)} to {max(known)} (a test compares them); odd `n` was not",
            "  generated here (no polycube has an odd number of corners).", ""]


def carrying_section(summary: dict) -> list[str]:
    rows = {n: c for n, c in summary.get("maps_by_classes", {}).items() if int(n) % 2 == 0}
    if not rows:
        return []
    most = max((int(k) for c in rows.values() for k in c), default=1)
    first = next((n for n, c in rows.items() if any(int(k) >= 2 for k in c)), None)
    lines = ["## Maps that carry several polycubes", "",
             "Each class lies on one quadrangulation (its quad mesh, mirror images identified);",
             "how many classes (up to all symmetries) the candidate maps carry:", "",
             "| corners | " + " | ".join(f"maps with {k}" for k in range(1, most + 1)) + " |",
             "|---:|" + "---:|" * most]
    for n, c in rows.items():
        lines.append(f"| {n} | " + " | ".join(str(c.get(str(k), 0)) for k in range(1, most + 1)) + " |")
    top = max(int(n) for n in rows)
    if first is None:
        lines += ["", f"Through {top} corners every quadrangulation carries at most one polycube class.", ""]
    else:
        several = sum(v for k, v in rows[first].items() if int(k) >= 2)
        lines += ["", f"Through {top} corners the smallest quadrangulations that carry two or more classes "
                  f"have {first} corners ({several} {'map' if several == 1 else 'maps'} there).", ""]
    return lines


def drafts(summary: dict) -> list[str]:
    top = max(int(n) for n in summary["counts"])
    lines = ["## Draft OEIS entries", "",
             "Offset 8; the terms are `a(n)` for even `n` (odd `n` gives 0 and is left out, as in the",
             "lists above). Program: `polyloops catalog --max-corners N -o DIR` (Python package",
             "polyloops), whose `summary.json` holds the three counts; `docs/catalog.md` says how",
             "the catalog is made and checked.", ""]
    count = {int(n): c for n, c in summary["counts"].items()}
    chiral = count[20]["rotation"] - count[20]["full"]
    examples = {"labelled": f"a(12) = {count[12]['labelled']}: the 2 x 1 x 1 box along each of the "
                            "three axes.",
                "rotation": f"a(16) = {count[16]['rotation']}: the 3 x 1 x 1 box and the L of three cubes.",
                "full": f"a(20) = {count[20]['full']} (up to rotation {count[20]['rotation']}: "
                        f"{chiral} {'class is' if chiral == 1 else 'classes are'} chiral)."}
    for mode, text in SEQUENCES.items():
        values = [c[mode] for n, c in summary["counts"].items() if int(n) % 2 == 0]
        lines += [f"### {mode}", "",
                  f"- Name: Number of {text}, for even n.",
                  f"- Data (n = 8, 10, ..., {top}): {', '.join(map(str, values))}",
                  "- Comments: polycubes may intersect themselves; the count is of polycube loop",
                  "  structures (Definition 4), which are in bijection with polycubes up to",
                  "  order-equivalence (Theorems 1 and 2 of Snoep, Speckmann and Verbeek).",
                  f"- Example: {examples[mode]}",
                  f"- b-file: [bfiles/{mode}.txt](bfiles/{mode}.txt)", ""]
    return lines


def orientation_counts(catalog: Path) -> dict[str, dict[int, int]]:
    """Per hole-orientation type (the invariant up to the axes' symmetries), the classes up to
    all symmetries by corners, from a catalog's records: the type its certificate states (which
    `conjecture check` computes again from the signature), else computed from the signature."""
    from polyloops.core.canonical import from_signature
    from polyloops.reach.conjecture import orientation_type

    cert = catalog / "reachability-certificate.jsonl"
    stated = {r["signature"]: r["orientation"] for r in map(json.loads, cert.read_text().splitlines()[1:])
              if "orientation" in r} if cert.is_file() else {}
    out: dict[str, dict[int, int]] = {}
    for line in (catalog / "catalog.jsonl").read_text().splitlines():
        record = json.loads(line)
        kind = stated.get(record["signature"]) or orientation_type(from_signature(record["signature"]))
        row = out.setdefault(kind, {})
        row[record["corners"]] = row.get(record["corners"], 0) + 1
    return out


def genus1_section(summary: dict, types: dict[str, dict[int, int]]) -> list[str]:
    counts = summary["counts"]
    top = max(int(n) for n in counts)
    first = next((int(n) for n, c in counts.items() if c["labelled"]), None)
    lines = ["## Genus 1", "",
             "Computed by `polyloops catalog --genus 1` (the torus search of",
             "[catalog.md](searches.md#genus-1-the-torus-search)) and regenerated from",
             "`catalogs/genus1/summary.json`. On the torus a loop structure has as many corners as",
             "crossings, and two loops may cross an odd number of times, so every number of corners",
             f"is searched. Through {top} corners the search is complete: "
             + (f"no genus-1 polycube has fewer than {first} corners." if first is not None
                else "no genus-1 polycube has that many corners or fewer."), ""]
    if first is not None:
        lines += ["| corners | labelled | up to rotation | up to rotation and reflection |",
                  "|---:|---:|---:|---:|"]
        for n, c in counts.items():
            if int(n) >= first:
                lines.append(f"| {n} | {c['labelled']} | {c['rotation']} | {c['full']} |")
        sizes = sorted({n for row in types.values() for n in row})
        lines += ["", "By hole orientation (the invariant of `polyloops.core.holes`, up to the symmetries of",
                  "the axes; moves never change it), classes up to rotation and reflection:", "",
                  "| orientation type | " + " | ".join(f"{n} corners" for n in sizes) + " |",
                  "|---|" + "---:|" * len(sizes)]
        for kind, row in sorted(types.items()):
            lines.append(f"| {kind} | " + " | ".join(str(row.get(n, 0)) for n in sizes) + " |")
    lines += ["", "B-files (`n a(n)` for every `n` from 8, zeros included): "
              + ", ".join(f"[{mode}](bfiles/genus1-{mode}.txt)" for mode in SEQUENCES) + ".", ""]
    return lines


# No genus-2 catalog ships (a run through 45 corners finds none), so this section is what the
# runs it names found, kept here beside the tables it follows; the runs carried in runs/ are read.
GENUS2 = """## Genus 2

Computed by `polyloops catalog --genus 2` (the `handles` generator:
[searches.md](searches.md#genus-2-the-same-two-stages-with-pieces)). A genus-2 loop structure
with `N` corners has `N + 2` crossings, and the search is complete through `N` corners when its
first stage lists every two-axis arrangement `B` with up to `(N + 2) / 3` crossings.

- **No genus-2 polycube has 45 corners or fewer.** `polyloops catalog --genus 2 --max-corners
  45 --workers 2 -o g2-45`: the first stage through 15 crossings (491,579 `B`: 2 with 6
  crossings, 23 with 8, 522 with 10, 1 with 11, 15,629 with 12, 21 with 13, 474,676 with 14,
  705 with 15, listed as square-tiled surfaces), then the third axis of each within 47
  crossings; four third axes passed the region search and none of their maps carries a
  polycube. Run in three sittings on two cores, each resumed from the finished shares' part
  files (the last: 24 min of wall time for 66 shares); its parts are kept (below). The run
  through 44 corners before it, the same `B` at 46 crossings: 7,160 s of user CPU in 64
  shares, 89 MB at the peak (`/usr/bin/time -v`); through 42: 2,576 s.
- **The smallest known have 48 corners**: the slab with two holes along one axis
  (`example:slab-2-holes`, its sparsest pair of axes crossing 10 times, the others 14 and 26)
  and the bar with holes along two axes (`example:two-axis-holes`, pairs 14, 18 and 18). Every
  genus-2 polycube with at most 48 corners whose sparsest pair crosses at most 12 times is the
  slab: the second stage from the 16,177 `B` with up to 12 crossings, at 50 crossings, built
  one map with a polycube, the slab's (`python benchmarks/genus2.py --bases 12 --corners 48`:
  0.5 s of CPU for the first stage, 2,762 s for the second, 2,576 of them on the 15,629 `B` of
  12 crossings; one process).
- At 46 and 47 corners the question is open: a genus-2 polycube with 46 or 47 corners has a
  pair crossing at most 16 times (`(47 + 2) / 3`), and `two-axis-holes` shows that the sparsest
  pair of a 48-corner one can cross 14 times. Every `B` through 16 crossings is now listed
  (14,362,363, 13,870,784 of them with 16), and the third axes of all of them cost about 60 to
  110 hours of CPU through 47 corners and 105 to 200 through 48 (measured on whole shares:
  [searches.md](searches.md#genus-2-the-same-two-stages-with-pieces)): the run is a cluster's
  ([cluster.md](cluster.md#genus-2-through-48-corners)).
{runs}- Moves from the slab (`polyloops reach example:slab-2-holes --max-corners 60 --symmetry full`):
  4,872 classes, none with fewer than 48 corners. The two known 48-corner polycubes have
  different hole orientations (the slab `XY: rank 0; XZ: rank 2; YZ: rank 2`, the bar with holes
  along two axes `XY: rank 1; XZ: rank 1; YZ: rank 2`; `polyloops info`), so no sequence of
  moves joins them: at genus 2 too the reachability question is one per orientation type.
"""


def runs_section(root: Path = ROOT) -> str:
    """A bullet a genus-2 run carried in ``runs/``, finished or in progress (its parts, read by
    ``catalog status``)."""
    from polyloops.catalog.status import run_status

    out = []
    for directory in sorted((root / "runs").glob("genus2-*")):
        plan = run_status(directory).plans[0]
        top, secs = plan.max_corners, round(sum(plan.seconds))
        said = "no class found in them" if not plan.found else \
            "found in them: " + ", ".join(f"{c:,} with {n} corners" for n, c in plan.found.items())
        if not plan.missing:
            out.append(
                f"- **The run through {top} corners, finished** (`runs/{directory.name}` in the "
                f"repository): the part files of all {plan.shares:,} shares (`polyloops catalog status "
                f"runs/{directory.name}` reads them, as a resumed run would): {secs:,} s of worker time, "
                f"{said}.")
            continue
        rest = "no share has finished yet" if plan.estimate is None else \
            f"at their mean so far the others need about {plan.estimate / 3600:,.0f} hours of one core"
        out.append(
            f"- **The run through {top} corners, in progress** (`runs/{directory.name}` in the "
            f"repository; `runs/README.md` says how to go on): `polyloops catalog --genus 2 --max-corners "
            f"{top}`, resumable anywhere from its finished shares (`polyloops catalog status` reads them): "
            f"**{len(plan.done):,} of the {plan.shares:,} shares** finished, {secs:,} s of worker time, "
            f"{said}. A share's `B` are a subtree of the first stage's listing, not a range of corners, so "
            f"the finished shares decide nothing about any corner count until all are in (then the run "
            f"decides every count through {top}); {rest}.")
    return "".join(wrap(line) + "\n" for line in out)


def wrap(line: str, width: int = 96) -> str:
    """A Markdown bullet wrapped as the page's others are (continuation lines indented)."""
    import textwrap

    return "\n".join(textwrap.wrap(line, width, subsequent_indent="  ", break_long_words=False,
                                    break_on_hyphens=False))


def write_all(summary: dict | None = None, genus1: dict | None = None) -> dict[Path, str]:
    """Every file the shipped summaries give (read from catalogs/ when not given)."""
    summary = summary or json.loads((ROOT / "catalogs" / "genus0" / "summary.json").read_text())
    g1_dir = ROOT / "catalogs" / "genus1"
    if genus1 is None and (g1_dir / "summary.json").exists():
        genus1 = json.loads((g1_dir / "summary.json").read_text())
    text = page(summary)
    files: dict[Path, str] = {}
    if genus1 is not None:
        text += "\n" + "\n".join(genus1_section(genus1, orientation_counts(g1_dir)))
        for mode in SEQUENCES:
            files[ROOT / "docs" / "bfiles" / f"genus1-{mode}.txt"] = bfile(genus1, mode)
    files[ROOT / "docs" / "counts.md"] = text + "\n" + GENUS2.format(runs=runs_section())
    for mode in (*SEQUENCES, "simple-strips"):
        files[ROOT / "docs" / "bfiles" / f"{mode}.txt"] = bfile(summary, mode)
    return files


if __name__ == "__main__":
    for path, text in write_all().items():
        path.parent.mkdir(exist_ok=True)
        path.write_text(text)
        print(f"wrote {path}")
