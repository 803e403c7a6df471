"""A certificate claims only what was checked: `conjecture check` compares the header with the
catalog's complete range, checks every field it prints, and reports bad records by line."""

import json
import re
import shutil

import pytest

from polyloops.catalog.census import read_catalog
from polyloops.catalog.run import build_catalog, write_census
from polyloops.cli import main
from polyloops.reach.conjecture import (
    ConjectureError,
    certificate_lines,
    check_certificate,
    settle_catalog,
)
from shipped import REAL, small_catalog

SHIPPED = small_catalog(30)  # the checks of refusals replay this smaller copy
CERT = SHIPPED / "reachability-certificate.jsonl"


def shipped_lines() -> list[str]:
    return CERT.read_text().splitlines()


def with_header(lines: list[str], **changes) -> list[str]:
    header = json.loads(lines[0])
    header.update(changes)
    return [json.dumps(header), *lines[1:]]


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def write(tmp_path, lines: list[str]) -> str:
    path = tmp_path / "cert.jsonl"
    path.write_text("\n".join(lines) + "\n")
    return str(path)


@pytest.mark.parametrize("beyond", [1, 10**12])
def test_a_header_claiming_more_than_the_catalog_fails(tmp_path, capsys, beyond):
    top = json.loads(shipped_lines()[0])["max_corners"]
    claim = top + beyond
    cert = write(tmp_path, with_header(shipped_lines(), max_corners=claim))
    status, out, _ = run(capsys, "conjecture", "check", cert, "--catalog", str(SHIPPED))
    assert status == 1
    assert f"through {claim} corners" in out and f"only through {top}" in out
    assert f"through {top} corners" in out  # the range actually checked is printed
    assert "valid: every" not in out


@pytest.mark.parametrize("claim", [-5, 0, 30.0, "30", True, None, "1e999"])
def test_non_positive_or_non_integer_bounds_are_bad_input(tmp_path, capsys, claim):
    value = float("inf") if claim == "1e999" else claim
    lines = with_header(shipped_lines(), max_corners=value)
    if claim == "1e999":
        lines[0] = lines[0].replace("Infinity", "1e999")
    status, out, err = run(capsys, "conjecture", "check", write(tmp_path, lines), "--catalog", str(SHIPPED))
    assert status == 2 and "max_corners" in err and err.count("\n") == 1 and out == ""


@pytest.mark.parametrize("catalog", [pytest.param(REAL, marks=pytest.mark.slow), SHIPPED],
                         ids=["shipped", "cut at 30"])
def test_the_shipped_certificate_states_its_range(capsys, catalog):
    cert = catalog / "reachability-certificate.jsonl"
    status, out, _ = run(capsys, "conjecture", "check", str(cert), "--catalog", str(catalog), "--json")
    data = json.loads(out)
    top = max(int(n) for n in json.loads((catalog / "summary.json").read_text())["counts"])
    assert status == 0 and data["valid"]
    assert data["checked_corners"] == data["catalog_corners"] == data["max_corners"] == top


def test_a_smaller_claim_checks_only_its_range():
    lines = shipped_lines()
    cut = [lines[0]] + [line for line in lines[1:] if json.loads(line)["corners"] <= 20]
    check = check_certificate(with_header(cut, max_corners=20, classes=len(cut) - 1), SHIPPED)
    assert check.valid and check.checked_corners == 20


def detour_index(lines: list[str]) -> int:
    return next(i for i, line in enumerate(lines) if '"detour"' in line)


@pytest.mark.parametrize("field,value,words", [
    ("slack", 6, "slack 6 is not max_corners"),
    ("max_corners", 36, "slack 8 is not max_corners 36"),
    ("max_corners", float("inf"), "must be integers"),
    ("slack", 12, "slack 12"),
])
def test_every_detour_field_is_checked(field, value, words):
    lines = shipped_lines()
    i = detour_index(lines)
    record = json.loads(lines[i])
    record["detour"][field] = value
    if field == "slack" and value == 12:
        record["detour"]["max_corners"] = record["corners"] + 12
    lines[i] = json.dumps(record)
    problems = check_certificate(lines, SHIPPED).problems
    assert [p.line for p in problems] == [i + 1] and words in problems[0].message, problems


