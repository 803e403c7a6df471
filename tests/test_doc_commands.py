"""Every command line the README and the docs show in a shell block is a real command: each one
parses (the default run, in a second), and each one runs with the exit status its comment
promises, in order, in a folder laid out like a clone (the quick ones in the default run, the
ones that draw, build or replay, and those that read what such a one wrote, with
``--run-slow``); plain ``polyloops`` lines run through the command's ``main`` in this process,
the others (shell syntax, worker processes, ``python`` scripts) as a shell runs them.  The few
that reproduce a shipped catalog
(hours of CPU, or writing into the shipped catalog itself) are parsed, not run: they are listed
in REPRODUCTIONS with the reason."""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pytest

from polyloops.cli.main import build_parser

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")), ROOT / "catalogs" / "README.md"]

# Shown to say how a shipped catalog was made: each takes from half an hour to hours of CPU, or
# writes into the shipped catalog's own folder, or runs on a cluster (docs/cluster.md).  Parsed,
# never run by the tests.
REPRODUCTIONS = ("--max-corners 30 --generator plantri", "--max-corners 36 --generator loops",
                 "--max-corners 40 --generator loops", "/shared/genus0-44", "/shared/genus1-47",
                 "/shared/genus2-48", "--genus 1 --max-corners 47", "--genus 1 --max-corners 48",
                 "-o catalogs/genus0/", "-o catalogs/genus1/", "tools/ship_catalog.py")
# Commands that draw, build or replay: seconds to minutes each, run with --run-slow.
HEAVY = ("render", "view", "sheet", "gallery", "catalog", "reach", "conjecture", "path", "segment")


@dataclass(frozen=True)
class Shown:
    page: str
    line: str  # the command as shown, without its comment
    status: int  # what the comment promises: 1 where it says "exit 1", else 0

    @property
    def heavy(self) -> bool:
        words = self.line.split()
        return len(words) > 1 and words[1] in HEAVY

    @property
    def reproduction(self) -> bool:
        return any(r in self.line + "/" for r in REPRODUCTIONS)


def shown_commands(page: Path) -> list[Shown]:
    """The ``polyloops`` (and ``python tools/...``) lines of a page's shell blocks, in order."""
    text = page.read_text(encoding="utf-8")
    out = []
    for block in re.findall(r"```(?:sh|bash|shell|console)\n(.*?)```", text, re.S):
        for raw in block.splitlines():
            line = raw.strip().removeprefix("$ ")
            if not re.match(r"(polyloops|python tools/)\s", line):
                continue
            command, _, comment = line.partition(" #")  # a comment starts at " #"
            out.append(Shown(page.relative_to(ROOT).as_posix(), command.strip(),
                             1 if comment.strip().startswith("exit 1") else 0))
    return out


ALL = [shown for page in PAGES for shown in shown_commands(page)]


def test_the_pages_show_commands():
    assert len(ALL) >= 60 and {s.page for s in ALL} >= {"README.md", "docs/moves.md", "docs/pictures.md"}


@pytest.mark.parametrize("shown", [s for s in ALL if s.line.startswith("polyloops ")],
                         ids=lambda s: f"{s.page}:{s.line[:60]}")
def test_every_shown_command_parses(shown):
    """Options, choices and arguments as the program has them today."""
    words = shlex.split(shown.line)[1:]
    try:
        build_parser().parse_args(words)
    except SystemExit as stop:  # --help or --version would exit 0; nothing shown does that
        pytest.fail(f"{shown.page}: {shown.line}: exits {stop.code} while parsing")
    except Exception as err:  # the parser's usage errors
        pytest.fail(f"{shown.page}: {shown.line}: {err}")


def clone_like(tmp: Path) -> Path:
    """A folder laid out like a clone (its data folders linked) with the inputs the pages
    assume the reader has made: a big structure, a mesh with labels, a structure of their own."""
    from polyloops.core.directions import Direction
    from polyloops.io.formats import dumps
    from polyloops.io.meshes import write_triangle_mesh
    from polyloops.shapes.builders import box
    from polyloops.shapes.meshes import ellipsoid
    from polyloops.surface.mesh import LabelledMesh

    for name in ("tests", "catalogs", "src", "tools", "docs"):
        (tmp / name).symlink_to(ROOT / name)
    (tmp / "big.json").write_text(dumps(box(6, 6, 2).dualize()))
    (tmp / "my.json").write_text(dumps(box(2, 2, 1)))
    examples = ROOT / "src" / "polyloops" / "examples"
    shutil.copy(examples / "overhang.obj", tmp / "shape.obj")
    shutil.copy(examples / "overhang.labels", tmp / "shape.labels")
    shutil.copy(examples / "sokolov-ramp.obj", tmp / "ramp.obj")
    shutil.copy(examples / "sokolov-ramp.labels", tmp / "ramp.labels")
    points, triangles = (tuple(map(tuple, a.tolist())) for a in ellipsoid(1.5, 1, 0.7))
    write_triangle_mesh(tmp / "shape.stl", LabelledMesh(points, triangles, (Direction.PX,) * len(triangles)))
    (tmp / "scratch").mkdir()
    return tmp


def _outputs(line: str) -> list[str]:
    """The files a command may write: its file-like words but the first (its input)."""
    words = [w for w in shlex.split(line) if "." in w and not w.startswith("-")]
    return words[1:] or words[-1:]


