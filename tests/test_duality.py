"""Theorems 1 and 2: dualize, primalize and order-equivalence, on random polycubes of genus 0-2."""


import networkx as nx
from hypothesis import given
from hypothesis import strategies as st

from polyloops.core.duality import dualize, is_order_equivalent, primalize
from polyloops.io.examples import load_example
from polyloops.shapes.voxels import polycube_from_voxels
from polyloops.verify import check_polycube, check_polycube_loop_structure
from strategies import perturbed_structures, polycubes, renumbered


def brute_order_equivalent(p, q) -> bool:
    """The slow twin of is_order_equivalent: VF2 on corners plus face nodes, arcs labelled by
    the order of their ends on each axis."""

    def graph(x):
        g = nx.DiGraph()
        for f, face in enumerate(x.faces):
            g.add_node(("f", f), kind="face")
            for i, u in enumerate(face):
                v = face[(i + 1) % 4]
                a, b = x.positions[u], x.positions[v]
                rel = tuple((b[k] > a[k]) - (b[k] < a[k]) for k in range(3))
                g.add_node(u, kind="corner")
                g.add_edge(u, v, rel=rel)
                g.add_edge(("f", f), u, rel="face")
        return g

    matcher = nx.algorithms.isomorphism.DiGraphMatcher(
        graph(p), graph(q), node_match=lambda a, b: a["kind"] == b["kind"],
        edge_match=lambda a, b: a["rel"] == b["rel"])
    return matcher.is_isomorphic()


@given(polycubes())
def test_dual_of_a_polycube_is_a_polycube_loop_structure(q):
    assert check_polycube(q).valid
    ls = dualize(q)
    assert check_polycube_loop_structure(ls).valid


@given(polycubes())
def test_round_trips(q):
    ls = dualize(q)
    p = primalize(ls)
    assert dualize(p) == ls
    assert is_order_equivalent(p, q) is not None
    # Compact: every axis starts at 0 with no gaps.
    for k in range(3):
        assert sorted({pos[k] for pos in p.positions}) == list(range(max(pos[k] for pos in p.positions) + 1))


@given(polycubes(max_size=6), st.randoms(use_true_random=False), st.booleans())
def test_order_equivalence_finds_renumbered_copies(q, seed, invert):
    r = renumbered(q.inverse() if invert else q, seed)
    f = is_order_equivalent(q, r)
    assert f is not None
    assert sorted(f) == list(range(q.map.num_corners))
    for face in q.faces:  # f maps faces to faces, in some orientation
        image = [f[c] for c in face]
        assert any(sorted(image) == sorted(g) for g in r.faces)


@given(polycubes(max_size=5), perturbed_structures(max_size=5))
def test_order_equivalence_agrees_with_brute_force(q, ls):
    if not check_polycube_loop_structure(ls).valid:
        return
    p = primalize(ls)
    assert (is_order_equivalent(p, q) is not None) == brute_order_equivalent(p, q)
    assert (is_order_equivalent(p, dualize(q).primalize()) is not None) == brute_order_equivalent(
        p, dualize(q).primalize())


def test_order_equivalence_distinguishes_a_flip():
    # A slab with a bump: flipping the bump's Z-loop turns it into a dent (the paper's
    # protruding and indented blocks share one labelled loop structure).
    q = polycube_from_voxels([(i, j, 0) for i in range(3) for j in range(3)] + [(1, 1, 1)])
    ls = dualize(q)
    found_different = False
    for lp in ls.loops:
        other = ls.flipped(lp.id)
        if check_polycube_loop_structure(other).valid:
            p = primalize(other)
            same = is_order_equivalent(p, q) is not None
            assert same == brute_order_equivalent(p, q)
            found_different |= not same
    assert found_different


def test_inverse_is_order_equivalent():
    q = load_example("ring")
    assert is_order_equivalent(q, q.inverse()) is not None
