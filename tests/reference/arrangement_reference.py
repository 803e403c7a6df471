"""The slow obvious twin of the compiled arrangement search, for the tests.

It shares no code with ``_arrangements.c``: curves are drawn on a copy of the map at every step,
children are kept whatever loop was added (no canonical construction), every level is
deduplicated with a canonical code that tries every root (no invariant to choose roots), and the
only cut is the counting bound on each finished arrangement.  So it lists every connected
arrangement of simple loops that passes the bound: the same set of arrangements the compiled
search visits.
"""

from __future__ import annotations


def need(sides: int) -> int:
    """Crossings a region of ``sides`` sides still needs to end with pieces of 3 to 6 sides."""
    if sides > 6:
        return (sides - 5) // 2
    return max(0, 3 - sides)


def canonical_code(rot: list[int], twin: list[int]) -> tuple[int, ...]:
    """The least breadth-first code over every root dart and both orientations."""
    n = len(rot)
    irot = [0] * n
    for d in range(n):
        irot[rot[d]] = d
    best: tuple[int, ...] | None = None
    for turn in (rot, irot):
        for root in range(n):
            num = [-1] * n
            order: list[int] = []

            def visit(t: int, turn: list[int] = turn, num: list[int] = num, order: list[int] = order) -> None:
                for _ in range(4):
                    num[t] = len(order)
                    order.append(t)
                    t = turn[t]

            visit(root)
            code = []
            for i in range(n):
                t = twin[order[i]]
                if num[t] < 0:
                    visit(t)
                code.append(num[t])
            if best is None or tuple(code) < best:
                best = tuple(code)
    assert best is not None
    return best


def faces(rot: list[int], twin: list[int]) -> list[list[int]]:
    n = len(rot)
    irot = [0] * n
    for d in range(n):
        irot[rot[d]] = d
    seen, out = set(), []
    for d in range(n):
        if d in seen:
            continue
        face, e = [], d
        while e not in seen:
            seen.add(e)
            face.append(e)
            e = irot[twin[e]]
        out.append(face)
    return out


def bound(rot: list[int], twin: list[int]) -> int:
    return len(rot) // 4 + sum(need(len(f)) for f in faces(rot, twin))


def is_candidate(rot: list[int], twin: list[int]) -> bool:
    fs = faces(rot, twin)
    where = {d: i for i, f in enumerate(fs) for d in f}
    if any(not 3 <= len(f) <= 6 for f in fs):
        return False
    pairs = [(where[d], where[twin[d]]) for d in range(len(rot))]
    return all(a != b for a, b in pairs) and len(set(pairs)) == len(pairs)


def _drop_markers(rot: list[int], twin: list[int], org: list[int]) -> tuple[list[int], list[int]]:
    n = len(rot)
    degree: dict[int, int] = {}
    for v in org:
        degree[v] = degree.get(v, 0) + 1
    twin = list(twin)
    dead = set()
    for d in range(n):
        if degree[org[d]] == 2 and d not in dead:
            b = rot[d]
            twin[twin[d]], twin[twin[b]] = twin[b], twin[d]
            dead.update((d, b))
    keep = [d for d in range(n) if d not in dead]
    index = {d: i for i, d in enumerate(keep)}
    return [index[rot[d]] for d in keep], [index[twin[d]] for d in keep]


