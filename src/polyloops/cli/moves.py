"""The loop-move commands: ``moves`` (list or count), ``add`` and ``remove``."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from polyloops.cli.args import (
    AddCommand,
    count_arg,
    emit,
    plural,
    seconds_arg,
    stream,
    structure_facts,
    written,
)
from polyloops.cli.load import EXIT_INVALID, EXIT_OK, CliError, read_valid_structure, write_output
from polyloops.core.directions import Axis
from polyloops.io.formats import to_data


def _count_additions(ls: Any, axes: list[Axis], args: argparse.Namespace) -> Any:
    from tqdm import tqdm

    from polyloops.reach.listing import count_additions_within

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


def cmd_moves(args: argparse.Namespace) -> int:
    from polyloops.core.moves import RemovalCheck, check_removal, loop_names, removals
    from polyloops.reach.listing import list_additions

    if sum(map(bool, (args.count, args.shortest is not None, args.sample is not None))) > 1:
        raise CliError("--count, --shortest and --sample are different questions: ask one")
    if (args.shortest is not None or args.sample is not None) and args.remove:
        raise CliError("--shortest and --sample choose additions; --remove lists loops")
    if args.seed is not None and args.sample is None and not args.estimate:
        raise CliError("--seed goes with --sample or --estimate")
    ls = read_valid_structure(args.file)
    picking = args.shortest is not None or args.sample is not None
    want_add = args.add is not None or not args.remove or picking
    want_remove = not picking and (args.remove or args.add is None)
    axes = list(Axis) if args.add in (None, "all") else [Axis.parse(args.add)]
    data: dict[str, Any] = {}
    if args.estimate and not args.count:
        raise CliError("--estimate goes with --count")
    if args.walks is not None and not args.estimate:
        raise CliError("--walks goes with --estimate")
    if args.count and args.estimate:
        return _estimate(ls, axes if want_add else [], want_remove, args)
    if args.count:
        lines: list[str] = []
        if want_add:
            counted = _count_additions(ls, axes, args)
            data["additions"], data["complete"] = counted.counts, counted.complete
            shown = [f"{a}:{'' if counted.complete[a] else '>='}{n}" for a, n in counted.counts.items()]
            lines.append("additions " + "  ".join(shown))
            unfinished = [a for a, done in counted.complete.items() if not done]
            if unfinished:
                why = ("the time limit, shared across the axes" if args.time_limit is not None
                       and args.limit is None else "a limit")
                lines.append(f"(>=: {' and '.join(unfinished)} not finished, stopped by {why}; "
                             f"{'a lower bound' if len(unfinished) == 1 else 'lower bounds'})")
        if want_remove:
            data["removals"] = len(removals(ls))
            lines.append(f"removals  {data['removals']}")
        emit(args, data, "\n".join(lines))
        return EXIT_OK
    if want_add:
        rows: list[dict[str, Any]] = []

        def show(index: str, mv: Any) -> None:
            row = {"index": index, **mv.to_json(ls)}
            rows.append(row)
            stream(args, f"add {index:>5}  {mv.axis}-loop past corners {list(mv.cycle)} "
                   f"(+ side on the right), crossing segments {row['segments']}")

        listing = list_additions(ls, axes, limit=args.limit, seconds=args.time_limit,
                                 shortest=args.shortest, sample=args.sample, seed=args.seed or 0,
                                 on_found=show)
        if listing.stopped_by:
            stream(args, f"(stopped by {listing.stopped_by}: the listing is incomplete)")
        data["additions"], data["complete"] = rows, listing.complete
    if want_remove:
        removal_rows = []
        removable = set(removals(ls))
        names = loop_names(ls)
        for lp in ls.loops:
            # The reasons come from the loop-by-loop test, asked only where the verdict is no.
            check = RemovalCheck(lp.id, True) if lp.id in removable else check_removal(ls, lp.id)
            removal_rows.append({"loop": lp.id, "name": names[lp.id], "axis": str(ls.axes[lp.id]),
                                 "segments": list(lp.edges), "removable": check.valid,
                                 "reason": check.reason})
            stream(args, f"remove {names[lp.id]:>5}  loop {lp.id}, of {plural(len(lp), 'segment')}: "
                   + ("removable" if check.valid else f"not removable: {check.reason}"))
        data["removals"] = removal_rows
    if args.json:
        emit(args, data, "")
    return EXIT_OK


def _estimate(ls: Any, axes: list[Axis], want_remove: bool, args: argparse.Namespace) -> int:
    """``moves --count --estimate``: additions estimated by random walks, removals counted."""
    from polyloops.core.moves import estimate_additions, removals
    from polyloops.reach.listing import TimeShares

    budget = TimeShares(args.time_limit, len(axes))
    data: dict[str, Any] = {"estimates": {}}
    lines = []
    for a in axes:
        est = estimate_additions(ls, a, args.walks or 10000, args.seed or 0, budget.next_share())
        data["estimates"][a.name] = est.to_json()
        if not est.made:
            lines.append(f"additions {a}: no estimate (the time limit ended before the first random walk)")
            continue
        lines.append(f"additions {a}: about {est.estimate:.4g} (95% interval {est.low:.4g} to "
                     f"{est.high:.4g}, {plural(est.walks, 'random walk')})")
    if want_remove:
        data["removals"] = len(removals(ls))
        lines.append(f"removals  {data['removals']}")
    emit(args, data, "\n".join(lines))
    return EXIT_OK


def cmd_add(args: argparse.Namespace) -> int:
    from polyloops.core.moves import InvalidMoveError, MoveError, add_loop, parse_addition

    ls = read_valid_structure(args.file)
    try:
        move = parse_addition(ls, args.move)
    except InvalidMoveError as err:
        raise CliError(f"{args.file}: {err}", EXIT_INVALID) from None
    except MoveError as err:
        advice = f"'polyloops moves {args.file}' lists the valid additions"
        raise CliError(f"{args.file}: {err} ({advice})") from None
    child = add_loop(ls, move)
    written(args, write_output(args.output, child),
            {"move": {"add": move.axis.name, "corners": list(move.cycle)}, **structure_facts(child)},
            document=to_data(child))
    return EXIT_OK


def cmd_remove(args: argparse.Namespace) -> int:
    from polyloops.core.moves import MoveError, check_removal, parse_removal, remove_loop

    ls = read_valid_structure(args.file)
    try:
        loop = parse_removal(ls, args.loop)
    except MoveError as err:
        advice = f"'polyloops moves {args.file} --remove' lists the loops"
        raise CliError(f"{args.file}: {err} ({advice})") from None
    check = check_removal(ls, loop)
    if not check.valid:
        raise CliError(f"{args.file}: loop {args.loop} is not removable: {check.reason}", EXIT_INVALID)
    child = remove_loop(ls, loop)
    written(args, write_output(args.output, child),
            {"move": {"remove": loop, "axis": ls.axes[loop].name}, **structure_facts(child)},
            document=to_data(child))
    return EXIT_OK


def add_commands(command: AddCommand) -> None:
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
    p.add_argument("--seed", type=count_arg(0), metavar="S",
                   help="the seed of --sample or --estimate (default 0)")
    p.add_argument("--estimate", action="store_true",
                   help="with --count: estimate the additions by random walks (Knuth's estimator, "
                   "with a 95%% interval) instead of counting them, for layouts too large to count")
    p.add_argument("--walks", type=count_arg(1), metavar="N",
                   help="random walks of --estimate (default 10000)")
    p = command("add", cmd_add, "add one loop: MOVE is an index from 'polyloops moves' (Y3: the "
                "fourth valid Y-loop; a plain N counts through X, Y and Z), or AXIS:c0,c1,... (the "
                "corners the loop walks past, + side on the right)")
    p.add_argument("move", metavar="MOVE")
    p.add_argument("-o", "--output", metavar="OUT", help="write the new structure here")
    p = command("remove", cmd_remove, "remove one loop, if that leaves a polycube loop structure")
    p.add_argument("loop", metavar="LOOP", help="a loop as 'polyloops moves --remove' names it: its "
                   "axis and rank among that axis's loops (X0: the first X-loop), or its id (3)")
    p.add_argument("-o", "--output", metavar="OUT", help="write the new structure here")
