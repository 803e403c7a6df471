"""The file formats polyloops reads and writes, by name, extension and content: one registry
that every command and :func:`polyloops.read` / :func:`polyloops.write` go through.

========== ============================== ======================================== =====
format     extensions                     what                                     reads
========== ============================== ======================================== =====
json       .json                          polyloops JSON (polycube or structure)   yes
apg        .graph .apg                    DualCube's Abstract Polycube Graph       yes
obj        .obj                           Wavefront OBJ quad mesh (a polycube)     yes
planar     .pc .plc .planarcode           plantri's planar code (one map)          yes
ply off    .ply .off .vtk .vtu .mesh .msh polycube meshes through meshio           yes
vtk ...
stl        .stl                           triangles through meshio (two a quad)    no
========== ============================== ======================================== =====

A name without a known extension (standard input ``-`` among them) is read by its content;
an output name must have a known extension, or its format must be given.

>>> format_for("shape.graph").name, format_for("-", writing=True).name
('apg', 'json')
>>> format_for("ring.xyz", writing=True)  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
polyloops.io.registry.FormatChoiceError: ring.xyz: polyloops does not write .xyz files; it writes .json, ...
"""

from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass

from polyloops.core.polycube import Polycube
from polyloops.io.exchange import apg_text, parse_apg, parse_obj
from polyloops.io.files import OutputError, Sink, read_bytes, resolve_output, write_atomic
from polyloops.io.formats import Document, FormatError, Structure, dumps, parse_document, to_obj

__all__ = ["FORMATS", "FileFormat", "FormatChoiceError", "Source", "UnknownExampleError", "format_for",
           "open_source", "parse_bytes", "read", "read_document", "sniff", "write", "write_structure"]


class FormatChoiceError(FormatError):
    """A format name or extension polyloops does not read or write; the message lists those it does."""


def _text(data: bytes) -> str:
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as err:
        raise FormatError(f"not UTF-8 text ({err.reason} at byte {err.start})") from None


def _read_planar(data: bytes) -> Document:
    """Planar code gives a document of kind ``map`` (faces only): it has no axis labels, and
    finding the map's polycube loop structure is a search
    (:func:`polyloops.core.labellings.only_structure_on`)."""
    from polyloops.io.planar_code import read_planar_code

    maps = read_planar_code(data)
    if len(maps) != 1:
        raise FormatError(f"holds {len(maps)} maps; polyloops reads one map per file")
    return Document("map", [list(f) for f in maps[0].faces])


def _write_planar(obj: Structure) -> bytes:
    from polyloops.io.planar_code import planar_code

    return planar_code([obj.map])


def _read_mesh(name: str) -> Callable[[bytes], Document]:
    def read(data: bytes) -> Document:
        from polyloops.io.meshes import read_polycube_mesh

        return read_polycube_mesh(data, name)

    return read


def _first_words(data: bytes) -> list[str]:
    """The words of the first line that is not a comment (for formats known by their words)."""
    for line in data.decode("utf-8", "replace").splitlines():
        if line.strip() and not line.lstrip().startswith(("#", "/")):
            return line.split()
    return []


@dataclass(frozen=True)
class FileFormat:
    """One file format, one row: its name, extensions, what it writes (``polycube``: only
    polycubes; ``any``: polycubes and loop structures), its reader and writer, and how its
    content looks when a name has no known extension."""

    name: str
    suffixes: tuple[str, ...]
    reader: Callable[[bytes], Document] | None  # None: polyloops does not read it
    writes: str  # "any" or "polycube"
    writer: Callable[[Structure], str | bytes] | None = None  # None: written through meshio
    looks: Callable[[bytes], bool] | None = None  # whether bytes look like this format
    mesh: bool = False  # written (and read) through meshio

    @property
    def reads(self) -> bool:
        """Whether polyloops reads this format."""
        return self.reader is not None


