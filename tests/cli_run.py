"""Running the command line in a test: its status (argparse's own exits included) and output."""

from __future__ import annotations

from polyloops.cli import main


def run(capsys, *argv: str) -> tuple[int, str, str]:
    """``polyloops ARGV...``: the exit status, standard output and standard error."""
    try:
        status = main(list(argv))
    except SystemExit as stop:  # argparse's own checks
        status = int(stop.code or 0)
    out, err = capsys.readouterr()
    return status, out, err
