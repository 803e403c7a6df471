"""The level start of ``polyloops segment`` and the run over several starts: on a polycube's own
surface the sections between consecutive levels are its loops; a run keeps the best-scoring
certified start, the same with one worker or two, and reports every start's terms."""

import csv
import io
import json

import numpy as np
import pytest
from hypothesis import given, settings

from cli_run import run
from polyloops.cli import main
from polyloops.core.canonical import canonical_form
from polyloops.segment.labellings import naive_label_indices
from polyloops.segment.levels import level_grid, level_planes, levels
from polyloops.segment.run import Candidate, segment_mesh
from polyloops.segment.starts import recipes
from polyloops.segment.surface import surface_of
from polyloops.shapes.coarsen import coarsen, coarsen_polycube
from polyloops.shapes.meshes import ellipsoid
from polyloops.surface.construct import labelled_mesh_from_polycube
from strategies import polycubes


def _surface(q):
    m = labelled_mesh_from_polycube(q)
    return surface_of(np.array(m.points, dtype=float), np.array(m.triangles))


@settings(max_examples=25, deadline=None)
@given(polycubes(max_size=6))
def test_on_a_polycube_the_level_start_is_its_loop_structure_up_to_flat_bands(q):
    """Every section between consecutive levels is taken, the structure is a polycube loop
    structure as cut (nothing to mend), it has no more loops than the polycube's own, and
    removing the loops in flat bands gives what it gives on the polycube's own structure."""
    s = _surface(q)
    g = level_grid(s)
    assert g.violations == 0 and sorted(g.chosen) == list(range(len(g.loops)))
    assert len(g.chosen) <= len(q.dualize().loops)
    assert canonical_form(coarsen(g.embedded.structure).structure, "labelled") == canonical_form(
        coarsen_polycube(q).structure, "labelled")


@settings(max_examples=25, deadline=None)
@given(polycubes(max_size=6))
def test_the_levels_of_a_polycube_are_its_face_planes(q):
    """A polycube's levels along an axis are exactly the coordinates of its faces normal to it,
    and each plane lies halfway between two consecutive ones; grouping charts instead of
    triangles changes nothing there."""
    s = _surface(q)
    found = levels(s, s.points)
    for a in range(3):
        faces = sorted({float(q.positions[face[0]][a]) for f, face in enumerate(q.faces)
                        if int(q.face_normal(f).axis) == a})
        assert [lo for lo, hi, _ in found[a]] == faces == [hi for lo, hi, _ in found[a]]
    planes = sorted((p.axis, p.value) for p in level_planes(s, s.points))
    assert planes == sorted((a, (lower[0] + upper[0]) / 2) for a in range(3)
                            for lower, upper in zip(found[a], found[a][1:], strict=False))
    # a polycube's charts are flat, each at its face's level: the charts of its own labels
    # (and of the naive labelling, the same there) give the same levels and planes
    labels = naive_label_indices(s)
    assert [[(lo, hi) for lo, hi, _ in lv] for lv in levels(s, s.points, labels=labels)] == [
        [(lo, hi) for lo, hi, _ in lv] for lv in found]
    assert sorted((p.axis, p.value) for p in level_planes(s, s.points, labels=labels)) == planes


def _ellipsoid_run(workers: int):
    points, triangles = ellipsoid(2.0, 1.0, 0.7, level=1)
    return segment_mesh(points, triangles, budget=60, workers=workers, direct=False)


def test_a_run_keeps_the_best_scoring_start():
    """Every start is tried and reported; the result is the certified start of best score
    (fidelity less the loops' price)."""
    one = _ellipsoid_run(1)
    assert [c.start for c in one.candidates] == [r.name for r in recipes(0)]
    certified = [c for c in one.candidates if c.certified]
    assert certified and [c.kept for c in one.candidates].count(True) == 1
    kept = next(c for c in one.candidates if c.kept)
    assert kept.score == max(c.score for c in certified) and kept.start == one.start
    assert kept.score == pytest.approx(one.fidelity - 0.001 * one.loops) == pytest.approx(one.score)
    for c in certified:
        assert c.score == pytest.approx(c.fidelity - c.price * c.loops) and c.loops >= 3
        assert c.estimate is not None
    assert one.converged