def add_curves(rot: list[int], twin: list[int], budget: int) -> list[tuple[list[int], list[int]]]:
    """Every arrangement made by drawing one simple closed curve that crosses the map at most
    ``budget`` times: start on an edge, cross one edge of the current face at a time (splitting
    the faces passed), and close when the face holds the start's other side.  A partial curve
    stops when the regions it has not entered need more crossings than are left (each keeps
    its sides in the child; markers are counted as corners, which only weakens the cut)."""
    n0 = len(rot)
    parent_faces = faces(rot, twin)
    face_of = {d: i for i, f in enumerate(parent_faces) for d in f}
    needs = [need(len(f)) for f in parent_faces]  # markers counted: only weakens the cut
    org = [0] * n0
    seen = [False] * n0
    nv = 0
    for d in range(n0):
        if not seen[d]:
            e = d
            while not seen[e]:
                seen[e] = True
                org[e] = nv
                e = rot[e]
            nv += 1
    out = []

    def step(R: list[int], T: list[int], Org: list[int], S: list[int], path: set[int], x: int, y0: int,
             crossed: int, touched: frozenset[int]) -> None:
        irot = [0] * len(R)
        for d in range(len(R)):
            irot[R[d]] = d
        face, e = [], x
        while True:
            face.append(e)
            e = irot[T[e]]
            if e == x:
                break
        # the regions of the map the curve has not entered are regions of the child
        if crossed + sum(needs) - sum(needs[i] for i in touched) > budget:
            return
        if crossed >= 2 and y0 in face:
            r, t, o, s = list(R), list(T), list(Org), list(S)
            chord(r, t, o, s, x, y0)
            out.append(_drop_markers(r, t, o))
        if crossed < budget:
            for d in face:
                if d in path:
                    continue
                r, t, o, s = list(R), list(T), list(Org), list(S)
                e1, e2 = split(r, t, o, s, d)
                a, b = chord(r, t, o, s, x, e2)
                step(r, t, o, s, path | {a, b}, e1, y0, crossed + 1, touched | sides(S[d]))

    def sides(d: int) -> frozenset[int]:
        return frozenset((face_of[d], face_of[twin[d]]))

    def split(R: list[int], T: list[int], Org: list[int], S: list[int], e: int) -> tuple[int, int]:
        q = max(Org) + 1
        e1, e2, te = len(R), len(R) + 1, T[e]
        R.extend((e2, e1))
        T.extend((e, te))
        Org.extend((q, q))
        S.extend((S[e], S[e]))  # the parent's dart (or its twin: same edge, same two faces)
        T[e], T[te] = e1, e2
        return e1, e2

    def chord(R: list[int], T: list[int], Org: list[int], S: list[int], x: int, y: int) -> tuple[int, int]:
        a, b = len(R), len(R) + 1
        R.extend((R[x], R[y]))
        T.extend((b, a))
        Org.extend((Org[x], Org[y]))
        S.extend((-1, -1))
        R[x], R[y] = a, b
        return a, b

    for e in range(n0):
        if e < twin[e]:
            R, T, Org, S = list(rot), list(twin), list(org), list(range(n0))
            e1, e2 = split(R, T, Org, S, e)
            step(R, T, Org, S, set(), e1, e2, 1, sides(e))
    return out


def reference_arrangements(max_corners: int) -> dict[tuple[int, ...], bool]:
    """Every connected arrangement of simple loops that can still grow into a candidate map
    with at most ``max_corners`` corners: canonical code -> whether it is a candidate."""
    limit = max_corners - 2
    level = [([1, 0], [1, 0])]  # the single loop, with one marker vertex
    found: dict[tuple[int, ...], bool] = {}
    while level:
        nxt: dict[tuple[int, ...], tuple[list[int], list[int]]] = {}
        for rot, twin in level:
            crossings = len(rot) // 4 if len(rot) > 2 else 0
            for r, t in add_curves(rot, twin, limit - crossings):
                if bound(r, t) <= limit:
                    nxt.setdefault(canonical_code(r, t), (r, t))
        for code, (r, t) in nxt.items():
            found[code] = is_candidate(r, t)
        level = list(nxt.values())
    return found


def three_colourable(code: tuple[int, ...]) -> bool:
    """Whether the loops of the arrangement with canonical code ``code`` (its twin array, four
    darts a crossing in order) can be coloured with three colours so that crossing loops
    differ: every assignment tried (the arrangements of the tests have few loops)."""
    from itertools import product

    loop, rot = _loops_of_code(code)
    n, count = len(code), max(loop) + 1
    pairs = {(min(loop[d], loop[rot[d]]), max(loop[d], loop[rot[d]])) for d in range(n)}
    return any(all(c[a] != c[b] for a, b in pairs) for c in product(range(3), repeat=count))


def _loops_of_code(code: tuple[int, ...]) -> tuple[list[int], list[int]]:
    """Per dart of a canonical code (four darts a crossing in order), its loop; and the rot."""
    n = len(code)
    rot = [4 * (d // 4) + (d + 1) % 4 for d in range(n)]
    loop = [-1] * n
    count = 0
    for d in range(n):
        if loop[d] < 0:
            e = d
            while loop[e] < 0:
                loop[e] = loop[code[e]] = count
                e = rot[rot[code[e]]]
            count += 1
    return loop, rot


def most_sides_on_one_loop(code: tuple[int, ...]) -> list[tuple[int, int]]:
    """Per region of the arrangement with canonical code ``code``: its number of sides and the
    most of them that lie on one loop."""
    loop, rot = _loops_of_code(code)
    out = []
    for face in faces(rot, list(code)):
        counts: dict[int, int] = {}
        for d in face:
            counts[loop[d]] = counts.get(loop[d], 0) + 1
        out.append((len(face), max(counts.values())))
    return out


def meeting_bound(code: tuple[int, ...]) -> int:
    """Cut 5's bound: crossings plus, per region, the larger of cut 1's need and the pieces
    beyond the first that its sides on one loop must be cut into."""
    return len(code) // 4 + sum(max(need(s), k - 1) for s, k in most_sides_on_one_loop(code))


def meets_each_loop_once(code: tuple[int, ...]) -> bool:
    return all(k == 1 for _, k in most_sides_on_one_loop(code))
