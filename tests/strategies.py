"""Hypothesis strategies: polycubes (unions of unit cubes), loop structures grown by drawn
loop additions, and perturbed loop structures.

The strategies draw the shape itself, as curver's draw move sequences: every cube added is a
drawn index into the sorted frontier, every frame dimension and every loop addition a drawn
number.  Hypothesis therefore shrinks a failing case towards fewer cubes, smaller indices and
fewer moves, down to a small shape that still fails (``tests/test_strategies.py`` checks that
it does).  ``random_polycube(seed, ...)`` remains for benchmarks and seeded sweeps.
"""

from __future__ import annotations

import random

from hypothesis import assume
from hypothesis import strategies as st

from polyloops.core.directions import Axis, Direction
from polyloops.core.polycube import Polycube
from polyloops.core.structure import LoopStructure
from polyloops.shapes.voxels import Cell, VoxelError, polycube_from_voxels

NEIGHBOURS = [d.vector for d in Direction]


def _critical(cells: set[Cell], c: Cell) -> bool:
    """Whether some 2x2x2 block containing ``c`` is critical (two cubes meeting only at an edge
    or a corner, or the complement of that): sets with no critical block are well-composed and
    their boundary is a polycube without splitting."""
    for ox in (-1, 0):
        for oy in (-1, 0):
            for oz in (-1, 0):
                b = {(i, j, k): (c[0] + ox + i, c[1] + oy + j, c[2] + oz + k) in cells
                     for i in (0, 1) for j in (0, 1) for k in (0, 1)}
                for axis in range(3):
                    for layer in (0, 1):
                        sq = []
                        for u in (0, 1):
                            for v in (0, 1):
                                key = [u, v]
                                key.insert(axis, layer)
                                sq.append(b[(key[0], key[1], key[2])])
                        if sq[0] == sq[3] != sq[1] == sq[2]:
                            return True
                for i, j, k in ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)):
                    a, z = b[(i, j, k)], b[(1 - i, 1 - j, 1 - k)]
                    others = [v for key, v in b.items() if key not in ((i, j, k), (1 - i, 1 - j, 1 - k))]
                    if a == z and all(v != a for v in others):
                        return True
    return False


def well_composed_blob(seed: int, size: int) -> set[Cell]:
    """A random face-connected set of ``size + 1`` cubes with no critical 2x2x2 block."""
    rng = random.Random(seed)
    cells = {(0, 0, 0)}
    while len(cells) <= size:
        frontier = sorted({(c[0] + v[0], c[1] + v[1], c[2] + v[2])
                           for c in cells for v in NEIGHBOURS} - cells)
        rng.shuffle(frontier)
        for c in frontier:
            cells.add(c)
            if not _critical(cells, c):
                break
            cells.discard(c)
        else:
            break
    return cells


def _grow(rng: random.Random, cells: set[Cell], extra: int, allowed=None) -> set[Cell]:
    cells = set(cells)
    for _ in range(extra):
        frontier = sorted({(c[0] + v[0], c[1] + v[1], c[2] + v[2])
                           for c in cells for v in NEIGHBOURS} - cells)
        if allowed is not None:
            frontier = [c for c in frontier if allowed(c, cells)]
        if not frontier:
            break
        cells.add(rng.choice(frontier))
    return cells


def frame_cells(holes: int, w: int, hole: int, height: int) -> set[Cell]:
    """A slab with ``holes`` square holes (side ``hole``) through it, bars ``w`` wide and
    ``height`` thick: genus ``holes``."""
    return {(i, j, k) for i in range(holes * (w + hole) + w) for j in range(2 * w + hole)
            for k in range(height) if not ((i % (w + hole)) >= w and w <= j < w + hole)}


def _frame(rng: random.Random, holes: int) -> set[Cell]:
    return frame_cells(holes, rng.randint(1, 2), rng.randint(1, 2), rng.randint(1, 2))


