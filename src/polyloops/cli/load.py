"""Reading FILE arguments and writing outputs for the command line.

Every problem becomes a :class:`CliError` carrying the exit status and a
one-line message that names the file.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from polyloops.core.halfedge import FaceListError, MapError
from polyloops.core.loops import OddFaceError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LabelError, LoopStructure
from polyloops.io.files import (
    MAX_FILE_BYTES,
    InputError,
    OutputError,
    check_regular,
    read_bytes,
    resolve_output,
    write_atomic,
)
from polyloops.io.formats import Document, FormatError, Structure, dumps
from polyloops.io.registry import (
    BY_NAME,
    Source,
    UnknownExampleError,
    labelled,
    open_source,
    source_of,
    write_structure,
)

EXIT_OK, EXIT_INVALID, EXIT_USAGE = 0, 1, 2


class CliError(Exception):
    """A one-line error and its exit status; ``data`` is what ``--json`` prints with it (the
    error's object then holds it, ``error`` and ``status``)."""

    def __init__(self, message: str, status: int = EXIT_USAGE, data: dict[str, Any] | None = None):
        super().__init__(message)
        self.status = status
        self.data = data


def open_input(arg: str, given: str | None = None) -> Source:
    r"""A FILE argument, read once (:func:`polyloops.io.registry.open_source`); problems become
    one-line :class:`CliError`\ s naming it."""
    from polyloops.core.canonical import SignatureError

    try:
        if arg == "-":  # standard input can be read once: kept for a second look
            return source_of("-", read_bytes_file("-"), given)
        return open_source(arg, given)
    except UnknownExampleError as err:
        raise CliError(f"{arg}: {err}; 'polyloops examples' lists them") from None
    except (InputError, SignatureError) as err:
        raise CliError(str(err) if isinstance(err, InputError) else f"{arg}: {err}") from None
    except FormatError as err:
        raise CliError(f"{arg}: {err}" if not str(err).startswith(f"{arg}:") else str(err)) from None


def read_document(arg: str, given: str | None = None, source: Source | None = None) -> Document:
    """Parse a FILE argument: a path (any format :mod:`polyloops.io.registry` reads, by
    ``given``, extension or content; ``-`` is standard input), ``example:NAME`` or
    ``sig:SIGNATURE`` (``source``: the argument already read)."""
    source = source or open_input(arg, given)
    try:
        doc = source.document()
    except FormatError as err:
        raise CliError(f"{arg}: {err}") from None
    doc = _labelled(arg, doc)
    for note in doc.notes:
        print(f"{arg}: note: {note}", file=sys.stderr)
    return doc


def _labelled(arg: str, doc: Document) -> Document:
    """:func:`polyloops.io.registry.labelled`: a map that carries no structure is invalid
    (exit 1), one that carries several is ambiguous input (exit 2)."""
    from polyloops.core.labellings import MapStructureError

    try:
        return labelled(doc)
    except MapStructureError as err:
        raise CliError(f"{arg}: {err}", EXIT_INVALID if err.count == 0 else EXIT_USAGE) from None


FORMATS = tuple(BY_NAME)


def read_text_file(arg: str, limit: int = MAX_FILE_BYTES) -> str:
    """The text of a regular file of at most ``limit`` bytes (``-``: standard input).  A FIFO,
    a device such as ``/dev/zero`` or a directory is refused rather than read (it could block
    or never end)."""
    data = read_bytes_file(arg, limit)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise CliError(f"{arg}: cannot read: not UTF-8 text ({err.reason} at byte {err.start})") from None


_STDIN: list[bytes] = []  # standard input, once read: a command may look at its FILE twice


def read_bytes_file(arg: str, limit: int = MAX_FILE_BYTES) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes (see :func:`read_text_file`)."""
    try:
        if arg == "-":
            if not _STDIN:
                _STDIN.append(read_bytes(arg, limit))
            return _STDIN[0]
        return read_bytes(arg, limit)
    except InputError as err:
        raise CliError(str(err)) from None


def check_readable_file(arg: str, limit: int | None = MAX_FILE_BYTES) -> None:
    """What :func:`read_bytes_file` checks, without reading: for files a library reads."""
    try:
        check_regular(arg, limit)
    except InputError as err:
        raise CliError(str(err)) from None


def build(arg: str, doc: Document) -> Structure:
    """Build the model of a parsed file; bad input becomes a :class:`CliError`."""
    try:
        return doc.build()
    except MapError as err:
        raise CliError(f"{arg}: not a closed oriented surface: {err}") from None
    except (LabelError, FaceListError, OddFaceError) as err:
        raise CliError(f"{arg}: {err}") from None


def read_structure(arg: str, fix_orientation: bool = False, given: str | None = None) -> Structure:
    """Read and build a FILE argument.  An inside-out polycube (faces clockwise seen from
    outside) is refused with exit status 1, or turned outward with ``fix_orientation``."""
    obj = build(arg, read_document(arg, given))
    if isinstance(obj, Polycube) and obj.signed_volume() < 0:
        if fix_orientation:
            return obj.inverse()
        raise CliError(f"{arg}: the polycube is inside out (faces clockwise seen from outside); "
                       f"repair it with 'polyloops convert {arg} OUT --fix-orientation'", EXIT_INVALID)
    return obj


def read_loop_structure(arg: str, oriented: bool = False, valid: bool = False,
                        built: Structure | None = None) -> LoopStructure:
    """A FILE argument as a loop structure (:func:`polyloops.verify.as_loop_structure`): a
    polycube must pass Definition 1 and is dualized, and with ``valid`` the structure must be
    a polycube loop structure (exit 1 naming the first violation otherwise); with ``oriented``
    a structure without sides is refused (exit 2).  ``built`` is FILE already read."""
    from polyloops.verify import NeedsSidesError, NotAPolycubeError, as_loop_structure

    try:
        return as_loop_structure(read_structure(arg) if built is None else built,
                                 oriented=oriented, valid=valid)
    except NotAPolycubeError as err:
        raise CliError(f"{arg}: {err}", EXIT_INVALID) from None
    except NeedsSidesError as err:
        raise CliError(f"{arg}: {err}") from None


def read_valid_structure(arg: str) -> LoopStructure:
    """A FILE argument as a polycube loop structure (Definition 4): exit 1 naming the first
    violation otherwise."""
    return read_loop_structure(arg, valid=True)


def write_output(path: str | None, obj: Structure, given: str | None = None) -> str | None:
    """Write ``obj`` to ``path`` in the format its extension (or ``given``) names, or return
    the JSON text."""
    if path is None:
        return dumps(obj)
    try:
        write_structure(obj, path, given)
    except (OutputError, FormatError) as err:
        raise CliError(str(err)) from None
    return None


def write_text(path: str, text: str | bytes) -> None:
    """Write through the shared writer (:mod:`polyloops.io.files`: ``-`` is standard output,
    a link is followed, a device or FIFO written into); a failure becomes a one-line
    :class:`CliError`."""
    try:
        write_atomic(path, text)
    except OutputError as err:
        raise CliError(str(err)) from None


def write_error(path: object, err: OSError) -> CliError:
    """A failed write as a one-line error: the shared writer's own message, which names the
    file, or the system's reason."""
    if isinstance(err, (OutputError, InputError)):
        return CliError(str(err))
    reason = "no space left on device" if err.errno == 28 else err.strerror or str(err)
    return CliError(f"{path}: cannot write: {reason}")


def say(output: str | None, text: str) -> None:
    """A line about what was written: on standard output, or on standard error when the
    output itself went to standard output (``-o -``)."""
    print(text, file=sys.stderr if output == "-" else sys.stdout)


def streams(path: str) -> bool:
    """Whether an output is standard output or a device or FIFO (``-o /dev/null``): a picture
    there takes its command's first format, where a file names its own."""
    from polyloops.io.files import Sink, resolve_output

    try:
        return path == "-" or resolve_output(path).sink is Sink.STREAM
    except OutputError:  # reported by check_output, in its words
        return False


def picture_output(path: str, suffixes: tuple[str, ...] = (".png", ".svg")) -> str:
    """An output for a picture: ``-`` (standard output, as PNG or HTML) or a name with one of
    ``suffixes``, that may be written; checked before the work (exit 2)."""
    if not streams(path) and Path(path).suffix.lower() not in suffixes:  # ".png" alone has no suffix
        names = " or ".join(f"NAME{s}" for s in suffixes)
        what = "the viewer is" if ".html" in suffixes else "pictures are"
        raise CliError(f"{path}: {what} written as {names}")
    check_output(path)
    return path


def check_output(path: str) -> None:
    """Refuse an output that cannot be written before any work is done (exit 2)."""
    try:
        resolve_output(path)
    except OutputError as err:
        raise CliError(str(err)) from None


def output_dir(text: str) -> Path:
    """An output directory argument: a directory, or a name whose parent directory exists."""
    out = Path(text)
    if out.exists() and not out.is_dir():
        raise CliError(f"{out}: exists and is not a directory")
    if not out.absolute().parent.is_dir():
        raise CliError(f"{out}: the directory {out.absolute().parent} does not exist")
    return out
