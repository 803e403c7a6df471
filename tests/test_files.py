"""The shared writer and the readers' checks (polyloops.io.files): an output never replaces
anything but the regular file it writes.  Device nodes, FIFOs and sockets are made here in a
temporary directory (never the machine's own /dev nodes); where mknod is not permitted, the
tests that need a device node skip and say so."""

import contextlib
import os
import socket
import stat
import threading
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

from polyloops.cli import main
from polyloops.io.files import (
    InputError,
    OutputError,
    Sink,
    read_bytes,
    read_text,
    resolve_output,
    write_atomic,
    writing,
)

NULL, FULL = (1, 3), (1, 7)  # Linux's numbers for the null and full devices


def make_device(path: Path, numbers: tuple[int, int]) -> Path:
    try:
        os.mknod(path, stat.S_IFCHR | 0o666, os.makedev(*numbers))
    except (PermissionError, AttributeError) as err:
        pytest.skip(f"cannot make a device node here ({err})")
    return path


def read_fifo_in_background(path: Path) -> tuple[threading.Thread, list[bytes]]:
    got: list[bytes] = []

    def reader() -> None:
        with open(path, "rb") as fh:
            got.append(fh.read())

    thread = threading.Thread(target=reader, daemon=True)
    thread.start()
    return thread, got


def leftovers(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir() if p.name.endswith(".tmp"))


def test_new_and_existing_regular_files(tmp_path):
    target = tmp_path / "a.json"
    write_atomic(target, "one")
    target.chmod(0o640)
    write_atomic(target, b"two")
    assert target.read_text() == "two"
    assert stat.S_IMODE(target.stat().st_mode) == 0o640  # an existing file keeps its permissions
    assert leftovers(tmp_path) == []


def test_a_symlink_is_followed_and_stays_a_link(tmp_path):
    real = tmp_path / "real.json"
    real.write_text("old")
    link = tmp_path / "link.json"
    link.symlink_to(real)
    chain = tmp_path / "chain.json"
    chain.symlink_to(link)
    write_atomic(chain, "new")
    assert chain.is_symlink() and link.is_symlink()
    assert real.read_text() == "new"


def test_a_dangling_link_creates_its_target(tmp_path):
    link = tmp_path / "link.json"
    link.symlink_to(tmp_path / "made.json")
    write_atomic(link, "x")
    assert link.is_symlink() and (tmp_path / "made.json").read_text() == "x"


def test_link_loops_directories_and_sockets_are_refused(tmp_path):
    loop = tmp_path / "loop"
    loop.symlink_to(tmp_path / "loop")
    with pytest.raises(OutputError, match="loop"):
        write_atomic(loop, "x")
    with pytest.raises(OutputError, match="is a directory"):
        write_atomic(tmp_path, "x")
    sock_path = tmp_path / "s.sock"
    with contextlib.closing(socket.socket(socket.AF_UNIX)) as sock:
        sock.bind(str(sock_path))
        with pytest.raises(OutputError, match="neither a regular file"):
            write_atomic(sock_path, "x")
        assert stat.S_ISSOCK(sock_path.stat().st_mode)
    with pytest.raises(OutputError, match="does not exist"):
        write_atomic(tmp_path / "no" / "x.json", "x")


def test_a_block_device_is_refused_untouched(tmp_path):
    node = tmp_path / "blk"
    try:
        os.mknod(node, stat.S_IFBLK | 0o600, os.makedev(7, 250))
    except PermissionError as err:
        pytest.skip(f"cannot make a device node here ({err})")
    with pytest.raises(OutputError, match="neither a regular file"):
        write_atomic(node, "x")
    assert stat.S_ISBLK(node.lstat().st_mode)


def test_devices_are_written_into_not_replaced(tmp_path):
    null = make_device(tmp_path / "null", NULL)
    full = make_device(tmp_path / "full", FULL)
    write_atomic(null, "discarded")
    assert stat.S_ISCHR(null.lstat().st_mode)
    with pytest.raises(OutputError, match="no space left on device"):
        write_atomic(full, "x" * 10_000)
    with pytest.raises(OutputError, match="no space left on device"), writing(full) as out:
        Path(out.path).write_text("y" * 10_000)
    assert stat.S_ISCHR(full.lstat().st_mode)
    assert resolve_output(null).sink is Sink.STREAM


