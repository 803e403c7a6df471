"""Labelled segmentations: charts, local criteria, the global test and the realising polycube.

Oracles: labellings of real polycubes (their normals) must pass and give back polycubes with
the same charts; the chart view of the 126 corners must equal what segmenting every 2x2x2
block of cubes shows; the SAT verdict must equal a brute force over all boundary directions.
"""

from collections import Counter
from itertools import product
from pathlib import Path

import networkx as nx
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.core.corners import canonical_rotation
from polyloops.core.directions import Direction
from polyloops.core.polycube import Polycube
from polyloops.generate.corners import OCTANT_CELLS, chart_corners
from polyloops.io.examples import EXAMPLES, LABELLED_EXAMPLES, labelled_mesh_example, load_example
from polyloops.io.labelled_mesh import labels_text, triangle_obj_text
from polyloops.io.meshes import write_triangle_mesh
from polyloops.segmentation import check_segmentation, segment
from polyloops.segmentation.levels import chart_angles, check_global, corner_rule, corner_zones
from polyloops.shapes.builders import box
from polyloops.shapes.voxels import VoxelError, polycube_from_voxels
from polyloops.surface.construct import labelled_mesh_from_polycube
from polyloops.surface.mesh import LabelledMesh
from polyloops.verify import check_polycube
from strategies import polycubes

VALID_POLYCUBES = sorted(n for n, e in EXAMPLES.items() if e.valid and isinstance(load_example(n), Polycube))


def chart_structure(seg, chart_map=None):
    """Labels of charts, and the multiset of (left, right) chart pairs of boundaries and of
    cyclic chart sequences around corners, with charts renamed by ``chart_map``."""
    name = (lambda c: c) if chart_map is None else chart_map.__getitem__
    labels = {name(c.id): c.label for c in seg.charts}
    boundaries = Counter((name(b.left), name(b.right)) for b in seg.boundaries)
    corners = Counter(canonical_rotation([name(ch) for _, _, ch in c.sides]) for c in seg.corners)
    return labels, boundaries, corners


def assert_realises_same_charts(report):
    """The realising polycube passes Definition 1, and segmenting it by its own normals gives
    the same charts, boundaries and corners (charts matched through its quads)."""
    q = report.polycube
    assert q is not None and check_polycube(q).valid and q.signed_volume() > 0
    again = segment(labelled_mesh_from_polycube(q))
    # Quad f became triangles 2f and 2f+1; chart_of_face says which input chart it realises.
    chart_map = {}
    for f, c in enumerate(report.realisation.chart_of_face):
        new = again.chart_of_triangle[2 * f]
        assert chart_map.setdefault(new, c) == c
    assert sorted(chart_map.values()) == list(range(len(report.segmentation.charts)))
    assert chart_structure(again, chart_map) == chart_structure(report.segmentation)


@pytest.mark.parametrize("name", VALID_POLYCUBES)
def test_bundled_polycubes_labelled_by_their_normals_are_valid(name):
    report = check_segmentation(labelled_mesh_from_polycube(load_example(name)))
    assert report.local.valid and report.global_.valid and report.valid
    assert_realises_same_charts(report)


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(polycubes(max_size=12))
def test_labellings_of_real_polycubes_pass_and_come_back(q):
    report = check_segmentation(labelled_mesh_from_polycube(q))
    assert report.local.valid, report.local.violations
    assert report.global_.valid is True
    assert report.valid is True, report.reason
    assert_realises_same_charts(report)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(polycubes(kinds=("blob", "frame1"), max_size=8))
def test_the_solver_finds_directions_without_the_mesh(q):
    """The SAT path (not the mesh's own directions) accepts every real polycube's labels, and
    its directions pass the direct check."""
    seg = segment(labelled_mesh_from_polycube(q))
    result = check_global(seg, try_mesh_first=False)
    assert result.valid is True
    from polyloops.segmentation.levels import satisfies

    assert satisfies(seg, result.zones, result.directions)


