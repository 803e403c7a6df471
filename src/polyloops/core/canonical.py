"""Canonical forms and isomorphism signatures of loop structures.

Two structures are isomorphic when a bijection of darts commutes with ``next`` and ``twin``
and preserves every dart's direction (or axis, for a labelled structure), possibly after
reversing the orientation of one of them: a polycube and its inverse are order-equivalent,
so mirror images of the surface map are identified.  Symmetry modes widen this:
``"labelled"`` (no change of axes), ``"rotation"`` (the 24 rotations act on labels and
sides) and ``"full"`` (all 48 signed permutations).

The canonical form is the lexicographically least code over every root dart, both
orientations and every group element; a code lists, in breadth-first order from the root,
each dart's ``next``, ``twin`` and label.  Roots are restricted to darts with the least local
invariant, which automorphisms preserve, so the number of (element, orientation, root)
triples reaching the least code is the order of the automorphism group.

>>> from polyloops.io.examples import load_example
>>> cube = load_example("cube").dualize()
>>> form = canonical_form(cube, "full")
>>> form.automorphisms, form.achiral  # the 48 symmetries of the cube
(48, True)
>>> is_isomorphic(from_signature(form.signature), cube, "full")
True
"""

from __future__ import annotations

from array import array
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cache, cached_property

import numpy as np

from polyloops.core import compiled
from polyloops.core.arrays import gc_paused, use_arrays
from polyloops.core.directions import Axis, Direction
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import faces_from_next, permutation_orbits
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import SIGNED_PERMUTATIONS, SYMMETRY_MODES, SignedPermutation, Symmetry

MODES = SYMMETRY_MODES
ALPHABET = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_"
_INDEX = {ch: i for i, ch in enumerate(ALPHABET)}
_CHARS = frozenset(ALPHABET)


class SignatureError(PolyloopsError, ValueError):
    """A string that is not a polyloops signature."""


@dataclass(frozen=True)
class CanonicalForm:
    """A structure's canonical code in one symmetry mode, with the size of its automorphism group and,
    in full mode, whether it is achiral."""

    code: tuple[int, ...]
    oriented: bool
    automorphisms: int
    mode: Symmetry
    # Mode "full" only: whether some reflection of space maps the structure to itself
    # (it is then equivalent to its mirror image under rotations); None in other modes.
    achiral: bool | None

    @cached_property
    def signature(self) -> str:
        """The code as a short printable, versioned name (see :func:`signature`)."""
        return _encode(self.code, self.oriented)

    @property
    def structure(self) -> LoopStructure:
        """The class's canonical representative, the structure the code describes."""
        return from_signature(self.signature)


# How each group element acts on direction numbers (0..5) and on axis numbers (0..2).
_ON_DIRECTIONS = {g: tuple(int(g(d)) for d in Direction) for g in SIGNED_PERMUTATIONS}
_ON_AXES = {g: tuple(int(g.axis(a)) for a in Axis) for g in SIGNED_PERMUTATIONS}


def _code(nxt: list[int], twin: list[int], lab: list[int], root: int,
          best: tuple[int, ...] | None) -> tuple[int, ...] | None:
    """The BFS code from ``root``; ``None`` as soon as it is known to exceed ``best``."""
    n = len(nxt)
    index = [-1] * n
    order = [root]
    index[root] = 0
    out: list[int] = []
    equal_so_far = best is not None
    for i in range(n):
        d = order[i]
        for e in (nxt[d], twin[d]):
            if index[e] < 0:
                index[e] = len(order)
                order.append(e)
        item = (index[nxt[d]], index[twin[d]], lab[d])
        if equal_so_far:
            ref = best[3 * i: 3 * i + 3]  # type: ignore[index]
            if item > ref:
                return None
            if item < ref:
                equal_so_far = False
        out.extend(item)
    return tuple(out)


class _Scratch:
    """Index buffers shared by the codes of one canonical form: each code resets only the
    entries it wrote, so a root that loses early costs only what it explored."""

    def __init__(self, n: int):
        self.index = np.full(n, -1, dtype=np.int64)
        self.first_at = np.empty(n, dtype=np.int64)