def test_a_fifo_is_written_into(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    thread, got = read_fifo_in_background(fifo)
    write_atomic(fifo, "through the pipe")
    thread.join(5)
    assert got == [b"through the pipe"] and stat.S_ISFIFO(fifo.lstat().st_mode)
    thread, got = read_fifo_in_background(fifo)
    with writing(fifo) as out:
        Path(out.path).write_bytes(b"from a library writer")
    thread.join(5)
    assert got == [b"from a library writer"]
    assert leftovers(tmp_path) == []


def test_standard_output(capfdbinary):
    write_atomic("-", "to stdout\n")
    with writing("-") as out:
        Path(out.path).write_bytes(b"and again\n")
    assert capfdbinary.readouterr().out == b"to stdout\nand again\n"


def test_a_failed_writer_changes_nothing(tmp_path):
    target = tmp_path / "keep.json"
    target.write_text("precious")
    with pytest.raises(RuntimeError), writing(target) as out:
        Path(out.path).write_text("half")
        raise RuntimeError("the writer failed")
    assert target.read_text() == "precious" and leftovers(tmp_path) == []


KINDS = ["missing", "regular", "link", "dangling", "chain", "fifo", "null", "dir"]


def make_target(tmp_path: Path, kind: str, i: int) -> Path:
    path = tmp_path / f"t{i}"
    if kind == "regular":
        path.write_text("old")
    elif kind in ("link", "chain"):
        (tmp_path / f"r{i}").write_text("old")
        path.symlink_to(tmp_path / f"r{i}")
        if kind == "chain":
            (tmp_path / f"c{i}").symlink_to(path)
            path = tmp_path / f"c{i}"
    elif kind == "dangling":
        path.symlink_to(tmp_path / f"r{i}")
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "null":
        make_device(path, NULL)
    elif kind == "dir":
        path.mkdir()
    return path


def node_kinds(tmp_path: Path) -> dict[str, int]:
    return {p.name: stat.S_IFMT(p.lstat().st_mode) for p in tmp_path.iterdir()}


@given(cases=st.lists(st.tuples(st.sampled_from(KINDS), st.binary(max_size=64)), min_size=1, max_size=6))
def test_property_nothing_but_the_regular_file_is_replaced(tmp_path_factory, cases):
    """Over any mix of targets: every node keeps its kind (a link stays a link, a device a
    device), regular files and link targets hold exactly the new bytes, a FIFO's reader gets
    them, a directory is refused untouched, and no temporary file is left."""
    tmp_path = tmp_path_factory.mktemp("w")
    for i, (kind, data) in enumerate(cases):
        target = make_target(tmp_path, kind, i)
        before = node_kinds(tmp_path)
        if kind == "dir":
            with pytest.raises(OutputError):
                write_atomic(target, data)
        elif kind == "fifo":
            thread, got = read_fifo_in_background(target)
            write_atomic(target, data)
            thread.join(5)
            assert got == [data]
        else:
            write_atomic(target, data)
            if kind != "null":
                assert Path(os.path.realpath(target)).read_bytes() == data
        after = node_kinds(tmp_path)
        assert {k: v for k, v in after.items() if k in before} == before
        assert set(after) - set(before) <= {"dangling": {f"r{i}"}, "missing": {f"t{i}"}}.get(kind, set())
        assert leftovers(tmp_path) == []


def test_readers_take_regular_files_and_stdin(tmp_path, monkeypatch):
    import io
    import sys

    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    with pytest.raises(InputError, match="not a regular file"):
        read_bytes(fifo)  # no writer: must not block
    with pytest.raises(InputError, match="is a directory"):
        read_bytes(tmp_path)
    bom = tmp_path / "bom.txt"
    bom.write_bytes(b"\xef\xbb\xbfv 0 0 0\n")
    assert read_text(bom) == "v 0 0 0\n"
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(b"from stdin")))
    assert read_bytes("-") == b"from stdin"


# -- the command line on the same nodes -----------------------------------------------------------

def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_cli_outputs_into_devices_links_and_dirs(capsys, tmp_path):
    null = make_device(tmp_path / "null", NULL)
    full = make_device(tmp_path / "full", FULL)
    status, _, err = run(capsys, "convert", "example:cube", str(null))
    assert status == 0 and stat.S_ISCHR(null.lstat().st_mode), err
    for argv in (["convert", "example:cube", str(full)],
                 ["render", "example:cube", "-o", str(full.with_name("full.png"))]):
        if argv[0] == "render":
            full.with_name("full.png").symlink_to(full)
        status, _, err = run(capsys, *argv)
        assert status == 2 and "no space left on device" in err and "Traceback" not in err
        assert err.count("\n") == 1 and stat.S_ISCHR(full.lstat().st_mode)
    real = tmp_path / "real.json"
    real.write_text("{}")
    (tmp_path / "link.json").symlink_to(real)
    status, _, _ = run(capsys, "dualize", "example:cube", "-o", str(tmp_path / "link.json"))
    assert status == 0 and (tmp_path / "link.json").is_symlink() and '"loop-structure"' in real.read_text()
    (tmp_path / "d.json").mkdir()
    for argv in (["convert", "example:cube", str(tmp_path / "d.json")],
                 ["render", "example:cube", "-o", str(tmp_path)]):
        status, _, err = run(capsys, *argv)
        assert status == 2 and err.count("\n") == 1, err


def test_cli_picture_to_stdout(capfdbinary):
    status = main(["render", "example:cube", "-o", "-"])
    out = capfdbinary.readouterr().out
    assert status == 0 and out.startswith(b"\x89PNG")  # the PNG alone, no message mixed in


def test_cli_dash_is_stdout_and_stdin(capfd, tmp_path):
    import subprocess
    import sys

    status = main(["dualize", "example:l-shape", "-o", "-"])
    out, _ = capfd.readouterr()
    assert status == 0 and '"loop-structure"' in out
    status = main(["convert", "example:l-shape", "-", "--to", "obj"])
    out, _ = capfd.readouterr()
    assert status == 0 and out.startswith(("v ", "#"))
    data = main(["dualize", "example:cube"])
    text = capfd.readouterr().out
    assert data == 0
    done = subprocess.run([sys.executable, "-m", "polyloops", "verify", "-"], input=text,
                          capture_output=True, text=True)
    assert done.returncode == 0 and "valid" in done.stdout
