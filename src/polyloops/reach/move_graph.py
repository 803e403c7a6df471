"""The move graph of a catalog, class by class: what each removable loop leaves, which classes
lie one addition above, and a way down to the cube.

For every class of a census, each loop whose removal leaves a polycube loop structure is
removed and the result named in the catalog (full symmetry, so each class by its canonical
representative).  Reversed, these are the classes one addition above within the catalog.  The
way down to the cube (:class:`Descent`) takes removals while there are any, and for an
irreducible class the detour its reachability certificate gives (moves through larger
structures to a smaller class; the way leaves the detour at the first catalog class on it
where that saves moves); among such ways it is the one with the fewest moves, ties to the
earlier class in catalog order.  It is a way down, not necessarily a shortest path of the
move graph, which may also climb.  The distance from the cube is the move graph's among the
catalog's classes (breadth first: within the catalog an addition is a removal read
backwards), so a shortest path that stays within the catalog's range of corners; a class
reached only through larger structures has none.

At genus 1 the ways start at the *bases* of the reachability certificate instead, one class
per hole-orientation type (:mod:`polyloops.reach.conjecture`), since no move changes the
type: each class's distance and way down lead to the base of its type.

>>> from polyloops.catalog.census import read_catalog
>>> graph = move_graph(read_catalog().through(16))
>>> [(r.loop, r.axis, r.leaves) for r in graph.removals["P12.1"]]
[(1, 'Y', 'P8.1'), (3, 'Y', 'P8.1')]
>>> graph.above["P8.1"], graph.descents["P16.2"].names, graph.path_from_cube("P16.2")
(('P12.1',), ('P16.2', 'P12.1', 'P8.1'), ('P8.1', 'P12.1', 'P16.2'))
"""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

from polyloops.catalog.census import Census
from polyloops.core.canonical import canonical_form
from polyloops.core.moves import check_removal, remove_loop
from polyloops.core.structure import LoopStructure
from polyloops.reach.search import Move

CERTIFICATE = "reachability-certificate.jsonl"


@dataclass(frozen=True)
class Removal:
    """One removable loop of a class: its id and axis, and the class it leaves (``None`` when
    that class is not in the catalog, which a complete catalog rules out)."""

    loop: int
    axis: str
    leaves: str | None


@dataclass(frozen=True)
class DescentStep:
    """A step of a way down: the move from the step before (``None`` for the first), the
    structure, and its class's name when the catalog has it.  A step of a catalog class holds
    the class's representative (``from_signature``, the numbering its gallery page and viewer
    show), and the next move is in that numbering; the steps of a detour between classes are
    the structures the certificate's moves build, one from the other."""

    move: Move | None
    structure: LoopStructure
    name: str | None


def _named(step: DescentStep) -> tuple[LoopStructure, str | None]:
    return step.structure, step.name


@dataclass(frozen=True)
class Descent:
    """A way from a class down to the cube: removals, and certificate detours where a class
    has no removable loop."""

    steps: tuple[DescentStep, ...]

    @property
    def moves(self) -> int:
        """The number of moves to the cube."""
        return len(self.steps) - 1

    @property
    def names(self) -> tuple[str, ...]:
        """The catalog classes the way passes through, in order."""
        return tuple(s.name for s in self.steps if s.name is not None)


@dataclass(frozen=True)
class MoveGraph:
    """A catalog's removals, the classes one addition above each class, each class's way
    down to the cube (classes without one are absent from ``descents``), and its distance from
    the cube within the catalog (``parent``: the class before it on a shortest path)."""

    removals: dict[str, tuple[Removal, ...]]
    above: dict[str, tuple[str, ...]]
    descents: dict[str, Descent]
    parent: dict[str, str | None]
    bases: tuple[str, ...] = ()  # where the ways start: the cube, or one class a type (genus 1)
    genus: int = 0

    @cached_property
    def distance(self) -> dict[str, int]:
        """Each class's distance from the cube among the catalog's classes (the classes a
        shortest path reaches; the others have none)."""
        return {name: len(self.path_from_cube(name)) - 1 for name in self.parent}

    def path_from_cube(self, name: str) -> tuple[str, ...]:
        """A shortest path of moves from the cube (at genus 1, from the base of the class's
        orientation type) to class ``name`` among the catalog's classes (empty when there is
        none within the catalog's range)."""
        if name not in self.parent:
            return ()
        out = [name]
        while (before := self.parent[out[-1]]) is not None:
            out.append(before)
        return tuple(reversed(out))


def _parents(names: list[str], removals: dict[str, tuple[Removal, ...]],
             bases: tuple[str, ...]) -> dict[str, str | None]:
    """Breadth first from the bases (at genus 0 the cube, the catalog's first class) over the
    catalog's classes, a move an edge: within the catalog, an addition is a removal read
    backwards, so the removals are all the edges.  Neighbours in catalog order, so the paths
    depend on nothing else."""
    import networkx as nx

    if not names or not bases:
        return {}
    order = {n: i for i, n in enumerate(names)}
    g = nx.Graph()
    g.add_nodes_from(names)
    g.add_edges_from((name, r.leaves) for name, found in removals.items() for r in found
                     if r.leaves in order)
    root = object()  # joined to every base: one search from all of them
    g.add_edges_from((root, b) for b in bases)
    order[root] = -1  # type: ignore[index]
    edges = nx.bfs_edges(g, root, sort_neighbors=lambda ns: sorted(ns, key=order.__getitem__))
    return {child: (None if parent is root else parent) for parent, child in edges}