FORMATS: tuple[FileFormat, ...] = (
    FileFormat("json", (".json",), lambda data: parse_document(_text(data)), "any", dumps,
               lambda head: head.startswith((b"{", b"["))),
    FileFormat("apg", (".graph", ".apg"), lambda data: parse_apg(_text(data)), "any", apg_text,
               lambda head: (words := _first_words(head)) != [] and len(words) == 3
               and all(w.isdigit() for w in words)),
    FileFormat("obj", (".obj",), lambda data: parse_obj(_text(data)), "polycube", to_obj,  # type: ignore[arg-type]
               lambda head: (words := _first_words(head)) != []
               and words[0] in ("v", "f", "o", "g", "mtllib", "usemtl", "vn", "vt")),
    FileFormat("planar", (".pc", ".plc", ".planarcode"), _read_planar, "any", _write_planar,
               lambda head: head.startswith(b">>planar_code")),
    FileFormat("ply", (".ply",), _read_mesh("ply"), "polycube", looks=lambda head: head.startswith(b"ply"),
               mesh=True),
    FileFormat("off", (".off",), _read_mesh("off"), "polycube",
               looks=lambda head: head.startswith((b"OFF", b"COFF", b"NOFF")), mesh=True),
    FileFormat("vtk", (".vtk",), _read_mesh("vtk"), "polycube",
               looks=lambda head: head.startswith(b"# vtk DataFile"), mesh=True),
    FileFormat("vtu", (".vtu",), _read_mesh("vtu"), "polycube", mesh=True),
    FileFormat("medit", (".mesh",), _read_mesh("medit"), "polycube", mesh=True),
    FileFormat("gmsh", (".msh",), _read_mesh("gmsh"), "polycube", mesh=True),
    FileFormat("stl", (".stl",), None, "polycube", mesh=True),
)
BY_NAME = {f.name: f for f in FORMATS}
BY_SUFFIX = {s: f for f in FORMATS for s in f.suffixes}


def _listing(writing: bool) -> str:
    return ", ".join(s for f in FORMATS if writing or f.reads for s in f.suffixes)


def format_for(path: str | os.PathLike[str], given: str | None = None, *,
               writing: bool = False) -> FileFormat:
    """The format of ``path``: ``given`` by name, else by extension.  Reading a name with no
    known extension gives ``json`` here and is decided by content in :func:`read_document`;
    writing one is refused, except ``-`` (standard output), which is JSON.

    Raises
    ------
    FormatChoiceError
        For an unknown format name, an output extension polyloops does not write, or a
        format it does not read.
    """
    name = os.fspath(path)
    if given is not None:
        fmt = BY_NAME.get(given)
        if fmt is None:
            raise FormatChoiceError(f"{name}: unknown format {given!r} (choose from {', '.join(BY_NAME)})")
    else:
        suffix = os.path.splitext(name)[1].lower()
        fmt = BY_SUFFIX.get(suffix)
        if fmt is None:
            if writing and not _is_stream(name):
                shown = f"{suffix} files" if suffix else "files without an extension"
                raise FormatChoiceError(f"{name}: polyloops does not write {shown}; it writes "
                                        f"{_listing(True)}")
            return BY_NAME["json"]
    if not writing and not fmt.reads:
        raise FormatChoiceError(f"{name}: polyloops writes {fmt.name.upper()} but does not read it "
                                f"(it holds triangles); it reads {_listing(False)}")
    return fmt


def _is_stream(name: str) -> bool:
    """Whether an output goes to standard output, a device or a FIFO (written as JSON when its
    name has no extension, like ``/dev/null``)."""
    try:
        return resolve_output(name).sink is not Sink.REPLACE
    except OutputError:
        return False


def sniff(data: bytes) -> FileFormat | None:
    """The format some bytes look like, for names without a known extension; ``None`` when
    they look like none.

    >>> sniff(b'  {"polyloops": 1}').name, sniff(b">>planar_code<<").name, sniff(b"ply\\n").name
    ('json', 'planar', 'ply')
    """
    head = data[:4096].lstrip()
    if head.startswith(b"\xef\xbb\xbf"):
        head = head[3:].lstrip()
    return next((f for f in FORMATS if f.looks is not None and f.looks(head)), None)


