"""Nothing is claimed that was not searched: spilled run files prove they belong to their run,
a catalog is read only when its records prove its summary, a run's files stay in its
directory, one run writes a directory at a time, and a stopped merge is finished by a rerun."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from polyloops.catalog.census import Census, read_catalog
from polyloops.catalog.records import CatalogEntry, CatalogError, CatalogMismatchError
from polyloops.catalog.run import build_catalog, write_census
from polyloops.cli import main
from polyloops.generate.spill import SpillRefused, SpillTag, read_spill, write_spill
from shipped import small_catalog
from switch import needs


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def records(directory: Path) -> list[dict]:
    return [json.loads(line) for line in (directory / "catalog.jsonl").read_text().splitlines()]


# -- spilled files -------------------------------------------------------------------------------
@needs("arrangements")  # the loops generator: its compiled search
def test_a_smaller_runs_top_is_not_taken_for_this_runs(tmp_path, capsys):
    """A 20-corner loops run given the top of a 16-corner run under its own name recomputes it:
    11 records, not the 4 the smaller top leads to; and it never replaces a finished catalog
    with fewer records."""
    small = tmp_path / "small"
    build_catalog(small, 16, generator="loops")
    assert len(records(small)) == 4
    cat = tmp_path / "cat"
    (cat / "parts").mkdir(parents=True)
    shutil.copy(small / "parts" / "loops-top-16.bin", cat / "parts" / "loops-top-20.bin")
    built = build_catalog(cat, 20, generator="loops")
    assert built.records == 11 and len(records(cat)) == 11
    # the file there now is this run's own
    assert read_spill(cat / "parts" / "loops-top-20.bin", SpillTag("loops-top", _top_version(), 20)).records


def _top_version():
    from polyloops.generate.loops import frontier_tag

    return frontier_tag(0).version


@needs("arrangements")  # the loops generator: its compiled search
@pytest.mark.parametrize("damage", ["header-only", "half", "truncated", "junk", "padded", "edited"])
def test_a_damaged_top_is_recomputed(tmp_path, damage):
    """A top with its header and no nodes, half of its nodes, cut, junk, padded or with one
    byte changed is recomputed: the catalog is the one an untouched run writes."""
    good = tmp_path / "good"
    build_catalog(good, 20, generator="loops")
    path = tmp_path / "cat" / "parts" / "loops-top-20.bin"
    path.parent.mkdir(parents=True)
    data = (good / "parts" / "loops-top-20.bin").read_bytes()
    header_end = data.index(b"}", data.index(b"{")) + 1
    while data.count(b"{", 0, header_end) != data.count(b"}", 0, header_end):
        header_end = data.index(b"}", header_end) + 1
    body = data[header_end:]
    path.write_bytes({"header-only": data[:header_end], "half": data[:header_end + len(body) // 2],
                      "truncated": data[:-3], "junk": os.urandom(4000), "padded": data + b"\0" * 10,
                      "edited": data[:-1] + bytes([data[-1] ^ 1])}[damage])
    build_catalog(tmp_path / "cat", 20, generator="loops")
    assert (tmp_path / "cat" / "catalog.jsonl").read_bytes() == (good / "catalog.jsonl").read_bytes()


@needs("arrangements")  # the loops generator: its compiled search
def test_a_link_in_parts_is_neither_read_nor_written_through(tmp_path, capsys):
    """A spilled file's name that is a link (to a device, or to a file elsewhere) is refused in
    one line, exit 2: nothing is read from it or written into it."""
    cat = tmp_path / "cat"
    (cat / "parts").mkdir(parents=True)
    (cat / "parts" / "loops-top-20.bin").symlink_to("/dev/zero")
    status, _, err = run(capsys, "catalog", "--max-corners", "20", "-o", str(cat))
    assert status == 2 and err.count("\n") == 1 and "symbolic link" in err
    outside = tmp_path / "outside.bin"
    outside.write_bytes(b"mine")
    (cat / "parts" / "loops-top-20.bin").unlink()
    (cat / "parts" / "loops-top-20.bin").symlink_to(outside)
    status, _, err = run(capsys, "catalog", "--max-corners", "20", "-o", str(cat))
    assert status == 2 and outside.read_bytes() == b"mine"
    with pytest.raises(SpillRefused):
        write_spill(cat / "parts" / "loops-top-20.bin", SpillTag("x", 1, 1), [b""])


def test_an_edited_part_is_recomputed(tmp_path):
    """A finished job's part with one record removed no longer matches its digest: the rerun
    computes the job again instead of merging fewer records."""
    cat = tmp_path / "cat"
    build_catalog(cat, 20, generator="plantri")
    whole = (cat / "catalog.jsonl").read_bytes()
    def has_records(p: Path) -> bool:
        corners = json.loads(p.read_text())["result"]["corners"]
        return bool(corners.get("20", {}).get("records", {}).get("full"))

    part = next(p for p in (cat / "parts").glob("*.json") if has_records(p))
    data = json.loads(part.read_text())
    data["result"]["corners"]["20"]["records"]["full"].pop()
    part.write_text(json.dumps(data))
    for name in ("catalog.jsonl", "catalog.sqlite", "summary.json"):
        (cat / name).unlink()
    build_catalog(cat, 20, generator="plantri")
    assert (cat / "catalog.jsonl").read_bytes() == whole


# -- what a catalog's records prove ----------------------------------------------------------------

GENUS1 = read_catalog(small_catalog(44, genus=1))  # the edits' refusals need no more of it


def _copy(tmp_path: Path, census: Census = GENUS1) -> Path:
    return write_census(census, tmp_path / "cat")


def _edit(cat: Path, change) -> None:
    lines = records(cat)
    change(lines)
    (cat / "catalog.jsonl").write_text("".join(json.dumps(r, separators=(",", ":")) + "\n" for r in lines))
    summary = json.loads((cat / "summary.json").read_text())
    summary.pop("files")  # an editor who also drops the digest: the counts still tell
    (cat / "summary.json").write_text(json.dumps(summary))


EDITS = {
    "cut at 40": lambda rs: rs.__delitem__(slice(next(i for i, r in enumerate(rs) if r["corners"] > 40),
                                                 None)),
    "a record deleted": lambda rs: rs.pop(5),
    "a record twice": lambda rs: rs.insert(6, rs[5]),
    "corners edited": lambda rs: rs[-1].__setitem__("corners", 46),
}


@pytest.mark.parametrize("edit", EDITS)
def test_an_edited_genus_one_catalog_is_refused_by_every_reader(tmp_path, capsys, edit):
    """Records cut at 40 under a summary through 47, a deleted record, a duplicated record, a
    record whose corners were edited: conjecture check, conjecture genus1, identify, gallery and
    query refuse the catalog (exit 1), naming what differs; no certificate is written."""
    cat = _copy(tmp_path)
    _edit(cat, EDITS[edit])
    with pytest.raises(CatalogMismatchError):
        read_catalog(cat)
    cert = str(Path(GENUS1.directory) / "reachability-certificate.jsonl")
    out_cert = tmp_path / "new.jsonl"
    for argv in (["conjecture", "check", cert, "--catalog", str(cat)],
                 ["conjecture", "genus1", "--catalog", str(cat), "--max-corners", "44", "-o", str(out_cert)],
                 ["identify", "example:ring-y", "--catalog", str(cat)],
                 ["gallery", str(cat), "-o", str(tmp_path / "site")],
                 ["catalog", "query", str(cat), "corners = 32"]):
        status, out, err = run(capsys, *argv)
        assert status == 1 and "valid" not in out and err.count("\n") == 1, (argv, out, err)
        assert "not a catalog its records prove" in err
    assert not out_cert.exists()


def test_the_counts_mismatch_names_both_numbers(tmp_path):
    cat = _copy(tmp_path)
    _edit(cat, EDITS["a record deleted"])
    with pytest.raises(CatalogMismatchError, match=r"the summary counts 6 full classes with 36 corners; "
                       r"catalog.jsonl holds 5|should be named"):
        read_catalog(cat)


def test_an_edit_the_counts_cannot_see_the_digest_does(tmp_path):
    """A changed field that no count depends on (a record's automorphisms) is caught by the
    digest the summary records."""
    cat = _copy(tmp_path)
    text = (cat / "catalog.jsonl").read_text().replace('"automorphisms":16', '"automorphisms":8', 1)
    (cat / "catalog.jsonl").write_text(text)
    with pytest.raises(CatalogMismatchError, match="digest"):
        read_catalog(cat)


def test_a_garbage_signature_is_a_bad_record(tmp_path, capsys):
    cat = _copy(tmp_path)
    _edit(cat, lambda rs: rs[3].__setitem__("signature", "1oXYZ!!"))
    status, _, err = run(capsys, "conjecture", "check", "--genus", "1", "--catalog", str(cat))
    assert status == 2 and "line 4: not a catalog record (its signature" in err and err.count("\n") == 1


@pytest.mark.parametrize("name", ["../../x", "/abs/path", "P8.1/../../y", ""])
def test_a_record_named_as_a_path_is_a_bad_record(tmp_path, capsys, name):
    """Names become the gallery's file names: a name that is not a class name is refused when
    the records are read, and nothing is written outside the site."""
    cat = _copy(tmp_path, read_catalog().through(16))
    _edit(cat, lambda rs: rs[0].__setitem__("name", name))
    status, _, err = run(capsys, "gallery", str(cat), "-o", str(tmp_path / "site"))
    assert status == 2 and "not a class name" in err
    assert not (tmp_path / "x.png").exists() and not Path("/abs/path.png").exists()


def test_the_gallery_refuses_a_census_with_a_path_for_a_name(tmp_path):
    from polyloops.render.gallery import build_gallery

    census = read_catalog().through(12)
    bad = Census(census.directory, (CatalogEntry("../escape", census[0].symmetry, census[0].record),),
                 census.summary)
    with pytest.raises(ValueError, match="not named as a class"):
        build_gallery(bad, tmp_path / "site")
    assert not (tmp_path / "escape.png").exists()


def test_a_link_inside_the_site_is_not_written_through(tmp_path, capsys):
    site = tmp_path / "site"
    (site / "img").mkdir(parents=True)
    victim = tmp_path / "victim"
    victim.write_text("keep")
    (site / "index.html").symlink_to(victim)
    status, _, err = run(capsys, "gallery", str(_copy(tmp_path, read_catalog().through(12))), "-o", str(site))
    assert status == 2 and victim.read_text() == "keep" and "symbolic link" in err


# -- one run a directory, and a stopped merge finished ---------------------------------------------

def test_a_second_run_into_the_same_directory_is_refused(tmp_path):
    """While a run holds its directory, another run into it is refused at once."""
    from polyloops.catalog.run import CatalogRunError, locked

    cat = tmp_path / "cat"
    cat.mkdir()
    with locked(cat), pytest.raises(CatalogRunError, match="another catalog run"):
        build_catalog(cat, 16)
    assert build_catalog(cat, 16).records == 4  # released when the first run ends
@needs("arrangements")  # the loops generator: its compiled search
def test_two_runs_at_once_leave_the_larger_catalog(tmp_path):
    """A 28-corner run and a 24-corner run started together into one directory: one of them is
    refused, and the directory ends with the 28-corner catalog whichever finishes first."""
    cat = tmp_path / "cat"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    big = subprocess.Popen([sys.executable, "-m", "polyloops", "catalog", "--max-corners", "28",
                            "-o", str(cat)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    deadline = time.time() + 60
    while not (cat / ".polyloops-lock").exists() and time.time() < deadline:
        time.sleep(0.05)
    try:
        small = subprocess.run([sys.executable, "-m", "polyloops", "catalog", "--max-corners", "24",
                                "-o", str(cat)], capture_output=True, text=True, env=env)
        big.wait(timeout=300)
    finally:  # a failed or timed-out test leaves no run behind
        if big.poll() is None:
            big.kill()
            big.wait()
    assert big.returncode == 0
    assert small.returncode == 2 and ("another catalog run" in small.stderr or "with less" in small.stderr)
    assert max(r["corners"] for r in records(cat)) == 28


def _stop_before_the_summary(monkeypatch) -> None:
    """Make the next merge stop (as Ctrl-C would) when it comes to write ``summary.json``."""
    import polyloops.catalog.run as catalog_run

    real = catalog_run.write_atomic

    def stop_at_summary(path, text, **kw):
        if Path(path).name == "summary.json":
            raise KeyboardInterrupt
        return real(path, text, **kw)

    monkeypatch.setattr(catalog_run, "write_atomic", stop_at_summary)


def test_a_merge_stopped_before_its_summary_is_finished_by_a_rerun(tmp_path, monkeypatch):
    """A run stopped after writing its records and before its summary leaves a directory no
    reader accepts; the rerun resumes from the parts and writes the whole set."""
    cat = tmp_path / "cat"
    _stop_before_the_summary(monkeypatch)
    with pytest.raises(KeyboardInterrupt):
        build_catalog(cat, 20)
    monkeypatch.undo()
    assert (cat / "catalog.jsonl").exists() and not (cat / "summary.json").exists()
    with pytest.raises(CatalogError, match="missing"):
        read_catalog(cat)
    assert build_catalog(cat, 20).records == 11 and len(read_catalog(cat)) == 11


def test_a_merge_stopped_over_an_older_catalog_is_refused_then_finished(tmp_path, monkeypatch):
    """New records under the summary of the smaller catalog they replace: readers refuse the
    set (the digest), the rerun finishes it."""
    cat = tmp_path / "cat"
    build_catalog(cat, 16)
    _stop_before_the_summary(monkeypatch)
    with pytest.raises(KeyboardInterrupt):
        build_catalog(cat, 20)
    monkeypatch.undo()
    with pytest.raises(CatalogMismatchError, match="digest"):
        read_catalog(cat)
    assert build_catalog(cat, 20).records == 11


@pytest.mark.slow
def test_sigterm_during_a_run_leaves_a_directory_the_rerun_finishes(tmp_path):
    """SIGTERM at any moment of a run (here: several moments) never leaves a directory that the
    rerun refuses: it ends with the whole catalog."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    whole = None
    for delay in (0.3, 0.8, 1.5):
        cat = tmp_path / f"cat{delay}"
        proc = subprocess.Popen([sys.executable, "-m", "polyloops", "catalog", "--max-corners", "24",
                                 "--generator", "plantri", "-o", str(cat)],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        time.sleep(delay)
        proc.send_signal(signal.SIGTERM)
        proc.wait(timeout=60)
        rerun = subprocess.run([sys.executable, "-m", "polyloops", "catalog", "--max-corners", "24",
                                "--generator", "plantri", "-o", str(cat)],
                               capture_output=True, text=True, env=env)
        assert rerun.returncode == 0, rerun.stderr
        text = (cat / "catalog.jsonl").read_text()
        whole = whole or text
        assert text == whole and len(read_catalog(cat)) == 35


def test_a_spill_written_record_by_record_leaves_nothing_half_written(tmp_path):
    """``spilling`` writes records as they come to a temporary body beside the file: when the
    block fails, neither the file nor the body is left; when it ends, the file reads back whole
    and the body is gone."""
    from polyloops.generate.spill import SpillTag, read_spill, spilling

    tag = SpillTag("test", 1, 5)
    with pytest.raises(RuntimeError), spilling(tmp_path / "x.bin", tag) as out:
        out.add(b"one")
        raise RuntimeError("stopped")
    assert list(tmp_path.iterdir()) == []
    with spilling(tmp_path / "x.bin", tag) as out:
        out.extend([b"one", b"two"])
        out.meta = {"n": 2}
    assert [p.name for p in tmp_path.iterdir()] == ["x.bin"]
    spill = read_spill(tmp_path / "x.bin", tag)
    assert spill.records == (b"one", b"two") and spill.meta == {"n": 2}


def test_a_shipped_catalog_read_once_is_read_again_when_its_files_change(tmp_path, monkeypatch):
    """The shipped catalogs are kept once read and checked; a change to their files (an edited
    count, replaced records) is seen by the next reader, which checks them again."""
    import polyloops.catalog.census as census_module
    from polyloops.catalog.census import CatalogMismatchError, read_catalog
    from shipped import small_catalog

    copy = tmp_path / "genus0"
    shutil.copytree(small_catalog(20), copy)
    real = census_module.default_catalog
    monkeypatch.setattr(census_module, "default_catalog", lambda genus=0: copy if genus == 0 else real(genus))
    first = read_catalog()
    assert read_catalog() is first  # kept
    summary = json.loads((copy / "summary.json").read_text())
    summary["counts"]["20"]["full"] += 1
    (copy / "summary.json").write_text(json.dumps(summary))
    with pytest.raises(CatalogMismatchError):
        read_catalog()
