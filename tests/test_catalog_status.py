"""``catalog status``: a run's finished shares, counted the way the run itself reads them."""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import pytest

from cli_run import run
from polyloops.catalog.run import load_part, part_path
from polyloops.catalog.status import run_status
from polyloops.cli import main
from polyloops.generate.base import Job, generators


@pytest.fixture(scope="module")
def torus_run(tmp_path_factory):
    """A genus-1 run through 32 corners (16 shares; the square ring, the smallest, at 32)."""
    out = tmp_path_factory.mktemp("status") / "g1-32"
    assert main(["catalog", "--genus", "1", "--max-corners", "32", "-o", str(out)]) == 0
    return out


def test_a_finished_run_counts_what_its_summary_counts(torus_run, capsys):
    status = run_status(torus_run)
    assert status.finished and not status.damaged and len(status.plans) == 1
    plan = status.plans[0]
    summary = json.loads((torus_run / "summary.json").read_text())
    assert (plan.generator, plan.min_corners, plan.max_corners) == ("torus", 8, 32)
    assert plan.done == tuple(range(plan.shares)) and plan.missing == 0 and plan.estimate == 0
    assert plan.classes == {int(n): c["full"] for n, c in summary["counts"].items()}
    assert plan.classes[32] == 1 and not any(plan.classes[n] for n in range(8, 32))  # the square ring first
    assert plan.statistics == summary["search"]
    status_code, out, _ = run(capsys, "catalog", "status", str(torus_run), "--json")
    data = json.loads(out)
    assert status_code == 0 and data["plans"][0]["done"] == plan.shares and data["finished"] is True


def test_an_unfinished_run_and_damaged_parts(torus_run, tmp_path, capsys):
    """Parts removed (shares not run yet), one edited and one copied under another share's
    name: status counts only the parts the run would reuse, and the run agrees."""
    out = tmp_path / "run"
    shutil.copytree(torus_run, out, ignore=shutil.ignore_patterns("summary.json", "catalog.*"))
    whole = run_status(torus_run).plans[0]
    jobs = [Job("torus", 32, 8, r, whole.shares) for r in range(whole.shares)]
    part_path(out, jobs[0]).unlink()
    edited = part_path(out, jobs[1])
    data = json.loads(edited.read_text())
    data["result"]["seconds"] += 1  # the digest no longer holds
    edited.write_text(json.dumps(data))
    shutil.copyfile(part_path(out, jobs[3]), part_path(out, jobs[2]))  # share 3's result as share 2's
    status = run_status(out)
    plan = status.plans[0]
    assert not status.finished
    assert plan.done == tuple(range(3, whole.shares)) and plan.missing == 3
    assert sorted(status.damaged) == sorted(part_path(out, j).name for j in jobs[1:3])
    assert [load_part(out, j) is not None for j in jobs[:4]] == [False, False, False, True]
    assert plan.estimate == pytest.approx(sum(plan.seconds) / len(plan.seconds) * 3)
    assert sum(plan.classes.values()) <= sum(whole.classes.values())
    code, text, _ = run(capsys, "catalog", "status", str(out))
    assert code == 0 and f"{whole.shares - 3} of {whole.shares} shares done" in text
    assert "recomputed when the run resumes" in text and part_path(out, jobs[1]).name in text


def test_bad_directories(tmp_path, capsys):
    (tmp_path / "file").write_text("x")
    for where, words in ((tmp_path / "none", "no such directory"), (tmp_path / "file", "not a directory"),
                         (tmp_path, "holds no catalog run")):
        code, out, err = run(capsys, "catalog", "status", str(where))
        assert code == 2 and not out and words in err and len(err.strip().splitlines()) == 1


ROOT = Path(__file__).resolve().parent.parent


def test_committed_runs_are_finished_shares_and_the_docs_say_what_they_hold():
    """``runs/`` carries the finished shares of long genus-2 runs between machines: every part
    there is one its run would reuse (its digest holds, it is at its job's file name, of that
    run's plan: ``genus2-N`` is the handles search through ``N`` corners), and docs/counts.md
    states, for each run, how many shares are finished, their time, and what they found; no page
    says that no genus-2 polycube has N corners or fewer beyond a finished run that found none."""
    runs = sorted(p for p in (ROOT / "runs").glob("genus2-*") if p.is_dir())
    if not runs:
        pytest.skip("no runs/ in this installation (a checkout has it)")
    text = " ".join((ROOT / "docs" / "counts.md").read_text().split())
    decided = 0  # the most corners a finished run that found nothing searched
    for directory in runs:
        top = int(directory.name.removeprefix("genus2-"))
        status = run_status(directory)
        assert not status.damaged and not status.finished and len(status.plans) == 1, directory
        plan = status.plans[0]
        assert (plan.generator, plan.variant, plan.min_corners, plan.max_corners) == ("handles", "", 8, top)
        assert plan.shares == generators()["handles"].shares(top, workers=2)
        if plan.missing:
            said = re.search(rf"`runs/{directory.name}`[^*]*\*\*([\d,]+) of the ([\d,]+) shares\*\* "
                             r"finished, ([\d,]+) s of worker time, (.*?)\. ", text)
            assert said, f"docs/counts.md: the progress of runs/{directory.name} is not stated"
            done, shares, secs, words = said.groups()
        else:  # finished: every share, and what the whole run decides
            said = re.search(rf"`runs/{directory.name}`[^:]*: the part files of all ([\d,]+) shares "
                             r"[^:]*: ([\d,]+) s of worker time, (.*?)\.", text)
            assert said, f"docs/counts.md: the finished runs/{directory.name} is not stated"
            (done, secs, words), shares = said.groups(), said[1]
            assert plan.found or f"No genus-2 polycube has {top} corners or fewer." in text, directory.name
            if not plan.found:
                decided = max(decided, top)
        assert [int(x.replace(",", "")) for x in (done, shares, secs)] == \
            [len(plan.done), plan.shares, round(sum(plan.seconds))], directory.name
        found = ", ".join(f"{c:,} with {n} corners" for n, c in plan.found.items())
        assert words == ("found in them: " + found if found else "no class found in them")
    # and no page claims more than a finished run decided
    for page in (*(ROOT / "docs").glob("*.md"), ROOT / "README.md", ROOT / "runs" / "README.md"):
        words = " ".join(page.read_text().split())
        for n in re.findall(r"no genus-2 polycube (?:has|with) (\d+) corners or fewer", words, re.I):
            assert int(n) <= decided, f"{page.name}: no genus-2 polycube through {n} corners, beyond the runs"