def _code_arrays(nxt, twin, lab, root: int, best, scratch: _Scratch | None = None) -> np.ndarray | None:
    """:func:`_code` on arrays, one breadth-first level at a time: a level's darts are
    processed in order, so their new neighbours (``next`` before ``twin``) get the next
    indices in order of first occurrence, exactly as a queue would give them; the level's
    items are then compared with ``best`` at once, and ``None`` returned as soon as they
    exceed it."""
    scratch = scratch or _Scratch(len(nxt))
    index, first_at = scratch.index, scratch.first_at
    index[root] = 0
    frontier = np.array([root], dtype=np.int64)
    seen = [frontier]
    size = 1
    chunks = []
    done = 0
    equal_so_far = best is not None
    try:
        while len(frontier):
            children = np.empty(2 * len(frontier), dtype=np.int64)
            children[0::2], children[1::2] = nxt[frontier], twin[frontier]
            fresh = children[index[children] < 0]
            if len(fresh):
                places = np.arange(len(fresh))
                first_at[fresh[::-1]] = places[::-1]  # repeated darts: the earliest place is written last
                new = fresh[first_at[fresh] == places]
                index[new] = np.arange(size, size + len(new))
                seen.append(new)
                size += len(new)
            else:
                new = fresh
            items = np.empty(3 * len(frontier), dtype=np.int64)
            items[0::3], items[1::3], items[2::3] = index[nxt[frontier]], index[twin[frontier]], lab[frontier]
            if equal_so_far:
                ref = best[3 * done: 3 * done + len(items)]
                differ = np.flatnonzero(items != ref)
                if len(differ):
                    if items[differ[0]] > ref[differ[0]]:
                        return None
                    equal_so_far = False
            chunks.append(items)
            done += len(frontier)
            frontier = new
        return np.concatenate(chunks)
    finally:
        index[np.concatenate(seen)] = -1


class _Candidates:
    """The (element, orientation) candidates of a mode, sharing what does not depend on the
    candidate.  A candidate's labels are ``table[base]``; a dart's invariant is
    ``label * big^3 + rest[mirrored]``, with ``rest`` (degrees at both ends, face size) the
    same for every element, so the least invariant and its darts are found per base label,
    at most 2 x 6 arrays, not one full array per candidate; labels are made only for the
    candidates that own a root."""

    def __init__(self, ls: LoopStructure, mode: Symmetry):
        m = ls.map
        a = m.arrays
        n = m.num_darts
        self.twin, nxt, prev = a.twin, a.next, a.prev
        self.succ = (nxt, self.twin[prev[self.twin]])
        self.rotations = (self.twin[prev], nxt[self.twin])
        degree = np.bincount(a.origin, minlength=m.num_corners)[a.origin]
        face_size = np.diff(np.append(a.face_start, n))[a.face_of]
        self.base = ls.direction_codes
        big = int(max(degree.max(), face_size.max())) + 1
        self.rest = tuple((degree * big + degree[self.twin]) * big + fsize
                          for fsize in (face_size, face_size[self.twin]))
        self.darts_of_base = {int(v): np.flatnonzero(self.base == v) for v in np.unique(self.base)}
        self.elements = [(g, np.asarray((_ON_DIRECTIONS if ls.oriented else _ON_AXES)[g], dtype=np.int64))
                         for g in MODES[mode]]
        self._labels: dict[int, np.ndarray] = {}

    def labels(self, i: int) -> np.ndarray:
        if i not in self._labels:
            self._labels[i] = self.elements[i][1][self.base]
        return self._labels[i]

    def roots(self) -> list[tuple[int, bool, np.ndarray]]:
        """(element index, mirrored, darts) with the least invariant over all candidates."""
        least_label = min(int(table[v]) for _, table in self.elements for v in self.darts_of_base)
        found: list[tuple[int, bool, np.ndarray]] = []
        least_rest = None
        for i, (_g, table) in enumerate(self.elements):
            # a signed permutation is one-to-one on labels: at most one base label maps there
            v = next((v for v in self.darts_of_base if table[v] == least_label), None)
            if v is None:
                continue
            darts = self.darts_of_base[v]
            for mirrored in (False, True):
                rest = self.rest[mirrored][darts]
                low = int(rest.min())
                if least_rest is None or low < least_rest:
                    least_rest, found = low, []
                if low == least_rest:
                    found.append((i, mirrored, darts[rest == low]))
        return found


PREFIX = 4096  # code items a root is followed item by item before the array code takes over


