"""Files a catalog run spills into its ``parts/`` folder and reads back: one tagged format.

A run that computes something its workers share (the top of the loops search, the first
stage of the torus search) writes it once to ``DIR/parts/`` and each worker, and a rerun,
reads it back.  A file read back must be the one *this* run would write, so each file says
what it is and proves it:

- a magic line, then a 4-byte length and a JSON header: the format version, the ``kind`` of
  search that made it, that search's ``version`` (its schema and cuts), the ``bound`` it was
  run to (corners or crossings), the number of ``records``, the length and SHA-256 digest of
  the body, and free ``meta`` data (statistics) that is not matched;
- the body: each record as a 4-byte length and its bytes.

:func:`read_spill` accepts a file only when every tag matches the run that asks and the body
is exactly what the header counts and digests; anything else (another run's file, a truncated,
padded or edited file, junk) is a :class:`SpillMismatch`, and the run computes the file again.
A name in ``parts/`` that is not a regular file (a link to a device, a FIFO, a directory) is
neither read nor written through: :class:`SpillRefused`, one line naming it.

>>> import tempfile, pathlib
>>> tag = SpillTag("example", 1, 12)
>>> with tempfile.TemporaryDirectory() as tmp:
...     path = pathlib.Path(tmp) / "x.bin"
...     write_spill(path, tag, [b"ab", b"c"], {"visited": 3})
...     read_spill(path, tag).records, read_spill(path, tag).meta
...     read_spill(path, SpillTag("example", 1, 14))
Traceback (most recent call last):
...
polyloops.generate.spill.SpillMismatch: ...x.bin: made for bound 12, not 14
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import stat
import struct
import tempfile
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from polyloops.core.errors import PolyloopsError
from polyloops.io.files import OutputError, writing

__all__ = ["FORMAT_VERSION", "MAGIC", "SPILL_VERSION", "Spill", "SpillMismatch", "SpillRefused", "SpillTag",
           "SpillWriter", "iter_spill", "read_spill", "spill_state", "spilling", "write_spill"]

# The searches' own version, in every tag (``{"schema": SPILL_VERSION, ...}``): raised when a
# search changes what it spills, so that files of an older search are computed again.
SPILL_VERSION = 6

MAGIC = b"polyloops spill\n"
FORMAT_VERSION = 1
MAX_HEADER = 1 << 20  # the header holds statistics, never more than a few kB
_LEN = struct.Struct("<I")


class SpillMismatch(PolyloopsError, ValueError):
    """A spilled file that is not the one this run would write (another run's, damaged or
    edited): the run computes it again.  The message names the file and the difference."""


class SpillRefused(PolyloopsError, OSError):
    """A name in ``parts/`` that polyloops neither reads nor writes through: it is not a
    regular file (a link to a device, a FIFO, a directory)."""


@dataclass(frozen=True)
class SpillTag:
    """What a spilled file must be to serve a run: the search (``kind``), its ``version``
    (anything that changes its output: schema and cuts) and the ``bound`` it ran to."""

    kind: str
    version: Any
    bound: int


@dataclass(frozen=True)
class Spill:
    """A spilled file read back and proved: its tag, its records and its free ``meta``."""

    tag: SpillTag
    records: tuple[bytes, ...]
    meta: dict[str, Any] = field(default_factory=dict)


def spill_state(path: Path) -> str:
    """``"absent"``, ``"regular"``, or raises :class:`SpillRefused` for a name that is a link
    or anything but a regular file (nothing in ``parts/`` is a link polyloops made)."""
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        return "absent"
    except OSError as err:
        raise SpillRefused(f"{path}: cannot read: {err.strerror}") from None
    if stat.S_ISREG(info.st_mode):
        return "regular"
    kind = "a symbolic link" if stat.S_ISLNK(info.st_mode) else "not a regular file"
    raise SpillRefused(f"{path}: {kind}; polyloops neither reads nor writes its run files through it "
                       "(remove it and run again)")


def write_spill(path: Path, tag: SpillTag, records: Iterable[bytes],
                meta: dict[str, Any] | None = None) -> None:
    """Write ``records`` to ``path`` under ``tag``, atomically (a temporary file and a rename:
    a stopped run leaves the old file or none, never half of one).

    Raises
    ------
    SpillRefused
        When ``path`` is a link or not a regular file.
    """
    with spilling(path, tag) as out:
        out.extend(records)
        out.meta = meta or {}


class SpillWriter:
    """Records added one at a time to a temporary body beside the file, counted and digested as
    they come, so that a run spills more than it could hold in memory; :func:`spilling` writes
    the header and the body when the block ends (``meta`` may be set until then)."""

    def __init__(self, body: Any):
        self._body = body
        self._digest = hashlib.sha256()
        self.records = 0
        self.body_bytes = 0
        self.meta: dict[str, Any] = {}

    def add(self, record: bytes) -> None:
        """Add one record."""
        chunk = _LEN.pack(len(record)) + record
        self._body.write(chunk)
        self._digest.update(chunk)
        self.records += 1
        self.body_bytes += len(chunk)

    def extend(self, records: Iterable[bytes]) -> None:
        """Add records, in order."""
        for record in records:
            self.add(record)

    def header(self, tag: SpillTag) -> bytes:
        """The header of the records added so far, under ``tag``."""
        return json.dumps({"format": FORMAT_VERSION, "kind": tag.kind, "version": tag.version,
                           "bound": tag.bound, "records": self.records, "body_bytes": self.body_bytes,
                           "sha256": self._digest.hexdigest(), "meta": self.meta}, sort_keys=True).encode()


@contextlib.contextmanager
def spilling(path: Path, tag: SpillTag) -> Iterator[SpillWriter]:
    """A :class:`SpillWriter` for ``path``; when the block ends without an error the file is
    written atomically (header, then the body copied from the temporary one), and the
    temporary body is removed either way.

    Raises
    ------
    SpillRefused
        When ``path`` is a link or not a regular file.
    """
    spill_state(path)
    fd, body_name = tempfile.mkstemp(prefix=f".{Path(path).name}.", suffix=".body", dir=Path(path).parent)
    try:
        with os.fdopen(fd, "w+b") as body:
            out = SpillWriter(body)
            yield out
            header = out.header(tag)
            body.seek(0)
            try:
                with writing(path) as pending, open(pending.path, "wb") as fh:
                    fh.write(MAGIC + _LEN.pack(len(header)) + header)
                    shutil.copyfileobj(body, fh, 1 << 20)
            except OutputError as err:
                raise SpillRefused(str(err)) from None
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(body_name)


def _header(path: Path, fh: Any, tag: SpillTag) -> tuple[dict[str, Any], int]:
    """The checked header of an open spilled file, and the file's size."""
    size = os.fstat(fh.fileno()).st_size
    if fh.read(len(MAGIC)) != MAGIC:
        raise SpillMismatch(f"{path}: not a polyloops run file")
    raw = fh.read(4)
    if len(raw) < 4:
        raise SpillMismatch(f"{path}: truncated header")
    (length,) = _LEN.unpack(raw)
    if length > MAX_HEADER:
        raise SpillMismatch(f"{path}: damaged header ({length} bytes)")
    try:
        header = json.loads(fh.read(length))
    except (ValueError, RecursionError):
        raise SpillMismatch(f"{path}: damaged header") from None
    if not isinstance(header, dict) or header.get("format") != FORMAT_VERSION:
        raise SpillMismatch(f"{path}: another format of run file")
    for key, want in (("kind", tag.kind), ("version", tag.version), ("bound", tag.bound)):
        if header.get(key) != want:
            shown = want if key == "bound" else repr(want)
            raise SpillMismatch(f"{path}: made for {key} {header.get(key)!r}, not {shown}")
    body = header.get("body_bytes")
    if (type(body) is not int or type(header.get("records")) is not int
            or not isinstance(header.get("sha256"), str)):
        raise SpillMismatch(f"{path}: damaged header")
    if size != len(MAGIC) + 4 + length + body:
        raise SpillMismatch(f"{path}: {size} bytes where its header promises "
                            f"{len(MAGIC) + 4 + length + body} (truncated or padded)")
    return header, size


