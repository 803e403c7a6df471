"""Reading and writing files safely: the one place where polyloops touches the file system.

Writing follows the standard tools (``cp``, ``sort -o``, a shell's ``>``), but never leaves a
half-written file:

- a **symbolic link** is followed and its target written (a dangling link creates its target);
- a **regular file**, or a name that does not exist yet, is written through a temporary file in
  the same directory and a rename, so the old content stays whole until the new is complete
  (an existing file keeps its permissions);
- a **character device or FIFO** is written into directly (``/dev/null`` discards,
  ``/dev/full`` gives "no space left on device"); it is never replaced by a file;
- ``-`` is standard output;
- anything else (a directory, a block device, a socket) is refused with :class:`OutputError`.

Reading accepts regular files only (and ``-``, standard input, where a reader says so): a FIFO
or ``/dev/zero`` could block or never end.

>>> import tempfile, pathlib
>>> with tempfile.TemporaryDirectory() as tmp:
...     write_atomic(pathlib.Path(tmp) / "a.txt", "hello")
...     print((pathlib.Path(tmp) / "a.txt").read_text(), len(list(pathlib.Path(tmp).iterdir())))
hello 1
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import stat
import sys
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass
from enum import Enum

from polyloops.core.errors import PolyloopsError

STDIO = "-"
MAX_FILE_BYTES = 512 * 2**20


class OutputError(PolyloopsError, OSError):
    """An output that cannot be written (or must not be: a directory, a block device); the
    message names the file and the problem."""


class InputError(PolyloopsError, OSError):
    """An input that cannot be read: missing, unreadable, not a regular file, too large; the
    message names the file and the problem."""


class Sink(Enum):
    """How an output is written, by what its name leads to."""

    REPLACE = "replace"  # a regular file or a new name: temporary file and rename
    STREAM = "stream"    # a character device or FIFO: written into
    STDOUT = "stdout"    # '-'


@dataclass(frozen=True)
class Output:
    """Where an output goes: ``path`` as given, ``target`` with links followed, and how it is
    written."""

    path: str
    target: str
    sink: Sink


def _reason(err: OSError) -> str:
    if err.errno == errno.ENOSPC:
        return "no space left on device"
    return err.strerror or str(err)


def resolve_output(path: str | os.PathLike[str]) -> Output:
    """Where writing ``path`` would go, checked before any work is done.

    >>> resolve_output("-").sink
    <Sink.STDOUT: 'stdout'>
    >>> resolve_output("/").sink
    Traceback (most recent call last):
    ...
    polyloops.io.files.OutputError: /: is a directory
    """
    name = os.fspath(path)
    if name == STDIO:
        return Output(name, name, Sink.STDOUT)
    target = os.path.realpath(name)  # follows every link, dangling ones to the name they point at
    try:
        info = os.stat(target)
    except FileNotFoundError:
        parent = os.path.dirname(target)
        if not os.path.isdir(parent):
            raise OutputError(f"{name}: cannot write: the directory {parent} does not exist") from None
        return Output(name, target, Sink.REPLACE)
    except OSError as err:
        raise OutputError(f"{name}: cannot write: {_reason(err)}") from None
    if stat.S_ISREG(info.st_mode):
        return Output(name, target, Sink.REPLACE)
    if stat.S_ISCHR(info.st_mode) or stat.S_ISFIFO(info.st_mode):
        return Output(name, target, Sink.STREAM)
    if stat.S_ISDIR(info.st_mode):
        raise OutputError(f"{name}: is a directory")
    raise OutputError(f"{name}: is neither a regular file nor a character device or FIFO; "
                      "polyloops does not replace it")


def _default_mode() -> int:
    """The permissions a plain ``open(path, "w")`` would give (0o666 less the umask)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def _install(tmp: str, out: Output) -> None:
    """Move a finished temporary file into a REPLACE output, keeping an existing file's mode."""
    try:
        mode = stat.S_IMODE(os.stat(out.target).st_mode)
    except OSError:
        mode = _default_mode()
    os.chmod(tmp, mode)
    os.replace(tmp, out.target)


