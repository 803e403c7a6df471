"""The array kernels against their tuple twins.

Large maps (from :data:`polyloops.core.arrays.LARGE` darts on) go through numpy and scipy;
small ones through tuples.  Here both run on the same random structures, valid and broken,
and must give the same maps, loops, zones, zone genera and reports.
"""

import importlib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import polyloops.core.arrays as arrays
from polyloops.core.directions import Axis, Direction
from polyloops.core.halfedge import FaceListError, HalfEdgeMap, MapError
from polyloops.core.loops import _trace_loops_arrays, _trace_loops_tuples
from polyloops.core.structure import LabelError, LoopStructure
from polyloops.core.zones import _compute_zones_arrays, _compute_zones_tuples
from polyloops.io.examples import load_example
from polyloops.shapes.builders import box, torus_grid
from polyloops.verify import verify
from polyloops.verify.homology import _zone_genera_arrays, cut_zones
from strategies import grown_structures, handle_zone_polycubes, perturbed_structures, polycubes

# ``polyloops.verify`` the attribute is the function; the module is imported by name.
loop_structure = importlib.import_module("polyloops.verify.loop_structure")

SETTINGS = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def tuple_genera(ls, axis):
    pieces = cut_zones(ls, axis)
    return tuple(pieces[z].genus() for z in sorted(pieces))


@pytest.fixture
def arrays_everywhere(monkeypatch):
    """Every size counts as large, so the array kernels run on small structures too."""
    monkeypatch.setattr(arrays, "LARGE", 0)


def check_map_twins(faces):
    """The array construction gives the tuple map, or declines exactly when the tuple code
    raises (which then names the problems)."""
    fast = HalfEdgeMap._from_valid_faces_arrays([list(f) for f in faces])
    try:
        slow = HalfEdgeMap._from_faces_tuples([list(f) for f in faces])
    except (MapError, FaceListError):
        assert fast is None
        return None
    assert fast is not None
    for name in ("faces", "num_corners", "origin_of", "face_of", "next", "prev", "twin", "face_start"):
        assert getattr(fast, name) == getattr(slow, name), name
    return slow


@SETTINGS
@given(polycubes(), st.randoms(use_true_random=False))
def test_map_construction_twins_on_valid_and_broken_faces(q, seed):
    rng = seed  # a Random that hypothesis drives, so a failure replays and shrinks
    faces = [list(f) for f in q.faces]
    m = check_map_twins(faces)
    assert m is not None
    broken = [list(f) for f in faces]
    kind = rng.randrange(5)
    if kind == 0:
        broken.pop(rng.randrange(len(broken)))  # a hole: boundary edges
    elif kind == 1:
        broken[0] = broken[0][::-1]  # one face flipped
    elif kind == 2:
        broken.append(list(broken[rng.randrange(len(broken))]))  # an edge in three faces
    elif kind == 3:
        broken[1][0] = broken[1][1]  # a corner twice in a face
    else:
        n = q.map.num_corners
        broken += [[c + n for c in f] for f in faces]  # two components
    check_map_twins(broken)


def test_map_twins_on_a_pinched_corner():
    # Two tetrahedra sharing a corner: every edge in two faces, but corner 0 has two fans.
    faces = [[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2], [0, 4, 5], [0, 5, 6], [0, 6, 4], [4, 6, 5]]
    assert check_map_twins(faces) is None


@SETTINGS
@given(polycubes())
def test_loops_zones_and_genera_twins(q):
    ls = q.dualize()
    m = ls.map
    assert _trace_loops_arrays(m) == _trace_loops_tuples(m)
    for axis in Axis:
        assert _compute_zones_arrays(ls, axis) == _compute_zones_tuples(ls, axis)
        assert _zone_genera_arrays(ls, axis) == tuple_genera(ls, axis)


@SETTINGS
@given(handle_zone_polycubes())
def test_genera_twins_where_zones_have_handles(q):
    ls = q.dualize()
    for axis in Axis:
        assert _zone_genera_arrays(ls, axis) == tuple_genera(ls, axis)
    assert any(sum(_zone_genera_arrays(ls, a)) for a in Axis)


def test_genera_twins_on_a_closed_zone():
    ls = torus_grid(3, 3)  # no Z-loops: one closed zone of genus 1
    assert [_zone_genera_arrays(ls, a) for a in Axis] == [tuple_genera(ls, a) for a in Axis]