def parse_bytes(data: bytes, fmt: FileFormat) -> Document:
    """A document from a file's bytes in format ``fmt``.  Planar code gives a document of kind
    ``map`` (faces only): it has no axis labels, and finding the map's polycube loop structure
    is a search (:func:`polyloops.core.labellings.only_structure_on`).

    Raises
    ------
    FormatError
        For bytes that do not follow the format (the message says where).
    """
    if fmt.reader is None:
        raise FormatError(f"polyloops does not read {fmt.name} files")
    return fmt.reader(data)


class UnknownExampleError(FormatError):
    """``example:NAME`` with a name no bundled example has."""


@dataclass(frozen=True)
class Source:
    """One input, read once: a file (its bytes and format), a bundled example (its JSON), or a
    signature (``sig:NAME``, its document built directly).  :meth:`document` parses it."""

    name: str
    data: bytes
    format: FileFormat
    built: Document | None = None

    def document(self) -> Document:
        """The parsed document (planar code: a ``map`` document, see :func:`parse_bytes`).

        Raises
        ------
        FormatError
            For content that is not in the format (the message does not repeat the name).
        """
        return self.built if self.built is not None else parse_bytes(self.data, self.format)

    def json(self) -> object | None:
        """The parsed JSON of a JSON source, or ``None`` (another format, or not JSON)."""
        import json

        if self.format.name != "json" or self.built is not None:
            return None
        try:
            return json.loads(self.data.decode("utf-8-sig"))
        except (ValueError, RecursionError):
            return None


def open_source(name: str | os.PathLike[str], given: str | None = None) -> Source:
    """Read an input once: ``sig:SIGNATURE``, ``example:NAME``, ``-`` (standard input) or a
    path, its format ``given``, else by extension, else by content (see :func:`sniff`).

    Raises
    ------
    InputError
        When the file cannot be read (not a regular file, too large, missing).
    FormatError
        For a signature that does not decode, an unknown example or format name.
    """
    text = os.fspath(name)
    if text.startswith("sig:"):
        from polyloops.core.canonical import from_signature

        return Source(text, b"", BY_NAME["json"], Document.of(from_signature(text.removeprefix("sig:"))))
    if text.startswith("example:"):
        from polyloops.io.examples import EXAMPLES, example_text

        example = text.removeprefix("example:")
        if example not in EXAMPLES:
            raise UnknownExampleError(f"unknown example {example!r}")
        return Source(text, example_text(example).encode(), BY_NAME["json"])
    return source_of(text, read_bytes(text), given)


def source_of(name: str, data: bytes, given: str | None = None) -> Source:
    """The source of bytes already read from ``name``: format ``given``, else by extension,
    else by content (:func:`sniff`).

    >>> source_of("-", b'{"polyloops": 1}').format.name
    'json'
    """
    fmt = format_for(name, given)
    if given is None and os.path.splitext(name)[1].lower() not in BY_SUFFIX:
        fmt = sniff(data) or fmt
    return Source(name, data, fmt)


MAP_NOTE = "planar code has no axis labels; read the map's only polycube loop structure (up to symmetry)"


def labelled(doc: Document) -> Document:
    """A document with labels: a ``map`` document (planar code) becomes the map's only polycube
    loop structure; any other is returned as it is.

    Raises
    ------
    polyloops.core.labellings.MapStructureError
        When the map carries no polycube loop structure, or several.
    """
    if doc.kind != "map":
        return doc
    from polyloops.core.halfedge import HalfEdgeMap
    from polyloops.core.labellings import only_structure_on

    return Document.of(only_structure_on(HalfEdgeMap.from_faces(doc.faces)), notes=(MAP_NOTE,))


def read_document(path: str | os.PathLike[str], given: str | None = None) -> Document:
    """:func:`open_source` and parse it.

    Raises
    ------
    InputError
        When the file cannot be read (not a regular file, too large, missing).
    FormatError
        For content that is not in the format (the message does not repeat the file name).
    """
    return open_source(path, given).document()


