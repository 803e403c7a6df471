"""Genus 2: the torus search with the surface's genus a parameter (the ``handles`` generator),
against brute force, its compiled twin, and the smallest known genus-2 polycube."""

import itertools

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.generate.base import generators
from polyloops.generate.handles import HandlesGenerator
from polyloops.generate.torus import stages
from polyloops.generate.torus.arrangement import TorusArrangement, canonical, piece_of_mark
from polyloops.generate.torus.candidates import SecondStage, _third_axes
from polyloops.generate.torus.cuts import zones_split_every_loop
from polyloops.generate.torus.decompositions import canonical_decomposition, carries_polycube
from polyloops.generate.torus.drawing import roots
from polyloops.generate.torus.regions import _every_cycle, _walk_cycle
from polyloops.generate.torus.stages import torus_arrangements, torus_children, two_axis_bases
from polyloops.io.examples import load_example
from reference.torus_brute import _least_code, surface_maps_by_brute_force
from switch import needs, running


def by_size(arrangements, n):
    return {_least_code(list(a.twin)) for a in arrangements if a.crossings == n}


@pytest.mark.parametrize("compiled", [False, True])
@pytest.mark.parametrize(("genus", "n"), [(2, 3), (2, 4), pytest.param(2, 5, marks=pytest.mark.slow),
                                          pytest.param(2, 6, marks=pytest.mark.slow),
                                          pytest.param(3, 5, marks=pytest.mark.slow)])
def test_the_search_lists_what_brute_force_lists(genus, n, compiled):
    """Every cellular arrangement of simple loops on the surface of genus 2 (and 3) with n
    crossings, once: the marked search with pieces, in Python and compiled, against the brute
    force over all pairings of darts (2, 20, 98 and 671 with 3 to 6 crossings at genus 2, none
    with fewer; 40 with 5 at genus 3; from 5 crossings on, slow)."""
    with running("torus", compiled):
        found = list(torus_arrangements(n, genus=genus))
    assert all(by_size(found, k) == set() for k in range(1, 2 * genus - 1))  # F = n - 2(g - 1) >= 1
    codes = by_size(found, n)
    assert len(codes) == sum(a.crossings == n for a in found)  # none twice
    assert codes == surface_maps_by_brute_force(n, genus)


@pytest.mark.parametrize(("colours", "n"), [(2, 4), pytest.param(2, 5, marks=pytest.mark.slow),
                                             pytest.param(None, 5, marks=pytest.mark.slow)])
def test_each_curve_drawn_from_one_start_keeps_every_state(colours, n):
    """The first stage's shortcuts (one dart an edge, the least edge, the single loop's mark
    before the first point) keep the same states at genus 2 as drawing from every start
    (through 4 crossings; 5, slow)."""

    def states(every: bool) -> list:
        out: list = []
        stack: list = list(range(len(roots(2))))
        with running("torus", False):
            while stack:
                node = stack.pop()
                kids = torus_children(node, n, colours, False, stages.TorusSearchStats(), every_start=every,
                                      genus=2)
                out += [(kid.code, facts) for kid, facts in kids]
                stack.extend(kid for kid, _ in kids)
        return out

    once = states(False)
    assert once == states(True) and any(f.target for _, f in once)


@needs("torus")
@pytest.mark.parametrize(("colours", "n"), [(2, 5), (0, 5), pytest.param(2, 6, marks=pytest.mark.slow),
                                             pytest.param(0, 6, marks=pytest.mark.slow)])
def test_the_compiled_first_stage_keeps_what_the_python_one_keeps(colours, n):
    """Every state of the genus-2 first stage through 5 crossings (6, slow): the compiled search's
    children of each are the Python search's, compared by the Python canonical code of the
    marked map (pieces included), with the same facts (a target; two colours: the zones split
    every loop)."""
    stack: list = list(range(len(roots(2))))
    seen = 0
    while stack:
        node = stack.pop()
        with running("torus", False):
            slow = torus_children(node, n, colours or None, False, genus=2)
        fast = torus_children(node, n, colours or None, False, genus=2)
        key = {canonical(TorusArrangement(k.twin, k.marks))[0]: f for k, f in fast}
        want = {k.code: f for k, f in slow}
        assert set(key) == set(want)
        for code, f in want.items():
            split = zones_split_every_loop(TorusArrangement(code_twin(slow, code))) if f.target and colours \
                else None
            assert key[code].target == f.target and key[code].split in (None, split)
        seen += len(slow)
        stack.extend(k for k, _ in slow)
    assert seen > 50


def code_twin(kids, code):
    return next(k.twin for k, _ in kids if k.code == code)


def test_pieces_are_named_canonically():
    """Renumbering the pieces of a state (their ids are arbitrary) keeps its code; changing a
    piece's genus changes it."""
    a = TorusArrangement((2, 3, 0, 1), (("g1.4", 1),))
    b = TorusArrangement((2, 3, 0, 1), (("g1.0", 1),))
    c = TorusArrangement((2, 3, 0, 1), (("g0.0", 1),))
    assert canonical(a)[0] == canonical(b)[0] != canonical(c)[0]
    assert piece_of_mark("g1.4") == (1, "4")


