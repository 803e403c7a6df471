"""The strategies themselves: they reach the shapes the tests need, and hypothesis shrinks what
they draw to small shapes (so a failing property reports a small witness)."""

from hypothesis import HealthCheck, find, given, settings
from hypothesis import strategies as st

from polyloops.core.moves import removals
from polyloops.verify import verify
from strategies import grown_structures, polycubes, voxel_sets


def test_a_blob_beyond_the_cube_shrinks_to_two_cubes():
    q = find(polycubes(kinds=("blob",)), lambda q: q.map.num_corners > 8)
    assert q.map.num_corners == 12  # two cubes in a row: the smallest polycube after the cube


def test_a_handle_shrinks_to_the_smallest_frame():
    # the smallest frame: bars and hole one cube wide, one cube thick, nothing on top
    q = find(polycubes(kinds=("frame1",)), lambda q: q.genus >= 1)
    assert q.genus == 1 and len(q.map.faces) == 32


def test_grown_structures_shrink_to_one_loop_addition():
    ls = find(grown_structures(), lambda ls: len(ls.loops) > 3)
    assert len(ls.loops) == 4 and ls.map.num_corners == 12


@settings(max_examples=30, suppress_health_check=[HealthCheck.too_slow])
@given(polycubes())
def test_drawn_polycubes_are_valid_and_varied(q):
    assert verify(q).valid


def test_the_strategies_reach_every_kind_of_shape():
    """Each kind reaches the genus and size it is meant for (a strategy that collapsed to the
    cube would make every property above trivially true)."""
    for kinds, genus in ((("blob",), 0), (("smooth",), 0), (("frame1",), 1), (("frame2",), 2)):
        q = find(polycubes(kinds=kinds), lambda q, g=genus: q.genus == g and q.map.num_corners >= 20)
        assert q.genus == genus
    cells = find(voxel_sets(kinds=("blob",)), lambda c: len(c) >= 6)
    assert len(cells) == 6


@settings(max_examples=20, deadline=None)
@given(grown_structures(max_moves=3), st.data())
def test_grown_structures_are_polycube_loop_structures(ls, data):
    assert verify(ls).valid
    # Loop additions from the cube never produce an irreducible structure other than the cube.
    assert len(ls.loops) == 3 or removals(ls)