@pytest.mark.slow  # about 12 s
def test_two_workers_give_the_rows_and_labels_of_one():
    """With every search converged, two worker processes give the same rows and labels as one."""
    one, two = _ellipsoid_run(1), _ellipsoid_run(2)
    assert one.converged and two.converged
    strip = [(c.start, c.certified, c.fidelity, c.loops, c.score, c.estimate, c.charts, c.kept)
             for c in one.candidates]
    assert strip == [(c.start, c.certified, c.fidelity, c.loops, c.score, c.estimate, c.charts, c.kept)
                     for c in two.candidates]
    assert one.mesh.labels == two.mesh.labels


@pytest.mark.slow  # about 30 s
def test_a_higher_price_asks_fewer_loops():
    points, triangles = ellipsoid(2.0, 1.0, 0.7, level=2)
    cheap = segment_mesh(points, triangles, budget=60, direct=False, price=0.0)
    dear = segment_mesh(points, triangles, budget=60, direct=False, price=0.05)
    assert dear.loops <= cheap.loops and dear.fidelity <= cheap.fidelity + 1e-12


def test_segment_writes_the_score_of_every_start(tmp_path, capsys):
    out = tmp_path / "scores.csv"
    assert main(["segment", "example:egg", "--budget", "1", "--workers", "2", "--score-csv", str(out),
                 "--merge", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    assert tuple(rows[0]) == Candidate.FIELDS and len(rows) >= 1 and data["score_csv"] == str(out)
    kept = [r for r in rows if r["kept"] == "True"]
    assert len(kept) == 1 and kept[0]["start"] == data["start"]
    assert float(kept[0]["fidelity"]) == pytest.approx(data["fidelity"], abs=1e-6)
    for r in rows:
        if r["certified"] == "True":
            wanted = float(r["fidelity"]) - 0.001 * int(r["loops"])
            assert float(r["score"]) == pytest.approx(wanted, abs=2e-6)
        else:
            assert r["reason"]


@pytest.mark.parametrize("args, problem", [
    (["--price", "-1"], "--price -1.0"), (["--price", "nan"], "--price nan"),
    (["--workers", "0"], "--workers"), (["--score-csv", "/no/such/dir/s.csv"], "/no/such/dir"),
])
def test_segment_refuses_bad_scores_and_workers(args, problem, capsys):
    status, _, err = run(capsys, "segment", "example:egg", *args)
    assert status == 2
    assert problem in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_without_a_cube_near_the_centre_every_level_curve_is_taken_at_once(monkeypatch):
    """Where the curves nearest the centre make no cube, the level start takes every curve that
    crosses another at once: on a polycube's surface, the same structure."""
    import polyloops.segment.levels as lv
    from polyloops.io.examples import load_example
    from polyloops.segment.search import StartError

    s = _surface(load_example("l-shape"))
    usual = level_grid(s)

    def no_cube(r, loops):
        raise StartError("no three section curves make a cube (a stand-in)")

    monkeypatch.setattr(lv, "start_state", no_cube)
    fallback = level_grid(s)
    assert fallback.violations == 0 and len(fallback.chosen) == len(usual.chosen)
    assert canonical_form(fallback.embedded.structure, "labelled") == canonical_form(
        usual.embedded.structure, "labelled")



def test_the_two_sides_of_a_thin_plate_are_two_levels():
    """A 3 x 3 plate 0.005 thick under a unit column (a polycube with its Z layers moved to 0,
    0.005 and 1): its bottom and top face opposite ways and are two levels, though 0.5% of the
    height apart (under the 1% gap), so a plane cuts the plate's rim; two faces facing one way
    that close (the plate's top and the column's, layers at 0.995 and 1) stay one level."""
    from polyloops.shapes.voxels import polycube_from_voxels

    q = polycube_from_voxels([(i, j, 0) for i in range(3) for j in range(3)] + [(1, 1, 1)])
    m = labelled_mesh_from_polycube(q)
    points = np.array(m.points, dtype=float)
    points[:, 2] = np.array([0.0, 0.005, 1.0])[points[:, 2].astype(int)]
    s = surface_of(points, np.array(m.triangles))
    assert [(lo, hi) for lo, hi, _ in levels(s, s.points)[2]] == [(0.0, 0.0), (0.005, 0.005), (1.0, 1.0)]
    assert sorted(p.value for p in level_planes(s, s.points) if p.axis == 2) == [0.0025, 0.5025]
    # the same top faces, 0.5% apart: one level (a gentle step, not two sides of a plate)
    points[:, 2] = np.array([0.0, 0.995, 1.0])[np.array(m.points)[:, 2].astype(int)]
    s = surface_of(points, np.array(m.triangles))
    assert [(lo, hi) for lo, hi, _ in levels(s, s.points)[2]] == [(0.0, 0.0), (0.995, 1.0)]