def _code_prefix(succ, twin, lab, root: int, best: list[int] | None) -> list[int] | None:
    """The first :data:`PREFIX` items of the code from ``root``, flattened, or ``None`` as
    soon as they exceed ``best`` (a dictionary of indices, so a root that loses early costs
    only what it visits)."""
    index = {root: 0}
    order = [root]
    out: list[int] = []
    equal_so_far = best is not None
    for i in range(min(PREFIX, len(succ))):
        if i >= len(order):
            break
        d = order[i]
        for e in (succ[d], twin[d]):
            if e not in index:
                index[e] = len(order)
                order.append(e)
        item = [index[succ[d]], index[twin[d]], int(lab[d])]
        if equal_so_far:
            ref = best[3 * i: 3 * i + 3]  # type: ignore[index]
            if item > ref:
                return None
            if item < ref:
                equal_so_far = False
        out += item
    return out


@gc_paused
def _canonical_form_arrays(ls: LoopStructure, mode: Symmetry) -> CanonicalForm:
    """:func:`canonical_form` for large maps: the same roots and codes, found with arrays.

    Invariants are computed for every dart at once; the labels around both ends of the
    candidate roots are compared as rows of a matrix; each root's code is followed in
    Python while it may lose early, then built a breadth-first level at a time."""
    cands = _Candidates(ls, mode)
    twin = cands.twin
    rows, owners = [], []
    for i, mirrored, roots in cands.roots():
        lab = cands.labels(i)
        rot = cands.rotations[mirrored]
        cols = []
        for start in (roots, twin[roots]):
            e = start
            while True:  # every root has the same degree at each end (part of the invariant)
                cols.append(lab[e])
                e = rot[e]
                if np.array_equal(e, start):
                    break
        rows.append(np.stack(cols, axis=1))
        owners.append(np.stack([np.full(len(roots), 2 * i + mirrored), roots], axis=1))
    keys = np.concatenate(rows)
    who = np.concatenate(owners)
    keep = np.ones(len(keys), dtype=bool)
    for col in range(keys.shape[1]):  # the lexicographically least rows
        column = keys[:, col]
        keep &= column == column[keep].min()
    chosen = who[keep].tolist()
    # Following many roots item by item is cheaper on lists than on array scalars.
    many = Counter(k for k, _ in chosen)
    lists: dict[object, list[int]] = {}

    def listed(key: object, array: np.ndarray, k: int):
        if many[k] < 64:
            return array
        if key not in lists:
            lists[key] = array.tolist()
        return lists[key]

    # A tournament on code prefixes first, so that full codes are built only for the roots
    # tied on the least prefix.
    least_prefix: list[int] | None = None
    tied: list[tuple[int, int]] = []
    for k, root in chosen:
        i, side = divmod(k, 2)
        mirrored = bool(side)
        succ, lab = cands.succ[mirrored], cands.labels(i)
        args = (listed(("succ", mirrored), succ, k), listed("twin", twin, k), listed(("lab", i), lab, k))
        prefix = _code_prefix(*args, root, least_prefix)
        if prefix is None:
            continue
        if least_prefix is None or prefix < least_prefix:
            least_prefix, tied = prefix, [(k, root)]
        else:
            tied.append((k, root))
    best = None
    hits: list[tuple[SignedPermutation, bool]] = []
    scratch = _Scratch(len(twin))
    for k, root in tied:
        i, side = divmod(k, 2)
        mirrored = bool(side)
        g = cands.elements[i][0]
        code = _code_arrays(cands.succ[mirrored], twin, cands.labels(i), root, best, scratch)
        if code is None:
            continue
        if best is None or _less(code, best):
            best, hits = code, [(g, bool(mirrored))]
        elif np.array_equal(code, best):
            hits.append((g, bool(mirrored)))
    assert best is not None
    achiral = len({g.det for g, _ in hits}) == 2 if mode == "full" else None
    return CanonicalForm(tuple(best.tolist()), ls.oriented, len(hits), mode, achiral)


def _less(a: np.ndarray, b: np.ndarray) -> bool:
    differ = np.flatnonzero(a != b)
    return bool(len(differ)) and a[differ[0]] < b[differ[0]]