@SETTINGS
@given(st.one_of(perturbed_structures(), polycubes().map(lambda q: q.dualize())))
def test_reports_are_the_same_with_array_kernels(ls):
    """Definition 3, Definition 4 and Theorem 3 reports, valid or not, are identical."""
    expected = verify(ls).to_json()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(arrays, "LARGE", 0)
        again = LoopStructure(HalfEdgeMap.from_faces(ls.map.faces), ls.axes, ls.signs)
        assert again == ls
        assert verify(again).to_json() == expected


@SETTINGS
@given(polycubes(), st.randoms(use_true_random=False))
def test_edge_label_twins(q, seed):
    ls = q.dualize()
    labels = {(u, v): Direction.parse(lab) for u, v, lab in ls.edge_labels()}
    rng = seed  # a Random that hypothesis drives, so a failure replays and shrinks
    variants = [labels, {k: v.axis for k, v in labels.items()}]
    broken = dict(labels)
    key = rng.choice(list(broken))
    change = rng.randrange(3)
    if change == 0:
        broken[key] = -broken[key]  # sides disagree along a loop
    elif change == 1:
        del broken[key]  # missing
    else:
        broken[(key[1], key[0])] = broken.pop(key)  # same edge, other direction: fine
    variants.append(broken)
    for labelling in variants:
        fast = LoopStructure._from_valid_edge_labels_arrays(ls.map, labelling)
        try:
            slow = LoopStructure._from_edge_labels_tuples(ls.map, labelling)
        except LabelError:
            assert fast is None
            continue
        assert fast == slow


def test_large_structures_use_the_array_kernels_and_agree():
    """Above the threshold the public functions take the array paths; their results equal
    the tuple twins' on a box of about 5,000 faces."""
    q = box(30, 30, 12)
    assert q.map.num_darts >= arrays.LARGE
    ls = q.dualize()
    assert ls.map.loop_system == _trace_loops_tuples(ls.map)
    for axis in Axis:
        assert ls.zones(axis) == _compute_zones_tuples(ls, axis)
    assert verify(ls).valid


def test_examples_under_array_kernels(arrays_everywhere):
    for name in ("cube", "ring", "bridged-ring", "two-axis-holes", "torus-cycle", "double-plus-x",
                 "self-crossing", "degree-two"):
        obj = load_example(name)
        ls = obj.dualize() if hasattr(obj, "dualize") else obj
        rebuilt = LoopStructure(HalfEdgeMap.from_faces(ls.map.faces), ls.axes, ls.signs)
        assert rebuilt == ls


@SETTINGS
@given(st.one_of(polycubes(max_size=8).map(lambda q: q.dualize()),
                 st.sampled_from(["cube", "box-2x1x1", "ring", "two-axis-holes"]).map(
                     lambda name: load_example(name).dualize()),
                 polycubes(max_size=6).map(lambda q: q.dualize().forget_orientation())),
       st.sampled_from(["labelled", "rotation", "full"]))
def test_canonical_forms_are_the_same_with_array_kernels(ls, mode):
    """Same roots, same codes, same automorphism count and chirality; so the same signature."""
    from polyloops.core.canonical import _canonical_form_arrays, canonical_form

    assert _canonical_form_arrays(ls, mode) == canonical_form(ls, mode)


def test_symmetric_boxes_under_array_canonical_forms():
    from polyloops.core.canonical import _canonical_form_arrays, canonical_form

    for q in (box(3, 3, 3), box(4, 2, 2), box(3, 2, 1)):
        ls = q.dualize()
        for mode in ("labelled", "rotation", "full"):
            assert _canonical_form_arrays(ls, mode) == canonical_form(ls, mode)


definition1 = importlib.import_module("polyloops.verify.definition1")


@SETTINGS
@given(polycubes(max_size=8), st.randoms(use_true_random=False))
def test_definition1_reports_are_the_same_with_array_kernels(q, seed):
    """Valid polycubes and ones with a moved corner (bad edges, overlaps, low degree)."""
    from polyloops.core.polycube import Polycube
    from polyloops.verify import check_polycube

    rng = seed  # a Random that hypothesis drives, so a failure replays and shrinks
    positions = [list(p) for p in q.positions]
    if rng.random() < 0.6:
        c = rng.randrange(len(positions))
        positions[c][rng.randrange(3)] += rng.choice((-1, 1))
    moved = Polycube(q.map, tuple(tuple(p) for p in positions))
    expected = check_polycube(moved).to_json()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(arrays, "LARGE", 0)
        assert check_polycube(moved).to_json() == expected


