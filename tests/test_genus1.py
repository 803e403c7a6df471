"""The genus-1 catalog and its certificate: package data, every class the moves reach from the
three rings within its range, and the conjecture checked within each hole-orientation type."""

import json
from pathlib import Path

import pytest

from polyloops.catalog.census import default_catalog, read_catalog
from polyloops.cli import main
from polyloops.core.canonical import canonical_form, from_signature
from polyloops.io.examples import load_example
from polyloops.reach.conjecture import (
    ConjectureError,
    certificate_kind,
    check_certificate,
    complete_range,
    orientation_type,
)
from polyloops.reach.search import explore, stored_signatures
from shipped import small_catalog

G1 = default_catalog(1)
CERT = G1 / "reachability-certificate.jsonl"


def reached(name: str, max_corners: int, tmp: Path) -> list[str]:
    """The classes (up to all symmetries) the moves reach from an example within a bound."""
    explore(load_example(name).dualize(), max_corners, directory=tmp / name, mode="full")
    return stored_signatures(tmp / name)


@pytest.mark.slow
def test_the_shipped_genus_one_certificate_checks():
    """The certificate settles every class of the shipped genus-1 catalog within its type but
    the open ones, all with the catalog's most corners, so it proves every class below reachable
    (the default run checks the range through 36: the doctest of ``Certificate.check``)."""
    census = read_catalog(G1)
    top = complete_range(census, 1)
    check = check_certificate(CERT.read_text().splitlines(), G1)
    assert check.valid and check.genus == 1 and check.checked_corners == top >= 32
    assert check.records == len(census.entries)
    assert all(c.corners == top for c in check.open) and check.proven_corners >= top - 1