def brute_force_verdict(seg) -> bool:
    """Some directions meet every corner rule and chart turning number with acyclic level
    graphs: tried one by one (networkx for the cycles)."""
    rules = [corner_rule(seg, c.id) for c in seg.corners]
    zones = [corner_zones(seg, axis) for axis in range(3)]
    angles = [(chart, chart_angles(seg, chart.id)) for chart in seg.charts]
    axis_of = [seg.boundary_axis(b.id) for b in seg.boundaries]
    for signs in product((1, -1), repeat=len(seg.boundaries)):
        if any(tuple(signs[b] for b in bs) not in set(ok) for bs, ok in rules):
            continue
        turning_ok = True
        for chart, chart_angles_ in angles:
            reflex = 0
            for b2, f2, b, f in chart_angles_:
                d = Direction.of(axis_of[b], signs[b] if f else -signs[b])
                d2 = Direction.of(axis_of[b2], signs[b2] if f2 else -signs[b2])
                # reflex: d2 is d turned clockwise, seen from the chart's label
                normal = [d.vector[1] * d2.vector[2] - d.vector[2] * d2.vector[1],
                          d.vector[2] * d2.vector[0] - d.vector[0] * d2.vector[2],
                          d.vector[0] * d2.vector[1] - d.vector[1] * d2.vector[0]]
                reflex += tuple(normal) != chart.label.vector
            if len(chart_angles_) - 2 * reflex != 4 * chart.euler_characteristic:
                turning_ok = False
                break
        if not turning_ok:
            continue
        acyclic = True
        for axis in range(3):
            g = nx.MultiDiGraph()
            g.add_nodes_from(set(zones[axis]))
            for b in seg.boundaries:
                if axis_of[b.id] == axis:
                    u, v = zones[axis][b.start], zones[axis][b.end]
                    g.add_edge(*((u, v) if signs[b.id] > 0 else (v, u)))
            if not nx.is_directed_acyclic_graph(g):
                acyclic = False
                break
        if acyclic:
            return True
    return False


SMALL = [box(1, 1, 1), box(2, 1, 1), load_example("l-shape")]


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(range(len(SMALL))), st.lists(st.tuples(st.integers(0, 63), st.sampled_from(Direction)),
                                                   min_size=1, max_size=3))
def test_sat_agrees_with_brute_force_on_relabelled_shapes(which, changes):
    q = SMALL[which]
    labels = [q.face_normal(f) for f in range(q.map.num_faces)]
    for f, d in changes:
        labels[f % len(labels)] = d
    seg = segment(labelled_mesh_from_polycube(q, labels))
    assume(len(seg.boundaries) <= 14)
    result = check_global(seg, try_mesh_first=False)
    assume(result.valid is not None)  # opposite labels or closed boundaries: no arcs to test
    if result.witness is not None and result.witness.kind == "arc-inside-zone":
        assert not brute_force_verdict(seg)
    else:
        assert result.valid == brute_force_verdict(seg)


def test_chart_corners_equal_what_blocks_of_cubes_show():
    """Independent derivation: segment the polycube of every set of cubes in a 2x2x2 block,
    read each corner's boundaries off the mesh's coordinates and the charts' labels, and
    collect them; they must be the chart view of the 126 configurations."""
    seen = set()
    for mask in range(1, 256):
        cells = [c for bit, c in enumerate(OCTANT_CELLS) if mask >> bit & 1]
        try:
            q = polycube_from_voxels(cells)
        except VoxelError:
            continue
        seg = segment(labelled_mesh_from_polycube(q))
        mesh = seg.mesh
        for corner in seg.corners:
            pairs = []
            for b, forward, chart in corner.sides:
                bd = seg.boundaries[b]
                other = bd.vertices[1] if forward else bd.vertices[-2]
                p, r = mesh.points[corner.vertex], mesh.points[other]
                axis = next(k for k in range(3) if p[k] != r[k])
                pairs.append((Direction.of(axis, 1 if r[axis] > p[axis] else -1), seg.charts[chart].label))
            seen.add(canonical_rotation(pairs))
    assert seen == set(chart_corners())


def test_sokolov_ramp_passes_local_criteria_and_fails_globally():
    report = check_segmentation(labelled_mesh_example("sokolov-ramp"))
    seg = report.segmentation
    assert report.local.valid
    # two charts facing up and two facing down, as in the paper's description
    normal_to_z = Counter(c.label for c in seg.charts if c.label.axis == 2)
    assert normal_to_z == {Direction.PZ: 2, Direction.NZ: 2}
    # every corner has three charts of three axes: Eppstein and Mumford's conditions hold
    assert all(len(c.sides) == 3 and len({seg.charts[ch].label.axis for _, _, ch in c.sides}) == 3
               for c in seg.corners)
    assert report.global_.valid is False and report.valid is False
    witness = report.global_.witness
    assert witness.kind == "no-directions" and (witness.corners or witness.turning)
    # The same charts labelled by the mesh's normals (three up, one down) are a polycube.
    mesh = labelled_mesh_example("sokolov-ramp")
    q = polycube_from_voxels([(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 0, 1), (2, 0, 1)])
    assert check_segmentation(labelled_mesh_from_polycube(q)).valid
    assert len(mesh.triangles) == 2 * q.map.num_faces


