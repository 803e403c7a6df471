"""The 126 corner configurations: two derivations, symmetry classes, witnesses, the picture."""

import json
from collections import Counter
from fractions import Fraction

import networkx as nx
import pytest
from hypothesis import given

from polyloops.cli import main
from polyloops.core.corners import CATEGORIES, classify, corner_configurations, corner_histogram, transform
from polyloops.core.directions import Direction
from polyloops.core.symmetry import ROTATIONS, SIGNED_PERMUTATIONS, SYMMETRY_MODES
from polyloops.generate.corners import corner_classes, witness
from polyloops.verify import check_polycube, check_polycube_loop_structure
from strategies import perturbed_structures, polycubes


def category_by_shape(cycle):
    """A second way to name the category, from axis multiset and antipodal positions."""
    axes = Counter(d.axis for d in cycle)
    if len(cycle) == 6:
        position = {d: i for i, d in enumerate(cycle)}
        gaps = {(position[-d] - position[d]) % 6 for d in cycle}
        return "symmetric-complex" if gaps == {3} else "asymmetric-complex"
    return {3: "simple", 5: "bent"}.get(len(cycle)) or ("edge" if len(axes) == 3 else "flat")


def perpendicular_cycles():
    """Independent derivation: directed cycles of length >= 3 in the graph on the six
    directions, two joined when perpendicular (each cycle is one cyclic order)."""
    g = nx.DiGraph([(a, b) for a in Direction for b in Direction if a.axis != b.axis])
    return [tuple(c) for c in nx.simple_cycles(g) if len(c) >= 3]


def test_counts_agree_with_perpendicularity_graph():
    configs = corner_configurations()
    cycles = perpendicular_cycles()
    assert len(configs) == len(cycles) == 126
    mine = Counter(c.category for c in configs)
    theirs = Counter(category_by_shape(c) for c in cycles)
    assert mine == theirs
    assert [mine[c] for c in CATEGORIES] == [16, 24, 6, 48, 8, 24]  # the paper's 16+24+6+48+8+24
    assert {classify(c).id for c in cycles} == {c.id for c in configs}


def test_ids_and_canonical_rotations():
    configs = corner_configurations()
    assert [c.id for c in configs] == list(range(126))
    for c in configs:
        rotations = [c.directions[i:] + c.directions[:i] for i in range(c.degree)]
        assert c.directions == min(rotations)
        assert all(classify(r) == c for r in rotations)
        # The reversed order is the mirror image: a different configuration.
        assert classify(tuple(reversed(c.directions))) != c


def burnside(group, members):
    """Number of orbits = average number of fixed points (an independent count)."""
    total = sum(sum(1 for c in members if transform(c, g) == c) for g in group)
    return Fraction(total, len(group))


@pytest.mark.parametrize("symmetry", ["labelled", "rotation", "full"])
def test_classes_match_burnside(symmetry):
    group = SYMMETRY_MODES[symmetry]
    classes = corner_classes(symmetry)
    assert sorted(m for cl in classes for m in cl.members) == list(range(126))
    for cat in CATEGORIES:
        members = [c for c in corner_configurations() if c.category == cat]
        assert burnside(group, members) == sum(1 for cl in classes if cl.category == cat)


def test_group_action():
    configs = corner_configurations()
    g, h = SIGNED_PERMUTATIONS[7], SIGNED_PERMUTATIONS[29]

    def compose(a, b):  # a after b
        from polyloops.core.symmetry import SignedPermutation

        perm = tuple(a.perm[b.perm[i]] for i in range(3))
        signs = tuple(b.signs[i] * a.signs[b.perm[i]] for i in range(3))
        return SignedPermutation(perm, signs)

    for c in configs:
        assert transform(transform(c, g), h) == transform(c, compose(h, g))
        assert transform(c, g).category == c.category
    assert len(ROTATIONS) == 24


