"""Reading and writing structures: JSON (one structure per file) and Wavefront OBJ.

Polycube::

    {"polyloops": 1, "kind": "polycube",
     "faces": [[0, 1, 2, 3], ...], "positions": [[x, y, z], ...]}

Loop structure (``"+X"`` on ``[u, v, ...]`` means ``v`` lies on the ``+``
side of the X-loop crossing edge ``uv``; ``"X"`` without a sign makes a
labelled structure)::

    {"polyloops": 1, "kind": "loop-structure",
     "faces": [[0, 1, 2, 3], ...], "edges": [[u, v, "+X"], ...]}

Faces are counter-clockwise seen from outside.  Reading checks the format
(:class:`FormatError`); building the model can then fail with
:class:`~polyloops.core.halfedge.MapError` (not a closed oriented surface) or
:class:`~polyloops.core.structure.LabelError`.

>>> from polyloops.io.examples import load_example
>>> text = dumps(load_example("cube"))
>>> loads(text) == load_example("cube")
True
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass
from itertools import chain
from typing import Any

from polyloops.core.arrays import EdgeLabels
from polyloops.core.directions import Axis, Direction
from polyloops.core.errors import PolyloopsError
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure

FORMAT_VERSION = 1
KINDS = ("polycube", "loop-structure")

Structure = Polycube | LoopStructure


class FormatError(PolyloopsError, ValueError):
    """A file that does not follow the polyloops JSON format."""


@dataclass(frozen=True)
class Document:
    """A parsed file, checked against the format but not yet built into a model."""

    kind: str
    faces: list[list[int]]
    positions: list[tuple[int, int, int]] | None = None
    labels: Mapping[tuple[int, int], Direction | Axis] | None = None
    notes: tuple[str, ...] = ()  # what a reader wants its user to know (not errors)

    @classmethod
    def of(cls, obj: Structure, notes: tuple[str, ...] = ()) -> Document:
        """The document of a structure already built (what reading its JSON would give),
        without writing and parsing text.

        >>> from polyloops.io.examples import load_example
        >>> ls = load_example("l-shape").dualize()
        >>> doc = Document.of(ls)
        >>> doc.kind, doc.build().edge_labels() == ls.edge_labels()
        ('loop-structure', True)
        """
        if isinstance(obj, Polycube):
            return cls("polycube", [list(f) for f in obj.faces], [(p[0], p[1], p[2]) for p in obj.positions],
                       notes=notes)
        m = obj.map
        label = obj.direction if obj.oriented else obj.axis_of_dart
        labels = {(m.origin(d), m.target(d)): label(d) for d in m.edge_darts}
        return cls("loop-structure", [list(f) for f in obj.map.faces], labels=labels, notes=notes)

    def build(self) -> Structure:
        """The model; raises ``MapError``, ``LabelError`` or ``FaceListError``."""
        if self.kind == "polycube":
            assert self.positions is not None
            return Polycube.from_faces(self.faces, self.positions)
        assert self.labels is not None
        return LoopStructure.from_edge_labels(self.faces, self.labels)


def _is_int(x: object) -> bool:
    return isinstance(x, int) and not isinstance(x, bool)


def _faces(raw: Any, quads: bool) -> list[list[int]]:
    if not isinstance(raw, list) or not raw:
        raise FormatError('"faces" must be a non-empty list of faces')
    # The common case in one sweep of C loops; the per-face loop names the first bad face.
    if set(map(type, raw)) == {list} and set(map(type, chain.from_iterable(raw))) == {int} \
            and min(chain.from_iterable(raw), default=0) >= 0 and min(map(len, raw)) >= 3 \
            and (not quads or set(map(len, raw)) == {4}):
        return raw
    for f, face in enumerate(raw):
        if not isinstance(face, list) or not all(_is_int(c) and c >= 0 for c in face):
            raise FormatError(f"face {f} must be a list of non-negative integer corner ids")
        if quads and len(face) != 4:
            raise FormatError(f"face {f} has {len(face)} corners; polycube faces are quads")
        if len(face) < 3:
            raise FormatError(f"face {f} has {len(face)} corners; a face needs at least 3")
    return raw


def _positions(raw: Any, n: int) -> list[tuple[int, int, int]]:
    if not isinstance(raw, list):
        raise FormatError('"positions" must be a list of [x, y, z]')
    if len(raw) != n:
        raise FormatError(f'"positions" has {len(raw)} entries but the faces use {n} corners')
    out = []
    for c, p in enumerate(raw):
        if not isinstance(p, list) or len(p) != 3:
            raise FormatError(f"position of corner {c} must be [x, y, z]")
        for x in p:
            if not _is_int(x):
                raise FormatError(f"position of corner {c} has a non-integer coordinate {x!r}")
        out.append((p[0], p[1], p[2]))
    return out


LABELS: dict[str, Direction | Axis] = {**{str(d): d for d in Direction}, **{a.name: a for a in Axis}}


def _label(text: Any, i: int) -> Direction | Axis:
    label = LABELS.get(text) if isinstance(text, str) else None
    if label is None:
        raise FormatError(f"edge {i} has unknown label {text!r} (expected +X -X +Y -Y +Z -Z, or X Y Z)")
    return label


def _labels(raw: Any) -> Mapping[tuple[int, int], Direction | Axis]:
    if not isinstance(raw, list):
        raise FormatError('"edges" must be a list of [u, v, label]')
    fast = _labels_fast(raw)
    if fast is not None:
        return fast
    out: dict[tuple[int, int], Direction | Axis] = {}
    for i, item in enumerate(raw):
        if not (isinstance(item, list) and len(item) == 3 and _is_int(item[0]) and _is_int(item[1])):
            raise FormatError(f"edge {i} must be [u, v, label] with integer corners")
        u, v = item[0], item[1]
        if (u, v) in out or (v, u) in out:
            raise FormatError(f"edge ({u}, {v}) is listed twice")
        out[(u, v)] = _label(item[2], i)
    return out


_CODES = {**{str(d): int(d) for d in Direction}, **{a.name: 6 + int(a) for a in Axis}}


def _labels_fast(raw: list) -> EdgeLabels | None:
    """The labels of a well-formed list in a few sweeps of C loops, or ``None`` (then the
    item-by-item reader finds and names the first problem)."""
    import numpy as np

    if not raw or set(map(type, raw)) != {list} or set(map(len, raw)) != {3}:
        return None
    us, vs, texts = zip(*raw, strict=True)
    if set(map(type, us)) | set(map(type, vs)) != {int} or set(map(type, texts)) != {str}:
        return None
    codes = np.fromiter(map(_CODES.get, texts, [-1] * len(texts)), dtype=np.int64, count=len(texts))
    if codes.min() < 0:
        return None
    u = np.fromiter(us, dtype=np.int64, count=len(us))
    v = np.fromiter(vs, dtype=np.int64, count=len(vs))
    low, high = np.minimum(u, v), np.maximum(u, v)
    if low.min() < 0:
        return None
    keys = np.sort(low * (int(high.max()) + 1) + high)
    if np.any(keys[1:] == keys[:-1]):
        return None  # an edge listed twice, in either direction
    return EdgeLabels(u, v, codes)


def parse_document(text: str) -> Document:
    """Check ``text`` against the format; raise :class:`FormatError` with the reason."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as err:
        raise FormatError(f"not valid JSON: {err.msg} at line {err.lineno} column {err.colno}") from None
    except RecursionError:
        raise FormatError("not a polyloops file: JSON nested too deeply") from None
    if not isinstance(data, dict):
        raise FormatError("the top level must be a JSON object")
    version = data.get("polyloops")
    if not (_is_int(version) and version == FORMAT_VERSION):  # not 1.0, not true
        raise FormatError(f'missing or unsupported "polyloops" version {version!r} '
                          f'(expected the integer {FORMAT_VERSION})')
    kind = data.get("kind")
    if kind not in KINDS:
        raise FormatError(f'"kind" must be "polycube" or "loop-structure", not {kind!r}')
    faces = _faces(data.get("faces"), quads=kind == "polycube")
    if kind == "polycube":
        n = max(c for face in faces for c in face) + 1
        return Document(kind, faces, positions=_positions(data.get("positions"), n))
    return Document(kind, faces, labels=_labels(data.get("edges")))


