"""The ``orient`` command: sides for the loops of a labelled loop structure."""

from __future__ import annotations

import argparse
import json
from typing import Any

from polyloops.cli.args import AddCommand, emit
from polyloops.cli.load import (
    EXIT_INVALID,
    EXIT_OK,
    CliError,
    read_loop_structure,
    say,
    write_output,
    write_text,
)
from polyloops.io.formats import to_data


def _components_json(problem: Any) -> dict[str, list[list[int]]]:
    from polyloops.core.directions import Axis

    return {a.name: [list(c.loops) for c in problem.components_of(a)] for a in Axis}


def cmd_orient(args: argparse.Namespace) -> int:
    from polyloops.solvers import OrientationProblem, axis_flip_factor, explain, make_solver
    from polyloops.solvers.base import count as count_solutions
    from polyloops.solvers.base import feasible_locally

    problem = OrientationProblem(read_loop_structure(args.file))
    solver = make_solver(args.solver)
    info: dict[str, Any] = {"solver": args.solver, "k": problem.k, "components": _components_json(problem)}
    summary = (f"{args.file}: k = {problem.k} free choices (side-graph components: "
               + ", ".join(f"{a}: {len(v)}" for a, v in info["components"].items()) + ")")

    def fail() -> int:
        why = explain(problem)
        assert why is not None
        info.update(found=False, condition=why.condition, reason=why.reason, witness=why.witness)
        if not args.json:
            print(summary)
        raise CliError(f"{args.file}: no orientation: {why.reason}", EXIT_INVALID, data=info)

    if args.count:
        n = count_solutions(solver, problem)
        info.update(count=n, count_modulo_axis_flips=n // axis_flip_factor(problem) if n else 0)
        if n == 0 and not args.json:
            return fail()
        emit(args, info, f"{summary}\n{n} orientations ({info['count_modulo_axis_flips']} up to "
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
            say(args.output, f"{summary}\nwrote {len(lines)} orientations to {args.output} "
                "(one JSON per line)")
            return EXIT_OK
        n = 0
        found: list[list[int]] = []
        for s in structures:
            if args.json:  # one object at the end, the orientations a list inside it
                found.append(list(s.signs or ()))
            else:
                print(" ".join("+" if x > 0 else "-" for x in s.signs or ()), flush=True)
            n += 1
        if not n:
            return fail()
        if args.json:
            print(json.dumps({**info, "count": n, "orientations": found}, indent=2))
        return EXIT_OK
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
        say(args.output, f"{summary}\nwrote an orientation to {args.output}")
    return EXIT_OK


def add_commands(command: AddCommand) -> None:
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
