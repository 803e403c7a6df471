"""What the ``polyloops`` command sets before numpy loads.

The command uses numpy for arrays, never for large linear algebra, and OpenBLAS starts a
spinning thread per core when numpy is imported: about 0.1 s of CPU on every command
(measured with ``farm-bench``, docs/performance.md).  So the command, and only the command
(``polyloops ...`` or ``python -m polyloops ...``), asks for one BLAS thread; a library user's
settings are left alone, and an explicit setting always wins.
"""

from __future__ import annotations

import os
import sys

BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def started_as_the_command() -> bool:
    """Whether this process is the ``polyloops`` command."""
    argv = getattr(sys, "orig_argv", sys.argv)
    prog = os.path.basename(sys.argv[0]) if sys.argv else ""
    return prog == "polyloops" or any(argv[i:i + 2] == ["-m", "polyloops"] for i in range(len(argv)))


def pin_blas_threads() -> None:
    """One BLAS thread for the command (unless set already, or numpy is loaded)."""
    if started_as_the_command() and "numpy" not in sys.modules:
        for var in BLAS_THREADS:
            os.environ.setdefault(var, "1")


pin_blas_threads()