def random_voxels(seed: int, kind: str, size: int) -> set[Cell]:
    rng = random.Random(seed)
    if kind == "blob":
        return _grow(rng, {(0, 0, 0)}, size)
    if kind == "smooth":
        return well_composed_blob(seed, size)
    holes = {"frame1": 1, "frame2": 2}[kind]
    base = _frame(rng, holes)
    top = max(c[2] for c in base) + 1
    # Cubes stacked on top of the slab: a height field keeps the genus.
    return _grow(rng, base, size, allowed=lambda c, cells: c[2] >= top and (c[0], c[1], c[2] - 1) in cells)


def random_polycube(seed: int, kind: str = "blob", size: int = 6) -> Polycube:
    """A random polycube; shapes whose split boundary is not a polycube are redrawn."""
    for attempt in range(100):
        try:
            return polycube_from_voxels(random_voxels(seed * 101 + attempt, kind, size))
        except VoxelError:
            continue
    raise RuntimeError(f"no {kind} of size {size} from seed {seed} is a polycube in 100 draws")


KINDS = ("blob", "smooth", "frame1", "frame2")


def _frontier(cells: set[Cell], allowed=None) -> list[Cell]:
    out = sorted({(c[0] + v[0], c[1] + v[1], c[2] + v[2]) for c in cells for v in NEIGHBOURS} - cells)
    return out if allowed is None else [c for c in out if allowed(c, cells)]


def grow_by_choices(cells: set[Cell], choices: list[int], smooth: bool = False, allowed=None) -> set[Cell]:
    """Add one cube per choice: the ``choice``-th cube of the sorted frontier (modulo its size);
    with ``smooth``, the first one from there on that keeps the set well-composed."""
    cells = set(cells)
    for choice in choices:
        frontier = _frontier(cells, allowed)
        if not frontier:
            break
        k = choice % len(frontier)
        if not smooth:
            cells.add(frontier[k])
            continue
        for c in frontier[k:] + frontier[:k]:
            cells.add(c)
            if not _critical(cells, c):
                break
            cells.discard(c)
    return cells


@st.composite
def voxel_sets(draw, kinds=KINDS, max_size: int = 10) -> set[Cell]:
    """A drawn set of cubes: a blob (any cubes), a smooth (well-composed) blob, or a frame with
    one or two holes and cubes stacked on it, every cube a drawn choice."""
    kind = draw(st.sampled_from(kinds))
    choices = draw(st.lists(st.integers(0, 10**6), max_size=max_size))
    if kind in ("blob", "smooth"):
        return grow_by_choices({(0, 0, 0)}, choices, smooth=kind == "smooth")
    holes = {"frame1": 1, "frame2": 2}[kind]
    height = draw(st.integers(1, 2))
    base = frame_cells(holes, draw(st.integers(1, 2)), draw(st.integers(1, 2)), height)
    # Cubes stacked on top of the slab: a height field keeps the genus.
    return grow_by_choices(base, choices, allowed=lambda c, cells: c[2] >= height
                           and (c[0], c[1], c[2] - 1) in cells)


@st.composite
def polycubes(draw, kinds=KINDS, max_size: int = 10) -> Polycube:
    """The polycube bounding a drawn set of cubes (:func:`voxel_sets`); a set whose split
    boundary is no polycube (a surface meeting itself badly) is rejected, not redrawn."""
    cells = draw(voxel_sets(kinds, max_size))
    try:
        return polycube_from_voxels(cells)
    except VoxelError:
        assume(False)
        raise


@st.composite
def grown_structures(draw, max_moves: int = 4, start: str = "cube") -> LoopStructure:
    """A polycube loop structure reached from a bundled example by drawn loop additions: each
    move a drawn axis and a drawn index among that axis' first valid additions.  Shrinks
    towards fewer moves and earlier additions."""
    from polyloops.core.moves import add_loop, additions
    from polyloops.io.examples import load_example

    first = load_example(start)
    ls = first.dualize() if isinstance(first, Polycube) else first
    for _ in range(draw(st.integers(0, max_moves))):
        axis = draw(st.sampled_from(list(Axis)))
        found = list(additions(ls, axis, limit=6))
        if found:
            ls = add_loop(ls, found[draw(st.integers(0, len(found) - 1))])
    return ls