def test_signed_volume_on_arrays_adds_up_like_the_loop():
    """The volume is a sum over faces: the array sum over all faces equals the loop's sum
    over chunks too small for the arrays."""
    from polyloops.core.polycube import signed_volume

    q = box(20, 14, 10)
    faces, pos = q.faces, q.positions
    assert arrays.use_arrays(4 * len(faces))
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(arrays, "LARGE", 10**9)  # the loop, in chunks
        chunks = sum(signed_volume(faces[i:i + 500], pos) for i in range(0, len(faces), 500))
    assert signed_volume(faces, pos) == chunks == 20 * 14 * 10
    flipped = [f[::-1] for f in faces]
    assert signed_volume(flipped, pos) == -chunks


@SETTINGS
@given(polycubes(max_size=8), st.randoms(use_true_random=False))
def test_dualize_twins(q, seed):
    """The same loop structure, or the same refusal, with the array kernel."""
    from polyloops.core.duality import DualityError, dualize
    from polyloops.core.polycube import Polycube

    rng = seed  # a Random that hypothesis drives, so a failure replays and shrinks
    positions = [list(p) for p in q.positions]
    if rng.random() < 0.5:
        positions[rng.randrange(len(positions))][rng.randrange(3)] += 1
    moved = Polycube(q.map, tuple(tuple(p) for p in positions))
    results = []
    for large in (10**9, 0):
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(arrays, "LARGE", large)
            try:
                results.append(dualize(moved))
            except DualityError:
                results.append("refused")
    assert results[0] == results[1]


@SETTINGS
@given(st.one_of(polycubes(max_size=10), handle_zone_polycubes()))
def test_removal_by_reachability_sets_equals_the_search(q):
    """Whether another path joins the ends of a loop's arc, from bit sets computed once,
    agrees with a depth-first search per loop."""
    from polyloops.core import moves, zones

    ls = q.dualize()
    fast = [moves.check_removal(ls, lp.id).valid for lp in ls.loops]
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(zones.LevelArcs, "bypassed", lambda self, axis: None)
        slow = [moves.check_removal(ls, lp.id).valid for lp in ls.loops]
    assert fast == slow


@SETTINGS
@given(st.one_of(perturbed_structures(), polycubes().map(lambda q: q.dualize())))
def test_labels_read_as_arrays_build_the_same_structure(ls):
    """A file's labels arrive as arrays (:class:`EdgeLabels`); the array kernels read them
    directly, the tuple code through the mapping interface: the same structure."""
    from polyloops.io.formats import EdgeLabels, dumps, parse_document

    doc = parse_document(dumps(ls))
    assert isinstance(doc.labels, EdgeLabels)
    fast = LoopStructure._from_valid_edge_labels_arrays(ls.map, doc.labels)
    slow = LoopStructure._from_edge_labels_tuples(ls.map, dict(doc.labels))
    assert fast == slow == ls


@SETTINGS
@given(st.one_of(polycubes(max_size=10).map(lambda q: q.dualize()),
                 polycubes(max_size=6).map(lambda q: q.dualize().forget_orientation())),
       st.sampled_from(["labelled", "full"]))
def test_signature_text_twins(ls, mode):
    """The signature written from arrays is the signature written character by character,
    and reads back to the same structure."""
    import numpy as np

    from polyloops.core import canonical

    form = canonical.canonical_form(ls, mode)
    n = len(form.code) // 3
    w = 1
    while 64 ** w <= n:
        w += 1
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(arrays, "LARGE", 10**9)
        by_characters = canonical._encode(form.code, form.oriented)
    by_arrays = canonical._encode_arrays(np.asarray(form.code), form.oriented, w)
    assert by_arrays == by_characters
    assert canonical.canonical_form(canonical.from_signature(by_arrays), mode) == form


def check_removal_twins(ls):
    """The array removal test gives the loop-by-loop verdict of every loop, wherever it
    applies (oriented, all quads); returns the number of removable loops."""
    from polyloops.core import moves, removal_arrays

    if not removal_arrays.applies(ls):
        return None
    fast = removal_arrays.removable_loops(ls).tolist()
    slow = [moves.check_removal(ls, lp.id).valid for lp in ls.loops]
    assert fast == slow
    return sum(fast)


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(polycubes(max_size=12), handle_zone_polycubes(), grown_structures(max_moves=5),
                 perturbed_structures()))
