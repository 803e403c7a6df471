"""Bad input never reaches an internal error, a hang or a silent wrong answer.

Hypothesis mutates valid documents and signatures and feeds them through every command that
reads a FILE; named classes of bad input that once failed are checked one by one.  The
contract: exit 0, 1 or 2; on exit 2 one line on standard error naming the input; never a
traceback or an internal error (exit 3)."""

import contextlib
import io
import json
import os
import subprocess
import sys
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.core.canonical import ALPHABET, signature
from polyloops.io.examples import EXAMPLES, example_text, load_example

NAMES = sorted(n for n in EXAMPLES if n != "self-intersecting")
SIGNATURES = [signature(load_example(n)) for n in ("cube", "l-shape", "ring")]


def run(argv):
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(argv)
        except SystemExit as exc:  # argparse usage errors
            code = exc.code
    return code, out.getvalue(), err.getvalue(), time.perf_counter() - start


def assert_contract(argv, seconds=20.0):
    code, _, err, took = run(argv)
    assert code in (0, 1, 2), (argv, code, err)
    assert "Traceback" not in err and "internal error" not in err, (argv, err)
    if code == 2:
        problem = "".join(line + "\n" for line in err.splitlines() if ": note: " not in line)  # a twin's note
        assert problem.count("\n") == 1 or problem.startswith("usage:"), (argv, err)
        assert len(problem) < 400, (argv, err)
    assert took < seconds, (argv, took)
    return code, err


JUNK = st.one_of(st.none(), st.booleans(), st.floats(allow_nan=True), st.text(max_size=3),
                 st.integers(-10, 10), st.just(10**9), st.just(10**30), st.just([]), st.just({}))


@st.composite
def mutated_documents(draw):
    data = json.loads(example_text(draw(st.sampled_from(NAMES))))
    for _ in range(draw(st.integers(1, 3))):
        key = draw(st.sampled_from(sorted(data)))
        op = draw(st.integers(0, 7))
        value = data[key]
        if op == 0:
            del data[key]
        elif op == 1:
            data[key] = draw(JUNK)
        elif isinstance(value, list) and value:
            i = draw(st.integers(0, len(value) - 1))
            item = value[i]
            if op == 2:
                del value[i]
            elif op == 3:
                value.append(item)
            elif op == 4 and isinstance(item, list) and item:
                item[draw(st.integers(0, len(item) - 1))] = draw(JUNK)
            elif op == 5 and isinstance(item, list):
                value[i] = item[::-1]
            elif op == 6 and isinstance(item, list) and item:
                item.append(item[0])
            else:
                value[i] = draw(JUNK)
    return data


COMMANDS = [["verify"], ["info"], ["dualize"], ["primalize"], ["signature"], ["orient"],
            ["moves", "--count"], ["add", "{}", "X0"], ["remove", "{}", "0"], ["convert", "{}", "{out}"],
            ["reach", "{}", "--max-corners", "16"], ["path", "{}", "example:cube", "--max-corners", "16"]]