def _stream_into(out: Output, data: bytes | None = None, source: str | None = None) -> None:
    """Write ``data`` or the file ``source`` into a device, FIFO or standard output."""
    if out.sink is Sink.STDOUT:
        if source is not None:
            with open(source, "rb") as src:
                data = src.read()
        sys.stdout.flush()
        fh = getattr(sys.stdout, "buffer", None)
        if fh is None:  # a text stream standing in for stdout (a notebook, a doctest)
            sys.stdout.write((data or b"").decode("utf-8", "replace"))
        else:
            fh.write(data or b"")
            fh.flush()
        return
    with open(out.target, "wb") as fh:  # truncation means nothing to a device or FIFO
        if source is not None:
            with open(source, "rb") as src:
                shutil.copyfileobj(src, fh)
        else:
            fh.write(data or b"")


def check_within(path: str | os.PathLike[str], root: str | os.PathLike[str]) -> None:
    """Refuse a file an output directory's writer would place outside ``root`` or write
    through anything but a regular file: a name that leaves it (``../x``, an absolute path), a
    symbolic link on the way or in its place, a device or FIFO.  Such writers (the gallery's
    pages, a catalog's files, a run's ``parts/``) own every name below their directory, so they
    never follow a link out of it.

    >>> check_within("site/a/b.html", "site")
    >>> check_within("site/../b.html", "site")
    Traceback (most recent call last):
    ...
    polyloops.io.files.OutputError: site/../b.html: outside the output directory site
    """
    name, top = os.path.abspath(os.fspath(path)), os.path.abspath(os.fspath(root))
    rel = os.path.relpath(name, top)
    if rel == os.curdir or rel.split(os.sep)[0] == os.pardir or os.path.isabs(rel):
        raise OutputError(f"{os.fspath(path)}: outside the output directory {os.fspath(root)}")
    at = top
    parts = rel.split(os.sep)
    for i, part in enumerate(parts):
        at = os.path.join(at, part)
        try:
            info = os.lstat(at)
        except FileNotFoundError:
            return
        except OSError as err:
            raise OutputError(f"{os.fspath(path)}: cannot write: {_reason(err)}") from None
        if stat.S_ISLNK(info.st_mode):
            raise OutputError(f"{at}: a symbolic link inside the output directory {os.fspath(root)}; "
                              "polyloops does not write through it")
        last = i == len(parts) - 1
        if last and not stat.S_ISREG(info.st_mode):
            raise OutputError(f"{at}: not a regular file; polyloops does not replace it")
        if not last and not stat.S_ISDIR(info.st_mode):
            raise OutputError(f"{at}: not a directory")


def write_atomic(path: str | os.PathLike[str], text: str | bytes, *,
                 within: str | os.PathLike[str] | None = None) -> None:
    """Write text (UTF-8) or bytes to ``path`` as the module says: a regular file through a
    temporary file and a rename, a device or FIFO directly, ``-`` to standard output.  With
    ``within``, the file must be a regular file (or new) inside that directory, reached
    through no link (:func:`check_within`).

    Raises
    ------
    OutputError
        When ``path`` must not be replaced or the write fails (no space, no permission).
    """
    if within is not None:
        check_within(path, within)
    data = text.encode("utf-8") if isinstance(text, str) else text
    out = resolve_output(path)
    if out.sink is not Sink.REPLACE:
        try:
            _stream_into(out, data=data)
        except OSError as err:
            raise OutputError(f"{out.path}: cannot write: {_reason(err)}") from None
        return
    with writing(path) as pending, open(pending.path, "wb") as fh:
        fh.write(data)


@dataclass(frozen=True)
class Pending:
    """What :func:`writing` hands to the writer: the temporary ``path`` to write into."""

    path: str
    output: Output