@pytest.mark.parametrize("signature", [["a", "list"], {"an": "object"}, 17, None])
def test_records_with_a_strange_signature_are_bad_records(tmp_path, capsys, signature):
    lines = shipped_lines()
    record = json.loads(lines[2])
    record["signature"] = signature
    lines[2] = json.dumps(record)
    status, out, err = run(capsys, "conjecture", "check", write(tmp_path, lines), "--catalog", str(SHIPPED))
    assert status == 1 and "line 3" in out and "internal error" not in err


def test_records_with_huge_or_odd_numbers_are_bad_records(tmp_path, capsys):
    lines = shipped_lines()
    for i, (key, value) in enumerate([("corners", "1e999"), ("removable", "1e999"), ("corners", "true")]):
        record = json.loads(lines[2 + i])
        text = json.dumps({**record, key: "X"}).replace('"X"', value)
        lines[2 + i] = text
    status, out, err = run(capsys, "conjecture", "check", write(tmp_path, lines), "--catalog", str(SHIPPED),
                           "--json")
    data = json.loads(out)
    assert status == 1 and "internal error" not in err
    assert [p.split(" ")[1] for p in data["problems"][:3]] == ["3", "4", "5"]


def test_missing_classes_are_named(tmp_path):
    lines = shipped_lines()
    i = detour_index(lines)
    check = check_certificate([*lines[:i], *lines[i + 1:]], SHIPPED)
    missing = [p for p in check.problems if p.line == 0]
    assert [str(p).split(":")[0] for p in missing] == ["P26.20"]


def test_not_a_certificate_is_bad_input(tmp_path, capsys):
    with pytest.raises(ConjectureError):
        check_certificate(['{"kind": "something else", "max_corners": 8, "slack": 2}'], SHIPPED)
    cert = write(tmp_path, ["not json"])
    status, _, err = run(capsys, "conjecture", "check", cert, "--catalog", str(SHIPPED))
    assert status == 2 and err.count("\n") == 1


def test_genus0_beyond_the_catalog_is_refused(tmp_path, capsys):
    top = max(int(n) for n in json.loads((SHIPPED / "summary.json").read_text())["counts"])
    status, _, err = run(capsys, "conjecture", "genus0", "--catalog", str(SHIPPED), "--max-corners",
                         str(top + 2), "-o", str(tmp_path / "c.jsonl"))
    assert status == 2 and f"only through {top}" in err and not (tmp_path / "c.jsonl").exists()
    with pytest.raises(ConjectureError):
        settle_catalog(SHIPPED, top + 2, 4)


def test_a_partial_catalog_proves_nothing(tmp_path):
    part = tmp_path / "part"
    build_catalog(part, 16, res=0, mod=2, generator="plantri")
    with pytest.raises(ConjectureError, match="partial"):
        settle_catalog(part, 16, 4)
    whole = tmp_path / "whole"
    build_catalog(whole, 16, generator="plantri")
    lines = list(certificate_lines(settle_catalog(whole, 16, 4)))
    assert check_certificate(lines, whole).valid
    with pytest.raises(ConjectureError, match="partial"):
        check_certificate(lines, part)


def test_a_catalog_starting_above_the_cube_proves_nothing(tmp_path):
    cat = tmp_path / "c"
    build_catalog(cat, 16, min_corners=12, generator="plantri")
    with pytest.raises(ConjectureError, match="start"):
        settle_catalog(cat, 16, 4)


def test_a_copy_of_the_shipped_catalog_cut_short_fails_the_shipped_certificate(tmp_path, capsys):
    cat = write_census(read_catalog(SHIPPED).through(24), tmp_path / "cat")
    status, out, _ = run(capsys, "conjecture", "check", str(CERT), "--catalog", str(cat))
    assert status == 1 and "only through 24" in out