@settings(max_examples=250, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(mutated_documents(), st.sampled_from(COMMANDS))
def test_mutated_documents(tmp_path, data, command):
    path = tmp_path / "in.json"
    path.write_text(json.dumps(data))
    argv = [part.format(path, out=tmp_path / "out.json") for part in command]
    argv = argv if "{}" in command else [*argv[:1], str(path), *argv[1:]]
    assert_contract(argv)


@settings(max_examples=120)
@given(st.sampled_from(SIGNATURES), st.integers(0, 10**6), st.sampled_from(ALPHABET),
       st.sampled_from(["replace", "insert", "delete", "cut"]))
def test_mutated_signatures(sig, where, char, how):
    i = where % len(sig)
    bad = {"replace": sig[:i] + char + sig[i + 1:], "insert": sig[:i] + char + sig[i:],
           "delete": sig[:i] + sig[i + 1:], "cut": sig[:i]}[how]
    code, err = assert_contract(["verify", f"sig:{bad}"])
    if bad != sig:
        # The check characters catch every changed character, so no other structure is named.
        assert code == 2 and "sig:" in err


@pytest.mark.parametrize("text", [
    "",  # empty
    "[" * 100000 + "]" * 100000,  # deeply nested JSON
    '{"polyloops": 1.0, "kind": "polycube", "faces": [[0,1,2,3]], "positions": []}',
    '{"polyloops": true, "kind": "polycube", "faces": [[0,1,2,3]], "positions": []}',
    '{"polyloops": 1, "kind": "polycube", "faces": [[0, 1, 1000000000, 2]], "positions": []}',
    '{"polyloops": 1, "kind": "loop-structure", "faces": [[0, 1, 1000000000, 2]], "edges": []}',
    '{"polyloops": 1, "kind": "loop-structure", "faces": [[0, 1, 1, 2], [2, 1, 0, 3]], "edges": []}',
    "\udcff not utf-8",
])
@pytest.mark.parametrize("command", ["verify", "info", "signature", "moves", "render"])
def test_named_bad_documents(tmp_path, text, command):
    path = tmp_path / "in.json"
    path.write_bytes(text.encode("utf-8", "surrogateescape"))
    extra = ["-o", str(tmp_path / "x.png")] if command == "render" else []
    code, _ = assert_contract([command, str(path), *extra])
    assert code in (1, 2)


def test_version_must_be_the_integer_1(tmp_path):
    doc = json.loads(example_text("cube"))
    for bad in (1.0, True, "1"):
        (tmp_path / "c.json").write_text(json.dumps({**doc, "polyloops": bad}))
        code, err = assert_contract(["verify", str(tmp_path / "c.json")])
        assert code == 2 and "version" in err


def test_repeated_or_unused_corner_is_reported_by_verify(tmp_path):
    doc = json.loads(example_text("cube"))
    doc["faces"][0][1] = doc["faces"][0][0]
    (tmp_path / "c.json").write_text(json.dumps(doc))
    code, _ = assert_contract(["verify", str(tmp_path / "c.json")])
    assert code == 1


def test_non_rectangular_polycube_is_refused_by_every_reader(tmp_path):
    doc = json.loads(example_text("l-shape"))
    doc["positions"][0] = [p + 1 for p in doc["positions"][0]]
    path = tmp_path / "bent.json"
    path.write_text(json.dumps(doc))
    for command in (["signature"], ["orient"], ["moves"], ["add", "{}", "X0"], ["remove", "{}", "0"],
                    ["dualize"], ["info"]):
        argv = [p.format(path) for p in command] if "{}" in command else [*command, str(path)]
        code, err = assert_contract(argv)
        assert code in (0, 1) if command == ["info"] else code == 1, (command, err)


@pytest.mark.parametrize("argv", [
    ["moves", "example:cube", "--limit", "-1"],
    ["render", "example:cube", "-o", "x.png", "--views", "0"],
    ["sheet", "example:cube", "-o", "x.png", "--columns", "0"],
    ["sheet", "example:cube", "-o", "x.png", "--limit", "-1"],
    ["remove", "example:cube", "-3"],
    ["render", "example:cube", "-o", ".png"],
])
def test_out_of_range_options_are_usage_errors(argv, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _ = assert_contract(argv)
    assert code == 2
    assert not list(tmp_path.iterdir())


def test_huge_coordinates_render(tmp_path):
    doc = json.loads(example_text("cube"))
    doc["positions"] = [[x * 10**30 for x in p] for p in doc["positions"]]
    (tmp_path / "c.json").write_text(json.dumps(doc))
    code, _ = assert_contract(["render", str(tmp_path / "c.json"), "-o", str(tmp_path / "c.png")])
    assert code == 0 and (tmp_path / "c.png").stat().st_size > 0


def test_long_arguments_are_not_echoed(tmp_path):
    code, err = assert_contract(["verify", "sig:1o" + "A" * 100000])
    assert code == 2 and len(err) < 400
    long_sig = "sig:" + signature(load_example("non-incremental"))
    assert len(long_sig) > 255  # longer than a file name may be
    code, _ = assert_contract(["sheet", long_sig, "-o", str(tmp_path / "s.png")])
    assert code == 0
    code, _ = assert_contract(["verify", "x" * 5000])
    assert code == 2


def test_bad_catalog_line_for_sheet(tmp_path):
    (tmp_path / "cat").mkdir()
    (tmp_path / "cat" / "catalog.jsonl").write_text('{"signature": "x"\nnot json\n')
    code, err = assert_contract(["sheet", str(tmp_path / "cat"), "-o", str(tmp_path / "s.png")])
    assert code == 2 and "line 1" in err


def test_catalog_refuses_a_fake_plantri_and_missing_parents(tmp_path):
    code, err = assert_contract(["catalog", "--max-corners", "10", "--plantri", "/bin/true",
                                 "-o", str(tmp_path / "c")])
    assert code == 2 and "planar code" in err
    assert not (tmp_path / "c" / "catalog.jsonl").exists()
    code, err = assert_contract(["catalog", "--max-corners", "10", "-o", str(tmp_path / "a" / "b" / "c")])
    assert code == 2 and not (tmp_path / "a").exists()


def cli(*args, timeout=60):
    return subprocess.run([sys.executable, "-m", "polyloops", *args], capture_output=True, text=True,
                          timeout=timeout, stdin=subprocess.DEVNULL)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_special_files_do_not_hang(tmp_path):
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    for path in (str(fifo), "/dev/zero"):
        done = cli("verify", path)
        assert done.returncode == 2 and "not a regular file" in done.stderr


def _children(pid: int) -> list[str]:
    ps = subprocess.run(["ps", "-o", "pid=", "--ppid", str(pid)], capture_output=True, text=True).stdout
    return ps.split()


def test_terminated_write_leaves_no_temporary_file(tmp_path):
    """SIGTERM during a long catalog run: workers stop and no temporary file is left."""
    out = tmp_path / "c"
    proc = subprocess.Popen([sys.executable, "-m", "polyloops", "catalog", "--max-corners", "32",
                             "--workers", "2", "-o", str(out)], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, stdin=subprocess.DEVNULL)
    deadline = time.monotonic() + 30
    while time.monotonic() < deadline and not _children(proc.pid):  # its workers started
        time.sleep(0.1)
    assert _children(proc.pid), "the run started no workers"
    time.sleep(0.5)  # and are at work
    proc.terminate()
    proc.wait(timeout=30)
    assert proc.returncode == 130
    assert not [p for p in tmp_path.rglob("*") if p.name.endswith(".tmp")]
    ps = subprocess.run(["ps", "-eo", "args"], capture_output=True, text=True).stdout
    assert str(out) not in ps


READ_FORMATS = ["ply", "off", "vtk", "vtu", "medit", "gmsh", "apg", "obj", "planar"]


def valid_files() -> list[tuple[bytes, str]]:
    """Files polyloops writes, in every format it reads, of three examples (planar code holds
    genus-0 maps only, so not the ring)."""
    import tempfile

    import polyloops as pl
    from polyloops.io.registry import BY_NAME

    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("l-shape", "ring", "cube"):
            for fmt in READ_FORMATS:
                if fmt == "planar" and name == "ring":
                    continue
                suffix = BY_NAME[fmt].suffixes[0]
                path = os.path.join(tmp, name + suffix)
                pl.write(load_example(name), path)
                with open(path, "rb") as fh:
                    out.append((fh.read(), suffix))
    return out


VALID_FILES = valid_files()


@st.composite
def mutated_files(draw):
    """A valid file in one of the formats polyloops reads (written by polyloops), with bytes
    replaced, inserted or cut; half the time under a name without extension (read by content)."""
    base, suffix = draw(st.sampled_from(VALID_FILES))
    data = bytearray(base)
    for _ in range(draw(st.integers(1, 6))):
        i = draw(st.integers(0, max(len(data) - 1, 0)))
        how = draw(st.sampled_from(["replace", "insert", "delete", "cut"]))
        if how == "replace" and data:
            data[i] = draw(st.integers(0, 255))
        elif how == "insert":
            data[i:i] = draw(st.binary(min_size=1, max_size=8))
        elif how == "delete":
            del data[i:i + draw(st.integers(1, 40))]
        else:
            del data[i:]
    return bytes(data), suffix if draw(st.booleans()) else ""


@settings(max_examples=200, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(mutated_files(), st.sampled_from([["verify"], ["info"], ["signature"], ["identify"]]))
def test_mutated_files_of_every_format(tmp_path, case, command):
    data, suffix = case
    path = tmp_path / f"in{suffix}"
    path.write_bytes(data)
    assert_contract([*command, str(path)], seconds=10.0)


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")  # the dropped exception
def test_sigterm_whose_exception_a_finalizer_swallows_still_ends_interrupted(monkeypatch, capsys):
    """A signal handler's exception raised inside a finalizer is printed and dropped by Python;
    the command still ends "interrupted" (exit 130), not as if it had run to the end."""
    import argparse
    import gc
    import signal

    cli_main = sys.modules["polyloops.cli.main"]

    class SignalsWhenCollected:
        def __del__(self):
            os.kill(os.getpid(), signal.SIGTERM)  # the handler runs here, inside the finalizer

    def command(args):
        SignalsWhenCollected()
        gc.collect()
        return 0

    real = cli_main.build_parser

    def parser():
        built = real()
        parse = built.parse_args
        built.parse_args = lambda argv: argparse.Namespace(**{**vars(parse(argv)), "func": command})
        return built

    monkeypatch.setattr(cli_main, "build_parser", parser)
    assert cli_main.main(["examples"]) == 130
    assert "interrupted" in capsys.readouterr().err
    monkeypatch.undo()
    assert cli_main.main(["examples"]) == 0  # the next command in the process is not marked
