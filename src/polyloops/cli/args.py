"""What every command shares: the parser class, argument types, output, and the FILE help."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable
from typing import Any

from polyloops.core.errors import PolyloopsError
from polyloops.core.symmetry import MODE_ALIASES, Symmetry
from polyloops.core.words import plural
from polyloops.io.registry import FORMATS

# Every format the registry reads, so that the help never lists fewer than the program takes.
_MESHES = ", ".join(s for f in FORMATS if f.reads and f.name not in ("json", "apg", "planar")
                    for s in f.suffixes)
FILE_HELP = ("a file polyloops reads (polyloops JSON .json, DualCube .graph/.apg, plantri's planar code "
             f".pc/.plc, or a quad mesh: {_MESHES}), example:NAME for a bundled example ('polyloops "
             "examples' lists them), or sig:SIGNATURE")

# The symmetry modes' names, as every --symmetry option offers them.
SYMMETRIES = tuple(mode.value for mode in Symmetry)
# The corners command also accepts 'none', an older name for 'labelled'.
SYMMETRIES_WITH_ALIASES = (SYMMETRIES[0], *MODE_ALIASES, *SYMMETRIES[1:])

# Local worker processes: more than a machine has cores only queue; a typo of 10**9 must not fork.
MAX_WORKERS = 1024

Command = Callable[[argparse.Namespace], int]
# command(name, func, help, file_arg=True, json_flag=True) -> the command's parser
AddCommand = Callable[..., argparse.ArgumentParser]


class UsageError(PolyloopsError):
    """A command line that does not parse: ``main`` prints ``line`` and exits 2 (with
    ``--json``, also one object)."""

    def __init__(self, prog: str, message: str):
        super().__init__(message)
        self.message = message
        self.line = f"{prog}: {message} (see --help)"


class Parser(argparse.ArgumentParser):
    """Usage errors as one line and exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(self.prog, message)


def emit(args: argparse.Namespace, data: Any, text: str) -> None:
    """JSON for scripts with ``--json``, else the text; on standard error when the command's
    output file is standard output (``-o -``), so the two never mix."""
    out = sys.stderr if getattr(args, "output", None) == "-" else sys.stdout
    print(json.dumps(data, indent=2) if getattr(args, "json", False) else text, file=out)


def structure_facts(obj: Any) -> dict[str, Any]:
    """The counts a JSON summary gives for a polycube or loop structure it wrote."""
    from polyloops.core.polycube import Polycube

    m = obj.map
    facts: dict[str, Any] = {"kind": "polycube" if isinstance(obj, Polycube) else "loop-structure",
                             "corners": m.num_corners, "faces": m.num_faces, "genus": obj.genus}
    if not isinstance(obj, Polycube):
        facts["loops"] = len(obj.loops)
    return facts


def written(args: argparse.Namespace, text: str | None, facts: dict[str, Any],
            line: str | None = None, document: Any = None) -> None:
    """What a command that writes a file says.  Without ``--json``: the written text itself
    when it went to standard output (no ``-o``), else ``line``.  With ``--json``: one object,
    ``output`` (the file; ``null`` when the text went to standard output, and then
    ``document`` holds it: the structure's JSON document as data, or the text) and ``facts``."""
    from polyloops.cli.load import say

    if getattr(args, "json", False):
        data: dict[str, Any] = {"output": getattr(args, "output", None), **facts}
        if text is not None:
            data["document"] = text if document is None else document
        emit(args, data, "")
    elif text is not None:
        print(text, end="")
    else:
        output = getattr(args, "output", None)
        say(output, line if line is not None else f"wrote {output}: {fact_line(facts)}")


def fact_line(facts: dict[str, Any]) -> str:
    """The facts of what a command wrote, in words (for a writer given no line of its own).

    >>> fact_line({"kind": "loop-structure", "corners": 8, "faces": 6, "genus": 0, "loops": 3})
    'a loop structure with 8 corners, 6 faces and 3 loops, genus 0'
    >>> fact_line({"rows": 1})
    '1 row'
    """
    if "kind" in facts:
        parts = [plural(facts["corners"], "corner"), plural(facts["faces"], "face")]
        if "loops" in facts:
            parts.append(plural(facts["loops"], "loop"))
        counts = ", ".join(parts[:-1]) + " and " + parts[-1]
        return f"a {facts['kind'].replace('-', ' ')} with {counts}, genus {facts['genus']}"
    return ", ".join(plural(v, k.removesuffix("s")) for k, v in facts.items()
                     if isinstance(v, int) and not isinstance(v, bool))


def stream(args: argparse.Namespace, line: str) -> None:
    """Text output goes out as it is found (flushed), so a long listing shows progress."""
    if not getattr(args, "json", False):
        print(line, flush=True)


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


def json_flag(p: argparse.ArgumentParser) -> None:
    p.add_argument("--json", action="store_true", help="print one JSON object for scripts")


def genus_option(p: argparse.ArgumentParser, what: str = "catalog") -> None:
    """``--genus G``: which shipped catalog (or certificate) a command reads when none is given."""
    from polyloops.catalog.census import shipped_genera

    genera = shipped_genera()
    p.add_argument("--genus", type=int, choices=genera, default=None, metavar="G",
                   help=f"without a {what}: the shipped one of genus G (one of "
                   f"{', '.join(map(str, genera))}; default 0)")


def catalog_dir(given: str | None, genus: int | None) -> Any:
    """The catalog directory a command reads: the one given, else the shipped one of ``genus``
    (installed with the package)."""
    from pathlib import Path

    from polyloops.catalog.census import default_catalog

    return Path(given) if given else default_catalog(genus or 0)
