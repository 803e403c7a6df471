"""JSON and OBJ formats."""

import json

import pytest
from hypothesis import given

from polyloops.core.halfedge import MapError
from polyloops.core.structure import LabelError
from polyloops.io.examples import load_example
from polyloops.io.formats import FormatError, dumps, loads, parse_document, to_obj
from strategies import perturbed_structures, polycubes


@given(polycubes())
def test_polycube_round_trip(q):
    assert loads(dumps(q)) == q


@given(perturbed_structures())
def test_loop_structure_round_trip(ls):
    assert loads(dumps(ls)) == ls
    labelled = ls.forget_orientation()
    assert loads(dumps(labelled)) == labelled


def test_obj():
    text = to_obj(load_example("cube"))
    assert text.count("\nv ") == 8 and text.count("\nf ") == 6


def cube_data():
    return json.loads(dumps(load_example("cube")))


def ls_data():
    return json.loads(dumps(load_example("cube").dualize()))


@pytest.mark.parametrize("mutate, error, words", [
    (lambda d: "{", FormatError, "not valid JSON"),
    (lambda d: {**d, "positions": [[0.5, 0, 0], *d["positions"][1:]]}, FormatError, "non-integer"),
    (lambda d: {**d, "faces": [d["faces"][0] + [1], *d["faces"][1:]]}, FormatError, "quads"),
    (lambda d: {**d, "kind": "mesh"}, FormatError, '"kind"'),
    (lambda d: {**d, "polyloops": 7}, FormatError, "version"),
    (lambda d: {**d, "faces": d["faces"][:-1]}, MapError, "lies in 1 faces"),
])
def test_bad_polycube_files(mutate, error, words):
    data = mutate(cube_data())
    text = data if isinstance(data, str) else json.dumps(data)
    with pytest.raises(error, match=words):
        loads(text)


def _relabel_one(d, label):
    d["edges"][0][2] = label
    return d


@pytest.mark.parametrize("mutate, error, words", [
    (lambda d: _relabel_one(d, "+W"), FormatError, "unknown label"),
    (lambda d: {**d, "edges": d["edges"][1:]}, LabelError, "missing"),
    (lambda d: _relabel_one(d, "+Z" if d["edges"][0][2][1] != "Z" else "+X"), LabelError, "disagree"),
    (lambda d: _relabel_one(d, "-" + d["edges"][0][2][1] if d["edges"][0][2][0] == "+"
                            else "+" + d["edges"][0][2][1]), LabelError, "signs disagree"),
    (lambda d: _relabel_one(d, d["edges"][0][2][1]), LabelError, "signed"),
    (lambda d: {**d, "edges": [*d["edges"], [0, 7, "+X"]]}, LabelError, "not an edge"),
])
def test_bad_loop_structure_files(mutate, error, words):
    with pytest.raises(error, match=words):
        loads(json.dumps(mutate(ls_data())))


def test_document_keeps_kind():
    assert parse_document(dumps(load_example("ring"))).kind == "polycube"


def test_each_format_is_one_row_that_knows_its_own_output():
    """A format is one row of the registry (reader, writer, how its content looks): what a row
    writes, sniffing recognises as that row, and its reader reads back."""
    from polyloops.io.examples import load_example
    from polyloops.io.registry import FORMATS, parse_bytes, sniff

    cube = load_example("cube")
    for fmt in FORMATS:
        if fmt.writer is None or fmt.looks is None:
            continue
        data = fmt.writer(cube)
        data = data.encode() if isinstance(data, str) else data
        assert sniff(data) is fmt, fmt.name
        assert parse_bytes(data, fmt).faces, fmt.name