def loads(text: str) -> Structure:
    """Parse polyloops JSON text and build the polycube or loop structure it describes.

    Parameters
    ----------
    text:
        A polyloops JSON document (see ``docs/formats.md``).

    Returns
    -------
    Polycube or LoopStructure

    Raises
    ------
    FormatError
        When the text is not a polyloops document (the message names the place).
    MapError, LabelError, FaceListError
        When the faces are not a closed oriented surface, or the labels do not fit it.

    >>> from polyloops.io.examples import load_example
    >>> q = load_example("l-shape")
    >>> loads(dumps(q)).positions == q.positions
    True
    """
    return parse_document(text).build()


def to_data(obj: Structure) -> dict[str, Any]:
    """The polyloops JSON document of a structure as Python data (what :func:`dumps` writes)."""
    if isinstance(obj, Polycube):
        return {"polyloops": FORMAT_VERSION, "kind": "polycube",
                "faces": [list(f) for f in obj.faces],
                "positions": [list(p) for p in obj.positions]}
    return {"polyloops": FORMAT_VERSION, "kind": "loop-structure",
            "faces": [list(f) for f in obj.map.faces],
            "edges": [list(e) for e in obj.edge_labels()]}


def dumps(obj: Structure) -> str:
    """Polyloops JSON text: compact, with one face, position or edge per line.

    Parameters
    ----------
    obj:
        A polycube or a loop structure.

    Returns
    -------
    str
        Text that :func:`loads` reads back to an equal structure.

    Notes
    -----
    Nothing is raised for a built structure (every structure has a JSON form).

    >>> from polyloops.io.examples import load_example
    >>> dumps(load_example("cube")).splitlines()[2].strip()
    '"kind": "polycube",'
    """
    data = to_data(obj)
    lines = ["{", f'  "polyloops": {FORMAT_VERSION},', f'  "kind": "{data["kind"]}",']
    keys = [k for k in ("faces", "positions", "edges") if k in data]
    for j, key in enumerate(keys):
        items = ",\n".join("    " + json.dumps(x) for x in data[key])
        lines.append(f'  "{key}": [\n{items}\n  ]' + ("," if j < len(keys) - 1 else ""))
    lines.append("}")
    return "\n".join(lines) + "\n"


def to_obj(q: Polycube) -> str:
    """Wavefront OBJ text: ``v`` lines in corner order, ``f`` lines 1-based, counter-clockwise.

    Parameters
    ----------
    q:
        A polycube.

    Returns
    -------
    str

    Raises
    ------
    AttributeError
        When ``q`` is a loop structure (it has no positions; primalize it first).

    >>> from polyloops.io.examples import load_example
    >>> lines = to_obj(load_example("cube")).splitlines()
    >>> sum(line.startswith("v ") for line in lines), sum(line.startswith("f ") for line in lines)
    (8, 6)
    """
    out = ["# polyloops polycube"]
    out += [f"v {x} {y} {z}" for x, y, z in q.positions]
    out += ["f " + " ".join(str(c + 1) for c in face) for face in q.faces]
    return "\n".join(out) + "\n"
