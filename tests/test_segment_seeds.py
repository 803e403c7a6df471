"""Seeds of ``polyloops segment``: a valid labelling's own loops, drawn on the surface through
its map onto the realising polycube (:mod:`polyloops.segment.seeds`)."""

from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from polyloops.core.canonical import is_isomorphic
from polyloops.core.directions import Direction
from polyloops.core.duality import dualize
from polyloops.io.labelled_mesh import read_triangle_mesh
from polyloops.segment.embedded import read_structure
from polyloops.segment.labellings import graphcut_labels
from polyloops.segment.search import StartError
from polyloops.segment.seeds import polycube_map, seed_start
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.shapes.builders import ring
from polyloops.shapes.meshes import _subdivide, sphere
from polyloops.surface.construct import labelled_mesh_from_polycube
from polyloops.surface.mesh import LabelledMesh
from polyloops.verify import check_polycube_loop_structure
from strategies import polycubes


def _wobbled(q, times: int, amount: float):
    """``q``'s surface subdivided ``times`` and wobbled by ``amount``, labelled by its faces'
    normals (each triangle keeps its face's label), with the checker's report."""
    m = labelled_mesh_from_polycube(q)
    points, triangles = np.array(m.points, dtype=float), np.array(m.triangles)
    labels = list(m.labels)
    for _ in range(times):
        points, triangles = _subdivide(points, triangles)
        labels = [d for d in labels for _ in range(4)]
    points = points + amount * np.sin(3 * points[:, [1, 2, 0]])
    mesh = LabelledMesh(tuple(map(tuple, points.tolist())), tuple(map(tuple, triangles.tolist())),
                        tuple(labels))
    return surface_of(points, triangles), labels, check_segmentation(mesh)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(polycubes(max_size=5), st.integers(0, 1), st.sampled_from([0.0, 0.05]))
def test_a_valid_labellings_loops_are_recovered_as_its_polycubes(q, times, amount):
    """The seed drawn from a valid labelling is the loop structure of the polycube that realises
    it (up to isomorphism): the structure is recovered, not approximated."""
    s, labels, report = _wobbled(q, times, amount)
    assert report.valid is True or amount > 0
    assume(report.valid is True)  # a wobble the checker does not pass is no seed
    r, loops, chosen, _ = seed_start(s, labels, "face", report)
    found = read_structure(r, [loops[i] for i in chosen]).structure
    assert is_isomorphic(found, dualize(report.polycube))


@settings(max_examples=15, deadline=None)
@given(polycubes(max_size=5))
def test_the_map_puts_each_chart_on_its_level_and_stays_between_the_levels(q):
    """Per axis, a chart labelled along it lies at its polycube face's level, and every other
    vertex between the lowest and highest level of its neighbours (the maximum principle of
    positive weights): on the polycube's own surface, each corner at its place."""
    s, _, report = _wobbled(q, 1, 0.0)
    heights = polycube_map(s, report)
    seg, cube = report.segmentation, report.polycube
    for chart in seg.charts:
        a = int(chart.label.axis)
        vs = np.unique(s.triangles[list(chart.triangles)])
        assert np.ptp(heights[vs, a]) < 1e-9
    for corner in seg.corners:
        assert np.allclose(heights[corner.vertex], cube.positions[corner.id])
    for a in range(3):
        lo, hi = min(p[a] for p in cube.positions), max(p[a] for p in cube.positions)
        assert lo - 1e-9 <= heights[:, a].min() and heights[:, a].max() <= hi + 1e-9


def test_a_genus_one_labellings_loops_are_recovered():
    s, labels, report = _wobbled(ring(), 1, 0.03)
    r, loops, chosen, how = seed_start(s, labels, "face", report)
    found = read_structure(r, [loops[i] for i in chosen]).structure
    assert found.genus == 1 and is_isomorphic(found, dualize(report.polycube))
    assert how == "the loops of the valid face labelling"


def test_an_invalid_labelling_gives_no_seed():
    s = surface_of(*sphere(2))
    labels = [Direction.PX] * len(s.triangles)  # one label everywhere: one chart, no corner
    with pytest.raises(StartError, match="not valid"):
        seed_start(s, labels)


SHARED = Path(__file__).resolve().parents[2] / "shared" / "meshes"


@pytest.mark.slow
@pytest.mark.skipif(not SHARED.is_dir(), reason="../shared/meshes is not here")
def test_every_valid_graph_cut_labelling_of_the_shared_meshes_gives_back_its_loops():
    """On each shared mesh whose graph-cut labelling the checker finds valid, the seed is a
    polycube loop structure, and at genus 0 and 1 the realising polycube's own (at higher
    genus a map onto a face that is not convex may fold, and two of its level sets cross where
    the loops do not: mending then makes another structure, as on the genus-2 dtorus)."""
    seeded = 0
    for path in sorted(SHARED.glob("*/*.stl")):
        points, triangles = read_triangle_mesh(path)
        s = surface_of(np.array(points, dtype=float), np.array(triangles))
        labels = graphcut_labels(s)
        report = check_segmentation(LabelledMesh(tuple(map(tuple, s.points.tolist())),
                                                 tuple(map(tuple, s.triangles.tolist())), labels))
        if report.valid is not True:
            continue
        r, loops, chosen, _ = seed_start(s, labels, "graph-cut", report)
        found = read_structure(r, [loops[i] for i in chosen]).structure
        assert check_polycube_loop_structure(found).valid, path.name
        if s.genus <= 1:
            assert is_isomorphic(found, dualize(report.polycube)), path.name
        seeded += 1
    assert seeded >= 20