def _bases(census: Census) -> tuple[str, ...]:
    """Where the ways start: the cube at genus 0; at genus 1 the certificate's base records
    (without a certificate, the first class of each orientation type with fewest corners)."""
    entries = list(census)
    if census.genus == 0:
        return tuple(e.name for e in entries if e.corners == 8)
    path = census.directory / CERTIFICATE
    if path.is_file():
        based = {json.loads(line)["signature"] for line in path.read_text(encoding="utf-8").splitlines()[1:]
                 if '"base"' in line}
        return tuple(e.name for e in entries if e.signature in based)
    from polyloops.reach.conjecture import orientation_bases, orientation_type

    types = {e.signature: orientation_type(e.structure()) for e in entries}
    chosen = set(orientation_bases(types, {e.signature: e.corners for e in entries}).values())
    return tuple(e.name for e in entries if e.signature in chosen)


def _detours(census: Census) -> dict[str, list[Move]]:
    """The certificate's detours by class signature (none when the catalog has no certificate)."""
    path = census.directory / CERTIFICATE
    if not path.is_file():
        return {}
    out = {}
    for line in path.read_text(encoding="utf-8").splitlines()[1:]:
        record = json.loads(line)
        if "detour" in record:
            out[record["signature"]] = [Move.from_json(m) for m in record["detour"]["moves"]]
    return out


def _removals_of(signature: str) -> tuple[tuple[int, str, str], ...]:
    """A class's removable loops: (loop, axis, the full signature of what it leaves); a job
    for a worker."""
    from polyloops.core.canonical import from_signature

    ls = from_signature(signature)
    return tuple((lp.id, ls.axes[lp.id].name,
                  canonical_form(remove_loop(ls, lp.id, checked=False), "full").signature)
                 for lp in ls.loops if check_removal(ls, lp.id).valid)


def move_graph(census: Census, progress: Callable[[str], None] | None = None,
               workers: int = 1) -> MoveGraph:
    """The move graph of ``census`` (a catalog in full symmetry); ``progress`` is called with
    each class's name once its removals are known; the removals are worked out in ``workers``
    local processes."""
    from polyloops.parallel import run_jobs

    def named(signature: str) -> str | None:
        entry = census.by_signature.get(signature)
        return entry.name if entry is not None else None

    def name_of(ls: LoopStructure) -> str | None:
        return named(canonical_form(ls, "full").signature)

    structures = {e.name: e.structure() for e in census}
    removals: dict[str, tuple[Removal, ...]] = {}
    entries = list(census)
    batch = max(1, min(64, len(entries) // (8 * workers)))
    results = run_jobs(_removals_of, [e.signature for e in entries], workers, batch=batch)
    for entry, rows in zip(entries, results, strict=True):
        removals[entry.name] = tuple(Removal(loop, axis, named(sig)) for loop, axis, sig in rows)
        if progress is not None:
            progress(entry.name)
    above: dict[str, list[str]] = {e.name: [] for e in census}
    for name, found in removals.items():
        for r in found:
            if r.leaves is not None and name not in above[r.leaves]:
                above[r.leaves].append(name)
    detours = _detours(census)
    bases = _bases(census)
    descents: dict[str, Descent] = {}
    for entry in sorted(census, key=lambda e: e.corners):  # smaller classes first (stable)
        ls = structures[entry.name]
        first = DescentStep(None, ls, entry.name)
        if entry.name in bases:  # the cube, or the base of an orientation type
            descents[entry.name] = Descent((first,))
            continue
        options = []
        for r in removals[entry.name]:
            if r.leaves in descents:
                below = descents[r.leaves]
                # The removal, then the way down from the class it leaves (its representative).
                options.append((1 + below.moves, Move.remove(r.loop), below))
        if options:
            # The removal, then the way down from the class it leaves, whose steps start from
            # that class's own numbering (its representative, as its page shows it).
            _, move, below = min(options, key=lambda o: o[0])
            descents[entry.name] = Descent((first, DescentStep(move, *_named(below.steps[0])),
                                            *below.steps[1:]))
            continue
        moves = detours.get(entry.signature)
        if not moves:
            continue
        steps, current = [first], ls
        for move in moves:
            current = move.apply(current)
            steps.append(DescentStep(move, current, name_of(current)))
        # Leave the detour at a catalog class with a way down (at its end at the latest), where
        # that gives the fewest moves; the way on starts from that class's own numbering.
        cuts = [(k + descents[s.name].moves, k) for k, s in enumerate(steps) if k and s.name in descents]
        if cuts:
            _, k = min(cuts)
            below = descents[steps[k].name]  # type: ignore[index]
            descents[entry.name] = Descent((*steps[:k], DescentStep(steps[k].move, *_named(below.steps[0])),
                                            *below.steps[1:]))
    return MoveGraph(removals, {k: tuple(v) for k, v in above.items()}, descents,
                     _parents([e.name for e in entries], removals, bases), bases, census.genus)
