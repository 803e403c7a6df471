"""The ``polyloops`` command line: a thin layer over the Python API.

Each command group lives in its own module (``structures``, ``corners``, ``orient``, ``moves``,
``catalog``, ``pictures``, ``reach``, ``segmentation``): argument parsing, one library call,
printing.  This module builds the parser and runs a command.

Exit status: 0 when done or valid, 1 when the input was checked and is invalid, 2 for bad
input or usage, 3 for an internal error (a bug).  Errors are one line naming the file.
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
from collections.abc import Sequence

from polyloops import __version__
from polyloops.cli import catalog, corners, moves, orient, pictures, reach, segmentation, structures
from polyloops.cli.args import FILE_HELP, Command, Parser
from polyloops.cli.load import EXIT_OK, CliError

EXIT_INTERNAL = 3


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="polyloops", description="Polycubes via their dual loops: check, convert, explore.")
    parser.add_argument("--version", action="version", version=f"polyloops {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    sub.required = True

    def command(name: str, func: Command, help_text: str, file_arg: bool = True,
                json_flag: bool = True, listed: bool = True) -> argparse.ArgumentParser:
        # An unlisted command (an older spelling) gets no line in 'polyloops --help'.
        p = (sub.add_parser(name, description=help_text, help=help_text) if listed
             else sub.add_parser(name, description=help_text))
        if file_arg:
            p.add_argument("file", metavar="FILE", help=FILE_HELP)
        if json_flag:
            p.add_argument("--json", action="store_true", help="print one JSON object for scripts")
        p.set_defaults(func=func)
        return p

    def hidden(name: str, func: Command, help_text: str, json_flag: bool = True) -> argparse.ArgumentParser:
        return command(name, func, help_text, file_arg=False, json_flag=json_flag, listed=False)

    structures.add_commands(command)
    corners.add_commands(command)
    orient.add_commands(command)
    moves.add_commands(command)
    catalog.add_commands(command, hidden)
    pictures.add_commands(command)
    reach.add_commands(command)
    segmentation.add_command(command)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(list(sys.argv[1:] if argv is None else argv))
    # 'catalog-query' is an older spelling of 'catalog query'; other names keep their hyphen
    command = args.command.replace("-", " ") if args.command.startswith("catalog-") else args.command
    name = command + (f" {args.action}" if getattr(args, "action", None) else "")
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
