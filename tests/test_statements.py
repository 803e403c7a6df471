"""The paper's smaller statements, each as a property of random polycubes (docs/statements.md
lists every statement with its function and tests)."""

import networkx as nx
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.core.directions import Axis
from polyloops.verify import check_polycube_loop_structure, check_quad_loop_structure
from strategies import grown_structures, handle_zone_polycubes, polycubes

shapes = st.one_of(polycubes(max_size=8), handle_zone_polycubes(max_bumps=1))


@given(shapes)
def test_lemma_every_face_is_an_axis_aligned_rectangle(q):
    """Lemma ``lem:rectface``: every edge is axis-aligned and every face a rectangle."""
    for face in q.faces:
        p = [q.positions[c] for c in face]
        for i in range(4):
            a, b, c = p[i], p[(i + 1) % 4], p[(i + 2) % 4]
            assert sum(x != y for x, y in zip(a, b, strict=True)) == 1  # axis-aligned edge
            u = [y - x for x, y in zip(a, b, strict=True)]
            v = [y - x for x, y in zip(b, c, strict=True)]
            assert sum(x * y for x, y in zip(u, v, strict=True)) == 0  # a right angle


@given(shapes)
def test_corollary_no_corner_has_more_than_six_neighbours(q):
    """The corollary after ``lem:rectface``: each corner has at most six adjacent corners."""
    assert max(q.map.degree(c) for c in range(q.map.num_corners)) <= 6


@given(shapes)
def test_nonintersection_theorem(q):
    """Theorem ``thm:nonintersecting``: loops with the same axis label never cross (no face is
    crossed by two loops of one axis, nor twice by one loop)."""
    ls = q.dualize()
    system = ls.map.loop_system
    for f in range(ls.map.num_faces):
        a, b = system.loops_of_face(ls.map, f)
        assert ls.axes[a] != ls.axes[b]


@settings(max_examples=40)
@given(st.one_of(shapes.map(lambda q: q.dualize()), grown_structures(max_moves=3)))
def test_lemma_polycube_loop_structures_are_quad_loop_structures(ls):
    """Lemma ``lem:polycube_is_quad``: a polycube loop structure (Definition 4, checked alone)
    satisfies Definition 3, checked by its own checker."""
    assert check_polycube_loop_structure(ls).valid
    assert check_quad_loop_structure(ls).valid


@given(polycubes(kinds=("blob", "smooth"), max_size=10))
def test_corollary_genus0_level_graphs_are_trees(q):
    """Corollary ``cor:tree``: at genus 0 the X-, Y- and Z-graphs are trees."""
    ls = q.dualize()
    for axis in Axis:
        g = ls.level_graph(axis)  # a multigraph: parallel arcs would make a cycle
        assert nx.is_weakly_connected(g) and g.number_of_edges() == g.number_of_nodes() - 1