def brute_cycles(arcs: dict[int, tuple[int, int]]) -> set[frozenset[int]]:
    """Every set of arcs that is one simple cycle, by trying every subset."""
    out = set()
    for k in range(1, len(arcs) + 1):
        for chosen in itertools.combinations(sorted(arcs), k):
            degree: dict[int, int] = {}
            for lp in chosen:
                for z in arcs[lp]:
                    degree[z] = degree.get(z, 0) + 1
            one = len(_walk_cycle({lp: arcs[lp] for lp in chosen})) == k
            if all(v == 2 for v in degree.values()) and one:
                out.add(frozenset(chosen))
    return out


@st.composite
def level_graphs(draw):
    """A connected multigraph without self-loops: a tree on some zones, and a few more arcs."""
    zones = draw(st.integers(2, 6))
    arcs = [(draw(st.integers(0, z - 1)), z) for z in range(1, zones)]
    for _ in range(draw(st.integers(0, 4))):
        a, b = draw(st.integers(0, zones - 1)), draw(st.integers(0, zones - 1))
        if a != b:
            arcs.append((a, b))
    order = draw(st.permutations(range(len(arcs))))
    return {lp: (arcs[i] if draw(st.booleans()) else arcs[i][::-1]) for lp, i in enumerate(order)}


@given(level_graphs())
@settings(max_examples=150, deadline=None)
def test_every_cycle_of_a_level_graph_is_found(arcs):
    """The cycles the genus-2 level-graph cut keeps from being forced one way are every simple
    cycle of the level graph (against trying every set of arcs), each walked consistently: the
    arcs in order round it, each with its sense."""
    found = _every_cycle(arcs)
    assert {frozenset(lp for lp, _ in c) for c in found} == brute_cycles(arcs)
    for cycle in found:
        at = None
        for lp, rho in cycle:
            left, right = arcs[lp] if rho == 1 else arcs[lp][::-1]
            assert at in (None, left)
            at = right
        first = cycle[0]
        assert at == (arcs[first[0]][0] if first[1] == 1 else arcs[first[0]][1])  # closed


def slab_base() -> tuple[TorusArrangement, TorusArrangement]:
    """The slab with two holes (48 corners, 50 crossings) as an arrangement, and the ``B`` its
    axis of fewest crossings leaves when deleted."""
    slab = load_example("slab-2-holes").dualize()  # type: ignore[union-attr]
    a = TorusArrangement(tuple(slab.map.twin))
    axes = slab_axes(slab, a)
    base = min((a.without_loops({lp for lp, x in axes.items() if x == d}) for d in range(3)),
               key=lambda b: b.crossings)
    return a, base


def test_the_second_stage_builds_the_smallest_known_genus_2_polycube():
    """From the slab's ``B`` (10 crossings), the second stage at 50 crossings builds exactly the
    slab, as its canonical decomposition, with a polycube."""
    a, base = slab_base()
    assert (a.crossings, len(a.faces), base.crossings) == (50, 48, 10)
    built = [kid for kid in _third_axes(base, 50, stages.TorusSearchStats(), SecondStage.REGIONS)
             if carries_polycube(kid) and canonical_decomposition(kid)]
    assert [canonical(TorusArrangement(k.twin))[0] for k in built] == [canonical(a)[0]]


@pytest.mark.slow
def test_the_first_stage_lists_the_slabs_base():
    """The slab's ``B`` is among the 522 ``B`` with 10 crossings of the genus-2 first stage
    (20 to 40 s)."""
    _, base = slab_base()
    bases = {canonical(b)[0] for b in two_axis_bases(10, genus=2) if b.crossings == 10}
    assert len(bases) == 522 and canonical(base)[0] in bases


def slab_axes(structure, a: TorusArrangement) -> dict[int, int]:
    """The axis of each loop of ``a`` (the arrangement of ``structure``'s map, same darts)."""
    m = structure.map
    faces: dict[int, set[int]] = {}
    for v in range(m.num_faces):
        for lp in m.loop_system.loops_of_face(m, v):
            faces.setdefault(lp, set()).add(v)
    crossings: dict[int, set[int]] = {}
    for v in range(a.crossings):
        for d in (4 * v, 4 * v + 1):
            crossings.setdefault(a.loop_of[d], set()).add(v)
    mine = {frozenset(vs): lp for lp, vs in crossings.items()}
    return {mine[frozenset(faces[lp])]: int(structure.axes[lp]) for lp in range(len(m.loop_system.loops))}


def test_the_genus_2_generator_plugs_in():
    """``handles`` is the generator of genus 2; a map with N corners has N + 2 crossings, and
    its first stage through 6 crossings holds the two smallest ``B`` (6 crossings)."""
    gen = generators()["handles"]
    assert isinstance(gen, HandlesGenerator) and gen.genus == 2 and gen.crossings(16) == 18
    assert sorted(b.crossings for b in two_axis_bases(6, genus=2)) == [6, 6]


def test_a_genus_2_catalog_runs_through_the_pipeline(tmp_path):
    """``polyloops catalog --genus 2`` builds a catalog of genus 2 end to end; through 24
    corners (``B`` through 8 crossings) no map carries a polycube, and the summary says so
    for every corner count."""
    import json

    from polyloops.cli.main import main

    out = tmp_path / "g2"
    assert main(["catalog", "--genus", "2", "--max-corners", "24", "-o", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["genus"] == 2 and summary["generator"] == "handles"
    assert set(summary["counts"]) == {str(n) for n in range(8, 25)}
    assert all(not any(row.values()) for row in summary["counts"].values())
    assert (out / "catalog.jsonl").read_text() == ""


