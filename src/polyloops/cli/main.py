"""The ``polyloops`` command line: a thin layer over the Python API.

Exit status: 0 when done or valid, 1 when the input was checked and is
invalid, 2 for bad input or usage, 3 for an internal error (a bug).  Errors
are one line naming the file.
"""

from __future__ import annotations

import argparse
import json
import os
import signal
import sys
from collections.abc import Callable, Sequence
from typing import Any

from polyloops import __version__
from polyloops.cli.info import describe, format_summary
from polyloops.cli.load import (
    EXIT_INVALID,
    EXIT_OK,
    EXIT_USAGE,
    FORMATS,
    CliError,
    first_violation,
    read_bytes_file,
    read_document,
    read_loop_structure,
    read_structure,
    read_text_file,
    read_valid_structure,
    write_output,
    write_text,
)
from polyloops.core.duality import DualityError, dualize, primalize
from polyloops.core.examples import EXAMPLES
from polyloops.core.formats import to_data
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LabelError, LoopStructure
from polyloops.verify import Report, verify, verify_document

EXIT_INTERNAL = 3
FILE_HELP = ("a polyloops JSON file, a DualCube .graph/.apg file or an OBJ quad mesh, "
             "example:NAME for a bundled example ('polyloops examples' lists them), or sig:SIGNATURE")


def _emit(args: argparse.Namespace, data: Any, text: str) -> None:
    print(json.dumps(data, indent=2) if getattr(args, "json", False) else text)


# -- commands -----------------------------------------------------------------------------

def cmd_examples(args: argparse.Namespace) -> int:
    rows = [{"name": e.name, "valid": e.valid, "description": e.description} for e in EXAMPLES.values()]
    width = max(len(r["name"]) for r in rows)
    text = "\n".join(f"{r['name']:<{width}}  {'valid  ' if r['valid'] else 'invalid'}  {r['description']}"
                     for r in rows)
    _emit(args, rows, text)
    return EXIT_OK


def format_report(source: str, report: Report) -> str:
    verdict = "valid" if report.valid else f"INVALID ({len(report.violations)} violations)"
    lines = [f"{source}: {report.kind}: {verdict}"]
    for c in report.checks:
        note = f" ({c.note})" if c.note else ""
        lines.append(f"  {c.definition} condition {c.condition:<10} {c.status:<22} {c.statement}{note}")
    for v in report.violations:
        lines.append(f"  violation: {v.definition} condition {v.condition}: {v.message}")
    return "\n".join(lines)


def cmd_verify(args: argparse.Namespace) -> int:
    from polyloops.cli.reach import read_path_file, verify_path_file

    path_doc = read_path_file(args.file)
    if path_doc is not None:
        return verify_path_file(args.file, path_doc, args.json)
    doc = read_document(args.file)
    try:
        report = verify_document(doc)
    except LabelError as err:
        raise CliError(f"{args.file}: {err}") from None
    _emit(args, report.to_json(), format_report(args.file, report))
    return EXIT_OK if report.valid else EXIT_INVALID


def cmd_primalize(args: argparse.Namespace) -> int:
    ls = read_structure(args.file)
    if isinstance(ls, Polycube):
        raise CliError(f"{args.file}: is a polycube; primalize takes a loop structure (try dualize)")
    if not ls.oriented:
        raise CliError(f"{args.file}: is a labelled loop structure without sides; orient it first")
    report = verify(ls)
    if not report.valid:
        raise CliError(f"{args.file}: not a polycube loop structure: {first_violation(report)}",
                       EXIT_INVALID)
    # A structure and its mirror have one polycube; write it outward, as the format says.
    text = write_output(args.output, primalize(ls).outward())
    if text is not None:
        print(text, end="")
    return EXIT_OK


def cmd_dualize(args: argparse.Namespace) -> int:
    q = read_structure(args.file)
    if not isinstance(q, Polycube):
        raise CliError(f"{args.file}: is a loop structure; dualize takes a polycube (try primalize)")
    report = verify(q)
    if not report.valid:
        raise CliError(f"{args.file}: not a polycube: {first_violation(report)}", EXIT_INVALID)
    try:
        ls = dualize(q)
    except DualityError as err:  # pragma: no cover - Definition 1 rules this out (Lemma 1)
        raise CliError(f"{args.file}: {err}", EXIT_INVALID) from None
    text = write_output(args.output, ls)
    if text is not None:
        print(text, end="")
    return EXIT_OK


def cmd_convert(args: argparse.Namespace) -> int:
    obj = read_structure(args.file, fix_orientation=args.fix_orientation, given=args.source_format)
    write_output(args.output, obj, args.target_format)
    return EXIT_OK


def cmd_from_voxels(args: argparse.Namespace) -> int:
    import io

    from polyloops.core.voxels import VoxelError, parse_voxel_text, polycube_from_voxels, voxels_from_grid

    try:
        if args.file.lower().endswith(".npy"):
            import numpy as np

            try:
                grid = np.load(io.BytesIO(read_bytes_file(args.file)), allow_pickle=False)
            except (ValueError, OSError, EOFError) as err:
                raise ValueError(f"not a NumPy .npy array: {_clip_words(str(err))}") from None
            cells = voxels_from_grid(grid)
        else:
            cells = parse_voxel_text(read_text_file(args.file))
    except ValueError as err:
        raise CliError(f"{args.file}: {err}") from None
    try:
        q = polycube_from_voxels(cells)
    except VoxelError as err:
        raise CliError(f"{args.file}: {err}", EXIT_INVALID) from None
    text = write_output(args.output, q)
    if text is not None:
        print(text, end="")
    else:
        print(f"{len(cells)} cubes: a polycube with {q.map.num_corners} corners and {q.map.num_faces} faces, "
              f"genus {q.genus}, written to {args.output}")
    return EXIT_OK


