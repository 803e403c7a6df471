"""Ship a larger catalog run as the package's catalog of its genus, checked, with its certificate.

    python tools/ship_catalog.py RUN_DIR [--into src/polyloops/catalogs/genusG] [--slack 10]

RUN_DIR is a finished ``polyloops catalog`` run (full classes) that goes further than the
shipped catalog. Before anything is replaced, the run must agree with the shipped catalog
over the shipped range, record for record and count for count. The run's summary keeps the
numbers of plantri's maps the shipped catalog counted (the loops generator does not visit
them: larger corner counts stay ``null``). Then the reachability certificate is made for the
whole range and checked with ``conjecture check``'s checker, and the docs' tables
(docs/counts.md, the b-files, catalogs/README.md) are written again. The shipped certificate's
records are taken for the classes they settle, and its open classes are searched again from
the slack they were searched to: shipping the same run again with a larger ``--slack`` deepens
the search of the open classes alone.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SHIPPED = ROOT / "src" / "polyloops" / "catalogs" / "genus0"


def shipped(genus: int) -> Path:
    """Where the package's catalog of ``genus`` lives in the source tree."""
    return ROOT / "src" / "polyloops" / "catalogs" / f"genus{genus}"


class ShipError(Exception):
    """The run does not extend the shipped catalog faithfully."""


def merged_summary(old: dict, new: dict) -> dict:
    """The run's summary, with the counts of maps the old catalog knew (where the run has
    none) kept; the two must agree on the classes over the old range."""
    top = max(int(n) for n in old["counts"])
    if max(int(n) for n in new["counts"]) < top or min(int(n) for n in new["counts"]) > 8:
        raise ShipError("the run does not cover the shipped range")
    for n, row in old["counts"].items():
        if new["counts"][n] != row:
            raise ShipError(f"{n} corners: the run counts {new['counts'][n]}, the shipped catalog {row}")
    out = dict(new)
    for table in ("quadrangulations", "simple_strips"):
        out[table] = {n: (old[table].get(n) if v is None and n in old[table] else v)
                      for n, v in new[table].items()}
    return out


def shipped_summary(summary: dict, into: Path) -> dict:
    """The summary as shipped: the records' mode and the digest of the one file that ships
    (catalog.jsonl; queries build the database from it)."""
    from polyloops.catalog.run import file_digest

    first = (into / "catalog.jsonl").read_text().partition("\n")[0]
    mode = json.loads(first)["symmetry"] if first else "full"
    return {**summary, "symmetry": mode, "files": {"catalog.jsonl": file_digest(into / "catalog.jsonl")}}


def check_records(old_dir: Path, new_dir: Path) -> None:
    top = max(int(n) for n in json.loads((old_dir / "summary.json").read_text())["counts"])
    old = (old_dir / "catalog.jsonl").read_text().splitlines()
    new = [line for line in (new_dir / "catalog.jsonl").read_text().splitlines()
           if json.loads(line)["corners"] <= top]
    if old != new:
        raise ShipError(f"the run's records through {top} corners differ from the shipped ones")


def ship(run: Path, into: Path = SHIPPED, slack: int = 10, workers: int = 1) -> dict:
    """Check ``run`` against ``into`` and replace ``into``'s catalog with it; returns the
    certificate check's summary."""
    from polyloops.io.files import write_atomic
    from polyloops.reach.conjecture import (
        CERTIFICATE_NAME,
        certificate_lines,
        check_certificate,
        read_records,
        settle_catalog,
    )

    new = json.loads((run / "summary.json").read_text())
    certificate = into / CERTIFICATE_NAME
    earlier = read_records(certificate.read_text().splitlines()) if certificate.exists() else []
    top = max(int(n) for n in new["counts"])
    if (into / "summary.json").exists():
        old = json.loads((into / "summary.json").read_text())
        if old.get("genus", 0) != new.get("genus", 0):
            raise ShipError(f"the run is of genus {new.get('genus', 0)}, "
                            f"the shipped catalog of {old.get('genus', 0)}")
        check_records(into, run)
        summary = merged_summary(old, new)
    else:  # the first catalog of its genus
        into.mkdir(parents=True, exist_ok=True)
        summary = new
    # The records ship once: queries of a catalog without catalog.sqlite build the table in
    # memory from catalog.jsonl (census.query), so the database is not copied.
    shutil.copyfile(run / "catalog.jsonl", into / ".catalog.jsonl.new")
    (into / ".catalog.jsonl.new").replace(into / "catalog.jsonl")
    (into / "catalog.sqlite").unlink(missing_ok=True)
    write_atomic(into / "summary.json", json.dumps(shipped_summary(summary, into), indent=1) + "\n")
    from tqdm import tqdm

    from polyloops.catalog.run import file_digest

    # and those of this run's earlier passes, whatever their slack (a stopped pass is not lost)
    earlier += journal_records(run / "parts", file_digest(into / "catalog.jsonl"), top)

    total = sum(int(row["full"]) for row in summary["counts"].values())
    with tqdm(total=total, desc="certificate", unit="class", disable=None, file=sys.stderr) as bar:
        # the classes settled so far, kept in the run's parts: a stopped ship resumes
        result = settle_catalog(into, top, slack, workers, progress=lambda _: bar.update(1),
                                journal=run / "parts" / f"settle-journal-{slack}.jsonl", earlier=earlier)
    lines = list(certificate_lines(result))
    check = check_certificate(lines, into)
    if not check.valid:
        raise ShipError(f"the certificate does not check: {check.problems[0]}")
    write_atomic(certificate, "\n".join(lines) + "\n")
    return {"max_corners": top, "classes": check.records, "proves": check.statement(),
            "unsettled": {c.name: c.searched for c in check.open},
            "by_corners": [row.to_json() for row in result.table()]}


def journal_records(parts: Path, digest: str, top: int) -> list:
    """The records of the run's settle journals (one a slack) of this catalog and range; an
    open one without its search stated was searched to its journal's slack."""
    from dataclasses import replace

    from polyloops.reach.conjecture import ClassRecord, journal_lines

    out: list[ClassRecord] = []
    for path in sorted(parts.glob("settle-journal*.jsonl")):
        lines = path.read_bytes().decode("utf-8", "replace").splitlines()
        try:
            head = json.loads(lines[0]) if lines else {}
        except ValueError:
            continue
        if not isinstance(head, dict) or head.get("kind") != "settle-journal" \
                or head.get("catalog") != digest or head.get("max_corners") != top:
            continue
        out += (record if record.settled or record.searched is not None
                else replace(record, searched=head["slack"]) for record in journal_lines(lines[1:]))
    return out


def _tool(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / "tools" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)  # type: ignore[arg-type]
    spec.loader.exec_module(module)  # type: ignore[union-attr]
    return module


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", type=Path)
    parser.add_argument("--into", type=Path, help="default: the package's catalog of the run's genus")
    parser.add_argument("--slack", type=int, default=10)
    parser.add_argument("--workers", type=int, default=1)
    args = parser.parse_args()
    genus = json.loads((args.run / "summary.json").read_text()).get("genus", 0)
    into = args.into or shipped(genus)
    try:
        report = ship(args.run, into, args.slack, args.workers)
    except ShipError as err:
        sys.exit(f"ship_catalog: {err}")
    print(json.dumps(report, indent=1))
    if into.resolve() == shipped(genus).resolve():
        for path, text in _tool("counts_page").write_all().items():
            path.write_text(text)
        _tool("catalog_readme").write_all()


if __name__ == "__main__":
    main()
