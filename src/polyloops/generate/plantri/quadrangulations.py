"""Genus-0 quad meshes from plantri, filtered in batches and decoded.

The quad mesh of a genus-0 polycube is a simple quadrangulation of the sphere with minimum
degree 3, which ``plantri -qc2 N`` generates (one map per isomorphism class, mirror images
identified).  plantri writes *planar code*: per map, the number of vertices and, for each
vertex, its neighbours in clockwise order ending with 0.  For a fixed number of vertices
``n`` every record has ``5n - 7`` bytes, so a batch is a 2D array.

A loop (strip) that crosses itself rules a map out (Condition 3), and almost every
quadrangulation has one, so a batch filter drops those maps (and maps with a corner of degree
above 6) before any per-map work: the compiled extension ``_strips`` when the install built
it, else its numpy twin, which traces the strips of every map of a batch at once.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import sysconfig
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from polyloops.core import compiled
from polyloops.core.errors import PolyloopsError
from polyloops.core.halfedge import HalfEdgeMap, faces_from_next

HEADER = b">>planar_code<<"


class PlantriError(PolyloopsError, RuntimeError):
    """plantri is missing or failed."""


def find_plantri(explicit: str | None = None) -> str:
    """The plantri executable: ``explicit``, ``$POLYLOOPS_PLANTRI``, the one that
    passagemath-plantri installs (``sage_wheels/bin/plantri`` in site-packages), or PATH."""
    for candidate in (explicit, os.environ.get("POLYLOOPS_PLANTRI")):
        if candidate:
            if Path(candidate).is_file() and os.access(candidate, os.X_OK):
                return str(candidate)
            raise PlantriError(f"{candidate}: not an executable plantri")
    roots = {sysconfig.get_paths()["purelib"], sysconfig.get_paths()["platlib"], *sys.path}
    for root in sorted(r for r in roots if r):
        p = Path(root) / "sage_wheels" / "bin" / "plantri"
        if p.is_file() and os.access(p, os.X_OK):
            return str(p)
    found = shutil.which("plantri")
    if found:
        return found
    raise PlantriError("plantri not found: install passagemath-plantri, or set POLYLOOPS_PLANTRI")


def record_size(n: int) -> int:
    """The bytes of one map with ``n`` vertices in plantri's planar code (two-byte form when needed)."""
    return 5 * n - 7


def plantri_batches(n: int, plantri: str, res: int = 0, mod: int = 1,
                    batch: int = 4000) -> Iterator[np.ndarray]:
    """Run ``plantri -qc2 n [res/mod]`` and yield its maps as uint8 arrays of ``batch`` rows."""
    args = [plantri, "-qc2", str(n)] + ([f"{res}/{mod}"] if mod > 1 else [])
    size = record_size(n)
    with subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE) as proc:
        assert proc.stdout is not None
        head = proc.stdout.read(len(HEADER))
        if head != HEADER:  # plantri writes the header even when there are no maps
            proc.kill()
            raise PlantriError(f"{plantri} did not write planar code (is it plantri?): "
                               f"its output began {head[:20]!r}")
        while True:
            chunk = proc.stdout.read(size * batch)
            if not chunk:
                break
            if len(chunk) % size:
                raise PlantriError("plantri output ended inside a map")
            yield np.frombuffer(chunk, dtype=np.uint8).reshape(-1, size)
        err = proc.stderr.read().decode() if proc.stderr else ""
    if proc.returncode:
        raise PlantriError(f"plantri failed ({proc.returncode}): {err.strip()}")


def plantri_count(n: int, plantri: str, res: int = 0, mod: int = 1) -> int:
    """The number of maps plantri reports for ``-qc2 n`` (it generates without writing)."""
    args = [plantri, "-qc2u", str(n)] + ([f"{res}/{mod}"] if mod > 1 else [])
    out = subprocess.run(args, capture_output=True, text=True, check=True).stderr
    for line in out.splitlines():
        words = line.split()
        if len(words) > 1 and words[1].startswith("quadrangulation"):
            return int(words[0])
    raise PlantriError(f"cannot read plantri's count from: {out.strip()}")


