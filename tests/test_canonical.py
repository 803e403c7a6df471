"""Signatures: invariant under renumbering, re-rooting, rotation and mirroring; distinct for
non-isomorphic structures (checked against a brute-force isomorphism test)."""

import itertools
import random

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.core.canonical import (
    SignatureError,
    canonical_form,
    from_signature,
    signature,
    transformed,
)
from polyloops.core.directions import Axis, Direction
from polyloops.core.structure import LoopStructure
from polyloops.core.symmetry import ROTATIONS, SIGNED_PERMUTATIONS, SYMMETRY_MODES
from polyloops.io.examples import EXAMPLES, load_example
from strategies import labelled_structures, perturbed_structures, polycubes


def renumber(ls: LoopStructure, rng: random.Random) -> LoopStructure:
    m = ls.map
    perm = list(range(m.num_corners))
    rng.shuffle(perm)
    faces = []
    for face in m.faces:
        k = rng.randrange(len(face))
        faces.append([perm[c] for c in face[k:] + face[:k]])
    rng.shuffle(faces)
    labels = {}
    for u, v, lab in ls.edge_labels():
        if rng.random() < 0.5:
            labels[(perm[u], perm[v])] = parse_label(lab)
        else:
            flipped = lab if len(lab) == 1 else ("-" if lab[0] == "+" else "+") + lab[1]
            labels[(perm[v], perm[u])] = parse_label(flipped)
    return LoopStructure.from_edge_labels(faces, labels)


def parse_label(text: str) -> Direction | Axis:
    """An edge label as ``edge_labels`` writes it: a direction (``+X``) or, without sides, an axis."""
    return Direction.parse(text) if len(text) == 2 else Axis.parse(text)


def mirror(ls: LoopStructure) -> LoopStructure:
    """The inverse: every face reversed, every direction kept."""
    faces = [tuple(reversed(f)) for f in ls.map.faces]
    return LoopStructure.from_edge_labels(faces, {(u, v): parse_label(lab) for u, v, lab in ls.edge_labels()})


def dart_graph(ls: LoopStructure, mirrored: bool) -> nx.DiGraph:
    m = ls.map
    g = nx.DiGraph()
    for d in range(m.num_darts):
        lab = int(ls.direction(d)) if ls.oriented else int(ls.axis_of_dart(d))
        g.add_node(d, lab=lab)
    for d in range(m.num_darts):
        nxt = m.twin[m.prev[m.twin[d]]] if mirrored else m.next[d]
        g.add_edge(d, nxt, kind="n")
        g.add_edge(d, m.twin[d], kind="t")
    return g


def matchers(a: LoopStructure, b: LoopStructure, mode: str):
    """VF2 matchers from ``a`` to every image of ``b`` under the mode's group, both orientations."""
    ga = dart_graph(a, False)
    for g in SYMMETRY_MODES[mode]:
        bt = transformed(b, g)
        for mirrored in (False, True):
            yield nx.algorithms.isomorphism.DiGraphMatcher(
                ga, dart_graph(bt, mirrored), node_match=lambda x, y: x["lab"] == y["lab"],
                edge_match=lambda x, y: x["kind"] == y["kind"])


def brute_isomorphic(a: LoopStructure, b: LoopStructure, mode: str = "labelled") -> bool:
    if (a.map.num_darts, a.oriented) != (b.map.num_darts, b.oriented):
        return False
    return any(m.is_isomorphic() for m in matchers(a, b, mode))


@given(perturbed_structures(), st.randoms(use_true_random=False))
def test_signature_ignores_numbering_and_mirror(ls, seed):
    rng = seed  # a Random that hypothesis drives, so a failure replays and shrinks
    sig = signature(ls, "labelled")
    assert signature(renumber(ls, rng), "labelled") == sig
    assert signature(mirror(ls), "labelled") == sig
    assert signature(ls.forget_orientation(), "labelled") != sig  # labelled vs oriented differ


@given(polycubes(max_size=6), st.integers(0, 47))
def test_signature_under_symmetries(q, k):
    ls = q.dualize()
    g = SIGNED_PERMUTATIONS[k]
    image = transformed(ls, g)
    assert signature(image, "full") == signature(ls, "full")
    if g.is_rotation:
        assert signature(image, "rotation") == signature(ls, "rotation")