def canonical_form(obj: LoopStructure | Polycube, mode: Symmetry | str = Symmetry.FULL) -> CanonicalForm:
    """The canonical form of a structure: a code equal exactly for isomorphic structures in a
    symmetry mode, with the size of its automorphism group (a polycube is dualized first).

    Parameters
    ----------
    obj:
        A polycube or a loop structure (oriented or labelled).
    mode:
        A :class:`~polyloops.core.symmetry.Symmetry` or its name: ``labelled`` (renumbering only,
        order-equivalence), ``rotation`` (24 rotations) or ``full`` (48 signed permutations).

    Returns
    -------
    CanonicalForm
        Its ``signature`` names the class; ``automorphisms`` counts the symmetries; ``achiral``
        (full mode) says whether a reflection maps the structure to itself up to rotation.

    Raises
    ------
    ValueError
        For an unknown mode.
    DualityError
        When a polycube's faces are not axis-aligned rectangles.

    >>> from polyloops.io.examples import load_example
    >>> form = canonical_form(load_example("cube"), "full")
    >>> form.automorphisms, form.achiral
    (48, True)
    """
    mode = Symmetry.parse(mode)
    ls = obj.dualize() if isinstance(obj, Polycube) else obj
    m = ls.map
    if use_arrays(m.num_darts):
        return _canonical_form_arrays(ls, mode)
    if compiled.in_use("canonical"):  # the compiled twin of the tuple code (the switchboard's)
        return _canonical_form_compiled(ls, mode)
    nxt = list(m.next)
    twin = list(m.twin)
    n = m.num_darts
    mirror_next = [m.twin[m.prev[m.twin[d]]] for d in range(n)]
    # Turning around a corner: counter-clockwise in the map, the other way in its mirror.
    rotations = ([m.twin[m.prev[d]] for d in range(n)], [m.next[m.twin[d]] for d in range(n)])
    degree = [m.degree(m.origin(d)) for d in range(n)]
    face_size = [len(m.faces[m.face_of[d]]) for d in range(n)]
    candidates = []
    base = ls.direction_code_list
    for g in MODES[mode]:
        table = (_ON_DIRECTIONS if ls.oriented else _ON_AXES)[g]
        lab = [table[x] for x in base]
        for mirrored, succ in ((False, nxt), (True, mirror_next)):
            fsize = face_size if not mirrored else [face_size[twin[d]] for d in range(n)]
            inv = [(lab[d], degree[d], degree[twin[d]], fsize[d]) for d in range(n)]
            candidates.append((g, mirrored, succ, lab, inv))
    least = min(min(c[4]) for c in candidates)

    def around(lab: list[int], rot: list[int], d: int) -> tuple[int, ...]:
        out, e = [lab[d]], rot[d]
        while e != d:
            out.append(lab[e])
            e = rot[e]
        return tuple(out)

    # Refine the roots with the least invariant by the labels around both ends of the dart.
    roots = []
    for g, mirrored, succ, lab, inv in candidates:
        rot = rotations[mirrored]
        for r in range(n):
            if inv[r] == least:
                roots.append(((around(lab, rot, r), around(lab, rot, twin[r])), g, mirrored, succ, lab, r))
    key = min(item[0] for item in roots)
    best: tuple[int, ...] | None = None
    hits: list[tuple[SignedPermutation, bool]] = []
    for k, g, mirrored, succ, lab, root in roots:
        if k != key:
            continue
        code = _code(succ, twin, lab, root, best)
        if code is None:
            continue
        if best is None or code < best:
            best, hits = code, [(g, mirrored)]
        elif code == best:
            hits.append((g, mirrored))
    assert best is not None
    # The hits are a coset h * Aut of the automorphism group; the structure is achiral when
    # Aut holds a reflection, that is, when the hits have both determinants.  (Testing for one
    # hit with det < 0 would ask about h, which depends on the input's position.)
    achiral = len({g.det for g, _ in hits}) == 2 if mode == "full" else None
    return CanonicalForm(best, ls.oriented, len(hits), mode, achiral)


@cache
def _group_tables(mode: Symmetry, oriented: bool) -> tuple[bytes, bytes]:
    """The elements of a mode for the compiled code: their actions on labels (six int32 each;
    axes use the first three) and their determinants."""
    tables, dets = array("i"), array("i")
    for g in MODES[mode]:
        row = (_ON_DIRECTIONS if oriented else _ON_AXES)[g]
        tables.extend(list(row) + [0] * (6 - len(row)))
        dets.append(g.det)
    return tables.tobytes(), dets.tobytes()