def witness_is_unsatisfiable(seg, corners, charts) -> bool:
    """z3, independently of the SAT encoding: the rules of these corners and the turning
    numbers of these charts have no common solution."""
    import z3

    x = [z3.Bool(f"b{b.id}") for b in seg.boundaries]
    sign = [z3.If(v, 1, -1) for v in x]
    solver = z3.Solver()
    for c in corners:
        bs, ok = corner_rule(seg, c)
        solver.add(z3.Or([z3.And([x[b] if s > 0 else z3.Not(x[b]) for b, s in zip(bs, signs, strict=True)])
                          for signs in ok]))
    for chart_id in charts:
        chart = seg.charts[chart_id]
        angles = chart_angles(seg, chart_id)
        reflex = []
        for b2, f2, b, f in angles:
            # reflex exactly when (d x d2) is minus the label; d x d2 flips with either sign
            axis, axis2 = seg.boundary_axis(b), seg.boundary_axis(b2)
            base = Direction.of(3 - axis - axis2, 1 if (axis2 - axis) % 3 == 1 else -1)
            same = (base == chart.label) == (f == f2)  # with both signs +1: is d x d2 the label?
            product_ = sign[b] * sign[b2]
            reflex.append(z3.If(product_ == (1 if same else -1), 0, 1))
        solver.add(len(angles) - 2 * z3.Sum(reflex) == 4 * chart.euler_characteristic if reflex
                   else z3.BoolVal(len(angles) == 4 * chart.euler_characteristic))
    return solver.check() == z3.unsat


def test_the_witness_is_a_certificate_and_minimal():
    seg = segment(labelled_mesh_example("sokolov-ramp"))
    witness = check_global(seg).witness
    assert witness is not None and not witness.cycles
    corners, charts = list(witness.corners), list(witness.turning)
    assert witness_is_unsatisfiable(seg, corners, charts)
    for c in corners:
        assert not witness_is_unsatisfiable(seg, [k for k in corners if k != c], charts)
    for ch in charts:
        assert not witness_is_unsatisfiable(seg, corners, [k for k in charts if k != ch])


def test_overhang_is_valid_with_a_different_polycube():
    report = check_segmentation(labelled_mesh_example("overhang"))
    assert report.valid is True
    assert_realises_same_charts(report)


@pytest.mark.parametrize("name", sorted(LABELLED_EXAMPLES))
def test_shipped_labelled_meshes_match_their_builders(name):
    built = LABELLED_EXAMPLES[name].build()
    shipped = labelled_mesh_example(name)
    assert shipped.triangles == built.triangles and shipped.labels == built.labels
    assert shipped.points == built.points
    assert LABELLED_EXAMPLES[name].valid == check_segmentation(shipped).valid


@pytest.mark.parametrize("change", ["top faces down", "all reversed"])
def test_wrong_signs_on_a_cube_fail_only_globally(change):
    """Labels of the right axes but wrong signs pass every local criterion; the turning
    numbers of the charts rule them out (all reversed: the cube inside out)."""
    q = load_example("cube")
    labels = [q.face_normal(f) for f in range(6)]
    if change == "top faces down":
        labels = [Direction.NZ if d == Direction.PZ else d for d in labels]
    else:
        labels = [-d for d in labels]
    report = check_segmentation(labelled_mesh_from_polycube(q, labels))
    assert report.local.valid
    assert report.global_.valid is False and report.global_.witness.turning


def test_a_chart_bent_over_an_edge():
    q = load_example("cube")
    labels = [q.face_normal(f) for f in range(6)]
    labels[labels.index(Direction.PZ)] = Direction.PX  # the top joins the +X side
    report = check_segmentation(labelled_mesh_from_polycube(q, labels))
    rules = {v.rule for v in report.local.violations}
    assert {"opposite-labels", "few-boundaries", "corner"} <= rules
    assert report.valid is False and report.global_.valid is None


