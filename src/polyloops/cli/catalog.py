"""The catalog commands: ``catalog`` (build or resume), ``catalog query``, ``catalog export`` and
``catalog status``."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from polyloops.cli.args import (
    MAX_WORKERS,
    SYMMETRIES,
    AddCommand,
    Parser,
    catalog_dir,
    count_arg,
    emit,
    genus_option,
    plural,
    written,
)
from polyloops.cli.load import EXIT_OK, CliError, write_text
from polyloops.generate.bounds import MAX_CATALOG_CORNERS


def cmd_catalog(args: argparse.Namespace) -> int:
    if args.action == "query":
        return cmd_catalog_query(args)
    if args.action == "export":
        return cmd_catalog_export(args)
    if args.action == "status":
        return cmd_catalog_status(args)
    missing = [flag for flag, value in (("--max-corners", args.max_corners), ("-o/--output", args.output))
               if value is None]
    if missing:
        raise CliError(f"the following arguments are required: {', '.join(missing)} (see --help)")
    from tqdm import tqdm

    from polyloops.catalog.jobs import JobResult
    from polyloops.catalog.run import (
        CatalogRunError,
        WouldLoseResultsError,
        build_catalog,
        choose_generator,
    )
    from polyloops.generate.base import generators
    from polyloops.generate.plantri.quadrangulations import PlantriError

    try:
        generator, note = choose_generator(args.generator, args.method, args.plantri, args.genus)
    except CatalogRunError as err:
        raise CliError(f"--generator {args.generator}: {err}" if args.generator else str(err)) from None
    try:
        configured = generators()[generator].with_options(plantri=args.plantri, method=args.method)
    except (KeyError, ValueError):
        configured = None  # build_catalog names the problem
    notes = [line for line in [note, *(configured.notes() if configured else [])] if line]
    bar = tqdm(unit="job", desc="catalog", disable=None, file=sys.stderr)
    maps = [0]

    def planned(jobs: list[Any]) -> None:
        # said once the run is checked and planned: bad input stays one line
        for line in notes:
            bar.write(f"polyloops catalog: note: {line}", file=sys.stderr)
        bar.reset(total=len(jobs))

    visits = generators()[generator].visits

    def progress(result: JobResult) -> None:
        maps[0] += result.visited  # what the generator visits: maps read, arrangements built
        bar.update(1)
        bar.set_postfix({"corners": result.job.n, visits: maps[0]})

    try:
        built = build_catalog(args.output, args.max_corners, args.min_corners, args.symmetry,
                              workers=args.workers, res=args.res, mod=args.mod, dask=args.dask,
                              plantri=args.plantri, method=args.method, generator=generator,
                              progress=progress, on_plan=planned, overwrite=args.overwrite,
                              genus=args.genus)
    except WouldLoseResultsError as err:
        raise CliError(f"{err}; pass --overwrite to replace it, or build into another directory") from None
    except (CatalogRunError, PlantriError) as err:
        raise CliError(with_flags(str(err))) from None
    finally:
        bar.close()
    summary = built.summary

    def shown(table: str, k: str) -> Any:
        return "-" if summary[table][k] is None else summary[table][k]

    rows = [[k, shown("quadrangulations", k), shown("simple_strips", k), *v.values()]
            for k, v in summary["counts"].items()]
    text = "corners  quadrangulations  simple strips  labelled  rotation  full\n" + "\n".join(
        f"{r[0]:>7}  {r[1]:>16}  {r[2]:>13}  {r[3]:>8}  {r[4]:>8}  {r[5]:>4}" for r in rows)
    key = generators()[generator].statistics_key
    search = summary.get(key, {}) if key else {}
    built_count = search.get("arrangements", search.get("states"))
    if built_count is not None:
        text += f"\narrangements built: {built_count} (generator {generator})"
    emit(args, summary, f"{text}\nwrote {plural(built.records, 'record')} ({args.symmetry}) to {args.output}")
    return EXIT_OK


def cmd_catalog_query(args: argparse.Namespace) -> int:
    from polyloops.catalog.census import CatalogError, query

    try:
        columns, rows = query(catalog_dir(args.dir, args.genus), args.where)
    except CatalogError as err:
        raise CliError(str(err), getattr(err, "status", 2)) from None
    if args.json:
        print(json.dumps({"catalog": str(catalog_dir(args.dir, args.genus)), "where": args.where,
                          "count": len(rows),
                          "rows": [dict(zip(columns, r, strict=True)) for r in rows]}, indent=1))
    else:
        print("\t".join(columns))
        for r in rows:
            print("\t".join(str(x) for x in r))
    return EXIT_OK


def cmd_catalog_export(args: argparse.Namespace) -> int:
    from polyloops.catalog.census import CatalogError, export_csv

    try:
        text = export_csv(catalog_dir(args.dir, args.genus))
    except CatalogError as err:
        raise CliError(str(err), getattr(err, "status", 2)) from None
    rows = max(0, text.count("\n") - 1)  # the header line aside
    if args.output:
        write_text(args.output, text)
        written(args, None, {"rows": rows}, None)
    else:
        written(args, text, {"rows": rows})
    return EXIT_OK


def cmd_catalog_status(args: argparse.Namespace) -> int:
    from polyloops.catalog.run import CatalogRunError
    from polyloops.catalog.status import run_status

    try:
        status = run_status(args.dir)
    except CatalogRunError as err:
        raise CliError(str(err)) from None
    lines = [f"{args.dir}: " + ("catalog written" if status.finished else "catalog not written yet")
             + ("" if status.plans else "; no finished share kept in its parts/")]
    for plan in status.plans:
        lines.append(plan.describe())
        lines.append("  classes found so far (up to all symmetries): " + (
            ", ".join(f"{c:,} with {n}" for n, c in plan.found.items()) if plan.found else "none")
            + f" (of {plan.min_corners} to {plan.max_corners} corners)")
    if status.damaged:
        lines.append(f"recomputed when the run resumes (damaged, edited or misnamed): "
                     f"{', '.join(status.damaged)}")
    emit(args, status.to_json(), "\n".join(lines))
    return EXIT_OK


# The library names its parameters and alternatives; the command line adds the flags for them.
FLAGS = {
    "max_corners": "--max-corners",
    "min_corners": "--min-corners",
    "the plantri generator": "the plantri generator (--generator plantri)",
    "the numpy filter": "the numpy filter (--method numpy)",
    "workers must": "--workers must",
    "a share is res and mod together": "--res R and --mod M go together",
}


def with_flags(message: str) -> str:
    """A library message with the command line's flags for what it names.

    >>> with_flags("max_corners must be at least min_corners")
    '--max-corners must be at least --min-corners'
    """
    for words, flag in FLAGS.items():
        message = message.replace(words, flag)
    return message


QUERY_HELP = "rows of a catalog matching an SQL WHERE clause"
EXPORT_HELP = "a catalog's table as CSV"
STATUS_HELP = ("a run's finished shares (DIR/parts): how many of how many, their seconds and an "
               "estimate for the others, the classes they found by corners")


def _query_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("dir", metavar="DIR", nargs="?", help="a catalog directory (default: the shipped one)")
    genus_option(p)
    p.add_argument("where", metavar="WHERE", help='an SQL condition, e.g. "corners = 20 AND chiral"')


def _export_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("dir", metavar="DIR", nargs="?", help="a catalog directory (default: the shipped one)")
    genus_option(p)
    p.add_argument("--csv", action="store_true", required=True, help="CSV (the only format so far)")
    p.add_argument("-o", "--output", metavar="OUT.csv", help="write here instead of to standard output")


def add_commands(command: AddCommand, hidden: AddCommand) -> None:
    from polyloops.generate.base import generators

    p = command("catalog", cmd_catalog, "the catalog of polycubes of one genus up to "
                "order-equivalence, by number of corners: at genus 0 from arrangements of loops or "
                "plantri's quadrangulations, at genus 1 from the torus search (two stages: "
                "arrangements of two axes' loops, then the third axis region by region); 'catalog "
                "query [DIR] WHERE' searches one, 'catalog export [DIR] --csv OUT' writes its table "
                "(without DIR: the shipped catalog of --genus), 'catalog status DIR' says how far a run "
                "got", file_arg=False)
    p.add_argument("--max-corners", type=count_arg(0, MAX_CATALOG_CORNERS), metavar="N",
                   help=f"required to build; at most {MAX_CATALOG_CORNERS} (the searches' arrays hold no "
                   "more, and no run gets near: 36 corners take minutes of CPU at genus 0)")
    p.add_argument("--min-corners", type=count_arg(8, MAX_CATALOG_CORNERS), default=8, metavar="M")
    genera = sorted({g.genus for g in generators().values()})
    p.add_argument("--genus", type=int, choices=genera, default=0, metavar="G",
                   help=f"a genus a generator searches: {', '.join(map(str, genera))} (0, the sphere, the "
                   "default; 1, the torus: the smallest genus-1 polycube, the square ring, has 32 "
                   "corners and is found in about 10 s)")
    p.add_argument("--symmetry", choices=SYMMETRIES, default="full",
                   help="which classes the records list (summary.json counts all three); default full")
    p.add_argument("--workers", type=count_arg(1, MAX_WORKERS), default=1, metavar="K",
                   help="local worker processes")
    p.add_argument("--generator", choices=sorted(generators()), default=None,
                   help="where candidate maps come from: loops (arrangements built one loop at a "
                   "time, compiled at install; the default where it was built) or plantri (every "
                   "quadrangulation, filtered; the default otherwise, and when --method or "
                   "--plantri is given); same records either way; torus for --genus 1")
    p.add_argument("--res", type=count_arg(0), metavar="R", help="only slice R of M (with --mod)")
    p.add_argument("--mod", type=count_arg(1), metavar="M")
    p.add_argument("--dask", metavar="ADDRESS", help="run the jobs on a Dask cluster (an address, or local)")
    p.add_argument("--plantri", metavar="PATH", help="the plantri to use (default: the one from "
                   "passagemath-plantri, $POLYLOOPS_PLANTRI, or PATH)")
    p.add_argument("--method", choices=("auto", "compiled", "numpy"), default="auto",
                   help="the strip filter: compiled (built at install when a C compiler is there), "
                   "numpy (the reference twin), or auto (compiled when built); same output either way")
    p.add_argument("-o", "--output", metavar="DIR", help="catalog directory (resumable); required to build")
    p.add_argument("--overwrite", action="store_true", help="replace a catalog in DIR that covers more "
                   "(more corners, another --symmetry, the whole search where this is one share); "
                   "without it such a build is refused, and a smaller catalog is resumed or extended")
    actions = p.add_subparsers(dest="action", metavar="[query|export|status]", parser_class=Parser)
    q = actions.add_parser("query", help=QUERY_HELP, description=QUERY_HELP)
    _query_arguments(q)
    q.add_argument("--json", action="store_true", default=argparse.SUPPRESS,
                   help="print one JSON object for scripts")
    e = actions.add_parser("export", help=EXPORT_HELP, description=EXPORT_HELP)
    _export_arguments(e)
    e.add_argument("--json", action="store_true", default=argparse.SUPPRESS,
                   help="print one JSON object for scripts (what was written and how many rows)")
    st = actions.add_parser("status", help=STATUS_HELP, description=STATUS_HELP)
    st.add_argument("dir", metavar="DIR", help="a catalog run's directory (-o of the run)")
    st.add_argument("--json", action="store_true", default=argparse.SUPPRESS,
                    help="print one JSON object for scripts")
    # The older spellings 'catalog-query' and 'catalog-export' still work.
    _query_arguments(hidden("catalog-query", cmd_catalog_query, QUERY_HELP))
    _export_arguments(hidden("catalog-export", cmd_catalog_export, EXPORT_HELP))