@contextlib.contextmanager
def writing(path: str | os.PathLike[str], suffix: str = ".tmp", *,
            within: str | os.PathLike[str] | None = None) -> Iterator[Pending]:
    """For writers that need a file name (matplotlib, meshio, SQLite): yields a temporary file
    to write (``.path``, with ``suffix`` for writers that choose a format by extension), and
    puts it in place as the module says once the block succeeds; on failure nothing changes
    and the temporary file is removed.

    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     with writing(pathlib.Path(tmp) / "b.txt") as out:
    ...         _ = pathlib.Path(out.path).write_text("made by a library")
    ...     print((pathlib.Path(tmp) / "b.txt").read_text())
    made by a library

    ``within`` confines the file as :func:`write_atomic` says.
    """
    if within is not None:
        check_within(path, within)
    out = resolve_output(path)
    where = os.path.dirname(out.target) if out.sink is Sink.REPLACE else None
    name = os.path.basename(out.target)
    try:
        fd, tmp = tempfile.mkstemp(dir=where, prefix=f".{name}.", suffix=suffix)
        os.close(fd)
    except OSError as err:
        raise OutputError(f"{out.path}: cannot write: {_reason(err)}") from None
    pending = Pending(tmp, out)
    try:
        yield pending
        if out.sink is Sink.REPLACE:
            _install(tmp, out)
        else:
            _stream_into(out, source=tmp)
    except OSError as err:
        if isinstance(err, OutputError):
            raise
        raise OutputError(f"{out.path}: cannot write: {_reason(err)}") from None
    finally:
        with contextlib.suppress(OSError):
            os.unlink(tmp)


def read_bytes(path: str | os.PathLike[str], limit: int = MAX_FILE_BYTES, *, stdin: bool = True) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes; ``-`` reads standard input
    (with ``stdin``).  A FIFO, a device such as ``/dev/zero`` or a directory is refused rather
    than read (it could block or never end).

    Raises
    ------
    InputError
        Naming the file and the problem.
    """
    name = os.fspath(path)
    if name == STDIO and stdin:
        data = sys.stdin.buffer.read(limit + 1)
        if len(data) > limit:
            raise _too_large(name, limit)
        return data
    return _open_regular(name, limit, read=True)


def read_text(path: str | os.PathLike[str], limit: int = MAX_FILE_BYTES, *, stdin: bool = True) -> str:
    """The UTF-8 text of a regular file (see :func:`read_bytes`); a byte-order mark is dropped."""
    data = read_bytes(path, limit, stdin=stdin)
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise InputError(f"{os.fspath(path)}: cannot read: not UTF-8 text "
                         f"({err.reason} at byte {err.start})") from None


def check_regular(path: str | os.PathLike[str], limit: int | None = MAX_FILE_BYTES) -> None:
    """What :func:`read_bytes` checks, without reading: for files a library (SQLite, meshio,
    numpy) opens itself.  ``limit=None`` accepts any size."""
    _open_regular(os.fspath(path), limit, read=False)


def _too_large(name: str, limit: int) -> InputError:
    return InputError(f"{name}: larger than {limit // 2**20} MiB; polyloops reads files up to that size")


def _open_regular(name: str, limit: int | None, read: bool) -> bytes:
    try:
        # O_NONBLOCK: opening a FIFO with no writer must not wait; regular files ignore it.
        fd = os.open(name, os.O_RDONLY | os.O_NONBLOCK)
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            os.close(fd)
            kind = "is a directory" if stat.S_ISDIR(info.st_mode) else "not a regular file"
            raise InputError(f"{name}: {kind}")
        with os.fdopen(fd, "rb") as fh:
            if limit is not None and info.st_size > limit:
                raise _too_large(name, limit)
            data = fh.read(limit + 1 if limit is not None else -1) if read else b""
    except InputError:
        raise
    except OSError as err:
        raise InputError(f"{name}: cannot read: {_reason(err)}") from None
    if limit is not None and len(data) > limit:
        raise _too_large(name, limit)
    return data


def read_only_uri(path: str | os.PathLike[str]) -> str:
    """An SQLite URI that opens ``path`` read-only and never creates it, whatever characters
    (``#``, ``%``, ``?``) its name holds.

    >>> read_only_uri("/tmp/a#b/c?.sqlite")
    'file:///tmp/a%23b/c%3F.sqlite?mode=ro'
    """
    from pathlib import Path

    return Path(os.path.abspath(path)).as_uri() + "?mode=ro"


__all__ = ["MAX_FILE_BYTES", "STDIO", "InputError", "Output", "OutputError", "Pending", "Sink",
           "check_regular", "check_within", "read_bytes", "read_only_uri", "read_text", "resolve_output",
           "write_atomic", "writing"]