def _canonical_form_compiled(ls: LoopStructure, mode: Symmetry) -> CanonicalForm:
    """:func:`canonical_form`'s tuple code, compiled (``_canonical.c``): the same roots,
    codes and counts."""
    m = ls.map
    tables, dets = _group_tables(mode, ls.oriented)
    code, hits, dets_hit = compiled.require("canonical").canonical(
        array("i", m.next).tobytes(), array("i", m.twin).tobytes(), array("i", m.prev).tobytes(),
        array("i", ls.direction_code_list).tobytes(), tables, dets)
    achiral = dets_hit == 3 if mode == "full" else None
    return CanonicalForm(tuple(array("i", code)), ls.oriented, hits, mode, achiral)


def signature(obj: LoopStructure | Polycube, mode: Symmetry | str = Symmetry.FULL) -> str:
    """A short printable name of a structure's class: equal exactly for isomorphic structures in
    that mode.  ``sig:NAME`` reads it back anywhere the command line takes a FILE.

    Parameters
    ----------
    obj:
        A polycube or a loop structure.
    mode:
        ``labelled``, ``rotation`` or ``full`` (the default), as in :func:`canonical_form`.

    Returns
    -------
    str
        Versioned: a leading ``1`` names the encoding.

    Raises
    ------
    ValueError
        For an unknown mode.

    >>> from polyloops.io.examples import load_example
    >>> q = load_example("l-shape")
    >>> signature(q) == signature(q.inverse()), signature(q).startswith("1o")
    (True, True)
    """
    return canonical_form(obj, mode).signature


def is_isomorphic(a: LoopStructure | Polycube, b: LoopStructure | Polycube,
                  mode: Symmetry | str = Symmetry.FULL) -> bool:
    """Whether two structures are isomorphic in a symmetry mode; the default is
    :func:`signature`'s, so that ``is_isomorphic(a, b)`` says ``signature(a) == signature(b)``.

    Parameters
    ----------
    a, b:
        Polycubes or loop structures.
    mode:
        ``labelled``, ``rotation`` or ``full`` (the default).

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        For an unknown mode.

    >>> from polyloops.io.examples import load_example
    >>> l_shape = load_example("l-shape")
    >>> is_isomorphic(l_shape, l_shape.inverse()), is_isomorphic(l_shape, load_example("cube"))
    (True, False)
    """
    return canonical_form(a, mode).code == canonical_form(b, mode).code


# -- encoding --------------------------------------------------------------------------------
# A signature (version 1) is: the version "1"; "o" (oriented) or "l" (labelled); one character
# for the digit width w; the number of darts in w base-64 digits; then per dart one character
# holding its label and whether its next and twin are new darts in BFS order, followed by w
# digits for each of next and twin that is not new; then two check characters.  The check is
# sum((i mod 4092 + 1) * value(char_i)) mod 4093 over every character before it: 4093 is prime
# and exceeds every difference of two values times any weight, so changing any one character,
# or swapping two neighbours, always changes it.  Signatures of polyloops 0.1 had no version
# and no check (they start with "o" or "l") and are refused by name.

SIGNATURE_VERSION = "1"
_CHECK_MODULUS = 4093
_MAX_WIDTH = 5  # 64**5 darts: far beyond any structure a signature is read for


def _check(text: str) -> str:
    total = sum((i % (_CHECK_MODULUS - 1) + 1) * _INDEX[ch] for i, ch in enumerate(text))
    return _digits(total % _CHECK_MODULUS, 2)


def _digits(x: int, w: int) -> str:
    out = []
    for _ in range(w):
        out.append(ALPHABET[x & 63])
        x >>= 6
    return "".join(reversed(out))


def _encode(code: tuple[int, ...], oriented: bool) -> str:
    n = len(code) // 3
    w = 1
    while 64 ** w <= n:
        w += 1
    if use_arrays(n):
        return _encode_arrays(np.fromiter(code, dtype=np.int64, count=len(code)), oriented, w)
    part = compiled.load("canonical")
    if part is not None:
        return part.encode(array("i", code).tobytes(), oriented)
    parts = [SIGNATURE_VERSION, "o" if oriented else "l", ALPHABET[w], _digits(n, w)]
    seen = 1  # darts discovered so far: the root
    for i in range(n):
        nx_, tw, lab = code[3 * i: 3 * i + 3]
        flags = 0
        refs = []
        for bit, ref in ((1, nx_), (2, tw)):
            if ref == seen:
                flags |= bit
                seen += 1
            else:
                refs.append(ref)
        parts.append(ALPHABET[lab * 4 + flags])
        parts.extend(_digits(r, w) for r in refs)
    body = "".join(parts)
    return body + _check(body)


