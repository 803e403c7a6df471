"""``segment --start``: a given loop structure embedded on a surface by plane sections."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from polyloops.catalog.census import shipped_class
from polyloops.cli import main
from polyloops.core.canonical import is_isomorphic, transformed
from polyloops.core.symmetry import Symmetry
from polyloops.io.examples import load_example
from polyloops.segment.embedded import read_structure
from polyloops.segment.run import segment_mesh
from polyloops.segment.search import StartError
from polyloops.segment.start import StartMismatch, embed_start, start_levels
from polyloops.segment.surface import surface_of
from polyloops.segmentation import check_segmentation
from polyloops.shapes.builders import ring
from polyloops.shapes.meshes import ellipsoid, torus
from polyloops.verify import as_loop_structure


def turned_torus(hole: int):
    """A torus whose hole runs along axis ``hole``."""
    points, triangles = torus(2.0, 0.7, 32, 16)
    return np.roll(points, hole - 2, axis=1), triangles


def read_back(surface, start):
    """Where the start was placed, and the structure read off the surface there."""
    r, loops, placed = embed_start(surface, start)
    return placed, read_structure(r, [loops[i] for i in placed.curves]).structure


@pytest.mark.parametrize(("name", "hole"), [("ring", 0), ("ring", 2), ("ring-x", 1), ("ring-x", 0)])
def test_the_ring_is_embedded_on_a_torus_whatever_the_axis_of_either_hole(name, hole):
    """The curves chosen make exactly the start, turned by the reported symmetry: labels,
    sides and the rotation system (labelled isomorphism), so every loop lies in its class."""
    start = as_loop_structure(load_example(name))
    placed, read = read_back(surface_of(*turned_torus(hole)), start)
    assert is_isomorphic(read, transformed(start, placed.symmetry), Symmetry.LABELLED)
    assert placed.symmetry.axis(2 if name == "ring" else 0) == hole  # the hole went where the torus's is


@settings(max_examples=4, deadline=None)
@given(st.floats(0.6, 2.5), st.floats(0.6, 2.5), st.floats(0.6, 2.5), st.integers(0, 99))
def test_the_cube_and_the_box_are_embedded_on_ellipsoids(a, b, c, seed):
    surface = surface_of(*ellipsoid(a, b, c, level=2, jitter=0.02, seed=seed))
    for start in (load_example("cube").dualize(), load_example("box-2x1x1").dualize()):
        placed, read = read_back(surface, start)
        assert is_isomorphic(read, transformed(start, placed.symmetry), Symmetry.LABELLED)


def test_a_segmentation_from_the_catalogs_smallest_torus_is_certified():
    done = segment_mesh(*torus(2.0, 0.7, 32, 16), budget=2.0, start=shipped_class("T32.1"))
    assert done.certified and done.genus == 1 and check_segmentation(done.mesh).valid is True
    assert done.start.startswith("the given start, turned by")


def test_a_start_of_another_genus_or_no_polycube_structure_is_refused():
    with pytest.raises(StartMismatch, match="the start has genus 1 and the mesh genus 0"):
        embed_start(surface_of(*ellipsoid(1, 1, 1, level=2)), as_loop_structure(ring()))
    with pytest.raises(StartMismatch, match="no polycube loop structure"):
        embed_start(surface_of(*torus()), load_example("torus-cycle"))


def test_a_start_no_plane_section_reproduces_is_reported_not_forced():
    """A ring with a bridge over it: a round torus has no plane sections that make it."""
    with pytest.raises(StartError, match="not found among plane sections"):
        embed_start(surface_of(*torus(2.0, 0.7, 24, 12)), as_loop_structure(load_example("bridged-ring")),
                    grids=(5,), budget=1.0)


def test_levels_are_the_middles_of_what_each_loops_segments_span():
    levels = start_levels(as_loop_structure(ring()))
    assert [[(lv.value, lv.loops) for lv in axis] for axis in levels] == [
        [(1 / 6, 1), (0.5, 2), (5 / 6, 1)], [(1 / 6, 1), (0.5, 2), (5 / 6, 1)], [(0.5, 2)]]


def test_segment_command_takes_a_start_and_refuses_one_of_another_genus(tmp_path, capsys):
    labels = tmp_path / "t.labels"
    assert main(["segment", "example:torus", "--start", "T32.1", "--budget", "2", "-o", str(labels),
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["certified"] is True and data["start"].startswith("the given start")
    for mesh, start, words in (("sphere", "T32.1", "the start has genus 1 and the mesh genus 0"),
                               ("sphere", "P99.1", "no class P99.1"),
                               ("torus", "example:torus-cycle", "no polycube loop structure"),
                               ("sphere", "sig:1o?", "sig:1o?"),
                               ("sphere", str(tmp_path / "none.json"), "cannot read")):
        assert main(["segment", f"example:{mesh}", "--start", start]) == 2, start
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and words in err[0], err