@given(polycubes())
def test_every_corner_of_a_random_polycube_classifies_once(q):
    ls = q.dualize()
    for v in range(q.map.num_corners):
        seq = q.corner_directions(v)
        assert ls.corner_directions(v) == seq
        rotations = {seq[i:] + seq[:i] for i in range(len(seq))}
        matches = [c for c in corner_configurations() if c.directions in rotations]
        assert len(matches) == 1
        assert classify(seq) == matches[0]
    ids, cats, unclassified = corner_histogram(q)
    assert unclassified == 0 and sum(cats.values()) == sum(ids.values()) == q.map.num_corners


@given(perturbed_structures())
def test_invalid_corners_do_not_classify(ls):
    # A region of degree >= 3 (random polycubes keep it) is a corner configuration exactly when
    # Condition 3 reports neither the region nor a crossing in one of its faces.
    report = check_polycube_loop_structure(ls)
    bad_regions = {v.witness["region"] for v in report.violations if "region" in v.witness}
    for v in report.violations:
        for f in v.witness.get("faces", [v.witness.get("face")] if "face" in v.witness else []):
            bad_regions.update(ls.map.faces[f])
    for c in range(ls.map.num_corners):
        assert (classify(ls.corner_directions(c)) is None) == (c in bad_regions)


def test_every_configuration_has_a_small_witness():
    for c in corner_configurations():
        found = witness(c)
        assert found is not None
        cells, q = found
        assert 1 <= len(cells) <= 8 and check_polycube(q).valid
        assert c.id in corner_histogram(q)[0]


@pytest.mark.slow
def test_picture_renders_and_is_not_blank(tmp_path):
    import matplotlib.image as mpimg
    import numpy as np

    png = tmp_path / "corners.png"
    assert main(["corners", "--png", str(png)]) == 0
    img = mpimg.imread(png)[..., :3]
    assert img.shape[0] > 500 and img.shape[1] > 500
    coloured = np.any(np.abs(img - 1.0) > 0.1, axis=-1).mean()
    assert 0.05 < coloured < 0.9
    svg = tmp_path / "corners.svg"
    assert main(["corners", "--svg", str(svg)]) == 0
    assert svg.read_text().count("<path") > 126


def test_cli_json(capsys):
    assert main(["corners", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["configurations"]
    assert len(rows) == 126
    for r in rows:
        assert r["category"] in CATEGORIES
        assert r["directions"] == [str(d) for d in corner_configurations()[r["id"]].directions]
    assert main(["corners", "--json", "--symmetry", "full"]) == 0
    answer = json.loads(capsys.readouterr().out)
    assert answer["symmetry"] == "full" and sum(c["size"] for c in answer["classes"]) == 126


def test_info_reports_corner_histogram(capsys):
    assert main(["info", "example:l-shape", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert sum(data["corner_categories"].values()) == data["corners"]
    assert set(data["corner_categories"]) == set(CATEGORIES)


@pytest.mark.parametrize("mode", ["labelled", "rotation", "full"])
def test_classes_by_burnside_and_by_sympy_orbits(mode):
    """Three derivations of the number of corner classes agree: walking orbits
    (corner_classes), the orbits sympy finds of the group acting on the 126 ids, and Burnside's
    average number of fixed configurations."""
    from polyloops.generate.corners import burnside_count, corner_action

    G = corner_action(mode)
    orbits = sorted(sorted(o) for o in G.orbits())
    assert orbits == sorted(sorted(c.members) for c in corner_classes(mode))
    assert burnside_count(mode) == len(orbits)
    assert G.order() == len(SYMMETRY_MODES[mode])


def test_the_symmetry_groups_are_the_hyperoctahedral_group_and_its_rotations():
    from polyloops.core.symmetry import symmetry_group

    full, rotation = symmetry_group("full"), symmetry_group("rotation")
    assert (full.order(), rotation.order()) == (48, 24)
    # The rotations: a normal subgroup of index 2; the centre of the full group is the
    # central inversion and the identity.
    assert rotation.is_normal(full) and full.order() // rotation.order() == 2
    assert not full.is_abelian and full.center().order() == 2  # {identity, central inversion}