def test_a_summary_cut_short_over_all_the_records_is_no_catalog(tmp_path, capsys):
    """A summary that counts less than the records hold (or more) is refused by every reader,
    naming both sides: the certificate is not checked against it."""
    cat = tmp_path / "cat"
    shutil.copytree(SHIPPED, cat)
    summary = json.loads((cat / "summary.json").read_text())
    summary["counts"] = {k: v for k, v in summary["counts"].items() if int(k) <= 24}
    (cat / "summary.json").write_text(json.dumps(summary))
    status, _, err = run(capsys, "conjecture", "check", str(CERT), "--catalog", str(cat))
    assert status == 1 and "records with 26 corners, which the summary does not count" in err


def test_a_journal_resumes_a_stopped_certificate(tmp_path, monkeypatch):
    """With a journal, the records already settled are taken from it (a line cut short is
    settled again), the result is the one without it, and another run's journal is replaced."""
    from polyloops.reach import conjecture

    cat = small_catalog(22)
    plain = list(certificate_lines(settle_catalog(cat, 22, 6)))
    journal = tmp_path / "journal.jsonl"
    assert list(certificate_lines(settle_catalog(cat, 22, 6, journal=journal))) == plain
    lines = journal.read_text().splitlines()
    assert len(lines) == len(plain)  # the header and one line a class
    journal.write_text("\n".join(lines[:4]) + "\n" + lines[4][:20])  # stopped mid-line
    calls = []
    real = conjecture.settle
    monkeypatch.setattr(conjecture, "settle", lambda *a, **k: calls.append(a[0]) or real(*a, **k))
    assert list(certificate_lines(settle_catalog(cat, 22, 6, journal=journal))) == plain
    assert len(calls) == len(plain) - 4  # three taken from the journal
    calls.clear()
    settle_catalog(cat, 22, 4, journal=journal)  # another slack: the journal is not this run's
    assert len(calls) == len(plain) - 1
    assert json.loads(journal.read_text().splitlines()[0])["slack"] == 4


def test_the_command_keeps_its_journal_only_while_it_runs(tmp_path, capsys):
    cert = tmp_path / "c.jsonl"
    status, _, _ = run(capsys, "conjecture", "genus0", "--catalog", str(small_catalog(22)), "--max-corners",
                       "16", "--slack", "4", "-o", str(cert))
    assert status == 0 and cert.exists() and not (tmp_path / "c.jsonl.journal").exists()


def test_a_file_that_is_no_journal_is_not_overwritten(tmp_path, capsys):
    cert = tmp_path / "c.jsonl"
    mine = tmp_path / "c.jsonl.journal"
    mine.write_bytes(b"my notes\n\xff")
    status, _, err = run(capsys, "conjecture", "genus0", "--catalog", str(small_catalog(22)), "--max-corners",
                         "16", "--slack", "4", "-o", str(cert))
    assert status == 2 and err.count("\n") == 1 and "no journal" in err
    assert mine.read_bytes() == b"my notes\n\xff" and not cert.exists()


def test_records_read_back_as_written():
    from polyloops.reach.conjecture import ClassRecord

    for path in (CERT, REAL.parent / "genus1" / "reachability-certificate.jsonl"):
        for line in path.read_text().splitlines()[1:]:
            data = json.loads(line)
            assert ClassRecord.from_json(data).to_json() == data


def test_the_shape_of_the_shipped_detours_is_as_the_docs_say():
    """docs/reachability.md and ``find_long_detour`` say how many of the shipped certificates'
    detours add one loop and then only remove (45 of 56), and how many add at most two, each
    followed by removals (48)."""
    from polyloops.reach.conjecture import shipped_certificate

    shapes = []
    for genus in (0, 1):
        for line in shipped_certificate(genus).read_text().splitlines()[1:]:
            if '"detour"' in line:
                kinds = "".join("a" if "add" in m else "r" for m in json.loads(line)["detour"]["moves"])
                shapes.append(kinds)
    one = sum(bool(re.fullmatch("ar+", k)) for k in shapes)
    two = sum(bool(re.fullmatch("(ar+){1,2}", k)) for k in shapes)
    assert (len(shapes), one, two) == (56, 45, 48)
