"""Reading FILE arguments and writing outputs for the command line.

Every problem becomes a :class:`CliError` carrying the exit status and a
one-line message that names the file.
"""

from __future__ import annotations

from pathlib import Path

from polyloops.core.examples import EXAMPLES, example_text
from polyloops.core.formats import (
    Document,
    FormatError,
    Structure,
    dumps,
    parse_document,
    to_obj,
    write_atomic,
)
from polyloops.core.halfedge import FaceListError, MapError
from polyloops.core.loops import OddFaceError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LabelError

EXIT_OK, EXIT_INVALID, EXIT_USAGE = 0, 1, 2


class CliError(Exception):
    def __init__(self, message: str, status: int = EXIT_USAGE):
        super().__init__(message)
        self.status = status


def read_document(arg: str) -> Document:
    """Parse a FILE argument: a path, ``example:NAME`` or ``sig:SIGNATURE``."""
    if arg.startswith("sig:"):
        from polyloops.core.canonical import SignatureError, from_signature

        try:
            return parse_document(dumps(from_signature(arg.removeprefix("sig:"))))
        except SignatureError as err:
            raise CliError(f"{arg}: {err}") from None
    if arg.startswith("example:"):
        name = arg.removeprefix("example:")
        if name not in EXAMPLES:
            raise CliError(f"{arg}: unknown example; 'polyloops examples' lists them")
        text = example_text(name)
    else:
        try:
            text = Path(arg).read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as err:
            reason = err.strerror if isinstance(err, OSError) and err.strerror else str(err)
            raise CliError(f"{arg}: cannot read: {reason}") from None
    try:
        return parse_document(text)
    except FormatError as err:
        raise CliError(f"{arg}: {err}") from None


def build(arg: str, doc: Document) -> Structure:
    """Build the model of a parsed file; bad input becomes a :class:`CliError`."""
    try:
        return doc.build()
    except MapError as err:
        raise CliError(f"{arg}: not a closed oriented surface: {err}") from None
    except (LabelError, FaceListError, OddFaceError) as err:
        raise CliError(f"{arg}: {err}") from None


def read_structure(arg: str, fix_orientation: bool = False) -> Structure:
    """Read and build a FILE argument.  An inside-out polycube (faces clockwise seen from
    outside) is refused with exit status 1, or turned outward with ``fix_orientation``."""
    obj = build(arg, read_document(arg))
    if isinstance(obj, Polycube) and obj.signed_volume() < 0:
        if fix_orientation:
            return obj.inverse()
        raise CliError(f"{arg}: the polycube is inside out (faces clockwise seen from outside); "
                       f"repair it with 'polyloops convert {arg} OUT --fix-orientation'", EXIT_INVALID)
    return obj


def write_output(path: str | None, obj: Structure) -> str | None:
    """Write ``obj`` to ``path`` (OBJ if it ends in ``.obj``, else JSON), or return the JSON text."""
    if path is None:
        return dumps(obj)
    if path.endswith(".obj"):
        if not isinstance(obj, Polycube):
            raise CliError(f"{path}: only a polycube can be written as OBJ")
        text = to_obj(obj)
    else:
        text = dumps(obj)
    write_text(path, text)
    return None


def write_text(path: str, text: str) -> None:
    """Write atomically; a failure becomes a one-line :class:`CliError`."""
    try:
        write_atomic(path, text)
    except OSError as err:
        raise CliError(f"{path}: cannot write: {err.strerror or err}") from None
