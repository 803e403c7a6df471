"""The room for constructors of segmentations: what they build comes with the checker's report,
and nothing uncertified is handed out."""

import pytest
from hypothesis import given

from polyloops.segment.from_polycube import UncertifiedError, certified_from_polycube
from polyloops.segmentation import check_segmentation
from polyloops.shapes.builders import box
from strategies import polycubes


@given(polycubes(max_size=6))
def test_a_polycube_labelled_by_its_normals_is_certified(q):
    done = certified_from_polycube(q)
    assert done.report.valid is True and done.report.polycube is not None
    assert check_segmentation(done.mesh).valid is True  # the checker, called again on the output
    assert len(done.mesh.triangles) == 2 * q.map.num_faces
    assert [done.mesh.labels[2 * f] for f in range(q.map.num_faces)] == [q.face_normal(f)
                                                                         for f in range(q.map.num_faces)]


@pytest.mark.parametrize("verdict", [False, None])
def test_what_the_checker_does_not_pass_is_refused_not_handed_out(verdict, monkeypatch):
    import polyloops.segment.from_polycube as constructor

    class Report:
        valid = verdict
        reason = "a stand-in verdict"

    monkeypatch.setattr(constructor, "check_segmentation", lambda mesh: Report())
    word = "invalid" if verdict is False else "undecided"
    with pytest.raises(UncertifiedError, match=f"checker finds this labelling {word}"):
        certified_from_polycube(box(2, 1, 1))
