"""The switchboard of the compiled parts: one table, one environment variable, one context
manager, and ``polyloops --version`` saying what was built and what runs."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from polyloops.cli import main
from polyloops.core import compiled

SRC = Path(__file__).resolve().parent.parent / "src"


def test_the_table_names_every_extension_the_build_makes():
    sources = {p.relative_to(SRC).with_suffix("").as_posix().replace("/", ".")
               for p in SRC.rglob("_*.c")}
    assert {part.module for part in compiled.PARTS.values()} == sources
    assert len(compiled.PARTS) == 8


def test_the_normal_run_uses_every_part_it_built():
    if os.environ.get(compiled.ENV):
        pytest.skip(f"{compiled.ENV} is set for this run")
    assert all(s.in_use == s.built for s in compiled.status())
    if os.environ.get("CI"):  # CI installs a compiler: every part is built there
        assert all(s.built for s in compiled.status())


def test_pure_python_blocks_nest_and_end():
    before = {name: compiled.in_use(name) for name in compiled.PARTS}
    with compiled.pure_python("torus"):
        assert not compiled.in_use("torus")
        with compiled.pure_python():
            assert not any(compiled.in_use(name) for name in compiled.PARTS)
        assert not compiled.in_use("torus")
        assert compiled.in_use("canonical") == before["canonical"]
    assert {name: compiled.in_use(name) for name in compiled.PARTS} == before
    refused = pytest.raises(compiled.CompiledError, match="'nope' is no compiled part")
    with refused, compiled.pure_python("nope"):
        pass


def test_the_environment_switches_parts(monkeypatch):
    monkeypatch.setenv(compiled.ENV, "canonical, regions")
    assert compiled.forced() == {"canonical", "regions"}
    assert not compiled.in_use("canonical") and "switched to its Python twin" in compiled.why_not("canonical")
    monkeypatch.setenv(compiled.ENV, "all")
    assert compiled.forced() == set(compiled.PARTS)
    with pytest.raises(compiled.CompiledError):
        compiled.require("torus")


def test_a_twin_gives_the_same_answer():
    import polyloops as pl

    ring = pl.load_example("bridged-ring")
    fast = pl.signature(ring)
    with compiled.pure_python():
        assert pl.signature(ring) == fast


def test_version_lists_the_parts_and_a_bad_switch_is_refused(capsys, monkeypatch):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    out = capsys.readouterr().out
    assert out.startswith("polyloops ") and all(f"  {name} " in out for name in compiled.PARTS)
    monkeypatch.setenv(compiled.ENV, "canonical,bogus")
    assert main(["verify", "example:cube"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "'bogus' is no compiled part" in err


def test_a_whole_command_runs_on_the_twins():
    env = {**os.environ, compiled.ENV: "all"}
    done = subprocess.run([sys.executable, "-m", "polyloops", "catalog", "query", "--genus", "1",
                           "corners = 32"], env=env, capture_output=True, text=True)
    assert done.returncode == 0 and "T32.1" in done.stdout, done.stderr
