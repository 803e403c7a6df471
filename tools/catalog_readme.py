"""Write catalogs/README.md from catalogs/genus0/summary.json (a test checks they agree).

Run from the repository root: ``python tools/catalog_readme.py``.
"""

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BEGIN, END = "<!-- table: begin -->", "<!-- table: end -->"


def table(summary: dict) -> str:
    lines = ["| corners | quadrangulations | labelled | up to rotation | up to rotation and reflection |",
             "|---:|---:|---:|---:|---:|"]
    for n, c in summary["counts"].items():
        lines.append(f"| {n} | {summary['quadrangulations'][n]} | {c['labelled']} | {c['rotation']} "
                     f"| {c['full']} |")
    return "\n".join(lines)


def render(template: str, summary: dict) -> str:
    head, _, rest = template.partition(BEGIN)
    _, _, tail = rest.partition(END)
    return f"{head}{BEGIN}\n{table(summary)}\n{END}{tail}"


if __name__ == "__main__":
    readme = ROOT / "catalogs" / "README.md"
    summary = json.loads((ROOT / "catalogs" / "genus0" / "summary.json").read_text())
    readme.write_text(render(readme.read_text(), summary))
    print(f"wrote {readme}")
