"""Cubes whose boundary is not a polycube get a diagnosis that names cubes and positions, tells a
cavity from separate pieces, and suggests repairs that work; ``--coarsen`` removes the loops
that only subdivide flat faces."""

import pytest
from hypothesis import given

import polyloops as pl
from polyloops.cli import main
from polyloops.core.moves import check_removal
from polyloops.shapes.coarsen import coarsen, in_flat_band
from polyloops.shapes.voxels import VoxelError, _bad_corners, diagnose_voxels, polycube_from_voxels
from polyloops.verify import verify
from strategies import voxel_sets


@given(voxel_sets(max_size=12))
def test_a_diagnosis_exactly_when_the_boundary_is_no_polycube(cells):
    why = diagnose_voxels(cells)
    try:
        polycube_from_voxels(cells)
    except VoxelError as err:
        assert why is not None and str(err) == why
    else:
        assert why is None


@given(voxel_sets(max_size=12))
def test_every_suggested_repair_mends_its_corner(cells):
    why = diagnose_voxels(cells) or ""
    if "meets itself at the position" not in why:
        return
    position = eval(why.split("at the position ")[1].split(")")[0] + ")")
    assert position in _bad_corners(set(cells))
    for words in why.split(": ", 1)[1].removesuffix(" to mend it").split(" or "):
        cell = eval(words.split("the cube ")[1])
        changed = set(cells) ^ {cell}
        assert ("remove" in words) == (cell in cells)
        assert position not in _bad_corners(changed)


def test_pieces_and_cavities_are_told_apart():
    apart = diagnose_voxels([(0, 0, 0), (2, 0, 0), (5, 5, 5)])
    assert apart.startswith("the cubes form 3 pieces") and "(0, 0, 0)" in apart
    shell = {(x, y, z) for x in range(4) for y in range(3) for z in range(3)}
    hollow = shell - {(1, 1, 1), (2, 1, 1)}
    assert "a cavity of 2 empty cells, (1, 1, 1), (2, 1, 1)" in diagnose_voxels(hollow)
    assert diagnose_voxels(shell) is None


def ring_cells(nx: int, ny: int, nz: int) -> list[tuple[int, int, int]]:
    return [(x, y, z) for x in range(nx) for y in range(ny) for z in range(nz)
            if not (0 < x < nx - 1 and 0 < y < ny - 1)]


def test_a_sampled_ring_coarsens_to_the_square_ring():
    q = polycube_from_voxels(ring_cells(3, 3, 2))
    assert q.map.num_corners == 48
    c = coarsen(q.dualize())
    assert verify(c.structure).valid and c.structure.map.num_corners == 32
    assert pl.identify(c.structure).name == "T32.1"


@given(voxel_sets(max_size=10))
def test_coarsening_keeps_a_valid_structure_and_every_bend(cells):
    try:
        ls = polycube_from_voxels(cells).dualize()
    except VoxelError:
        return
    c = coarsen(ls)
    assert verify(c.structure).valid and c.structure.genus == ls.genus
    assert len(c.structure.loops) == len(ls.loops) - c.removed
    # nothing more goes by the same rule, unless the removal test refuses it
    assert not any(in_flat_band(c.structure, lp.id) and check_removal(c.structure, lp.id).valid
                   for lp in c.structure.loops)


def test_from_voxels_coarsen_writes_the_identified_ring(tmp_path, capsys):
    path = tmp_path / "ring.txt"
    path.write_text("".join(f"{x} {y} {z}\n" for x, y, z in ring_cells(3, 3, 2)))
    out = tmp_path / "ring.json"
    assert main(["from-voxels", str(path), "--coarsen", "-o", str(out)]) == 0
    line = capsys.readouterr().out
    assert "32 corners" in line and "2 loops removed" in line, line  # the middle layers of x and y
    assert main(["identify", str(out)]) == 0
    assert "T32.1" in capsys.readouterr().out


@pytest.mark.parametrize("flag", [[], ["--coarsen"]])
def test_from_voxels_json_is_one_object(flag, tmp_path, capsys):
    import json

    path = tmp_path / "l.txt"
    path.write_text("0 0 0\n1 0 0\n0 1 0\n")
    assert main(["from-voxels", str(path), *flag, "-o", str(tmp_path / "l.json"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["cubes"] == 3 and data["corners"] == 16
    assert ("removed loops" in data) == bool(flag)