def cmd_info(args: argparse.Namespace) -> int:
    summary = describe(read_structure(args.file))
    _emit(args, summary, format_summary(summary))
    return EXIT_OK


def cmd_corners(args: argparse.Namespace) -> int:
    from polyloops.core.corners import corner_configurations, corner_histogram
    from polyloops.enumerate.corners import corner_classes, witness

    configs = corner_configurations()
    in_examples: dict[int, list[str]] = {c.id: [] for c in configs}
    for name, ex in EXAMPLES.items():
        if ex.valid:
            for cid in corner_histogram(ex.build())[0]:
                in_examples[cid].append(name)
    for path, draw in ((args.png, "png"), (args.svg, "svg")):
        if path:
            from polyloops.render.corners import corner_sheet

            try:
                corner_sheet(path)
            except (OSError, ValueError) as err:
                raise CliError(f"{path}: cannot write the {draw} picture: {err}") from None
    if args.symmetry in ("labelled", "none"):
        rows = []
        for c in configs:
            row = c.to_json()
            row["examples"] = in_examples[c.id]
            if args.witnesses:
                found = witness(c)
                row["witness_cubes"] = [list(cell) for cell in found[0]] if found else None
            rows.append(row)
        text = "\n".join(
            f"{r['id']:>3}  {r['category']:<18} {' '.join(r['directions']):<20} "
            + (", ".join(r["examples"]) or "-")
            + (f"   witness {r['witness_cubes']}" if args.witnesses else "")
            for r in rows)
        shown = sum(1 for r in rows if r["examples"])
        header = (f"{len(rows)} corner configurations (id, category, directions counter-clockwise, "
                  f"bundled examples that contain it); {shown} appear in the bundled examples")
        _emit(args, rows, header + "\n" + text)
        return EXIT_OK
    classes = corner_classes(args.symmetry)
    rows = [c.to_json() for c in classes]
    text = "\n".join(f"{r['class']:>3}  {r['category']:<18} size {r['size']:>2}  "
                     f"{' '.join(r['representative']):<20} members {r['members']}" for r in rows)
    header = f"{len(rows)} classes of corner configurations under symmetry '{args.symmetry}'"
    _emit(args, rows, header + "\n" + text)
    return EXIT_OK


def _components_json(problem) -> dict[str, list[list[int]]]:
    from polyloops.core.directions import Axis

    return {a.name: [list(c.loops) for c in problem.components_of(a)] for a in Axis}