def bridged_ring(width: int, depth: int, holes: int, bumps: list[int]) -> set[Cell]:
    """A ring of unit cubes in the plane ``z = 0`` (``holes`` square holes side by side) whose
    bar at ``x = 0`` is lifted to ``z = 1``, leaving a tunnel under it.  The Z-zone at
    ``z = 1`` then runs around the hole and under the bridge: it has a handle (genus 1).
    ``bumps`` pick top faces on which one more cube stands."""
    length = holes * (width - 1) + 1
    cells = {(x, y, 0) for x in range(length) for y in range(depth)
             if x % (width - 1) == 0 or y in (0, depth - 1)}
    for y in range(1, depth - 1):
        cells.discard((0, y, 0))
        cells.add((0, y, 1))
    cells |= {(0, 0, 1), (0, depth - 1, 1)}
    tops = sorted(c for c in cells if (c[0], c[1], c[2] + 1) not in cells)
    for i in bumps:
        c = tops[i % len(tops)]
        cells.add((c[0], c[1], c[2] + 1))
    return cells


def transform_cells(cells: set[Cell], perm: tuple[int, int, int], signs: tuple[int, int, int]) -> set[Cell]:
    """The image of a set of cubes under a signed permutation of the axes."""
    return {tuple(-1 - c[perm[k]] if signs[k] < 0 else c[perm[k]] for k in range(3))  # type: ignore[misc]
            for c in cells}


@st.composite
def handle_zone_polycubes(draw, max_bumps: int = 2) -> Polycube:
    """Polycubes of genus 1 or 2 with a zone of positive genus, in any position in space:
    bridged rings (:func:`bridged_ring`) with drawn sizes, bumps and a signed permutation."""
    size = (draw(st.integers(3, 4)), draw(st.integers(3, 4)), draw(st.integers(1, 2)))
    bumps = draw(st.lists(st.integers(0, 60), max_size=max_bumps))
    perm = draw(st.permutations((0, 1, 2)))
    signs = draw(st.tuples(*[st.sampled_from((1, -1))] * 3))
    try:
        return polycube_from_voxels(transform_cells(bridged_ring(*size, bumps), tuple(perm), signs))
    except VoxelError:  # a bump that makes the surface meet itself: the ring without bumps
        return polycube_from_voxels(transform_cells(bridged_ring(*size, []), tuple(perm), signs))


@st.composite
def perturbed_structures(draw, max_size: int = 8) -> LoopStructure:
    """The loop structure of a random polycube with a few loops flipped or relabelled."""
    ls = draw(polycubes(max_size=max_size)).dualize()
    for _ in range(draw(st.integers(1, 3))):
        loop = draw(st.integers(0, len(ls.loops) - 1))
        if draw(st.booleans()):
            ls = ls.flipped(loop)
        else:
            ls = ls.relabelled(loop, draw(st.sampled_from([a for a in Axis if a != ls.axes[loop]])))
    return ls


def shuffled_document(ls, seed: int) -> dict:
    """A loop structure's JSON document as another program might write it: corners renumbered
    at random, faces and edges in random order, each face from a random corner."""
    rng = random.Random(seed)
    perm = list(range(ls.map.num_corners))
    rng.shuffle(perm)
    faces = []
    for f in ls.map.faces:
        k = rng.randrange(len(f))
        faces.append([perm[c] for c in (*f[k:], *f[:k])])
    rng.shuffle(faces)
    edges = [[perm[u], perm[v], str(lab)] for u, v, lab in ls.edge_labels()]
    rng.shuffle(edges)
    return {"polyloops": 1, "kind": "loop-structure", "faces": faces, "edges": edges}