@settings(max_examples=15)  # about 0.4 s each (VF2, three canonical forms); shipped records are decoded too
@given(perturbed_structures(max_size=5))
def test_from_signature_round_trip(ls):
    for mode in ("labelled", "rotation", "full"):
        form = canonical_form(ls, mode)
        back = from_signature(form.signature)
        assert canonical_form(back, mode).code == form.code
    assert brute_isomorphic(from_signature(signature(ls, "labelled")), ls)


def pool():
    from polyloops.core.moves import add_loop, additions

    items = [load_example(n) for n in EXAMPLES]
    items = [x.dualize() if hasattr(x, "dualize") else x for x in items]
    cube = items[0]
    items += [add_loop(cube, mv) for mv in additions(cube)]
    items += [x.flipped(i) for x in items[:4] for i in range(len(x.loops))]
    return items


def check_pairs(mode, max_darts=None):
    items = [x for x in pool() if max_darts is None or x.map.num_darts <= max_darts]
    sigs = [signature(x, mode) for x in items]
    for i in range(len(items)):
        for j in range(i + 1, len(items)):
            if items[i].map.num_darts != items[j].map.num_darts:
                assert sigs[i] != sigs[j]
                continue
            assert (sigs[i] == sigs[j]) == brute_isomorphic(items[i], items[j], mode), (i, j)


@pytest.mark.parametrize("mode", ["labelled", "rotation"])
def test_signatures_distinguish_exactly_the_non_isomorphic(mode):
    check_pairs(mode, max_darts=100)  # 26 structures; VF2 in rotation mode is the slow part


@pytest.mark.slow
@pytest.mark.parametrize("mode", ["labelled", "rotation"])
def test_signatures_distinguish_exactly_the_non_isomorphic_on_the_whole_pool(mode):
    check_pairs(mode)


def test_automorphism_orders_match_brute_force():
    for name in ("cube", "box-2x1x1", "l-shape"):
        ls = load_example(name).dualize()
        for mode in ("labelled", "rotation", "full"):
            # Every dart bijection onto some image of itself (group element, orientation).
            count = sum(sum(1 for _ in m.isomorphisms_iter()) for m in matchers(ls, ls, mode))
            assert canonical_form(ls, mode).automorphisms == count, (name, mode)


def test_rotations_are_the_proper_signed_permutations():
    """ROTATIONS are exactly the signed permutation matrices of determinant +1, derived here
    from itertools and a determinant, each once (24 of them)."""
    import numpy as np

    derived = set()
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1, -1), repeat=3):
            matrix = np.zeros((3, 3), dtype=int)
            for row, (col, sign) in enumerate(zip(perm, signs, strict=True)):
                matrix[row, col] = sign
            if round(np.linalg.det(matrix)) == 1:
                derived.add(tuple(map(tuple, matrix)))
    def matrix_of(g):  # column a is the image of e_a
        m = np.zeros((3, 3), dtype=int)
        for a in range(3):
            m[g.perm[a], a] = g.signs[a]
        return tuple(map(tuple, m))

    assert len(derived) == 24 and len(ROTATIONS) == 24
    assert {matrix_of(g) for g in ROTATIONS} == derived


def test_bad_signatures():
    for bad in ("", "x", "oB", "oBYD!!", signature(load_example("cube")) + "A"):
        with pytest.raises(SignatureError):
            from_signature(bad)


def test_cli_signature_and_sig_files(capsys):
    assert main(["signature", "example:l-shape", "--symmetry", "rotation"]) == 0
    sig = capsys.readouterr().out.strip().split()[0]
    assert main(["info", f"sig:{sig}", "--json"]) == 0
    assert '"corners": 16' in capsys.readouterr().out
    assert main(["verify", "sig:nonsense"]) == 2
    assert "sig:nonsense" in capsys.readouterr().err


REFLECTIONS = [g for g in SIGNED_PERMUTATIONS if g.det < 0]


@given(polycubes(kinds=("blob", "smooth"), max_size=7), st.sampled_from(SIGNED_PERMUTATIONS))
def test_chirality_is_an_invariant(q, g):
    """Chirality is a property of the class: the same for every image under the 48 symmetries,
    and it says whether the mirror image is a rotation of the structure."""
    ls = q.dualize()
    achiral = canonical_form(ls, "full").achiral
    assert canonical_form(transformed(ls, g), "full").achiral == achiral
    mirrored = transformed(ls, REFLECTIONS[0])
    assert achiral == (signature(mirrored, "rotation") == signature(ls, "rotation"))