def cmd_orient(args: argparse.Namespace) -> int:
    from polyloops.solvers import OrientationProblem, axis_flip_factor, explain, make_solver
    from polyloops.solvers.base import count as count_solutions
    from polyloops.solvers.base import feasible_locally

    ls = read_loop_structure(args.file)
    problem = OrientationProblem(ls)
    solver = make_solver(args.solver)
    info: dict[str, Any] = {"solver": args.solver, "k": problem.k, "components": _components_json(problem)}
    summary = (f"{args.file}: k = {problem.k} free choices (side-graph components: "
               + ", ".join(f"{a}: {len(v)}" for a, v in info["components"].items()) + ")")

    def fail() -> int:
        why = explain(problem)
        assert why is not None
        info.update(found=False, condition=why.condition, reason=why.reason, witness=why.witness)
        if args.json:
            print(json.dumps(info, indent=2))
        else:
            print(summary)
        raise CliError(f"{args.file}: no orientation: {why.reason}", EXIT_INVALID)

    if args.count:
        n = count_solutions(solver, problem)
        info.update(count=n, count_modulo_axis_flips=n // axis_flip_factor(problem) if n else 0)
        if n == 0 and not args.json:
            return fail()
        _emit(args, info, f"{summary}\n{n} orientations ({info['count_modulo_axis_flips']} up to "
              "flipping all loops of an axis)")
        return EXIT_OK if n else EXIT_INVALID
    if args.all:
        if not feasible_locally(problem):
            return fail()
        structures = (problem.structure.with_signs(signs) for signs in solver.solutions(problem))
        if args.output:
            lines = [json.dumps(to_data(s), separators=(",", ":")) for s in structures]
            if not lines:
                return fail()
            write_text(args.output, "\n".join(lines) + "\n")
            print(f"{summary}\nwrote {len(lines)} orientations to {args.output} (one JSON per line)")
            return EXIT_OK
        n = 0
        if args.json:
            print("[")
        for s in structures:
            if args.json:
                print(("," if n else "") + json.dumps({"signs": list(s.signs or ())}))
            else:
                print(" ".join("+" if x > 0 else "-" for x in s.signs or ()))
            n += 1
        if args.json:
            print("]")
        return EXIT_OK if n else fail()
    signs = next(solver.solutions(problem), None)
    if signs is None:
        return fail()
    oriented = problem.structure.with_signs(signs)
    if args.json:
        info.update(found=True, signs=list(signs), structure=to_data(oriented))
        print(json.dumps(info, indent=2))
        if args.output:
            write_output(args.output, oriented)
        return EXIT_OK
    text = write_output(args.output, oriented)
    if text is not None:
        print(text, end="")
    else:
        print(f"{summary}\nwrote an orientation to {args.output}")
    return EXIT_OK


def cmd_moves(args: argparse.Namespace) -> int:
    from polyloops.core.directions import Axis
    from polyloops.core.moves import check_removal

    if sum(map(bool, (args.count, args.shortest is not None, args.sample is not None))) > 1:
        raise CliError("--count, --shortest and --sample are different questions: ask one")
    if (args.shortest is not None or args.sample is not None) and args.remove:
        raise CliError("--shortest and --sample choose additions; --remove lists loops")
    if args.seed is not None and args.sample is None:
        raise CliError("--seed goes with --sample")
    ls = read_valid_structure(args.file)
    picking = args.shortest is not None or args.sample is not None
    want_add = args.add is not None or not args.remove or picking
    want_remove = not picking and (args.remove or args.add is None)
    axes = list(Axis) if args.add in (None, "all") else [Axis.parse(args.add)]
    data: dict[str, Any] = {}
    lines: list[str] = []
    if args.count:
        if want_add:
            counted = _count_additions(ls, axes, args)
            data["additions"], data["complete"] = counted.counts, counted.complete
            shown = [f"{a}:{'' if counted.complete[a] else '>='}{n}" for a, n in counted.counts.items()]
            lines.append("additions " + "  ".join(shown))
            if not all(counted.complete.values()):
                why = "the time limit" if args.time_limit is not None and args.limit is None else "a limit"
                lines.append(f"(>=: stopped by {why}; a lower bound)")
        if want_remove:
            data["removals"] = sum(1 for lp in ls.loops if check_removal(ls, lp.id).valid)
            lines.append(f"removals  {data['removals']}")
        _emit(args, data, "\n".join(lines))
        return EXIT_OK
    if want_add:
        data["additions"], data["complete"] = _list_additions(ls, axes, args)
    if want_remove:
        rows = []
        for lp in ls.loops:
            check = check_removal(ls, lp.id)
            rows.append({"loop": lp.id, "axis": str(ls.axes[lp.id]), "segments": list(lp.edges),
                         "removable": check.valid, "reason": check.reason})
            _stream(args, f"remove {lp.id:>3}  {ls.axes[lp.id]}-loop of {len(lp)} segments: "
                    + ("removable" if check.valid else f"not removable: {check.reason}"))
        data["removals"] = rows
    if args.json:
        _emit(args, data, "")
    return EXIT_OK


def _stream(args: argparse.Namespace, line: str) -> None:
    """Text output goes out as it is found (flushed), so a long listing shows progress."""
    if not args.json:
        print(line, flush=True)


def _count_additions(ls: Any, axes: list[Any], args: argparse.Namespace) -> Any:
    from tqdm import tqdm

    from polyloops.core.moves import count_additions_within

    bar = tqdm(unit=" loops", desc="counting", disable=None, file=sys.stderr, leave=False)
    shown = dict.fromkeys((a.name for a in axes), 0)

    def progress(label: str, n: int) -> None:
        shown[label] = n
        bar.n = sum(shown.values())
        bar.set_postfix(label=label, refresh=False)
        bar.refresh()

    try:
        return count_additions_within(ls, axes, args.limit, args.time_limit, progress)
    finally:
        bar.close()


def _list_additions(ls: Any, axes: list[Any], args: argparse.Namespace) -> tuple[list[Any], dict[str, bool]]:
    """List (and stream) additions: all of them, the shortest, or a random sample; the second
    value says per label whether the listing is complete."""
    import time

    from polyloops.core.moves import (
        SearchStopped,
        addition_index,
        additions,
        sample_additions,
        shortest_additions,
    )

    listed: list[dict[str, Any]] = []
    complete = {a.name: True for a in axes}

    def show(index: str, mv: Any) -> None:
        row = {"index": index, **mv.to_json(ls)}
        listed.append(row)
        _stream(args, f"add {index:>5}  {mv.axis}-loop past corners {list(mv.cycle)} "
                f"(+ side on the right), crossing segments {row['segments']}")

    deadline = None if args.time_limit is None else time.monotonic() + args.time_limit

    def expired() -> bool:
        return deadline is not None and time.monotonic() > deadline

    if args.shortest is not None or args.sample is not None:
        # Picked loops are named by their cycle: their index in the full listing is unknown.
        for a in axes:
            try:
                picked = (shortest_additions(ls, a, args.shortest, expired) if args.shortest is not None
                          else sample_additions(ls, a, args.sample, args.seed or 0))
            except SearchStopped:
                complete[a.name] = False
                continue
            for mv in picked:
                show(f"{a.name}:" + ",".join(map(str, mv.cycle)), mv)
        if not all(complete.values()):
            _stream(args, "(stopped by the time limit: the listing is incomplete)")
        return listed, complete

    total = 0
    for a in axes:
        i = 0
        try:
            for mv in additions(ls, a, stop=expired):
                if (args.limit is not None and total >= args.limit) or expired():
                    complete[a.name] = False
                    break
                show(addition_index(a, i), mv)
                i += 1
                total += 1
        except SearchStopped:
            complete[a.name] = False
    if not all(complete.values()):
        _stream(args, "(stopped by " + ("a limit" if args.limit is not None and total >= args.limit
                                       else "the time limit") + ": the listing is incomplete)")
    return listed, complete


MOVE_HELP = "write an index from 'polyloops moves' (such as Y3), or AXIS:c0,c1,..."


def _parse_move(arg: str, ls, text: str):
    from polyloops.core.directions import Axis
    from polyloops.core.moves import Addition, addition_at, is_valid_addition, parse_cycle

    if ":" in text:
        label, _, corners = text.partition(":")
        try:
            move = Addition(Axis.parse(label.strip().upper()), parse_cycle(corners))
        except ValueError:
            raise CliError(f"{arg}: move {text!r}: {MOVE_HELP}") from None
        if not is_valid_addition(ls, move):
            raise CliError(f"{arg}: move {text!r} is not a valid loop addition here", EXIT_INVALID)
        return move
    try:
        found = addition_at(ls, int(text) if text.strip().lstrip("-").isdigit() else text)
    except ValueError:
        raise CliError(f"{arg}: move {text!r}: {MOVE_HELP}") from None
    if found is None:
        raise CliError(f"{arg}: there is no addition {text} ('polyloops moves' lists them)")
    return found


def cmd_add(args: argparse.Namespace) -> int:
    from polyloops.core.moves import add_loop

    ls = read_valid_structure(args.file)
    result = add_loop(ls, _parse_move(args.file, ls, args.move))
    text = write_output(args.output, result)
    if text is not None:
        print(text, end="")
    return EXIT_OK


def cmd_remove(args: argparse.Namespace) -> int:
    from polyloops.core.moves import check_removal, remove_loop

    ls = read_valid_structure(args.file)
    if not 0 <= args.loop < len(ls.loops):
        raise CliError(f"{args.file}: there is no loop {args.loop} (loops are 0..{len(ls.loops) - 1})")
    check = check_removal(ls, args.loop)
    if not check.valid:
        raise CliError(f"{args.file}: loop {args.loop} is not removable: {check.reason}", EXIT_INVALID)
    text = write_output(args.output, remove_loop(ls, args.loop))
    if text is not None:
        print(text, end="")
    return EXIT_OK


def cmd_catalog(args: argparse.Namespace) -> int:
    from pathlib import Path

    from polyloops.enumerate.catalog_run import execute, plan_jobs, summarize, write_catalog
    from polyloops.enumerate.quadrangulations import PlantriError, find_plantri

    if args.max_corners < args.min_corners:
        raise CliError("--max-corners must be at least --min-corners")
    if (args.res is None) != (args.mod is None) or (args.mod is not None and not 0 <= args.res < args.mod):
        raise CliError("--res R --mod M go together, with 0 <= R < M")
    if args.workers < 1:
        raise CliError("--workers must be at least 1")
    try:
        plantri = find_plantri(args.plantri)
    except PlantriError as err:
        raise CliError(str(err)) from None
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise CliError(f"{out}: exists and is not a directory")
    if not out.absolute().parent.is_dir():  # like every other -o: the directory above must exist
        raise CliError(f"{out}: the directory {out.absolute().parent} does not exist")
    jobs = plan_jobs(args.min_corners, args.max_corners, args.res, args.mod, args.workers)
    from tqdm import tqdm

    bar = tqdm(total=len(jobs), unit="job", desc="catalog", disable=None, file=sys.stderr)
    maps = [0]

    def progress(result: dict[str, Any]) -> None:
        maps[0] += result["quadrangulations"]
        bar.update(1)
        bar.set_postfix(corners=result["n"], maps=maps[0])

    try:
        results = execute(jobs, out, plantri, args.workers, args.dask, progress, method=args.method)
    except (PlantriError, RuntimeError, OSError) as err:
        raise CliError(f"{out}: {err}") from None
    finally:
        bar.close()
    summary = summarize(results, args.min_corners, args.max_corners, partial=args.mod is not None)
    n = write_catalog(out, results, args.symmetry, summary)
    def shown(table: str, k: str) -> Any:
        return "-" if summary[table][k] is None else summary[table][k]

    rows = [[k, shown("quadrangulations", k), shown("simple_strips", k), *v.values()]
            for k, v in summary["counts"].items()]
    text = "corners  quadrangulations  simple strips  labelled  rotation  full\n" + "\n".join(
        f"{r[0]:>7}  {r[1]:>16}  {r[2]:>13}  {r[3]:>8}  {r[4]:>8}  {r[5]:>4}" for r in rows)
    _emit(args, summary, f"{text}\nwrote {n} records ({args.symmetry}) to {out}")
    return EXIT_OK


def cmd_catalog_query(args: argparse.Namespace) -> int:
    import sqlite3
    from pathlib import Path

    from polyloops.enumerate.catalog_run import query

    try:
        columns, rows = query(Path(args.dir), args.where)
    except FileNotFoundError as err:
        raise CliError(str(err)) from None
    except sqlite3.Error as err:
        raise CliError(f"{args.dir}: bad query: {err}") from None
    if args.json:
        print(json.dumps([dict(zip(columns, r, strict=True)) for r in rows], indent=1))
    else:
        print("\t".join(columns))
        for r in rows:
            print("\t".join(str(x) for x in r))
    return EXIT_OK


def cmd_catalog_export(args: argparse.Namespace) -> int:
    import sqlite3
    from pathlib import Path

    from polyloops.enumerate.catalog_run import export_csv

    try:
        text = export_csv(Path(args.dir))
    except (FileNotFoundError, sqlite3.Error) as err:
        raise CliError(f"{args.dir}: {err}") from None
    if args.output:
        write_text(args.output, text)
    else:
        print(text, end="")
    return EXIT_OK


def cmd_identify(args: argparse.Namespace) -> int:
    from pathlib import Path

    from polyloops.enumerate.catalog_run import default_catalog, identify

    ls = read_loop_structure(args.file, oriented=True)
    catalog = Path(args.catalog) if args.catalog else default_catalog()
    try:
        found = identify(ls, catalog)
    except (OSError, ValueError, KeyError) as err:
        raise CliError(f"{catalog}: not a catalog directory ({err})") from None
    if found.name is not None:
        text = f"{args.file}: {found.name}"
    elif found.genus != found.catalog_genus:
        text = (f"{args.file}: not in the catalog (genus {found.genus}; "
                f"the catalog has genus {found.catalog_genus})")
    elif found.beyond:
        text = (f"{args.file}: not in the catalog (it has {found.corners} corners; "
                f"the catalog goes to {found.max_corners})")
    else:
        text = f"{args.file}: not in the catalog"
    _emit(args, found.to_json(), text)
    return EXIT_OK if found.name is not None else EXIT_INVALID


def cmd_signature(args: argparse.Namespace) -> int:
    from polyloops.core.canonical import canonical_form

    form = canonical_form(read_loop_structure(args.file), args.symmetry)
    data = {"signature": form.signature, "symmetry": args.symmetry, "automorphisms": form.automorphisms}
    if form.achiral is not None:
        data["chiral"] = not form.achiral
    _emit(args, data, f"{form.signature}\n(symmetry {args.symmetry}, automorphism group of order "
          f"{form.automorphisms})")
    return EXIT_OK


def _picture_path(path: str) -> str:
    from pathlib import Path

    if Path(path).suffix.lower() not in (".png", ".svg"):  # ".png" alone has no suffix
        raise CliError(f"{path}: pictures are written as NAME.png or NAME.svg")
    return path


def cmd_render(args: argparse.Namespace) -> int:
    from polyloops.render.level_graphs import render_level_graphs
    from polyloops.render.polycube import PictureError, render_polycube

    out = _picture_path(args.output)
    obj = read_structure(args.file)
    report = verify(obj)
    ls = dualize(obj) if isinstance(obj, Polycube) and report.valid else obj
    if isinstance(ls, LoopStructure) and not ls.oriented:
        raise CliError(f"{args.file}: is a labelled loop structure without sides; orient it first")
    try:
        if args.level_graphs:
            if not isinstance(ls, LoopStructure):
                raise CliError(f"{args.file}: not a polycube, so it has no loop structure", EXIT_INVALID)
            render_level_graphs(ls, out)
        else:
            title = None if report.valid else f"not valid: {first_violation(report)}"[:110]
            try:
                render_polycube(obj, out, views=args.views, loops=args.loops, title=title)
            except DualityError as err:
                render_level_graphs(obj, out)  # type: ignore[arg-type]
                print(f"polyloops render: {args.file}: no polycube ({err}); drew the level graphs instead",
                      file=sys.stderr)
    except PictureError as err:
        raise CliError(f"{args.file}: {err}") from None
    except OSError as err:
        raise CliError(f"{out}: cannot write: {err.strerror or err}") from None
    return EXIT_OK


def _is_dir(path) -> bool:
    try:
        return path.is_dir()
    except OSError:  # a name too long for the file system, for example
        return False


def _caption(source: str, obj: Any) -> str:
    """A structure's catalog name when the shipped catalog has it, else where it came from;
    never a cut-off signature."""
    from pathlib import Path

    from polyloops.enumerate.catalog_run import identify

    try:
        found = identify(obj).name
    except (OSError, ValueError, KeyError):  # no shipped catalog next to this install
        found = None
    if found:
        return found
    label = "signature" if source.startswith("sig:") else source if source.startswith("example:") \
        else Path(source).name
    return f"{label} ({obj.map.num_corners} corners)"


def cmd_sheet(args: argparse.Namespace) -> int:
    from pathlib import Path

    from polyloops.core.canonical import from_signature
    from polyloops.render.polycube import PictureError
    from polyloops.render.sheet import render_sheet

    out = _picture_path(args.output)
    items = []
    for source in args.sources:
        path = Path(source)
        if not source.startswith(("sig:", "example:")) and _is_dir(path):
            listing = path / "catalog.jsonl"
            if not listing.is_file():
                raise CliError(f"{source}: a directory, but no catalog.jsonl in it")
            for i, line in enumerate(read_text_file(str(listing)).splitlines()):
                try:
                    rec = json.loads(line)
                    obj = from_signature(rec["signature"])
                    caption = f"{rec['name']}" if "name" in rec else f"#{i} {int(rec['corners'])}c"
                except (ValueError, KeyError, TypeError) as err:  # SignatureError is a ValueError
                    raise CliError(f"{listing}: line {i + 1}: not a catalog record: {err}") from None
                items.append((caption, obj))
        else:
            obj = read_structure(source)
            items.append((_caption(source, obj), obj))
    if args.limit is not None:
        items = items[: args.limit]
    if not items:
        raise CliError("nothing to draw")
    try:
        render_sheet(items, out, columns=args.columns)
    except DualityError as err:
        raise CliError(f"cannot draw: {err}", EXIT_INVALID) from None
    except PictureError as err:
        raise CliError(f"cannot draw: {err}") from None
    except OSError as err:
        raise CliError(f"{out}: cannot write: {err.strerror or err}") from None
    print(f"drew {len(items)} polycubes to {out}")
    return EXIT_OK


# -- parser -------------------------------------------------------------------------------

Command = Callable[[argparse.Namespace], int]


class _Parser(argparse.ArgumentParser):
    """Usage errors as one line and exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(EXIT_USAGE, f"{self.prog}: {message} (see --help)\n")


def count_arg(low: int, high: int | None = None) -> Callable[[str], int]:
    """An argparse type: an integer in ``low..high``; anything else is a usage error (exit 2)
    rather than a value quietly changed."""
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
        if value < low or (high is not None and value > high):
            span = f"at least {low}" if high is None else f"from {low} to {high}"
            raise argparse.ArgumentTypeError(f"{value} is out of range: must be {span}")
        return value

    parse.__name__ = "count"
    return parse


def seconds_arg(text: str) -> float:
    """An argparse type: a positive number of seconds."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"{text} is out of range: must be a positive number of seconds")
    return value


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="polyloops", description="Polycubes via their dual loops: check, convert, explore.")
    parser.add_argument("--version", action="version", version=f"polyloops {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    def command(name: str, func: Command, help_text: str, file_arg: bool = True,
                json_flag: bool = True) -> argparse.ArgumentParser:
        p = sub.add_parser(name, help=help_text, description=help_text)
        if file_arg:
            p.add_argument("file", metavar="FILE", help=FILE_HELP)
        if json_flag:
            p.add_argument("--json", action="store_true", help="print one JSON object for scripts")
        p.set_defaults(func=func)
        return p

    command("examples", cmd_examples, "list the bundled examples", file_arg=False)
    # verify also checks path files ({"kind": "path"}) step by step
    command("verify", cmd_verify, "check a file against the paper's definitions "
            "(Definition 1 for a polycube, Definitions 3 and 4 and Theorem 3 for a loop structure)")
    p = command("primalize", cmd_primalize, "the polycube of a polycube loop structure (Theorem 2), "
                "compact coordinates from the level graphs", json_flag=False)
    p.add_argument("-o", "--output", metavar="OUT", help="write here (.obj for Wavefront OBJ, else JSON)")
    p = command("dualize", cmd_dualize, "the oriented loop structure of a polycube (Theorem 1)",
                json_flag=False)
    p.add_argument("-o", "--output", metavar="OUT", help="write JSON here instead of to standard output")
    p = command("convert", cmd_convert, "write a polycube or loop structure in another format: "
                "polyloops JSON, DualCube's Abstract Polycube Graph (.graph, .apg), an OBJ quad mesh "
                "(.obj, polycubes only) or plantri's planar code (.pc, .plc: the quad map alone), "
                "chosen by extension or by --from/--to", json_flag=False)
    p.add_argument("output", metavar="OUT", help="the file to write (.graph/.apg, .obj, .pc, else JSON)")
    p.add_argument("--from", dest="source_format", choices=FORMATS,
                   help="the format of FILE (default: by its extension)")
    p.add_argument("--to", dest="target_format", choices=FORMATS,
                   help="the format of OUT (default: by its extension)")
    p.add_argument("--fix-orientation", action="store_true",
                   help="turn an inside-out polycube (faces clockwise seen from outside) outward")
    p = command("from-voxels", cmd_from_voxels, "the polycube bounding a set of unit cubes: FILE is a "
                "text file of 'x y z' lines or a 3D NumPy .npy grid of booleans; where cubes only "
                "touch along an edge or at a corner the surface is split there", file_arg=False,
                json_flag=False)
    p.add_argument("file", metavar="FILE", help="cubes: 'x y z' per line (# comments), or a .npy grid")
    p.add_argument("-o", "--output", metavar="OUT", help="write the polycube here (.json, .graph, .obj); "
                   "default: JSON on standard output")
    p = command("corners", cmd_corners, "the 126 polycube corner configurations, by category, "
                "or their classes under rotations or all signed permutations", file_arg=False)
    p.add_argument("--symmetry", choices=("labelled", "none", "rotation", "full"), default="labelled",
                   help="labelled: one row per configuration (default; 'none' is an older name for "
                   "it); rotation: classes under the 24 rotations; full: under all 48 signed "
                   "permutations, the same modes as 'polyloops signature'")
    p.add_argument("--witnesses", action="store_true",
                   help="for each configuration, a small set of unit cubes whose polycube has that corner")
    p.add_argument("--png", metavar="FILE", help="draw every configuration on one sheet (PNG)")
    p.add_argument("--svg", metavar="FILE", help="the same sheet as SVG")
    p = command("orient", cmd_orient, "orient the loops of a labelled loop structure so that it "
                "becomes a polycube loop structure (sides in the input are ignored; a polycube is "
                "dualized first)")
    p.add_argument("--solver", choices=("brute", "sat", "smt"), default="sat",
                   help="exhaustive search, SAT with lazy cycle cuts (default), or SMT with zone potentials")
    mode = p.add_mutually_exclusive_group()
    mode.add_argument("--all", action="store_true", help="every orientation: sign vectors, or "
                      "one structure per line with -o")
    mode.add_argument("--count", action="store_true", help="the number of orientations, raw and up to "
                      "flipping all loops of an axis")
    p.add_argument("-o", "--output", metavar="OUT",
                   help="write the oriented structure (JSON lines with --all)")
    p = command("moves", cmd_moves, "the valid loop additions and removals of a polycube loop structure")
    p.add_argument("--add", choices=("X", "Y", "Z", "all"), help="list additions of this label "
                   "(default: all labels, together with removals)")
    p.add_argument("--remove", action="store_true", help="list the loops and whether each is removable")
    p.add_argument("--limit", type=count_arg(0), metavar="N",
                   help="stop after N additions (per label with --count)")
    p.add_argument("--count", action="store_true", help="only count the moves")
    p.add_argument("--time-limit", type=seconds_arg, metavar="SECONDS",
                   help="stop counting or listing after this long; the answer then says it is a "
                   "lower bound (incomplete)")
    p.add_argument("--shortest", type=count_arg(1), metavar="K",
                   help="the K valid additions past the fewest corners, per label, found without "
                   "listing longer loops")
    p.add_argument("--sample", type=count_arg(1), metavar="N",
                   help="N different random valid additions per label (random walks: quick on large "
                   "structures, reproducible with --seed, not uniform)")
    p.add_argument("--seed", type=count_arg(0), metavar="S", help="the seed of --sample (default 0)")
    p = command("add", cmd_add, "add one loop: MOVE is an index from 'polyloops moves' (Y3: the "
                "fourth valid Y-loop; a plain N counts through X, Y and Z), or AXIS:c0,c1,... (the "
                "corners the loop walks past, + side on the right)", json_flag=False)
    p.add_argument("move", metavar="MOVE")
    p.add_argument("-o", "--output", metavar="OUT", help="write the new structure here")
    p = command("remove", cmd_remove, "remove one loop, if that leaves a polycube loop structure",
                json_flag=False)
    p.add_argument("loop", metavar="LOOP", type=count_arg(0),
                   help="a loop id from 'polyloops moves --remove'")
    p.add_argument("-o", "--output", metavar="OUT", help="write the new structure here")
    p = command("signature", cmd_signature, "a canonical name: equal exactly for isomorphic "
                "structures (mirror images of the surface identified); use it as sig:NAME anywhere")
    p.add_argument("--symmetry", choices=("labelled", "rotation", "full"), default="labelled",
                   help="labelled: axes fixed (order-equivalence); rotation: up to the 24 rotations; "
                   "full: up to all 48 signed permutations")
    p = command("catalog", cmd_catalog, "the catalog of genus-0 polycubes up to order-equivalence, by "
                "number of corners, from plantri's quadrangulations ('polyloops catalog query DIR "
                "WHERE' searches one)", file_arg=False)
    p.add_argument("--max-corners", type=count_arg(0), required=True, metavar="N")
    p.add_argument("--min-corners", type=count_arg(8), default=8, metavar="M")
    p.add_argument("--symmetry", choices=("labelled", "rotation", "full"), default="full",
                   help="which classes the records list (summary.json counts all three); default full")
    p.add_argument("--workers", type=count_arg(1), default=1, metavar="K", help="local worker processes")
    p.add_argument("--res", type=count_arg(0), metavar="R", help="only plantri's slice R of M (with --mod)")
    p.add_argument("--mod", type=count_arg(1), metavar="M")
    p.add_argument("--dask", metavar="ADDRESS", help="run the jobs on a Dask cluster (an address, or local)")
    p.add_argument("--plantri", metavar="PATH", help="the plantri to use (default: the one from "
                   "passagemath-plantri, $POLYLOOPS_PLANTRI, or PATH)")
    p.add_argument("--method", choices=("auto", "compiled", "numpy"), default="auto",
                   help="the strip filter: compiled (built at install when a C compiler is there), "
                   "numpy (the reference twin), or auto (compiled when built); same output either way")
    p.add_argument("-o", "--output", metavar="DIR", required=True, help="catalog directory (resumable)")
    p = command("catalog-query", cmd_catalog_query, "rows of a catalog matching an SQL WHERE clause",
                file_arg=False)
    p.add_argument("dir", metavar="DIR")
    p.add_argument("where", metavar="WHERE", help='an SQL condition, e.g. "corners = 20 AND chiral"')
    p = command("catalog-export", cmd_catalog_export, "a catalog's table as CSV "
                "('polyloops catalog export DIR --csv')", file_arg=False, json_flag=False)
    p.add_argument("dir", metavar="DIR")
    p.add_argument("--csv", action="store_true", required=True, help="CSV (the only format so far)")
    p.add_argument("-o", "--output", metavar="OUT.csv", help="write here instead of to standard output")
    p = command("identify", cmd_identify, "the catalog name of a polycube or loop structure (any "
                "numbering, position or mirror image); exit 1 when it is not in the catalog")
    p.add_argument("--catalog", metavar="DIR", help="a catalog directory (default: catalogs/genus0 "
                   "of this source tree)")
    p = command("render", cmd_render, "draw the polycube in 3D with its loops (a loop structure is "
                "primalized first), or its three level graphs", json_flag=False)
    p.add_argument("-o", "--output", metavar="OUT", required=True, help="OUT.png or OUT.svg")
    p.add_argument("--views", type=count_arg(1, 8), default=1, metavar="N",
                   help="N views from different octants (1 to 8)")
    p.add_argument("--loops", action=argparse.BooleanOptionalAction, default=True,
                   help="draw the loops on the surface (default) or not")
    p.add_argument("--level-graphs", action="store_true", help="draw the X-, Y- and Z-graphs instead")
    p = sub.add_parser("sheet", help="a grid of small renders with captions, from files or a catalog "
                       "directory", description="a grid of small renders with captions, from files or "
                       "a catalog directory")
    p.add_argument("sources", metavar="DIR|FILE", nargs="+", help="catalog directories or " + FILE_HELP)
    p.add_argument("-o", "--output", metavar="OUT", required=True, help="OUT.png or OUT.svg")
    p.add_argument("--columns", type=count_arg(1), default=6, metavar="N", help="pictures per row")
    p.add_argument("--limit", type=count_arg(1), metavar="N", help="draw at most N")
    p.set_defaults(func=cmd_sheet)
    command("info", cmd_info, "corners, faces, loops, genus, zones, level graphs and corner degrees")
    _reach_commands(command)
    from polyloops.cli import segmentation

    segmentation.add_command(command)
    return parser


