"""The first stage as square-tiled surfaces (:mod:`polyloops.generate.torus.squares`): against
brute force, against the marked search it replaces, its Python twin, and its shares."""

import array
from collections import Counter

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.generate.torus.arrangement import arrangement_of_twin
from polyloops.generate.torus.cuts import zones_split_every_loop
from polyloops.generate.torus.squares import square_bases
from polyloops.generate.torus.stages import first_stage, share_of_first_stage, two_axis_bases
from reference.torus_brute import _least_code, surface_maps_by_brute_force
from switch import running


def codes(twins):
    return [_least_code(list(array.array("H", t))) for t in twins]


def bipartite(a) -> bool:
    adj = a.crossing_graph()
    side = {0: 0}
    stack = [0]
    while stack:
        v = stack.pop()
        for u in adj[v]:
            if u not in side:
                side[u] = 1 - side[v]
                stack.append(u)
            elif side[u] == side[v]:
                return False
    return len(side) == a.num_loops  # and connected


@pytest.mark.parametrize(("genus", "n"), [(1, 2), (1, 3), (1, 4), (2, 3), (2, 4),
                                          pytest.param(1, 5, marks=pytest.mark.slow),
                                          pytest.param(2, 5, marks=pytest.mark.slow),
                                          pytest.param(2, 6, marks=pytest.mark.slow)])
def test_the_listing_is_what_brute_force_finds(genus, n):
    """Every B of the genus with n crossings, once: the brute force over all pairings of darts,
    kept when the crossing graph is bipartite and every loop has two zones on its sides."""
    twins, _ = square_bases(n, genus)
    mine = codes(twins)
    assert len(set(mine)) == len(mine)  # none twice
    brute = {c for c in surface_maps_by_brute_force(n, genus)
             if bipartite(arrangement_of_twin(array.array("H", c).tobytes()))
             and zones_split_every_loop(arrangement_of_twin(array.array("H", c).tobytes()))}
    assert set(mine) == brute


@pytest.mark.parametrize(("genus", "top"), [(1, 9), (2, 8), pytest.param(1, 11, marks=pytest.mark.slow),
                                            pytest.param(2, 10, marks=pytest.mark.slow)])
def test_the_first_stage_lists_what_the_marked_search_lists(genus, top):
    """The same B, by crossings, as the marked search (which builds them one loop at a time
    through non-cellular states), each once."""
    listed, stats = first_stage(top, genus)
    mine = codes(listed)
    assert len(set(mine)) == len(mine) == stats.targets
    theirs = Counter(_least_code(list(a.twin)) for a in two_axis_bases(top, genus=genus))
    assert Counter(mine) == theirs


@pytest.mark.parametrize(("genus", "n"), [(0, 5), (1, 6), (2, 6), (3, 6),
                                          pytest.param(2, 8, marks=pytest.mark.slow)])
def test_the_python_twin_takes_the_same_steps(genus, n):
    """The compiled listing and its Python twin: the same B in the same order, and the same
    counts of nodes, leaves and cut branches."""
    with running("squares", True):
        compiled = square_bases(n, genus)
    with running("squares", False):
        python = square_bases(n, genus)
    assert compiled == python


@settings(max_examples=25, deadline=None)
@given(genus=st.integers(1, 2), n=st.integers(4, 10), mod=st.integers(2, 7), split=st.integers(0, 30))
def test_the_shares_deal_out_the_listing(genus, n, mod, split):
    """Shares split the search's subtrees: together they list each B once, whatever the
    number of shares and the depth of the split."""
    whole, _ = square_bases(n, genus)
    parts = [square_bases(n, genus, res, mod, split) for res in range(mod)]
    assert Counter(t for twins, _ in parts for t in twins) == Counter(whole)
    assert len({stats.subtrees for _, stats in parts}) == 1


@pytest.mark.parametrize(("genus", "n"), [(1, 8), (2, 8), (2, 10)])
def test_each_listed_arrangement_is_a_base(genus, n):
    """Each B: darts of one parity joined, connected, of the genus (n + 2 - 2g faces), every
    loop with two zones on its sides; counted without keeping, the same number."""
    twins, stats = square_bases(n, genus)
    assert twins
    for raw in twins:
        a = arrangement_of_twin(raw)
        assert all((d ^ a.twin[d]) & 1 == 0 for d in range(4 * n))
        assert len(a.faces) == n + 2 - 2 * genus
        assert zones_split_every_loop(a) and bipartite(a)
    assert stats.kept == len(twins)
    assert square_bases(n, genus, keep=False) == ([], stats)


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="crossings"):
        square_bases(0, 1)
    with pytest.raises(ValueError, match="res"):
        square_bases(4, 1, 3, 3)


@pytest.mark.parametrize(("genus", "top"), [(1, 12), (2, 10)])
def test_the_shares_of_the_first_stage_list_it_once(genus, top):
    """A catalog run's shares each list their own B: together, the first stage, each B once."""
    shares = [share_of_first_stage(top, genus, res, 16)[0] for res in range(16)]
    assert Counter(t for share in shares for t in share) == Counter(first_stage(top, genus)[0])
    assert sum(1 for share in shares if share) > 8  # dealt round, not all in a few
