"""What the ``polyloops`` command sets before numpy loads.

The command uses numpy for arrays, never for large linear algebra, and OpenBLAS starts a
spinning thread per core when numpy is imported: about 0.1 s of CPU on every command
(measured with ``farm-bench``, docs/performance.md).  So the command, and only the command
(``polyloops ...`` or ``python -m polyloops ...``), asks for one BLAS thread; a library user's
settings are left alone, and an explicit setting always wins.

The command also keeps freed memory for reuse (glibc's ``mallopt``): a picture's pixel arrays
are a few MB each, and by default every such array is mapped from the kernel and unmapped
again, page faults included; for a gallery that was a quarter of its CPU time in the kernel.
Arrays up to 64 MB come from the heap, and the heap keeps up to 256 MB free before giving it
back.  Not on other C libraries, and not when ``MALLOC_MMAP_THRESHOLD_`` is set.
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


M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3  # mallopt's parameters (malloc.h)


def keep_freed_memory() -> None:
    """The command's allocation settings (see the module's comment); quietly nothing where
    glibc's ``mallopt`` is missing."""
    if not started_as_the_command() or "MALLOC_MMAP_THRESHOLD_" in os.environ \
            or not sys.platform.startswith("linux"):
        return
    import ctypes

    try:
        libc = ctypes.CDLL("libc.so.6")
        libc.mallopt(M_MMAP_THRESHOLD, 64 << 20)
        libc.mallopt(M_TRIM_THRESHOLD, 256 << 20)
    except (OSError, AttributeError):  # another C library
        pass


pin_blas_threads()
keep_freed_memory()
