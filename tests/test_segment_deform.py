"""Polycube-like heights (``segment/deform.py``), planes cutting them (``Refined.heights``), and
the grid start mended by added curves (``segment/grid.py``)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.segment.deform import axis_alignment, polycube_heights
from polyloops.segment.embedded import SurfaceLoop, read_structure
from polyloops.segment.grid import grid_start
from polyloops.segment.refine import Plane, Refined, _Builder, _clear_of_vertices, _cut_one, cut
from polyloops.segment.search import candidate_loops, crossing_only
from polyloops.segment.surface import surface_of
from polyloops.shapes.builders import box, ring
from polyloops.shapes.meshes import ellipsoid, torus
from polyloops.surface.construct import labelled_mesh_from_polycube
from polyloops.verify import check_polycube_loop_structure


def turned(points: np.ndarray, degrees: float, axis: int) -> np.ndarray:
    """``points`` turned by ``degrees`` about coordinate ``axis``."""
    a = np.radians(degrees)
    i, j = [k for k in range(3) if k != axis]
    out = points.copy()
    out[:, i] = np.cos(a) * points[:, i] - np.sin(a) * points[:, j]
    out[:, j] = np.sin(a) * points[:, i] + np.cos(a) * points[:, j]
    return out


@pytest.mark.parametrize("polycube", [box(2, 1, 1), ring(3, 1), ring(3, 2)], ids=["box", "ring", "tall ring"])
def test_a_polycube_is_its_own_deformation(polycube):
    """Every normal is already an axis: each round turns nothing and the solve gives the points
    back (the fixed point the deformation aims at)."""
    mesh = labelled_mesh_from_polycube(polycube)
    s = surface_of(np.array(mesh.points, dtype=float), np.array(mesh.triangles))
    assert np.allclose(polycube_heights(s), s.points, atol=1e-9)
    assert axis_alignment(s.points, s.triangles) == pytest.approx(1.0)


@settings(max_examples=12, deadline=None)
@given(a=st.floats(0.6, 2.5), b=st.floats(0.6, 2.5), c=st.floats(0.6, 2.5), tilt=st.floats(0, 45),
       axis=st.integers(0, 2))
def test_the_deformation_turns_normals_to_the_axes(a, b, c, tilt, axis):
    """On turned ellipsoids the heights' normals lie along the axes (alignment near 1, never
    below the surface's own), and the deformation is deterministic."""
    points, triangles = ellipsoid(a, b, c, level=3)
    s = surface_of(turned(points, tilt, axis), triangles)
    h = polycube_heights(s)
    assert axis_alignment(h, s.triangles) > max(0.98, axis_alignment(s.points, s.triangles) - 1e-9)
    assert np.array_equal(h, polycube_heights(s))
    assert np.allclose(h.mean(axis=0), s.points.mean(axis=0))


def test_planes_cut_the_heights_and_measure_the_points():
    """Cutting heights: every new vertex lies on its plane in the heights, and at the same place
    of its edge in the points as in the heights (so areas and normals are the surface's own);
    heights equal to the points cut exactly as the points do."""
    s = surface_of(*torus(2.0, 0.7, 24, 12))
    h = polycube_heights(s)
    plane = Plane(0, float(np.median(h[:, 0])) + 1e-3)
    r = cut(Refined.of(s, h), [plane])
    on = [v for v, planes in enumerate(r.on) if 0 in planes]
    assert on and np.allclose(r.heights[on, 0], r.planes[0].value)
    # every refined vertex has the same barycentric coordinates in its input triangle in the
    # points as in the heights, all of them non-negative: cut in the heights, placed on the surface
    tri = s.triangles[r.parent]
    for k in range(3):
        v = r.triangles[:, k]
        a, b, c = (s.points[tri[:, i]] for i in range(3))
        basis = np.stack([b - a, c - a], axis=2)
        coef = np.array([np.linalg.lstsq(basis[i], r.points[v[i]] - a[i], rcond=None)[0]
                         for i in range(len(v))])
        bary = np.column_stack([1 - coef.sum(axis=1), coef])
        assert bary.min() > -1e-9
        ha, hb, hc = (h[tri[:, i]] for i in range(3))
        assert np.allclose(bary[:, :1] * ha + bary[:, 1:2] * hb + bary[:, 2:] * hc, r.heights[v], atol=1e-9)
    assert abs(r.surface.area - s.area) < 1e-9 * s.area
    plain = cut(Refined.of(s), [Plane(2, 0.1)])
    same = cut(Refined.of(s, s.points.copy()), [Plane(2, 0.1)])
    assert np.array_equal(plain.triangles, same.triangles) and np.allclose(plain.points, same.points)
    assert not plain.deformed and same.deformed


