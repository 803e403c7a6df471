"""Command line interface; see :func:`polyloops.cli.main.main`."""

from polyloops.cli.main import main

__all__ = ["main"]