def _open(path: Path) -> Any:
    if spill_state(path) == "absent":
        raise SpillMismatch(f"{path}: absent")
    try:
        return open(path, "rb")
    except OSError as err:
        raise SpillRefused(f"{path}: cannot read: {err.strerror}") from None


def iter_spill(path: Path, tag: SpillTag) -> tuple[dict[str, Any], Iterator[bytes]]:
    """A spilled file's ``meta`` and its records one at a time (a worker keeps only its
    share).  The whole body is digested before this returns, so nothing is yielded from a file
    that is not proved; raises :class:`SpillMismatch` or :class:`SpillRefused` as
    :func:`read_spill` (a record count that differs from the header's, when the records are
    read)."""
    with _open(path) as fh:
        header, _ = _header(path, fh, tag)
        start = fh.tell()
        digest = hashlib.sha256()
        while chunk := fh.read(1 << 22):
            digest.update(chunk)
    if digest.hexdigest() != header["sha256"]:
        raise SpillMismatch(f"{path}: its body does not match its digest (edited or damaged)")

    def records() -> Iterator[bytes]:
        with _open(path) as fh:
            fh.seek(start)
            count = 0
            while raw := fh.read(4):
                (length,) = _LEN.unpack(raw) if len(raw) == 4 else (-1,)
                rec = fh.read(length) if length >= 0 else b""
                if length < 0 or len(rec) != length:
                    raise SpillMismatch(f"{path}: damaged record {count + 1}")
                count += 1
                yield rec
        if count != header["records"]:
            raise SpillMismatch(f"{path}: {count} records where its header counts {header['records']}")

    meta = header.get("meta")
    return (meta if isinstance(meta, dict) else {}), records()


def read_spill(path: Path, tag: SpillTag) -> Spill:
    """A spilled file read whole and proved to be the one ``tag`` asks for.

    Raises
    ------
    SpillMismatch
        When it is absent, of another kind, version or bound, or its body is not exactly the
        one its header counts and digests.
    SpillRefused
        When the name is a link or not a regular file.
    """
    with _open(path) as fh:
        header, _ = _header(path, fh, tag)
        body = fh.read()
    if hashlib.sha256(body).hexdigest() != header["sha256"]:
        raise SpillMismatch(f"{path}: its body does not match its digest (edited or damaged)")
    out: list[bytes] = []
    at = 0
    while at < len(body):
        if at + 4 > len(body):
            raise SpillMismatch(f"{path}: damaged record {len(out) + 1}")
        (length,) = _LEN.unpack_from(body, at)
        if at + 4 + length > len(body):
            raise SpillMismatch(f"{path}: damaged record {len(out) + 1}")
        out.append(bytes(body[at + 4:at + 4 + length]))
        at += 4 + length
    if len(out) != header["records"]:
        raise SpillMismatch(f"{path}: {len(out)} records where its header counts {header['records']}")
    meta = header.get("meta")
    return Spill(tag, tuple(out), meta if isinstance(meta, dict) else {})