def test_some_random_polycubes_are_chiral():
    """The invariance test above would pass vacuously if every sample were achiral."""
    from strategies import random_polycube

    flags = {canonical_form(random_polycube(seed, "blob", 4), "full").achiral for seed in range(12)}
    assert flags == {True, False}


def test_one_default_mode_everywhere(capsys, tmp_path):
    """A signature printed by the command finds the class in the catalog's table."""
    import json

    import polyloops as pl
    from polyloops.catalog.census import default_catalog

    assert main(["signature", "example:l-shape", "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["symmetry"] == "full"
    assert printed["signature"] == pl.signature(load_example("l-shape"))
    assert main(["catalog", "query", str(default_catalog()), f"signature = '{printed['signature']}'",
                 "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert [r["name"] for r in rows] == [pl.identify(load_example("l-shape")).name]


def python_form(ls, mode):
    """The canonical form by the tuple code in Python (the compiled code switched off)."""
    import polyloops.core.canonical as canonical
    from polyloops.core import compiled

    with compiled.pure_python("canonical"):
        form = canonical.canonical_form(ls, mode)
        return form, form.signature


@settings(max_examples=60, deadline=None)
@given(st.one_of(perturbed_structures(max_size=7), polycubes(max_size=8).map(lambda q: q.dualize()),
                 labelled_structures()),
       st.sampled_from(["labelled", "rotation", "full"]))
def test_compiled_canonical_form_is_the_python_one(ls, mode):
    """The compiled canonical form and signature text equal the Python ones: code,
    automorphism count, chirality and signature, on valid, perturbed and unoriented
    structures in every mode."""
    from polyloops.core import canonical, compiled

    if not compiled.in_use("canonical"):
        pytest.skip("the compiled canonical form does not run here")
    form = canonical.canonical_form(ls, mode)
    assert (form, form.signature) == python_form(ls, mode)


def test_compiled_canonical_form_on_every_example():
    from polyloops.core import canonical, compiled

    if not compiled.in_use("canonical"):
        pytest.skip("the compiled canonical form does not run here")
    for name in EXAMPLES:
        x = load_example(name)
        ls = x if isinstance(x, LoopStructure) else x.dualize()
        for mode in ("labelled", "rotation", "full"):
            form = canonical.canonical_form(ls, mode)
            assert (form, form.signature) == python_form(ls, mode), (name, mode)


@settings(max_examples=40, deadline=None)
@given(st.one_of(perturbed_structures(max_size=7), polycubes(max_size=8).map(lambda q: q.dualize())),
       st.sampled_from(["labelled", "rotation", "full"]))
def test_unchecked_signatures_read_back_the_same_structure(ls, mode):
    """Reading a signature without checking the map (as the reachability search reads its own
    states) gives the structure the checked reading gives."""
    sig = signature(ls, mode)
    assert from_signature(sig, checked=False) == from_signature(sig)


def _darts_one_by_one(sigs):
    from polyloops.core.canonical import SignatureError, signature_darts

    try:
        return [signature_darts(s) for s in sigs]
    except SignatureError as err:
        return str(err)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.sampled_from(sorted(EXAMPLES)), st.integers(0, 3), st.integers(0, 10_000),
                          st.sampled_from("AZaz09-_1lo é")), min_size=1, max_size=6))
def test_signatures_checked_together_agree_with_one_by_one(edits):
    """The batched check (one pass over many signatures) equals the check of each alone:
    the same numbers of darts, or the same error, whatever a signature lost or gained (a
    character changed, the text cut short, a character that is no digit)."""
    from polyloops.core.canonical import SignatureError, signatures_darts

    sigs = []
    for name, how, where, ch in edits:
        sig = signature(load_example(name))
        k = where % len(sig)
        sigs.append([sig, sig[:k] + ch + sig[k + 1:], sig[:k], sig[:k] + ch + sig[k:]][how])
    try:
        got = signatures_darts(sigs)
    except SignatureError as err:
        got = str(err)
    assert got == _darts_one_by_one(sigs)