def test_removal_arrays_give_the_loop_by_loop_verdicts(shape):
    """Valid polycubes of every kind, structures grown by additions, and structures with loops
    flipped or relabelled (so that every condition of the test fails somewhere)."""
    check_removal_twins(shape.dualize() if hasattr(shape, "dualize") else shape)


EXAMPLES_ORIENTED = ("cube", "box-2x1x1", "l-shape", "ring", "non-incremental", "bridged-ring",
                     "two-axis-holes", "self-intersecting", "torus-cycle", "double-plus-x", "self-crossing")


def test_removal_arrays_meet_every_reason():
    """The bundled examples and torus grids with every loop flipped or relabelled in turn, and
    every quadrangulation of the sphere with 16 to 18 vertices under seeded random labels and
    sides: the twins agree on all of them, and the cases include removable loops and loops
    refused for each reason that occurs in them.  (Rungs closing a cycle, and an edge joining a
    merged corner to itself, occur in none of these; the array test decides both by the same
    grouping as the others.)"""
    import random

    from polyloops.core import moves
    from polyloops.generate.plantri.quadrangulations import find_plantri, plantri_batches
    from polyloops.io.planar_code import HEADER, read_planar_code

    def variants(ls):
        yield ls
        for i in range(len(ls.loops)):
            yield ls.flipped(i)
            yield from (ls.relabelled(i, a) for a in Axis if a != ls.axes[i])

    shapes = [v for name in EXAMPLES_ORIENTED for v in variants(oriented(name))]
    shapes += [v for n, k in ((3, 3), (3, 4)) for v in variants(torus_grid(n, k))]
    rng = random.Random(3)
    for n in (16, 17, 18):
        for batch in plantri_batches(n, find_plantri()):
            for m in read_planar_code(HEADER + batch.tobytes()):
                count = len(m.loop_system.loops)
                shapes.append(LoopStructure(m, tuple(rng.choice(list(Axis)) for _ in range(count)),
                                            tuple(rng.choice((1, -1)) for _ in range(count))))
    reasons: set[str] = set()
    for shape in shapes:
        if check_removal_twins(shape) is None:
            continue
        for lp in shape.loops:
            words = moves.check_removal(shape, lp.id).reason.split()
            reasons.add(" ".join(w for w in words if not w.strip("[],").isdigit())[:24])
    assert reasons >= {"", "the loop crosses itself", "merged region would have", "edges would join corners",
                       "face would meet a merged", "two edges would join cor",
                       "the X-graph would get a "}, reasons


def oriented(name):
    x = load_example(name)
    return x if isinstance(x, LoopStructure) else x.dualize()


def _shuffled_file(ls, seed: int) -> str:
    import json

    from strategies import shuffled_document

    return json.dumps(shuffled_document(ls, seed))


@settings(max_examples=15, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(grown_structures(), perturbed_structures()), st.integers(0, 2**16),
       st.booleans())
def test_renumbered_files_give_the_same_reports(tmp_path_factory, ls, seed, large):
    """A structure read from a file in its own numbering and from a shuffled copy: the same
    verdict on every condition, the same signatures and the same removal count, through the
    commands, with the array kernels or the tuple kernels."""
    import json

    from polyloops.cli import main
    from polyloops.io.formats import dumps

    tmp = tmp_path_factory.mktemp("renumbered")
    own, shuffled = tmp / "own.json", tmp / "shuffled.json"
    own.write_text(dumps(ls))
    shuffled.write_text(_shuffled_file(ls, seed))
    saved = arrays.LARGE
    arrays.LARGE = 0 if large else saved
    try:
        outputs = []
        for path in (own, shuffled):
            answers = []
            for command in (["verify"], ["signature", "--symmetry", "labelled"], ["signature"],
                            ["moves", "--remove", "--count"]):
                import contextlib
                import io

                buffer = io.StringIO()
                with contextlib.redirect_stdout(buffer):
                    code = main([command[0], str(path), *command[1:], "--json"])
                data = json.loads(buffer.getvalue()) if buffer.getvalue() else None
                if isinstance(data, dict) and "error" in data:  # the message names the file
                    data = data["status"]
                elif command[0] == "verify" and data is not None:
                    data = [(c["condition"], c["status"]) for c in data["checks"]]
                answers.append((code, data))
            outputs.append(answers)
    finally:
        arrays.LARGE = saved
    assert outputs[0] == outputs[1]