@pytest.mark.parametrize("whole", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_every_class_the_rings_reach_is_in_the_catalog(whole, tmp_path):
    """Within the catalog's range (through 41 corners in the default run), the classes reached
    from the rings along X, Y and Z are catalog classes (one family: the three rings are one
    class up to symmetry), the ring is the smallest, and each class keeps the ring's
    orientation type."""
    census = read_catalog(G1)
    top = complete_range(census, 1) if whole else 41
    catalog = {e.signature: e for e in census.entries}
    ring_type = orientation_type(load_example("ring").dualize())
    for name in ("ring", "ring-x", "ring-y"):
        found = reached(name, top, tmp_path)
        assert found and set(found) <= set(catalog)
        assert all(orientation_type(from_signature(sig)) == ring_type for sig in found)
    smallest = min(e.corners for e in census.entries)
    ring = canonical_form(load_example("ring").dualize(), "full").signature
    assert catalog[ring].corners == smallest == 32 and catalog[ring].name == "T32.1"


def test_identify_names_the_ring(capsys):
    assert main(["identify", "example:ring-x", "--catalog", str(G1)]) == 0
    assert "T32.1" in capsys.readouterr().out


@pytest.mark.parametrize("top", [38, pytest.param(47, marks=pytest.mark.slow)])
def test_conjecture_genus1_writes_the_shipped_certificate(top, tmp_path, capsys):
    """The command writes the shipped certificate's records again through ``top`` corners
    (slow: through 47, about two minutes; the 48-corner classes take hours), every class there
    settled within the shipped slack."""
    shipped = CERT.read_text().splitlines()
    slack = json.loads(shipped[0])["slack"]  # the detours the shipped one allowed
    out = tmp_path / "cert.jsonl"
    argv = ["conjecture", "genus1", "--catalog", str(G1), "--max-corners", str(top), "--slack", str(slack),
            "-o", str(out)]
    assert main(argv) == 0
    within = [line for line in shipped[1:] if json.loads(line)["corners"] <= top]
    assert out.read_text().splitlines()[1:] == within and within
    assert main(["conjecture", "check", str(out), "--catalog", str(G1)]) == 0
    assert "reachable from the base class of its hole-orientation type" in capsys.readouterr().out
    # a genus-0 catalog is refused by the genus-1 command, and the other way round
    assert main(["conjecture", "genus1", "--catalog", str(default_catalog(0)), "--max-corners", "20",
                 "-o", str(tmp_path / "x.jsonl")]) == 2
    assert "genus 0, not 1" in capsys.readouterr().err


ZERO = "XY: rank 0; XZ: rank 0; YZ: rank 0"


@pytest.fixture(scope="module", params=[40, pytest.param(44, marks=pytest.mark.slow)],
                ids=["through 40", "whole"])
def extended(request):
    """The shipped catalog and certificate (through 40 corners in the default run, whole with
    --run-slow: the claims are the same, the check four times cheaper), two classes one
    addition above the ring, and the base of the type whose invariants are all zero (no loop
    runs round the hole, as in the bridged ring) with another class of that type, settled by a
    detour."""
    catalog = small_catalog(request.param, genus=1)
    lines = (catalog / "reachability-certificate.jsonl").read_text().splitlines()
    records = [json.loads(line) for line in lines[1:]]
    above = [r["signature"] for r in records if r["corners"] == 36][:2]
    zero = [r for r in records if r["orientation"] == ZERO]
    base = next(r["signature"] for r in zero if r.get("base"))
    other = next(r["signature"] for r in zero if "detour" in r)
    return catalog, lines, above, base, other


def _edit(lines: list[str], signature: str, **changes) -> list[str]:
    out = []
    for line in lines:
        data = json.loads(line)
        if data.get("signature") == signature:
            data = {k: v for k, v in {**data, **changes}.items() if v is not None}
        out.append(json.dumps(data))
    return out


def test_the_bases_are_the_smallest_class_of_each_type(extended):
    """Two orientation types, two bases: the ring, and a class of the type whose invariants
    are all zero, whose smallest members (the bridged ring among them) have 40 corners; the
    classes above the ring have removable loops."""
    catalog, lines, above, base, _ = extended
    check = check_certificate(lines, catalog)
    assert check.valid, check.problems
    records = {json.loads(line)["signature"]: json.loads(line) for line in lines[1:]}
    assert records[base].get("base") is True and records[base]["corners"] == 40
    assert min(r["corners"] for r in records.values() if r["orientation"] == ZERO) == 40
    assert sum(bool(r.get("base")) for r in records.values()) == 2
    bridged = canonical_form(load_example("bridged-ring").dualize(), "full").signature
    assert records[bridged]["orientation"] == ZERO
    assert records[base]["orientation"] != records[above[0]]["orientation"]
    assert all("removable" in records[sig] for sig in above)
    assert json.loads(lines[0])["kind"] == certificate_kind(1)


def test_a_genus_one_certificate_claims_only_what_it_checked(extended):
    """A wrong orientation, a base that is not the smallest of its type, a second base, or a
    class left unsettled is a problem; a genus-0 header on a genus-1 catalog is refused."""
    catalog, lines, above, _, other = extended
    wrong = _edit(lines, above[0], orientation=ZERO)
    assert "states orientation" in str(check_certificate(wrong, catalog).problems[0])
    not_smallest = _edit(lines, above[0], base=True, removable=None)
    assert "is a base" in str(check_certificate(not_smallest, catalog).problems[0])
    second = _edit(lines, other, base=True, detour=None)
    assert not check_certificate(second, catalog).valid
    unsettled = _edit(lines, other, detour=None, unsettled=True)
    assert "unsettled" in str(check_certificate(unsettled, catalog).problems[0])
    header = {**json.loads(lines[0]), "kind": certificate_kind(0)}
    with pytest.raises(ConjectureError, match="genus 1, not 0"):
        check_certificate([json.dumps(header), *lines[1:]], catalog)


@pytest.mark.slow
def test_the_gallery_walks_to_the_base_of_each_orientation(tmp_path):
    """A genus-1 gallery: each class page leads to the base of its orientation type (no class
    of genus 1 reaches the cube), and the move graph starts at the certificate's bases."""
    from polyloops.reach.move_graph import move_graph

    graph = move_graph(read_catalog(G1))
    assert graph.bases[0] == "T32.1" and len(graph.bases) == 2 and graph.genus == 1
    assert graph.path_from_cube("T32.1") == ("T32.1",)
    assert main(["gallery", str(G1), "-o", str(tmp_path / "site"), "--limit", "12"]) == 0
    page = (tmp_path / "site" / "class" / "T32.1.html").read_text()
    assert "base of its hole orientation (T32.1)" in page and "the cube" not in page
    assert "base of its hole orientation" in (tmp_path / "site" / "index.html").read_text()


@pytest.mark.slow  # about 30 s with two workers
def test_the_shipped_genus_one_catalog_rebuilds_byte_for_byte_through_38(tmp_path):
    """A run of the torus generator through 38 corners writes the shipped records of 32 to 38
    corners line for line, byte for byte, and the same counts (of every mode)."""
    out = tmp_path / "g1"
    assert main(["catalog", "--genus", "1", "--max-corners", "38", "--workers", "2", "-o", str(out)]) == 0
    shipped = json.loads((G1 / "summary.json").read_text())
    mine = json.loads((out / "summary.json").read_text())
    assert mine["counts"] == {k: v for k, v in shipped["counts"].items() if int(k) <= 38}
    theirs = [line for line in (G1 / "catalog.jsonl").read_bytes().splitlines()
              if json.loads(line)["corners"] <= 38]
    assert (out / "catalog.jsonl").read_bytes().splitlines() == theirs and theirs


@pytest.fixture(scope="module")
def open_at_2():
    """The genus-1 catalog through 40 corners, and its classes settled at slack 2 (the
    irreducible ones left open, searched to +2)."""
    from polyloops.reach.conjecture import settle_catalog

    catalog = small_catalog(40, genus=1)
    return catalog, settle_catalog(catalog, 40, 2)


def test_a_genus_one_run_resumes_from_earlier_records(monkeypatch, open_at_2):
    """Through 40 corners at slack 2 the irreducible classes stay open (searched to +2); a run
    at slack 4 from those records takes their orientation types instead of computing them,
    searches the open classes from +4 alone, and writes what a run at slack 4 from nothing
    writes."""
    from polyloops.reach import conjecture
    from polyloops.reach.conjecture import certificate_lines, read_records, settle_catalog

    catalog, low = open_at_2
    assert low.unsettled and all(r.searched == 2 for r in low.unsettled)
    records = read_records(certificate_lines(low))
    typed = []
    real = conjecture._orientation_job
    monkeypatch.setattr(conjecture, "_orientation_job", lambda sig: typed.append(sig) or real(sig))
    again = settle_catalog(catalog, 40, 4, earlier=records)
    assert typed == [] and all(r.searched == 4 for r in again.unsettled)
    monkeypatch.undo()
    assert list(certificate_lines(again)) == list(certificate_lines(settle_catalog(catalog, 40, 4)))


def test_long_detours_settle_what_the_breadth_first_search_left_open(open_at_2):
    """Through 40 corners at slack 2 the irreducible classes stay open; the long search within
    +10 (``--long 10``) settles some of them.  Each such record keeps the slack searched in vain
    (2), peaks where its slack says and replays within the header's slack; the breadth-first
    search finds no detour within +2 (the record's claim), and its own detours (the shipped
    certificate's, the least) are never longer.  A record whose ``searched`` reaches its own
    detour's slack is refused."""
    from polyloops.core.canonical import from_signature
    from polyloops.reach.conjecture import (
        Bases,
        certificate_lines,
        check_record,
        find_detour,
        read_records,
        settle_catalog,
    )

    catalog, low = open_at_2
    opened = {r.signature for r in low.unsettled}
    shipped = {r.signature: r for r in read_records((catalog / "reachability-certificate.jsonl").read_text()
                                                    .splitlines())}
    # the bridged ring's least detour is +12, beyond this search: its shipped record is taken (4 s saved)
    earlier = [shipped[r.signature] if (shipped[r.signature].slack or 0) > 10 else r
               for r in read_records(certificate_lines(low))]
    result = settle_catalog(catalog, 40, 2, earlier=earlier, long=10)
    long = [r for r in result.records if r.signature in opened and r.settled and r.searched == 2]
    assert len(long) == 3 and result.slack == max(r.slack for r in result.records if r.slack)
    for r in long:
        base = next(b for b in result.records if b.base and b.orientation == r.orientation)
        target = base.signature if r.corners == base.corners else None
        assert r.searched == 2 and r.slack > 2 and r.detour_peak() == r.slack == r.max_corners - r.corners
        assert find_detour(from_signature(r.signature), r.corners + 2, target) is None
        assert shipped[r.signature].slack <= r.slack  # the shipped detours are breadth-first: least
    based = [b for b in result.records if b.base]
    assert based and all(b.orientation is not None for b in based)
    bases = Bases({b.orientation: b.corners for b in based}, {b.orientation: b.signature for b in based})
    for r in long:  # replayed (the whole certificate of this catalog is checked elsewhere)
        assert check_record(r.to_json(), 40, result.slack, bases) is None
    data = long[0].to_json()
    data["searched"] = data["detour"]["slack"]
    assert "states that no detour within" in (check_record(data, 40, result.slack) or "")