def test_opposite_labels_across_a_boundary():
    q = box(2, 1, 1)
    labels = [q.face_normal(f) for f in range(q.map.num_faces)]
    # One of the two +Y quads becomes -Y: it borders the other +Y quad.
    f = next(f for f, d in enumerate(labels) if d == Direction.PY)
    labels[f] = Direction.NY
    report = check_segmentation(labelled_mesh_from_polycube(q, labels))
    assert "opposite-labels" in {v.rule for v in report.local.violations}
    assert report.valid is False and report.global_.valid is None


# -- files and the command line -----------------------------------------------------------

def write_pair(tmp_path, mesh: LabelledMesh, suffix: str):
    path = tmp_path / f"shape{suffix}"
    write_triangle_mesh(path, mesh)
    labels = tmp_path / "shape.labels"
    labels.write_text(labels_text(mesh))
    return str(path), str(labels)


@pytest.mark.parametrize("suffix", [".obj", ".stl", ".mesh"])
def test_cli_reads_every_mesh_format(suffix, tmp_path, capsys):
    mesh = labelled_mesh_from_polycube(load_example("l-shape"))
    path, labels = write_pair(tmp_path, mesh, suffix)
    out = tmp_path / "back.json"
    assert main(["segmentation", path, labels, "-o", str(out), "--json"]) == 0
    import json

    data = json.loads(capsys.readouterr().out)
    assert data["valid"] is True and data["local"]["valid"] and data["global"]["valid"]
    assert data["charts"] == 8 and out.exists()
    assert main(["verify", str(out)]) == 0


def test_cli_exit_codes_and_picture(tmp_path, capsys):
    assert main(["segmentation", "example:sokolov-ramp", "--png", str(tmp_path / "s.png")]) == 1
    text = capsys.readouterr().out
    assert "local criteria: pass" in text and "global test (level graphs): FAIL" in text
    assert (tmp_path / "s.png").stat().st_size > 1000
    assert main(["segmentation", "example:overhang"]) == 0
    assert main(["segmentation", "example:ring", "--json"]) == 0