_ALPHABET_BYTES = np.frombuffer(ALPHABET.encode("ascii"), dtype=np.uint8)
_VALUE_OF_BYTE = np.zeros(256, dtype=np.int64)
_VALUE_OF_BYTE[_ALPHABET_BYTES] = np.arange(64)


def _encode_arrays(code: np.ndarray, oriented: bool, w: int) -> str:
    """:func:`_encode` on arrays.  A reference is written as a flag exactly when it is the
    next new index, that is, when it exceeds every reference before it (indices are handed
    out in order), so the flags are a running maximum; every item then takes one character
    and ``w`` per reference that is not new, placed at offsets from a cumulative sum."""
    n = len(code) // 3
    refs = np.empty(2 * n, dtype=np.int64)
    refs[0::2], refs[1::2] = code[0::3], code[1::3]
    before = np.maximum.accumulate(np.concatenate([[0], refs[:-1]]))
    new = refs > before
    flags = new[0::2] * 1 + new[1::2] * 2
    written = (~new).reshape(n, 2)
    width = 1 + w * written.sum(axis=1)
    start = np.concatenate([[0], np.cumsum(width)[:-1]])
    body = np.empty(int(width.sum()), dtype=np.uint8)
    body[start] = _ALPHABET_BYTES[code[2::3] * 4 + flags]
    for k in range(2):  # the next reference, then the twin, each after what precedes it
        at = start + 1 + (w * written[:, 0] if k == 1 else 0)
        rows = np.flatnonzero(written[:, k])
        values = refs[2 * rows + k]
        for j in range(w):  # most significant digit first
            body[at[rows] + j] = _ALPHABET_BYTES[(values >> (6 * (w - 1 - j))) & 63]
    head = SIGNATURE_VERSION + ("o" if oriented else "l") + ALPHABET[w] + _digits(n, w)
    text = head + body.tobytes().decode("ascii")
    return text + _check_arrays(text)


def _check_arrays(text: str) -> str:
    """:func:`_check` on arrays."""
    values = _VALUE_OF_BYTE[np.frombuffer(text.encode("ascii"), dtype=np.uint8)]
    weights = np.arange(len(values), dtype=np.int64) % (_CHECK_MODULUS - 1) + 1
    return _digits(int((weights * values).sum() % _CHECK_MODULUS), 2)


def _unwrap(sig: str) -> str:
    """The signature without its version and check, after testing both."""
    if not sig:
        raise SignatureError("an empty signature")
    if sig[0] in "ol":
        raise SignatureError("an unversioned signature of polyloops 0.1 (no check characters); "
                             "compute it again from the structure")
    if sig[0] != SIGNATURE_VERSION:
        raise SignatureError(f"signature version {sig[0]!r} is not one this polyloops reads "
                             f"(version {SIGNATURE_VERSION})")
    if any(ch not in _INDEX for ch in sig):
        bad = next(ch for ch in sig if ch not in _INDEX)
        raise SignatureError(f"a signature has no character {bad!r}")
    if len(sig) < 6 or _check(sig[:-2]) != sig[-2:]:
        raise SignatureError("the check characters do not match: the signature was changed or cut")
    return sig[1:-2]


def signature_darts(sig: str) -> int:
    """The number of darts of the map a signature names, read from its head after its version
    and check characters are tested (the checks run on arrays: a catalog's thousands of
    signatures are read in a fraction of a second).  A loop structure's map is made of quads,
    so it has ``darts / 4`` faces and ``darts / 4 + 2 - 2g`` corners at genus ``g``.

    >>> from polyloops.io.examples import load_example
    >>> signature_darts(signature(load_example("cube")))
    24

    Raises
    ------
    SignatureError
        When the text is not a signature of a version this polyloops reads.
    """
    if not sig or not sig.isascii():
        raise SignatureError("not a polyloops signature")
    if sig[0] in "ol":
        _unwrap(sig)  # refused by name
    if sig[0] != SIGNATURE_VERSION:
        raise SignatureError(f"signature version {sig[0]!r} is not one this polyloops reads "
                             f"(version {SIGNATURE_VERSION})")
    if not _CHARS.issuperset(sig):
        bad = next(ch for ch in sig if ch not in _INDEX)
        raise SignatureError(f"a signature has no character {bad!r}")
    if len(sig) < 6 or _check_arrays(sig[:-2]) != sig[-2:]:
        raise SignatureError("the check characters do not match: the signature was changed or cut")
    return _head_darts(sig)