def renumbered(q: Polycube, rng: random.Random) -> Polycube:
    """The same polycube with shuffled corner ids, faces, face rotations and a translation."""
    n = q.map.num_corners
    perm = list(range(n))
    rng.shuffle(perm)
    faces = []
    for face in q.faces:
        k = rng.randrange(4)
        faces.append([perm[c] for c in face[k:] + face[:k]])
    rng.shuffle(faces)
    shift = [rng.randint(-5, 5) for _ in range(3)]
    positions = list(q.positions)
    for c, p in enumerate(q.positions):
        positions[perm[c]] = (p[0] + shift[0], p[1] + shift[1], p[2] + shift[2])
    return Polycube.from_faces(faces, positions)


def pillar_cells(px: int, py: int, pz: int, bumps: int = 0, seed: int = 0) -> set[Cell]:
    """A thick block joined by pillars to three slabs: ``pz`` pillars up to a slab above,
    ``px`` along X and ``py`` along Y to slabs beside it (genus ``px + py + pz - 3`` when all
    are at least 1).  Each pillar's loop is a free choice that acyclicity restricts, since the
    pillars of one axis join the same two zones.  ``bumps`` unit cubes on the top slab add
    free choices that acyclicity does not restrict."""
    rng = random.Random(seed)
    n = 2 * max(px, py, pz, 1) + 1
    cells = {(x, y, z) for x in range(n) for y in range(n) for z in range(3)}
    spots = [(x, y) for x in range(1, n - 1, 2) for y in range(1, n - 1, 2)]
    for x, y in rng.sample(spots, pz):
        cells.add((x, y, 3))
    if pz:
        cells |= {(x, y, 4) for x in range(n) for y in range(n)}
        tops = [(x, y) for x in range(0, n, 2) for y in range(0, n, 2)]
        for x, y in rng.sample(tops, min(bumps, len(tops))):
            cells.add((x, y, 5))
    for i in range(px):
        cells.add((n, 2 * i + 1, 1))
    if px:
        cells |= {(n + 1, y, z) for y in range(n) for z in range(3)}
    for i in range(py):
        cells.add((2 * i + 1, n, 1))
    if py:
        cells |= {(x, n + 1, z) for x in range(n) for z in range(3)}
    return cells


@st.composite
def labelled_structures(draw) -> LoopStructure:
    """Labelled structures to orient: forgotten sides of random polycubes (genus 0 to 3,
    including pillar shapes where acyclicity bites), and relabelled ones (mostly unsatisfiable)."""
    if draw(st.booleans()):
        q = polycube_from_voxels(pillar_cells(draw(st.integers(0, 2)), draw(st.integers(0, 2)),
                                              draw(st.integers(1, 3)), draw(st.integers(0, 2)),
                                              draw(st.integers(0, 100))))
    else:
        q = draw(polycubes(max_size=8))
    ls = q.dualize()
    if draw(st.integers(0, 3)) == 0:
        loop = draw(st.integers(0, len(ls.loops) - 1))
        ls = ls.relabelled(loop, draw(st.sampled_from([a for a in Axis if a != ls.axes[loop]])))
    return ls.forget_orientation()


@st.composite
def arrangements(draw, max_corners: int = 18, max_loops: int = 6):
    """An arrangement of loops from the canonical construction, drawn as a path down its search
    tree: each step a drawn index among the children (so failures shrink to shallow, early
    arrangements)."""
    from polyloops.generate.loops.arrangements import children

    node = None
    for _ in range(max_loops - 1):
        kids, _stats = children(node, max_corners)
        if not kids or (node is not None and not draw(st.booleans())):
            break
        node = kids[draw(st.integers(0, len(kids) - 1))]
    if node is None:
        node = children(None, max_corners)[0][0]
    return node
