"""The ``polyloops`` command line: a thin layer over the Python API.

Each command group lives in its own module (``structures``, ``corners``, ``orient``, ``moves``,
``catalog``, ``pictures``, ``reach``, ``segmentation``): argument parsing, one library call,
printing.  This module builds the parser and runs a command.

Exit status: 0 when done or valid, 1 when the input was checked and is invalid, 2 for bad
input or usage, 3 for an internal error (a bug).  Errors are one line naming the file.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import signal
import sys
from collections.abc import Sequence
from typing import Any

from polyloops import __version__
from polyloops.cli import catalog, corners, moves, orient, pictures, reach, segment, segmentation, structures
from polyloops.cli.args import FILE_HELP, Command, Parser, UsageError
from polyloops.cli.load import EXIT_OK, EXIT_USAGE, CliError

EXIT_INTERNAL = 3


def version_text() -> str:
    """``polyloops 0.1.0`` and a line per compiled part: built or not, in use or not."""
    from polyloops.core import compiled

    lines = [f"polyloops {__version__}", "compiled parts (POLYLOOPS_PURE_PYTHON=all or NAME,... runs their "
             "Python twins):"]
    for s in compiled.status():
        state = "in use" if s.in_use else "built, switched to its twin" if s.built else "not built"
        lines.append(f"  {s.part.name:<13} {state:<28} {s.part.what}")
    return "\n".join(lines)


class VersionAction(argparse.Action):
    """``--version``: the version and the compiled parts, worked out only when asked."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: Any,
                 option_string: str | None = None) -> None:
        print(version_text())
        parser.exit()


def build_parser() -> argparse.ArgumentParser:
    parser = Parser(prog="polyloops", description="Polycubes via their dual loops: check, convert, explore.")
    parser.add_argument("--version", action=VersionAction, nargs=0,
                        help="the version, and which compiled parts were built and are in use")
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
    segment.add_command(command)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    from polyloops.core import compiled

    parser = build_parser()
    given = list(sys.argv[1:] if argv is None else argv)
    try:  # the environment's switch is checked before anything runs
        compiled.forced()
    except compiled.CompiledError as err:
        print(f"polyloops: {err}", file=sys.stderr)
        return EXIT_USAGE
    try:
        args = parser.parse_args(given)
    except UsageError as err:
        print(err.line, file=sys.stderr)
        if "--json" in given:
            print(json.dumps({"error": err.message, "status": EXIT_USAGE}, indent=2))
        raise SystemExit(EXIT_USAGE) from None  # as argparse does: callers see a usage error
    # 'catalog-query' is an older spelling of 'catalog query'; other names keep their hyphen
    command = args.command.replace("-", " ") if args.command.startswith("catalog-") else args.command
    name = command + (f" {args.action}" if getattr(args, "action", None) else "")
    previous = _terminate_cleanly()
    guard = _ClosedPipeGuard.install()
    try:
        status = args.func(args)
        if _TERMINATED:  # the signal's exception was swallowed (raised inside a finalizer, say)
            raise KeyboardInterrupt
        return status
    except CliError as err:
        print(f"polyloops {name}: {_clip_words(str(err))}", file=sys.stderr)
        _json_error(args, str(err), err.status, err.data)
        return err.status
    except BrokenPipeError:  # output piped into head, for example
        return EXIT_OK
    except KeyboardInterrupt:
        print(f"polyloops {name}: interrupted", file=sys.stderr)
        return 130
    except Exception as err:  # a bug, not bad input: one line, the traceback on request
        if os.environ.get("POLYLOOPS_DEBUG"):
            raise
        message = f"internal error: {type(err).__name__}: {_clip_words(str(err))}"
        print(f"polyloops {name}: {message} (set POLYLOOPS_DEBUG=1 to see where)", file=sys.stderr)
        _json_error(args, message, EXIT_INTERNAL)
        return EXIT_INTERNAL
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)
        if guard is not None:
            guard.uninstall()


class _ClosedPipeGuard:
    """Standard output that a reader closed (``polyloops verify BAD | head -1``) swallows
    what is still written, so the command runs to its end and its exit status is its verdict,
    never the 0 of an aborted print.  Once the pipe is gone, the descriptor is pointed at
    ``/dev/null`` so that the interpreter's last flush cannot fail either."""

    def __init__(self, stream: Any):
        self._stream = stream
        self._gone = False

    @classmethod
    def install(cls) -> _ClosedPipeGuard | None:
        if isinstance(sys.stdout, cls) or not hasattr(sys.stdout, "fileno"):
            return None
        try:
            sys.stdout.fileno()
        except (OSError, ValueError):  # a stand-in for stdout (pytest's capture, a notebook)
            return None
        guard = cls(sys.stdout)
        sys.stdout = guard
        return guard

    def uninstall(self) -> None:
        if sys.stdout is self:
            sys.stdout = self._stream

    def _closed(self) -> None:
        self._gone = True
        with contextlib.suppress(OSError, ValueError):
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, self._stream.fileno())
            os.close(devnull)

    def write(self, text: str) -> int:
        if not self._gone:
            try:
                return self._stream.write(text)
            except BrokenPipeError:
                self._closed()
        return len(text)

    def flush(self) -> None:
        if not self._gone:
            try:
                self._stream.flush()
            except BrokenPipeError:
                self._closed()

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _json_error(args: argparse.Namespace | None, message: str, status: int,
                data: dict[str, Any] | None = None) -> None:
    """Under ``--json``, an error is one object on standard output too, as every result is."""
    if args is not None and getattr(args, "json", False):
        with contextlib.suppress(OSError, ValueError):
            print(json.dumps({**(data or {}), "error": _clip_words(message), "status": status}, indent=2))


_TERMINATED = False  # set by SIGTERM: the command ends "interrupted" even if its exception was lost


def _terminate_cleanly():
    """Turn SIGTERM into an exception, so that temporary files are removed and worker
    processes stopped on the way out, as for Ctrl-C.  Returns the previous handler (``None``
    outside the main thread, where handlers cannot be set)."""
    def stop(signum: int, frame: object) -> None:
        global _TERMINATED
        _TERMINATED = True
        raise KeyboardInterrupt

    global _TERMINATED
    _TERMINATED = False  # a new command (main may run several in one process)
    try:
        return signal.signal(signal.SIGTERM, stop)
    except ValueError:
        return None


def _clip_words(message: str, width: int = 256) -> str:
    """Messages name their inputs; a huge argument (a 100 kB sig:...) is shown shortened."""
    return " ".join(w if len(w) <= width else w[: width - 40] + "..." + w[-8:] for w in message.split(" "))


__all__ = ["build_parser", "main"]