def _head_darts(sig: str) -> int:
    """The number of darts a checked signature's head states."""
    if sig[1] not in "ol":
        raise SignatureError("a signature's kind is 'o' or 'l'")
    w = _INDEX[sig[2]]
    if not 1 <= w <= _MAX_WIDTH or len(sig) < 3 + w + 2:
        raise SignatureError("not a polyloops signature")
    n = 0
    for ch in sig[3:3 + w]:
        n = n * 64 + _INDEX[ch]
    return n


def signatures_darts(sigs: Sequence[str]) -> list[int]:
    """:func:`signature_darts` of many signatures at once: their check characters are summed
    in one pass over a few thousand signatures' characters at a time (a catalog of tens of
    thousands reads several times faster than one by one); a signature that fails is read again
    alone, for its own error.

    >>> from polyloops.io.examples import load_example
    >>> signatures_darts([signature(load_example(n)) for n in ("cube", "l-shape")])
    [24, 56]

    Raises
    ------
    SignatureError
        As :func:`signature_darts`, for the first signature that is not one.
    """
    fine: list[bool] = []
    for k in range(0, len(sigs), _BATCH):
        fine += _checks_hold(sigs[k:k + _BATCH])
    # a failure is read alone, which raises its reason
    return [_head_darts(sig) if ok else signature_darts(sig) for sig, ok in zip(sigs, fine, strict=True)]


_BATCH = 4096  # signatures checked together: a few megabytes of arrays
_KNOWN_BYTE = np.zeros(256, dtype=bool)
_KNOWN_BYTE[_ALPHABET_BYTES] = True


def _checks_hold(sigs: Sequence[str]) -> list[bool]:
    """Per signature, whether it is ASCII of the alphabet, of this version, at least six
    characters long and shorter than the check's period, and its check characters match.
    With ``p`` a character's place in its signature from ``s`` (its first place overall) and
    ``g = s + p`` its place overall, the check's sum of ``(p + 1) * value`` over the body is
    ``sum(g * value) - (s - 1) * sum(value)``: two sums per signature (exact in float64)."""
    joined = "".join(sigs)
    lengths = np.fromiter(map(len, sigs), dtype=np.int64, count=len(sigs))
    if not sigs or not joined.isascii() or lengths.min() < 6 or lengths.max() >= _CHECK_MODULUS - 1:
        return [False] * len(sigs)  # each read alone
    raw = np.frombuffer(joined.encode("ascii"), dtype=np.uint8)
    starts = np.concatenate([[0], np.cumsum(lengths)[:-1]])
    value = _VALUE_OF_BYTE[raw].astype(np.float64)
    checks = starts + lengths - 2  # the two check characters are no part of the body
    value_body = value.copy()
    value_body[checks] = 0.0
    value_body[checks + 1] = 0.0
    by_place = np.add.reduceat(value_body * np.arange(len(raw), dtype=np.float64), starts)
    total = (by_place - (starts - 1) * np.add.reduceat(value_body, starts)).astype(np.int64) % _CHECK_MODULUS
    stated = _VALUE_OF_BYTE[raw[checks]] * 64 + _VALUE_OF_BYTE[raw[checks + 1]]
    known = np.logical_and.reduceat(_KNOWN_BYTE[raw], starts)
    return ((total == stated) & known & (raw[starts] == ord(SIGNATURE_VERSION))).tolist()