@pytest.mark.parametrize("mesh_text, labels_text_, where, words", [
    ("v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n", "0\n", "shape.obj", "line 3"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1\n", "0\n", "shape.obj", "line 4: a face must be a triangle"),
    (None, "0\nseven\n", "shape.labels", "line 2"),
    (None, "0\n9\n", "shape.labels", "line 2: label 9"),
    (None, "0\n", "shape.labels", "1 labels for 12 triangles"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "0\n", "shape.obj", "not a closed oriented surface"),
    ("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n", "0\n", "shape.stl",
     "line 5: vertex"),
    ("solid x\nfacet normal 0 0 1\nouter loop\nvortex 0 0 0\n", "0\n", "shape.stl", "line 4: unexpected"),
    ("MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0 0\n", "0\n", "shape.mesh", "shape.mesh"),
    ("solid x\nendsolid x\n", "0\n", "shape.stl", "has no triangles"),
])
def test_cli_bad_files_name_the_file_and_line(mesh_text, labels_text_, where, words, tmp_path, capsys):
    suffix = "." + where.split(".")[-1] if where != "shape.labels" else ".obj"
    mesh_path = tmp_path / f"shape{suffix}"
    if mesh_text is None:
        mesh_path.write_text(triangle_obj_text(labelled_mesh_from_polycube(load_example("cube"))))
    else:
        mesh_path.write_text(mesh_text)
    labels = tmp_path / "shape.labels"
    labels.write_text(labels_text_)
    assert main(["segmentation", str(mesh_path), str(labels)]) == 2
    err = capsys.readouterr().err.strip()
    assert where in err and words in err and "\n" not in err and "Traceback" not in err


def test_cli_needs_labels(tmp_path, capsys):
    assert main(["segmentation", "example:nope"]) == 2
    assert "example:nope" in capsys.readouterr().err
    path = tmp_path / "a.obj"
    path.write_text("v 0 0 0\n")
    assert main(["segmentation", str(path)]) == 2
    assert "LABELS" in capsys.readouterr().err


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(polycubes(kinds=("blob", "frame1"), max_size=6), st.lists(st.sampled_from(Direction), min_size=1),
       st.randoms(use_true_random=False))
def test_any_labelling_gets_a_verdict_and_a_valid_verdict_is_backed(q, palette, seed):
    """Random labels (drawn from a random palette, so that some charts merge) never crash the
    check; a valid verdict always comes with a polycube that realises the same charts, and a
    global failure always with a witness."""

    rng = seed  # a Random that hypothesis drives, so a failure replays and shrinks
    labels = [rng.choice(palette) if rng.random() < 0.3 else q.face_normal(f) for f in range(q.map.num_faces)]
    report = check_segmentation(labelled_mesh_from_polycube(q, labels))
    assert report.valid in (True, False, None)
    if report.valid:
        assert_realises_same_charts(report)
    if report.global_.valid is False:
        assert report.global_.witness is not None
    if report.valid is None:
        assert report.reason


@st.composite
def obj_lines(draw):
    """Lines of a small OBJ triangle mesh, sometimes with one odd line put in (anything a file
    may hold: comments, other keywords, other polygons, bad or forward references)."""
    number = st.sampled_from(["0", "1", "-2.5", "3e2", "0.1", "7"])
    n = draw(st.integers(1, 6))
    lines = ["v " + " ".join(draw(st.lists(number, min_size=3, max_size=3))) for _ in range(n)]
    index = st.integers(1, n).map(str)
    lines += ["f " + " ".join(draw(st.lists(index, min_size=3, max_size=3)))
              for _ in range(draw(st.integers(0, 5)))]
    odd = st.sampled_from(["", "# note", "vn 0 0 1", "  v 1 2 3", "v\t1\t2\t3", "f 1 2 3 4", "f 1 2",
                           "v 1 2", "v 1 2 3 1", "o thing", "f  1  2  3", "f -1 -2 -3", "f 1/1 2/2 3/3",
                           "v 1e999 0 0", "v nan 0 0", "f 0 1 2", "f 1 2 99", "v x 0 0", "f", "v"])
    for _ in range(draw(st.integers(0, 2))):
        lines.insert(draw(st.integers(0, len(lines))), draw(odd))
    return lines


@settings(max_examples=300, deadline=None)
@given(lines=obj_lines())
def test_numpy_obj_reader_agrees_with_the_line_reader(lines):
    """Where the numpy reader takes a text, the line-by-line reader reads the same vertices
    and triangles from it; where the line reader refuses a text, the numpy reader does too."""
    from polyloops.io.exchange import ExchangeError, obj_polygons, obj_triangles

    text = "\n".join(lines) + "\n"
    fast = obj_triangles(text)
    try:
        points, faces = obj_polygons(text)
    except ExchangeError:
        assert fast is None
        return
    if fast is None:
        return
    assert fast[0].tolist() == [list(p) for p in points]
    assert fast[1].tolist() == [ids for _, ids in faces]


@pytest.mark.parametrize("change", ["top faces down", "all reversed"])
def test_the_picture_reddens_the_charts_the_witness_names(change):
    """A witness made of charts' turning numbers alone: those charts are drawn tinted red."""
    from polyloops.render.segmentation import hot_parts

    q = load_example("cube")
    labels = [q.face_normal(f) for f in range(6)]
    labels = ([Direction.NZ if d == Direction.PZ else d for d in labels] if change == "top faces down"
              else [-d for d in labels])
    report = check_segmentation(labelled_mesh_from_polycube(q, labels))
    charts, boundaries = hot_parts(report)
    assert report.global_.witness.turning and set(report.global_.witness.turning) <= charts
    assert set(report.global_.witness.all_boundaries()) <= boundaries


DUALCUBE = Path(__file__).resolve().parents[2] / "shared" / "segmentations" / "dualcube"


@pytest.mark.skipif(not DUALCUBE.is_dir(), reason="../shared/segmentations/dualcube is not here")
@pytest.mark.parametrize("name", ["bunny", "plane"])
def test_dualcubes_bunny_and_plane_are_decided(name):
    """DualCube's shipped bunny and plane are realised (the plane's top is a chart whose holes
    lie outside its outer boundary in the mesh's own projection, so the order of its zones must
    leave the mesh's), each time by the same polycube."""
    from polyloops.io.labelled_mesh import read_labelled_mesh

    mesh = read_labelled_mesh(DUALCUBE / f"{name}.obj", DUALCUBE / f"{name}.flag")
    first, again = check_segmentation(mesh), check_segmentation(mesh)
    assert first.valid is True and first.polycube.positions == again.polycube.positions