def _reach_commands(command: Callable[..., argparse.ArgumentParser]) -> None:
    from polyloops.cli import reach

    modes = ("labelled", "rotation", "full")
    moves_help = "add, remove, or add,remove (default)"
    p = command("reach", reach.cmd_reach, "breadth-first search over loop additions and removals from "
                "START (default: the cube), every state within --max-corners", file_arg=False)
    p.add_argument("start", metavar="START", nargs="?", default="example:cube", help=FILE_HELP)
    p.add_argument("--max-corners", type=count_arg(8), required=True, metavar="M")
    p.add_argument("--max-depth", type=count_arg(0), metavar="D", help="stop after D moves")
    p.add_argument("--moves", default="add,remove", help=moves_help)
    p.add_argument("--symmetry", choices=modes, default="labelled",
                   help="states up to renumbering (labelled, default), rotations, or all 48 symmetries")
    p.add_argument("-o", "--output", metavar="DIR", help="store the states in DIR/reach.sqlite "
                   "(resumable level by level) and the counts in DIR/summary.json")
    p.add_argument("--workers", type=count_arg(1), default=1, metavar="K", help="local worker processes")
    p.add_argument("--dask", metavar="ADDRESS", help="expand levels on a Dask cluster (an address, or local)")
    p = command("path", reach.cmd_path, "a shortest sequence of loop additions and removals from SOURCE "
                "to TARGET, every structure within --max-corners (exit 1 when there is none)",
                file_arg=False)
    p.add_argument("source", metavar="SOURCE", help=FILE_HELP)
    p.add_argument("target", metavar="TARGET", help=FILE_HELP)
    p.add_argument("--max-corners", type=count_arg(8), required=True, metavar="M")
    p.add_argument("--moves", default="add,remove", help=moves_help)
    p.add_argument("-o", "--output", metavar="OUT.json", help="write the path: every step as a loop "
                   "structure ('polyloops verify OUT.json' checks it)")
    p = command("conjecture", reach.cmd_conjecture_genus0, "the genus-0 reachability conjecture: "
                "'conjecture genus0' settles every catalog class, 'conjecture check' re-checks a "
                "certificate", file_arg=False, json_flag=False)
    sub = p.add_subparsers(dest="which", metavar="WHICH", parser_class=_Parser)
    sub.required = True
    g = sub.add_parser("genus0", help="settle every class of a genus-0 catalog up to N corners",
                       description="settle every class of a genus-0 catalog up to N corners: a removable "
                       "loop, or a detour to fewer corners within the slack; exit 1 if some class "
                       "is not settled")
    g.add_argument("--catalog", required=True, metavar="DIR", help="a catalog directory (catalogs/genus0)")
    g.add_argument("--max-corners", type=count_arg(8), required=True, metavar="N")
    g.add_argument("--slack", type=count_arg(2), default=10, metavar="K",
                   help="detours may go up to K corners above the class (tried 2, 4, ..., K; default 10)")
    g.add_argument("-o", "--output", required=True, metavar="CERT", help="the certificate (JSON lines)")
    g.add_argument("--workers", type=count_arg(1), default=1, metavar="K", help="local worker processes")
    g.add_argument("--dask", metavar="ADDRESS", help="a Dask cluster (an address, or local)")
    g.add_argument("--json", action="store_true", help="print one JSON object for scripts")
    g.set_defaults(func=reach.cmd_conjecture_genus0)
    c = sub.add_parser("check", help="re-check a certificate without trusting the search",
                       description="re-check a certificate against a catalog: every class present, "
                       "every removal and detour replayed with the Definition-4 checker")
    c.add_argument("certificate", metavar="CERT")
    c.add_argument("--catalog", required=True, metavar="DIR")
    c.add_argument("--json", action="store_true", help="print one JSON object for scripts")
    c.set_defaults(func=reach.cmd_conjecture_check)


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv[:2] in (["catalog", "query"], ["catalog", "export"]):
        argv = [f"catalog-{argv[1]}", *argv[2:]]
    args = parser.parse_args(argv)
    name = args.command.replace("-", " ")
    previous = _terminate_cleanly()
    try:
        return args.func(args)
    except CliError as err:
        print(f"polyloops {name}: {_clip_words(str(err))}", file=sys.stderr)
        return err.status
    except BrokenPipeError:  # output piped into head, for example
        return EXIT_OK
    except KeyboardInterrupt:
        print(f"polyloops {name}: interrupted", file=sys.stderr)
        return 130
    except Exception as err:  # a bug, not bad input: one line, the traceback on request
        if os.environ.get("POLYLOOPS_DEBUG"):
            raise
        print(f"polyloops {name}: internal error: {type(err).__name__}: {_clip_words(str(err))} "
              "(set POLYLOOPS_DEBUG=1 to see where)", file=sys.stderr)
        return EXIT_INTERNAL
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _terminate_cleanly():
    """Turn SIGTERM into an exception, so that temporary files are removed and worker
    processes stopped on the way out, as for Ctrl-C.  Returns the previous handler (``None``
    outside the main thread, where handlers cannot be set)."""
    def stop(signum: int, frame: object) -> None:
        raise KeyboardInterrupt

    try:
        return signal.signal(signal.SIGTERM, stop)
    except ValueError:
        return None


def _clip_words(message: str, width: int = 256) -> str:
    """Messages name their inputs; a huge argument (a 100 kB sig:...) is shown shortened."""
    return " ".join(w if len(w) <= width else w[: width - 40] + "..." + w[-8:] for w in message.split(" "))


__all__ = ["build_parser", "main"]