class Batch:
    """Darts of a batch of maps with ``n`` vertices: ``origin``, ``target``, ``twin``, face
    successor ``nxt`` and loop label (the least dart of the loop) ``loop``, each ``(B, 2E)``."""

    def __init__(self, rows: np.ndarray):
        n = int(rows[0, 0])
        self.n = n
        e2 = 2 * (2 * n - 4)
        body = rows[:, 1:]
        zero = body == 0
        vert = np.cumsum(zero, axis=1, dtype=np.int32) - zero
        nonzero = ~zero
        b = rows.shape[0]
        self.origin = vert[nonzero].reshape(b, e2)
        self.target = body[nonzero].reshape(b, e2).astype(np.int32) - 1
        pos = np.broadcast_to(np.arange(e2, dtype=np.int32), (b, e2))
        first = np.ones((b, e2), dtype=bool)
        first[:, 1:] = self.origin[:, 1:] != self.origin[:, :-1]
        block_start = np.maximum.accumulate(np.where(first, pos, 0), axis=1)
        last = np.ones((b, e2), dtype=bool)
        last[:, :-1] = first[:, 1:]
        cw_next = np.where(last, block_start, pos + 1)
        index = np.empty((b, n, n), dtype=np.int32)
        rows_ix = np.arange(b)[:, None]
        index[rows_ix, self.origin, self.target] = pos
        self.twin = index[rows_ix, self.target, self.origin]
        # Around a face: from u->v continue with v->w, w the clockwise successor of u at v.
        self.nxt = np.take_along_axis(cw_next, self.twin, axis=1)

    def __len__(self) -> int:
        return self.origin.shape[0]

    def without_self_crossing(self) -> np.ndarray:
        """Boolean mask of the maps none of whose loops crosses itself."""
        take = np.take_along_axis
        e2 = self.origin.shape[1]
        cross = take(self.twin, take(self.nxt, self.nxt, axis=1), axis=1)
        label = np.minimum(np.arange(e2, dtype=np.int32)[None, :], self.twin)
        step = cross
        for _ in range(int(np.ceil(np.log2(e2))) + 1):
            label = np.minimum(label, take(label, step, axis=1))
            step = take(step, step, axis=1)
        # A face is crossed by the loops of its two consecutive darts; equal means self-crossing.
        return ~(label == take(label, self.nxt, axis=1)).any(axis=1)

    def faces(self, i: int) -> list[list[int]]:
        """The faces of map ``i`` as corner lists."""
        return faces_from_next(self.nxt[i], self.origin[i])

    def map(self, i: int) -> HalfEdgeMap:
        """Map ``i`` of the batch as a half-edge map."""
        return HalfEdgeMap.from_faces(self.faces(i))


MAX_DEGREE = 6  # a polycube corner has at most one edge per direction


def max_degrees(rows: np.ndarray) -> np.ndarray:
    """The largest vertex degree of each map of a planar-code batch: every vertex's list of
    neighbours ends with a 0, so degrees are the gaps between consecutive zeros."""
    b, width = rows.shape
    n = int(rows[0, 0])
    body = rows[:, 1:]
    zeros = np.flatnonzero(body.ravel() == 0).reshape(b, n) - (np.arange(b) * (width - 1))[:, None]
    return (np.diff(zeros, axis=1, prepend=-1) - 1).max(axis=1)


def odd_corners_have_no_polycube(n: int) -> bool:
    """Why odd corner counts are skipped.  In a map with no self-crossing loop each face is the
    crossing of two different loops, and two simple closed curves on the sphere cross an even
    number of times (Jordan), so the number of faces is even; a quadrangulation of the sphere has
    ``faces = corners - 2``, so the number of corners is even too.  Returns ``n % 2 == 1``."""
    return n % 2 == 1


METHODS = ("auto", "compiled", "numpy")


def compiled_filter_available() -> bool:
    """Whether the compiled strip filter runs: built (it needs a C compiler) and not switched to
    its numpy twin (:mod:`polyloops.core.compiled`)."""
    return compiled.in_use("strips")


def resolve_method(method: str) -> str:
    """``auto`` is ``compiled`` when that was built, else ``numpy``; asking for ``compiled``
    without it is an error that says how to get it."""
    if method not in METHODS:
        raise ValueError(f"unknown filter method {method!r}: choose one of {', '.join(METHODS)}")
    if method == "auto":
        return "compiled" if compiled_filter_available() else "numpy"
    if method == "compiled" and not compiled_filter_available():
        raise PlantriError(f"the compiled strip filter {compiled.why_not('strips')}: use the numpy "
                           "filter, which keeps the same maps")
    return method


@dataclass(frozen=True)
class FilteredBatch:
    """One batch of plantri's maps after the filter: the surviving planar-code rows, how many
    maps were read and how many of those have only simple strips (whatever their degrees)."""

    rows: np.ndarray
    maps: int
    simple_strips: int


def _filter_numpy(rows: np.ndarray) -> FilteredBatch:
    simple = Batch(rows).without_self_crossing()
    keep = simple & (max_degrees(rows) <= MAX_DEGREE)
    return FilteredBatch(rows[keep], len(rows), int(simple.sum()))


def filtered_batches(n: int, plantri: str, res: int = 0, mod: int = 1,
                     method: str = "auto") -> Iterator[FilteredBatch]:
    """plantri's quadrangulations with ``n`` vertices, filtered batch by batch: a map survives
    when its corners have degree at most 6 (Condition 3 allows one edge per direction) and none
    of its loops crosses itself.  ``method`` picks the compiled filter or its numpy twin; the
    two keep the same maps in the same order (tested)."""
    method = resolve_method(method)
    if method == "numpy":
        for rows in plantri_batches(n, plantri, res, mod):
            yield _filter_numpy(rows)
        return
    filter_maps = compiled.require("strips").filter_maps
    size = record_size(n)
    for rows in plantri_batches(n, plantri, res, mod, batch=1 << 16):
        kept, simple = filter_maps(rows, n, MAX_DEGREE)
        yield FilteredBatch(np.frombuffer(kept, dtype=np.uint8).reshape(-1, size), len(rows), simple)


def candidate_maps(n: int, plantri: str, res: int = 0, mod: int = 1,
                   on_batch: Callable[[FilteredBatch], None] | None = None,
                   method: str = "auto") -> Iterator[HalfEdgeMap]:
    """The maps of :func:`filtered_batches`, decoded.  ``on_batch`` sees every batch (for
    progress and counts)."""
    for fb in filtered_batches(n, plantri, res, mod, method):
        if len(fb.rows):
            batch = Batch(fb.rows)
            for i in range(len(batch)):
                yield batch.map(i)
        if on_batch is not None:
            on_batch(fb)