def _decode(sig: str) -> tuple[list[int], list[int], list[int], bool]:
    sig = _unwrap(sig)
    try:
        if sig[0] not in "ol":
            raise SignatureError("a signature's kind is 'o' or 'l'")
        oriented = sig[0] == "o"
        w = _INDEX[sig[1]]
        if not 1 <= w <= _MAX_WIDTH:
            raise SignatureError(f"a digit width of {w} is out of range")
        pos = 2

        def read(k: int) -> int:
            nonlocal pos
            chunk = sig[pos: pos + k]
            if len(chunk) != k:
                raise SignatureError("the signature ends too early")
            pos += k
            x = 0
            for ch in chunk:
                x = x * 64 + _INDEX[ch]
            return x

        n = read(w)
        if n > len(sig) - pos:  # each dart takes at least one character
            raise SignatureError(f"the signature is too short for {n} darts")
        nxt, twin, lab = [0] * n, [0] * n, [0] * n
        seen = 1
        for i in range(n):
            sym = _INDEX[sig[pos]]
            pos += 1
            lab[i], flags = divmod(sym, 4)
            for bit, target in ((1, nxt), (2, twin)):
                if flags & bit:
                    target[i] = seen
                    seen += 1
                else:
                    target[i] = read(w)
        if pos != len(sig):
            raise SignatureError("unexpected characters after the signature")
    except (KeyError, IndexError):
        raise SignatureError("not a polyloops signature") from None
    return nxt, twin, lab, oriented


def from_signature(sig: str, *, checked: bool = True) -> LoopStructure:
    """The structure a signature names: its class's canonical representative.

    Parameters
    ----------
    sig:
        A signature from :func:`signature` (surrounding white space is ignored).
    checked:
        Check that the code describes a loop structure (the default).  The reachability
        search names its states by signatures it made itself, and passes ``False``: the
        version and check characters are still tested, the map and its labels are not.

    Returns
    -------
    LoopStructure
        Oriented or labelled, as the signature says.

    Raises
    ------
    SignatureError
        When the text is not a signature of a version this polyloops reads (older or unknown
        versions are refused by name, not mis-read).

    >>> from polyloops.io.examples import load_example
    >>> sig = signature(load_example("ring"))
    >>> signature(from_signature(sig)) == sig
    True
    """
    nxt, twin, lab, oriented = _decode(sig.strip())
    n = len(nxt)
    if not checked and oriented:
        return _trusted_structure(nxt, twin, lab)
    if sorted(nxt) != list(range(n)) or any(twin[twin[d]] != d or twin[d] == d for d in range(n)):
        raise SignatureError("the signature does not describe a map")
    corner = _corners(nxt, twin)
    faces = faces_from_next(nxt, corner)
    labels: dict[tuple[int, int], Direction | Axis] = {}
    for d in range(n):
        u, v = corner[d], corner[nxt[d]]
        if (v, u) not in labels:
            if not 0 <= lab[d] < (6 if oriented else 3):
                raise SignatureError("the signature has an unknown label")
            labels[(u, v)] = Direction(lab[d]) if oriented else Axis(lab[d])
    try:
        return LoopStructure.from_edge_labels(faces, labels)
    except ValueError as err:
        raise SignatureError(f"the signature does not describe a loop structure: {err}") from None


def _corners(nxt: list[int], twin: list[int]) -> list[int]:
    """Each dart's corner: the orbits of rotate(d) = twin(prev(d)), numbered by their lowest dart."""
    n = len(nxt)
    prev = [0] * n
    for d, e in enumerate(nxt):
        prev[e] = d
    corner = [0] * n
    for k, orbit in enumerate(permutation_orbits([twin[prev[d]] for d in range(n)])):
        for d in orbit:
            corner[d] = k
    return corner


def _trusted_structure(nxt: list[int], twin: list[int], lab: list[int]) -> LoopStructure:
    """The oriented structure of a canonical code known to be one (see :func:`from_signature`)."""
    n = len(nxt)
    corner = _corners(nxt, twin)
    members = tuple(Direction)
    labels = {(corner[d], corner[nxt[d]]): members[lab[d]] for d in range(n)}
    return LoopStructure.from_trusted_edge_labels(faces_from_next(nxt, corner), labels)


def transformed(obj: LoopStructure | Polycube, g: SignedPermutation) -> LoopStructure:
    """The image of a structure under a signed permutation of the axes: every direction is
    mapped by ``g``; a reflection also reverses the faces, as a mirror in space does."""
    ls = obj.dualize() if isinstance(obj, Polycube) else obj
    m = ls.map
    faces = [tuple(reversed(f)) for f in m.faces] if g.det < 0 else m.faces
    labels: dict[tuple[int, int], Direction | Axis] = {}
    for d in m.edge_darts:
        key = (m.origin(d), m.target(d))
        labels[key] = g(ls.direction(d)) if ls.oriented else g.axis(ls.axis_of_dart(d))
    return LoopStructure.from_edge_labels(faces, labels)