def weights(commands: list[Shown]) -> list[bool]:
    """Whether each command is heavy: a heavy command, or one that reads what a heavy one wrote
    (so that the default run does not draw or search only to feed a quick check)."""
    out, written = [], set()
    for shown in commands:
        heavy = shown.heavy or bool(written & set(shlex.split(shown.line)))
        if heavy:
            written |= set(_outputs(shown.line))
        out.append(heavy)
    return out


def run_page(page: str, tmp: Path, heavy: bool) -> int:
    """Run a page's commands in order (the README's from its scratch folder, as it says; the
    other pages' from the clone's top); those of the other weight only when a later command may
    need their output (they are run too, whatever their weight, if a file they write is read)."""
    root = clone_like(tmp)
    cwd = root / "scratch" if page == "README.md" else root
    exe = shutil.which("polyloops") or f"{sys.executable} -m polyloops"
    ran = 0
    commands = [s for s in ALL if s.page == page and not s.reproduction]
    weight = weights(commands)
    run = [w == heavy for w in weight]
    for k in reversed(range(len(commands))):  # and whatever a command run reads, first
        reads = {w for j in range(k + 1, len(commands)) if run[j] for w in shlex.split(commands[j].line)}
        run[k] = run[k] or bool(reads & set(_outputs(commands[k].line)))
    for k, shown in enumerate(commands):
        if not run[k]:
            continue
        if in_process(shown.line):
            status, err = run_here(shown.line, cwd)
        else:
            line = shown.line.replace("polyloops ", f"{exe} ", 1) if shown.line.startswith("polyloops ") \
                else f"{sys.executable} {shown.line.removeprefix('python ')}"
            res = subprocess.run(line, shell=True, cwd=cwd, capture_output=True, text=True, check=False)
            status, err = res.returncode, res.stderr
        assert status == shown.status, f"{page}: {shown.line}: exit {status}: {err[-600:]}"
        assert "Traceback" not in err, f"{page}: {shown.line}: {err[-600:]}"
        ran += weight[k] == heavy
    return ran


def in_process(line: str) -> bool:
    """Whether a shown command runs here, through the command's own ``main`` (a process's start
    saved: a quarter of a second each): a plain ``polyloops`` line, no shell syntax, no worker
    processes; the installed command itself runs in the README's block of ``.ci/run`` and in
    test_install."""
    return line.startswith("polyloops ") and not re.search(r"[|<>;&$`*]|--workers|--dask|--html|view ", line)


def run_here(line: str, cwd: Path) -> tuple[int, str]:
    """Run a ``polyloops`` line through ``main`` in ``cwd``: its exit status and what it wrote
    to standard error (an exception escaping ``main`` fails the test, as a traceback would)."""
    import contextlib
    import io
    import os

    from polyloops.cli import main

    out, err, before = io.StringIO(), io.StringIO(), Path.cwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                status = main(shlex.split(line)[1:])
            except SystemExit as stop:  # argparse's own exits
                status = int(stop.code or 0)
    finally:
        os.chdir(before)
    return status, err.getvalue()


RUN_PAGES = sorted({s.page for s in ALL if not s.reproduction})


@pytest.mark.parametrize("page", RUN_PAGES)
def test_the_quick_commands_run_as_shown(page, tmp_path):
    run_page(page, tmp_path, heavy=False)


@pytest.mark.slow  # the pictures, the catalogs, the searches, the gallery and the replays: minutes
@pytest.mark.parametrize("page", [p for p in RUN_PAGES if any(s.heavy for s in ALL if s.page == p)])
def test_the_heavy_commands_run_as_shown(page, tmp_path):
    assert run_page(page, tmp_path, heavy=True) > 0


def transcripts() -> list[tuple[str, str, list[str], int | None]]:
    """The console blocks' ``$ polyloops ...`` commands with the output shown under each (up to
    the next ``$``) and the status a following ``$ echo $?`` shows."""
    out = []
    for page in PAGES:
        text = page.read_text(encoding="utf-8")
        for block in re.findall(r"```console\n(.*?)```", text, re.S):
            entries: list[list] = []
            for line in block.splitlines():
                if line.startswith("$ "):
                    entries.append([line[2:].partition(" #")[0].strip(), []])
                elif entries:
                    entries[-1][1].append(line)
            for k, (command, lines) in enumerate(entries):
                if not command.startswith("polyloops ") or not lines:
                    continue
                status = None
                if k + 1 < len(entries) and entries[k + 1][0] == "echo $?":
                    status = int(entries[k + 1][1][0])
                out.append((page.relative_to(ROOT).as_posix(), command, lines, status))
    return out


@pytest.mark.parametrize("page, command, lines, status", transcripts(), ids=lambda v: str(v)[:50])
def test_transcripts_show_what_the_program_prints(page, command, lines, status, tmp_path):
    cwd = clone_like(tmp_path)
    exe = shutil.which("polyloops") or f"{sys.executable} -m polyloops"
    res = subprocess.run(command.replace("polyloops ", f"{exe} ", 1), shell=True, cwd=cwd,
                         capture_output=True, text=True, check=False)
    assert res.stdout.splitlines() == lines, f"{page}: {command}"
    assert status is None or res.returncode == status