def serialize(obj: Structure, fmt: FileFormat) -> str | bytes:
    """The text or bytes of ``obj`` in a format polyloops writes without meshio."""
    if fmt.writer is None:
        raise FormatError(f"{fmt.name} files are written through meshio")
    return fmt.writer(obj)


def write_structure(obj: Structure, path: str | os.PathLike[str], given: str | None = None) -> FileFormat:
    """Write ``obj`` to ``path`` in the format ``given`` or its extension names, through the
    shared writer; returns the format.

    Raises
    ------
    FormatChoiceError
        For an output extension polyloops does not write, or a loop structure in a format
        that holds polycubes only.
    FormatError
        When the structure cannot be written in that format (a map planar code cannot hold).
    OutputError
        When the output cannot be written.
    """
    name = os.fspath(path)
    fmt = format_for(name, given, writing=True)
    if fmt.writes == "polycube" and not isinstance(obj, Polycube):
        raise FormatChoiceError(f"{name}: only a polycube can be written as {fmt.name.upper()} (make one "
                                "with primalize)")
    if fmt.mesh:
        from polyloops.io.meshes import write_polycube_mesh

        write_polycube_mesh(obj, name, fmt.name)  # type: ignore[arg-type]
        return fmt
    try:
        data = serialize(obj, fmt)
    except FormatError:
        raise
    except ValueError as err:
        raise FormatError(f"{name}: {err}") from None
    write_atomic(name, data)
    return fmt


def read(path: str | os.PathLike[str], format: str | None = None) -> Structure:
    """Read a polycube or loop structure from a file in any format polyloops reads
    (:mod:`polyloops.io.registry`: JSON, DualCube's ``.graph``, OBJ, planar code, PLY, OFF, VTK,
    ...), by ``format``, extension or content.  Planar code, which has no axis labels, gives
    the map's only polycube loop structure.

    Parameters
    ----------
    path:
        The file; ``-`` is standard input.
    format:
        A format name of :data:`polyloops.io.registry.FORMATS` (``json``, ``apg``, ``obj``,
        ``planar``, ``ply``, ...), when the extension does not say it.

    Returns
    -------
    Polycube or LoopStructure

    Raises
    ------
    polyloops.io.files.InputError
        When the file cannot be read.
    polyloops.io.formats.FormatError
        When its content is not in the format (the message names the file).
    polyloops.core.halfedge.MapError
        When the faces do not form a closed oriented surface.

    >>> import tempfile
    >>> from polyloops.core.canonical import signature
    >>> from polyloops.io.examples import load_example
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     write(load_example("l-shape"), os.path.join(tmp, "l.ply"))
    ...     signature(read(os.path.join(tmp, "l.ply"))) == signature(load_example("l-shape"))
    True
    """
    name = os.fspath(path)
    try:
        doc = labelled(read_document(name, format))
    except FormatError as err:
        raise type(err)(f"{name}: {err}") from None
    return doc.build()


def write(obj: Structure, path: str | os.PathLike[str], format: str | None = None) -> None:
    """Write a polycube or loop structure in the format ``format`` or the extension names
    (JSON, ``.graph``, OBJ, planar code, and polycube meshes through meshio: PLY, OFF, VTK,
    VTU, MEDIT, Gmsh, STL), through the shared writer: ``-`` is standard output, a link is
    followed, nothing is left half-written.

    Parameters
    ----------
    obj:
        What to write (the mesh formats and OBJ take polycubes only).
    path:
        The output; ``-`` is standard output (JSON unless ``format`` says otherwise).
    format:
        A format name, when the extension does not say it.

    Returns
    -------
    None

    Raises
    ------
    polyloops.io.registry.FormatChoiceError
        For an extension polyloops does not write, or a loop structure in a mesh format.
    polyloops.io.files.OutputError
        When the output cannot be written.

    >>> from polyloops.io.examples import load_example
    >>> write(load_example("cube"), "-", "apg")  # doctest: +ELLIPSIS
    / written by polyloops: ...
    6 12 8
    ...
    """
    write_structure(obj, path, format)
