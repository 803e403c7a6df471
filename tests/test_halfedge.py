"""The half-edge map: construction, errors with witnesses, rotations."""

import pytest
from hypothesis import given

from polyloops.core.halfedge import FaceListError, HalfEdgeMap, MapError
from strategies import polycubes

CUBE = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]


def kinds(err: MapError) -> list[str]:
    return [p.kind for p in err.problems]


def test_cube_counts():
    m = HalfEdgeMap.from_faces(CUBE)
    assert (m.num_corners, m.num_edges, m.num_faces, m.genus) == (8, 12, 6, 0)
    assert all(m.degree(c) == 3 for c in range(8))


def test_boundary_edge_is_reported():
    with pytest.raises(MapError) as err:
        HalfEdgeMap.from_faces(CUBE[:-1])
    assert set(kinds(err.value)) == {"boundary-edge"}
    assert len(err.value.problems) == 4  # the four edges of the missing face


def test_branching_edge_is_reported():
    extra = [*CUBE, [0, 1, 8, 9], [9, 8, 1, 0]]
    with pytest.raises(MapError) as err:
        HalfEdgeMap.from_faces(extra)
    assert "branching-edge" in kinds(err.value)
    assert any(p.witness.get("edge") == [0, 1] for p in err.value.problems)


def test_inconsistent_orientation_is_reported():
    flipped = [list(reversed(CUBE[0])), *CUBE[1:]]
    with pytest.raises(MapError) as err:
        HalfEdgeMap.from_faces(flipped)
    assert set(kinds(err.value)) == {"orientation"}


def test_non_manifold_corner_is_reported():
    # Two cubes sharing only corner 7.
    other = [[c + 7 if c != 0 else 7 for c in f] for f in CUBE]
    with pytest.raises(MapError) as err:
        HalfEdgeMap.from_faces(CUBE + other)
    assert kinds(err.value) == ["non-manifold-corner"]
    assert err.value.problems[0].witness["corner"] == 7


def test_disconnected_is_reported():
    other = [[c + 8 for c in f] for f in CUBE]
    with pytest.raises(MapError) as err:
        HalfEdgeMap.from_faces(CUBE + other)
    assert kinds(err.value) == ["disconnected"]


@pytest.mark.parametrize("faces", [[[0, 1]], [[0, 1, 1, 2]], [[0, 1, 3]], []])
def test_bad_face_lists(faces):
    with pytest.raises(FaceListError):
        HalfEdgeMap.from_faces(faces)


@given(polycubes())
def test_map_invariants(q):
    m = q.map
    for d in range(m.num_darts):
        assert m.twin[m.twin[d]] == d != m.twin[d]
        assert m.next[m.prev[d]] == d
        assert m.origin(m.twin[d]) == m.target(d)
        assert m.origin(m.rotate(d)) == m.origin(d)
    assert sum(m.degree(c) for c in range(m.num_corners)) == m.num_darts
    assert m.reversed().genus == m.genus