def test_a_section_of_the_heights_reads_as_a_loop_structure():
    """Three curves of the deformed cube's central planes make the cube, sides from heights."""
    s = surface_of(*ellipsoid(2.0, 1.0, 0.7, level=3))
    r, loops, first = candidate_loops(s, 3, polycube_heights(s))
    e = read_structure(r, [loops[i] for i in first])
    assert len(e.region_triangles) == 8 and check_polycube_loop_structure(e.structure).valid


@pytest.mark.parametrize("tilt", [0, 30])
def test_the_grid_start_is_mended_into_a_polycube_loop_structure_on_tori(tilt):
    """The grid start on tori, upright and turned: a polycube loop structure of genus 1, in the
    coordinates and in the deformation alike (turned, the grid as cut breaks Definition 4 and
    is mended)."""
    points, triangles = torus(2.0, 0.7, 24, 12)
    s = surface_of(turned(points, tilt, 0), triangles)
    if tilt:
        r, loops, _ = candidate_loops(s, 5)
        as_cut = read_structure(r, [loops[i] for i in crossing_only(loops, list(range(len(loops))))])
        assert not check_polycube_loop_structure(as_cut.structure).valid
    for heights in (None, polycube_heights(s)):
        r, loops, chosen = grid_start(s, 5, heights)
        e = read_structure(r, [loops[i] for i in chosen])
        assert e.structure.genus == 1 and check_polycube_loop_structure(e.structure).valid
        assert all(isinstance(loops[i], SurfaceLoop) for i in chosen)


def cut_one_slowly(r: Refined, plane: Plane) -> Refined:
    """The triangle-by-triangle twin of the array cut (``refine._cut_one``)."""
    index = len(r.planes)
    sd = r.heights[:, plane.axis] - plane.value
    side = sd > 0
    b = _Builder(r)
    tris, parent = [], []
    keep = []
    for t, tri in enumerate(r.triangles.tolist()):
        s = [bool(side[v]) for v in tri]
        if all(s) or not any(s):
            keep.append(t)
            continue
        k = next(i for i in range(3) if s[i] != s[(i + 1) % 3] and s[i] != s[(i + 2) % 3])
        a, bb, c = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
        p_ab = b.point_on(a, bb, float(sd[a] / (sd[a] - sd[bb])), index)
        p_ca = b.point_on(c, a, float(sd[c] / (sd[c] - sd[a])), index)
        tris += [(a, p_ab, p_ca), (p_ab, bb, c), (p_ab, c, p_ca)]
        parent += [int(r.parent[t])] * 3
    old = [tuple(x) for x in r.triangles[keep].tolist()]
    return b.done(r, old + tris, r.parent[keep].tolist() + parent, (*r.planes, plane))


@settings(max_examples=25, deadline=None)
@given(shape=st.sampled_from(["egg", "torus"]), deform=st.booleans(),
       cuts=st.lists(st.tuples(st.integers(0, 2), st.floats(0.05, 0.95)), min_size=1, max_size=4))
def test_the_array_cut_is_its_triangle_by_triangle_twin(shape, deform, cuts):
    """Cutting plane after plane, the array cut and its slow twin give the same points, heights,
    triangles, parents and planes per vertex."""
    points, triangles = ellipsoid(1.5, 1.0, 0.8, level=2, jitter=0.02, seed=4) if shape == "egg" \
        else torus(2.0, 0.7, 16, 8)
    s = surface_of(points, triangles)
    fast = slow = Refined.of(s, polycube_heights(s, rounds=3) if deform else None)
    for axis, share in cuts:
        lo, hi = fast.heights[:, axis].min(), fast.heights[:, axis].max()
        plane = _clear_of_vertices(fast, Plane(axis, float(lo + share * (hi - lo))))
        fast, slow = _cut_one(fast, plane), cut_one_slowly(slow, plane)
        assert np.array_equal(fast.points, slow.points) and np.array_equal(fast.heights, slow.heights)
        assert np.array_equal(fast.triangles, slow.triangles) and np.array_equal(fast.parent, slow.parent)
        assert fast.on == slow.on and fast.deformed == slow.deformed == deform
