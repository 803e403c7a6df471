"""A plain (not editable) install works outside the source tree: the shipped catalog and the
examples are package data.  The wheel is built from the tracked files alone (what a clean clone
holds) and installed with ``pip install --target`` into a temporary directory, so the test uses
the dependencies already installed and downloads nothing but the build backend; it runs from a
directory that is not the source tree."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def tracked_files() -> list[str]:
    try:
        # tracked files, and new ones git does not ignore: what a clean clone holds once committed
        out = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                             cwd=ROOT, capture_output=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        pytest.skip("not a git checkout: the tracked files are unknown")
    return [name for name in out.stdout.decode().split("\0") if name]


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> Path:
    clone = tmp_path_factory.mktemp("clone")
    for name in sorted(set(tracked_files())):
        source = ROOT / name
        target = clone / name
        target.parent.mkdir(parents=True, exist_ok=True)
        if source.is_symlink():
            target.symlink_to(os.readlink(source))
        elif source.is_file():
            shutil.copy2(source, target)
    wheels = tmp_path_factory.mktemp("wheels")
    pip = [sys.executable, "-m", "pip", "--disable-pip-version-check", "-q"]
    done = subprocess.run([*pip, "wheel", "--no-deps", str(clone), "-w", str(wheels)],
                          capture_output=True, text=True)
    if done.returncode != 0:
        pytest.fail(f"pip wheel failed: {done.stderr[-2000:]}")
    target = tmp_path_factory.mktemp("site")
    wheel = next(wheels.glob("polyloops-*.whl"))
    subprocess.run([*pip, "install", "--no-deps", "--target", str(target), str(wheel)], check=True,
                   capture_output=True)
    return target


def run_installed(installed: Path, cwd: Path, *argv: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PYTHONPATH": str(installed)}
    return subprocess.run([sys.executable, *argv], cwd=cwd, env=env, capture_output=True, text=True)


def test_plain_install_has_the_census(installed, tmp_path):
    # the library, in one process: the wheel (not the source tree), both catalogs and both
    # certificates (whose whole checks run in test_certificates and below, with --run-slow)
    code = ("import polyloops as pl; print(pl.__file__); "
            "print(pl.identify(pl.load_example('l-shape')).name, len(pl.read_catalog().entries)); "
            "c = pl.read_certificate(); print(c.header['max_corners'], c.genus); "
            "c = pl.read_certificate(genus=1); print(c.header['max_corners'], c.genus); "
            "print(len(pl.read_catalog(genus=1)))")
    done = run_installed(installed, tmp_path, "-c", code)
    assert done.returncode == 0, done.stderr
    where, named, genus0, genus1, classes = done.stdout.splitlines()
    assert where.startswith(str(installed))
    assert named.split()[0] == "P16.2" and genus0.split() == ["40", "0"]
    source = json.loads((ROOT / "catalogs" / "genus1" / "summary.json").read_text())
    top = max(int(n) for n in source["counts"])
    assert genus1.split() == [str(top), "1"]
    assert classes == str(sum(row["full"] for row in source["counts"].values()))  # the source's copy
    # the command, from any directory
    done = run_installed(installed, tmp_path, "-m", "polyloops", "identify", "example:l-shape")
    assert done.returncode == 0 and "P16.2" in done.stdout, done.stderr
    done = run_installed(installed, tmp_path, "-m", "polyloops", "gallery", "-o", "site", "--limit", "3")
    assert done.returncode == 0 and (tmp_path / "site" / "index.html").is_file(), done.stderr
    # the genus-1 catalog ships beside it: identify finds the ring, query reads it
    done = run_installed(installed, tmp_path, "-m", "polyloops", "identify", "example:ring-x")
    assert done.returncode == 0 and "T32.1" in done.stdout, done.stderr
    done = run_installed(installed, tmp_path, "-m", "polyloops", "catalog", "query", "--genus", "1",
                         "corners = 40")
    assert done.returncode == 0 and done.stdout.count("T40.") == 73, done.stdout + done.stderr


@pytest.mark.slow
def test_the_shipped_genus_one_certificate_checks_in_a_plain_install(installed, tmp_path):
    """The shipped genus-1 catalog behind the front door: no path given, only --genus; the
    whole certificate is replayed against the installed catalog."""
    done = run_installed(installed, tmp_path, "-m", "polyloops", "conjecture", "check", "--genus", "1")
    assert done.returncode == 0 and "genus-1" in done.stdout, done.stdout + done.stderr
