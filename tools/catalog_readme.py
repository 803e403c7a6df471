"""Write the tables of catalogs/README.md from the shipped catalogs' summaries and reachability
certificates (genus 0, and genus 1 when it is shipped; a test checks they agree).

Run from the repository root: ``python tools/catalog_readme.py``.
"""

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BEGIN, END = "<!-- table: begin -->", "<!-- table: end -->"
REACH_BEGIN, REACH_END = "<!-- reachability: begin -->", "<!-- reachability: end -->"
G1_BEGIN, G1_END = "<!-- genus1 table: begin -->", "<!-- genus1 table: end -->"
G1_REACH_BEGIN, G1_REACH_END = "<!-- genus1 reachability: begin -->", "<!-- genus1 reachability: end -->"


def genus1_table(summary: dict) -> str:
    """Genus 1: the counts in the three modes from the smallest number of corners with a class
    (every smaller number has none)."""
    counts = summary["counts"]
    first = next((int(n) for n, c in counts.items() if c["labelled"]), None)
    lines = ["| corners | labelled | up to rotation | up to rotation and reflection |",
             "|---:|---:|---:|---:|"]
    if first is not None and first > 8:
        lines.append(f"| 8 to {first - 1} | 0 | 0 | 0 |")
    for n, c in counts.items():
        if first is not None and int(n) >= first:
            lines.append(f"| {n} | {c['labelled']} | {c['rotation']} | {c['full']} |")
    return "\n".join(lines)


def table(summary: dict) -> str:
    lines = ["| corners | quadrangulations | with simple strips | labelled | up to rotation "
             "| up to rotation and reflection |", "|---:|---:|---:|---:|---:|---:|"]
    for n, c in summary["counts"].items():
        maps = summary["quadrangulations"][n]
        strips = summary["simple_strips"][n]
        lines.append(f"| {n} | {'-' if maps is None else maps} | {'-' if strips is None else strips} "
                     f"| {c['labelled']} | {c['rotation']} | {c['full']} |")
    return "\n".join(lines)


def reach_table(rows: list[dict]) -> str:
    """Per number of corners: classes, irreducible classes, how many are settled, and the
    largest detour (extra corners above the class, number of moves)."""
    typed = any("orientation" in r for r in rows)
    lines = [("| orientation type " if typed else "")
             + "| corners | classes | irreducible | settled by a detour "
             "| largest detour (extra corners, moves) |",
             ("|---" if typed else "") + "|---:|---:|---:|---:|---:|"]
    for r in rows:
        detour = (f"+{r['largest_detour_corners']}, {r['largest_detour_moves']}"
                  if r["settled_irreducible"] else "-")
        lines.append((f"| {r['orientation']} " if typed else "")
                     + f"| {r['corners']} | {r['classes']} | {r['irreducible']} | {r['settled_irreducible']} "
                     f"| {detour} |")
    return "\n".join(lines)


def _replace(text: str, begin: str, end: str, body: str) -> str:
    head, _, rest = text.partition(begin)
    _, _, tail = rest.partition(end)
    return f"{head}{begin}\n{body}\n{end}{tail}"


def render(template: str, summary: dict, reach_rows: list[dict] | None = None,
           genus1: tuple[dict, list[dict]] | None = None) -> str:
    out = _replace(template, BEGIN, END, table(summary))
    if reach_rows is not None:
        out = _replace(out, REACH_BEGIN, REACH_END, reach_table(reach_rows))
    if genus1 is not None:
        out = _replace(out, G1_BEGIN, G1_END, genus1_table(genus1[0]))
        out = _replace(out, G1_REACH_BEGIN, G1_REACH_END, reach_table(genus1[1]))
    return out


def certificate_rows(path: Path) -> list[dict]:
    """The per-corner table of a certificate, recomputed from its records."""
    from polyloops.reach.conjecture import ClassRecord, ConjectureResult

    lines = path.read_text().splitlines()
    header = json.loads(lines[0])
    result = ConjectureResult(header["max_corners"], header["slack"])
    result.records.extend(ClassRecord.from_json(json.loads(line)) for line in lines[1:])
    return [row.to_json() for row in result.table()]


def genus1() -> tuple[dict, list[dict]] | None:
    """The shipped genus-1 catalog's summary and certificate table, if it is shipped."""
    where = ROOT / "catalogs" / "genus1"
    if not (where / "summary.json").exists():
        return None
    return (json.loads((where / "summary.json").read_text()),
            certificate_rows(where / "reachability-certificate.jsonl"))


def write_all() -> None:
    """catalogs/README.md (the tables) and docs/reachability.md (the certificates' tables)."""
    readme = ROOT / "catalogs" / "README.md"
    summary = json.loads((ROOT / "catalogs" / "genus0" / "summary.json").read_text())
    rows = certificate_rows(ROOT / "catalogs" / "genus0" / "reachability-certificate.jsonl")
    g1 = genus1()
    readme.write_text(render(readme.read_text(), summary, rows, g1))
    page = ROOT / "docs" / "reachability.md"
    text = _replace(page.read_text(), REACH_BEGIN, REACH_END, reach_table(rows))
    if g1 is not None:
        text = _replace(text, G1_REACH_BEGIN, G1_REACH_END, reach_table(g1[1]))
    page.write_text(text)
    print(f"wrote {readme} and {page}")


if __name__ == "__main__":
    write_all()
