"""The reachability commands: ``reach``, ``path`` and ``conjecture``."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from polyloops.cli.args import (
    FILE_HELP,
    MAX_WORKERS,
    SYMMETRIES,
    AddCommand,
    Parser,
    catalog_dir,
    count_arg,
    emit,
    genus_option,
    plural,
)
from polyloops.cli.load import (
    EXIT_INVALID,
    EXIT_OK,
    CliError,
    check_output,
    output_dir,
    read_text_file,
    read_valid_structure,
    write_text,
)


def _kinds(text: str):
    from polyloops.reach.search import parse_kinds

    try:
        return parse_kinds(text)
    except ValueError as err:
        raise CliError(f"--moves: {err}") from None


def cmd_reach(args: argparse.Namespace) -> int:
    from tqdm import tqdm

    from polyloops.io.files import write_atomic
    from polyloops.reach.search import ReachError, WouldReplaceSearchError, explore

    start = read_valid_structure(args.start)
    kinds = _kinds(args.moves)
    out = output_dir(args.output) if args.output else None
    bar = tqdm(desc="reach", unit="level", disable=None, file=sys.stderr)

    def progress(p: dict[str, Any]) -> None:
        bar.update(1)
        rate = p["states"] / p["seconds"] if p["seconds"] else 0.0
        bar.set_postfix(level=p["level"], states=p["states"], frontier=p["frontier"],
                        rate=f"{rate:.0f}/s")

    try:
        result = explore(start, args.max_corners, args.max_depth, kinds, args.symmetry, out,
                         args.workers, args.dask, progress, overwrite=args.overwrite)
    except WouldReplaceSearchError as err:
        raise CliError(f"{err}; pass --overwrite to replace it, or use another directory") from None
    except ReachError as err:
        raise CliError(str(err)) from None
    except ValueError as err:
        raise CliError(f"{args.start}: {err}") from None
    except RuntimeError as err:  # dask missing
        raise CliError(str(err)) from None
    finally:
        bar.close()
    data = result.to_json()
    if out is not None:
        try:
            write_atomic(out / "summary.json", json.dumps(data, indent=1) + "\n", within=out)
        except OSError as err:
            raise CliError(str(err)) from None
    lines = [f"{plural(result.states, 'state')} within {args.max_corners} corners "
             f"({args.symmetry}, moves {','.join(k.value for k in kinds)}), "
             f"largest distance {result.max_distance}, {result.seconds:.1f} s"
             + ("" if result.complete else f"; stopped at depth {args.max_depth}")]
    lines.append("corners  states")
    lines += [f"{c:>7}  {n:>6}" for c, n in result.by_corners.items()]
    if out is not None:
        lines.append(f"wrote {out / 'reach.sqlite'} and {out / 'summary.json'}")
    emit(args, data, "\n".join(lines))
    return EXIT_OK


def cmd_path(args: argparse.Namespace) -> int:
    from polyloops.reach.search import find_path, no_path_reason

    source = read_valid_structure(args.source)
    target = read_valid_structure(args.target)
    reason = no_path_reason(source, target)
    if reason is not None:
        raise CliError(f"{args.source} -> {args.target}: no path at any size ({reason})", EXIT_INVALID)
    if args.max_corners is None:
        raise CliError("--max-corners M is needed: the invariants moves keep agree, so only a search "
                       "within M corners can tell")
    for name, ls in ((args.source, source), (args.target, target)):
        if ls.map.num_corners > args.max_corners:
            raise CliError(f"{name}: has {ls.map.num_corners} corners, more than --max-corners")
    path = find_path(source, target, args.max_corners, _kinds(args.moves))
    if path is None:
        raise CliError(f"{args.source} -> {args.target}: no path within {args.max_corners} corners",
                       EXIT_INVALID)
    if args.output:
        write_text(args.output, json.dumps(path.to_json(), separators=(",", ":")) + "\n")
    corners = [s.map.num_corners for s in path.steps]
    data = {"moves": len(path.moves), "corners": corners, "max_corners": max(corners),
            "steps": [{"move": m.to_json(), "corners": corners[i + 1], "text": path.describe(i)}
                      for i, m in enumerate(path.moves)]}
    lines = [f"{plural(len(path.moves), 'move')}; corners along the path: {' '.join(map(str, corners))}"]
    lines += [f"  {i + 1}. {path.describe(i)}" for i in range(len(path.moves))]
    if args.output:
        lines.append(f"wrote {args.output}")
    emit(args, data, "\n".join(lines))
    return EXIT_OK


def verify_path_file(source: str, data: dict[str, Any], as_json: bool) -> int:
    """``polyloops verify`` on a path file: every step, then every consecutive pair (by its
    move, when the file gives the moves)."""
    from polyloops.io.formats import FormatError
    from polyloops.reach.search import check_path, path_moves, path_steps

    try:
        check = check_path(path_steps(data), path_moves(data))
    except FormatError as err:
        raise CliError(f"{source}: {err}") from None
    result = {"valid": check.valid, "kind": "path", "steps": check.steps, "bad_step": check.bad_step,
              "reason": check.reason}
    if as_json:
        print(json.dumps(result, indent=2))
    elif check.valid:
        moves = plural(check.steps - 1, "move")
        print(f"{source}: path: valid ({moves}, every step a polycube loop structure)")
    else:
        where = "" if check.bad_step is None else f" at step {check.bad_step}"
        print(f"{source}: path: INVALID{where}: {check.reason}")
    return EXIT_OK if check.valid else EXIT_INVALID


def cmd_conjecture_settle(args: argparse.Namespace) -> int:
    """``conjecture genusG``: settle every class of a catalog of genus G."""
    from tqdm import tqdm

    from polyloops.catalog.census import CatalogError, read_catalog
    from polyloops.reach.conjecture import (
        ConjectureError,
        catalog_signatures,
        certificate_lines,
        complete_range,
        read_records,
        settle_catalog,
    )

    genus = int(args.which.removeprefix("genus"))
    check_output(args.output)
    earlier = []
    if args.earlier:
        try:
            earlier = read_records(read_text_file(args.earlier).splitlines())
        except ConjectureError as err:
            raise CliError(f"{args.earlier}: {err}") from None
    try:
        census = read_catalog(catalog_dir(args.catalog, genus))
        covered = complete_range(census, genus)
        total = len(catalog_signatures(census, args.max_corners))
    except (CatalogError, ConjectureError) as err:
        raise CliError(str(err), getattr(err, "status", 2)) from None
    if args.max_corners > covered:
        raise CliError(f"--max-corners {args.max_corners}: the catalog {census.directory} holds every class "
                       f"only through {covered} corners; extend it first (polyloops catalog)")
    if args.slack < 2:
        raise CliError("--slack must be at least 2")
    if args.long and args.long <= args.slack:
        raise CliError(f"--long {args.long} must be above --slack {args.slack}")
    # Each class settled goes to CERT.journal as it is settled: a stopped run, started again
    # with the same catalog, range and slack, resumes from it; it goes once CERT is written.
    journal = None if args.output == "-" else Path(args.output).with_name(Path(args.output).name + ".journal")
    bar = tqdm(total=total, desc=args.which, unit="class", disable=None, file=sys.stderr)
    try:
        result = settle_catalog(census.directory, args.max_corners, args.slack, args.workers, args.dask,
                                progress=lambda _: bar.update(1), journal=journal, earlier=earlier,
                                long=args.long or 0)
    except (CatalogError, ConjectureError) as err:
        raise CliError(str(err), getattr(err, "status", 2)) from None
    except OSError as err:
        raise CliError(f"{journal}: cannot keep the journal there ({err.strerror or err})") from None
    finally:
        bar.close()
    write_text(args.output, "\n".join(certificate_lines(result)) + "\n")
    if journal is not None:
        journal.unlink(missing_ok=True)
    data = result.to_json()
    lines = ["corners  classes  irreducible  settled  largest detour (extra corners, moves)"]
    orientation = None
    for row in result.table():
        if row.orientation != orientation:
            orientation = row.orientation
            lines.append(f"orientation type {orientation}:")
        lines.append(f"{row.corners:>7}  {row.classes:>7}  {row.irreducible:>11}  "
                     f"{row.settled_irreducible:>7}  "
                     + (f"+{row.largest_detour_corners}, {row.largest_detour_moves}"
                        if row.settled_irreducible else "-"))
    lines.append(f"wrote {args.output}")
    if result.unsettled:
        lines.append("open (no detour within the slack searched, the certificate says so): "
                     + ", ".join(f"{census.by_signature[r.signature].name} (+{r.searched})"
                                 for r in result.unsettled))
    emit(args, data, "\n".join(lines))
    return EXIT_INVALID if result.unsettled else EXIT_OK


def cmd_conjecture_check(args: argparse.Namespace) -> int:
    from polyloops.catalog.census import CatalogError, read_catalog
    from polyloops.reach.conjecture import Certificate, ConjectureError, read_header, shipped_certificate

    given = args.certificate or str(shipped_certificate(args.genus or 0))
    text = read_text_file(given)
    lines = tuple(text.splitlines())
    try:
        cert = Certificate(Path(given), read_header(lines[0] if lines else ""), lines)
    except ConjectureError as err:  # not a certificate at all: bad input, not a failed check
        raise CliError(f"{given}: {err}") from None
    if args.genus is not None and cert.genus != args.genus:
        raise CliError(f"{given}: a genus-{cert.genus} certificate, not genus {args.genus}")
    args.catalog = str(catalog_dir(args.catalog, cert.genus))
    args.certificate = given
    try:
        check = cert.check(read_catalog(Path(args.catalog)))
    except CatalogError as err:
        raise CliError(str(err), getattr(err, "status", 2)) from None
    except ConjectureError as err:
        raise CliError(f"{args.catalog}: {err}") from None
    problems = check.problems
    data = {"valid": check.valid, "genus": check.genus, "max_corners": check.header["max_corners"],
            "checked_corners": check.checked_corners, "catalog_corners": check.catalog_corners,
            "records": check.records, "problems": [str(p) for p in problems],
            "complete": check.complete, "proven_corners": check.proven_corners,
            "open": [c.name or c.signature for c in check.open],
            "searched": {c.name or c.signature: c.searched for c in check.open}}
    checked = (f"checked every class of {args.catalog} through {check.checked_corners} corners "
               f"(the header claims {check.header['max_corners']}, the catalog is complete through "
               f"{check.catalog_corners})")
    if problems:
        text = (f"{args.certificate}: INVALID: {plural(len(problems), 'problem')}; first: {problems[0]}\n"
                f"  {checked}")
    else:
        text = (f"{args.certificate}: valid: {check.statement()}\n  {checked}; each record replayed "
                "with the Definition-4 checker")
    emit(args, data, text)
    return EXIT_INVALID if problems else EXIT_OK


def add_commands(command: AddCommand) -> None:
    modes = SYMMETRIES
    moves_help = "add, remove, or add,remove (default)"
    p = command("reach", cmd_reach, "breadth-first search over loop additions and removals from "
                "START (default: the cube), every state within --max-corners", file_arg=False)
    p.add_argument("start", metavar="START", nargs="?", default="example:cube", help=FILE_HELP)
    p.add_argument("--max-corners", type=count_arg(8), required=True, metavar="M")
    p.add_argument("--max-depth", type=count_arg(0), metavar="D", help="stop after D moves")
    p.add_argument("--moves", default="add,remove", help=moves_help)
    p.add_argument("--symmetry", choices=modes, default="labelled",
                   help="states up to renumbering (labelled, default), rotations, or all 48 symmetries")
    p.add_argument("-o", "--output", metavar="DIR", help="store the states in DIR/reach.sqlite "
                   "(resumable level by level) and the counts in DIR/summary.json")
    p.add_argument("--overwrite", action="store_true", help="replace a search of other parameters "
                   "stored in DIR (without it, refused; the same search is resumed)")
    p.add_argument("--workers", type=count_arg(1, MAX_WORKERS), default=1, metavar="K",
                   help="local worker processes")
    p.add_argument("--dask", metavar="ADDRESS", help="expand levels on a Dask cluster (an address, or local)")
    p = command("path", cmd_path, "a shortest sequence of loop additions and removals from SOURCE "
                "to TARGET, every structure within --max-corners (exit 1 when there is none)",
                file_arg=False)
    p.add_argument("source", metavar="SOURCE", help=FILE_HELP)
    p.add_argument("target", metavar="TARGET", help=FILE_HELP)
    p.add_argument("--max-corners", type=count_arg(8), metavar="M", help="search within M corners (needed "
                   "unless the genus or hole orientation already tells that no path exists)")
    p.add_argument("--moves", default="add,remove", help=moves_help)
    p.add_argument("-o", "--output", metavar="OUT.json", help="write the path: every step as a loop "
                   "structure ('polyloops verify OUT.json' checks it)")
    p = command("conjecture", cmd_conjecture_settle, "the reachability conjecture: 'conjecture genusG' "
                "settles every class of a catalog of genus G (genus0, genus1, ...), 'conjecture check' "
                "re-checks a certificate", file_arg=False, json_flag=False)
    sub = p.add_subparsers(dest="which", metavar="WHICH", parser_class=Parser)
    sub.required = True
    from polyloops.catalog.census import shipped_genera
    from polyloops.generate.base import generators

    sphere = "a removable loop, or a detour to fewer corners within the slack"
    handles = ("within each hole-orientation type (the invariant up to the axes' symmetries), a base "
               "class with fewest corners, and for every other class a removable loop, or a detour to "
               "fewer corners (or, at the type's fewest corners, to the base) within the slack")
    for genus in sorted({g.genus for g in generators().values()} | set(shipped_genera())):
        what = sphere if genus == 0 else handles
        g = sub.add_parser(f"genus{genus}", help=f"settle every class of a genus-{genus} catalog up to N "
                           "corners", description=f"settle every class of a genus-{genus} catalog up to N "
                           f"corners: {what}; exit 1 if some class is not settled (the certificate then "
                           "records it as open, and says how many in its header)")
        g.add_argument("--catalog", metavar="DIR",
                       help=f"a catalog directory (default: the shipped catalogs/genus{genus})")
        g.add_argument("--max-corners", type=count_arg(8), required=True, metavar="N")
        g.add_argument("--slack", type=count_arg(2), default=10, metavar="K",
                       help="detours may go up to K corners above the class (tried 2, 4, ..., K; default 10)")
        g.add_argument("-o", "--output", required=True, metavar="CERT",
                       help="the certificate (JSON lines); CERT.journal keeps the classes settled so far, "
                       "so that a stopped run started again resumes")
        g.add_argument("--from", dest="earlier", metavar="CERT",
                       help="an earlier certificate of the catalog: its records are taken, and its open "
                       "classes searched again from the slack they were searched to (when below K)")
        g.add_argument("--long", type=count_arg(3), metavar="L",
                       help="give the classes left open to a search for long detours within L corners "
                       "above them (loops added, each followed by removals alone; far higher than the "
                       "breadth-first search, but finding none proves nothing)")
        g.add_argument("--workers", type=count_arg(1, MAX_WORKERS), default=1, metavar="K",
                       help="local worker processes")
        g.add_argument("--dask", metavar="ADDRESS", help="a Dask cluster (an address, or local)")
        g.add_argument("--json", action="store_true", help="print one JSON object for scripts")
        g.set_defaults(func=cmd_conjecture_settle)
    c = sub.add_parser("check", help="re-check a certificate without trusting the search",
                       description="re-check a certificate against a catalog: every class present, "
                       "every removal and detour replayed with the Definition-4 checker, and as many open "
                       "classes as its header states; exit 0 when it holds, saying what it proves (with "
                       "open classes, every class below the smallest one, and the others of its size)")
    c.add_argument("certificate", metavar="CERT", nargs="?",
                   help="a certificate (default: the shipped one of --genus)")
    c.add_argument("--catalog", metavar="DIR", help="the catalog it settles (default: the shipped one of "
                   "the certificate's genus)")
    genus_option(c, "certificate")
    c.add_argument("--json", action="store_true", help="print one JSON object for scripts")
    c.set_defaults(func=cmd_conjecture_check)
