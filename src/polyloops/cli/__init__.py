"""The ``polyloops`` command line (:func:`polyloops.cli.main.main`): one small module per group
of commands, each parsing arguments, making one library call and printing; exit statuses and
one-line errors are kept in :mod:`polyloops.cli.load`.  It parses no file itself (the
layering test checks it): reading and writing go through :mod:`polyloops.io`."""

from polyloops.cli.main import main

__all__ = ["main"]
