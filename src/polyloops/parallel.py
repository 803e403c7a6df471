"""Running independent jobs in one process, in local worker processes, or on a Dask cluster.

Leaving a local pool for any reason (Ctrl-C, SIGTERM, an error) terminates its workers, and a
worker on Linux asks the kernel to stop it if the parent dies outright, so no run leaves
processes behind.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import Any, TypeVar

T = TypeVar("T")


def die_with_parent() -> None:
    """In a worker: stop quietly on SIGTERM (the pool's way to end it; a handler inherited from
    the parent would print a traceback), and on Linux ask the kernel to send SIGTERM when the
    parent dies."""
    import contextlib
    import ctypes
    import signal
    import sys

    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
    if sys.platform.startswith("linux"):
        with contextlib.suppress(OSError):
            ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def run_jobs(func: Callable[[Any], T], items: Sequence[Any], workers: int = 1, dask: str | None = None,
             ordered: bool = True, batch: int = 1) -> Iterator[T]:
    """``func(item)`` for every item: results in item order when ``ordered``, else as they
    finish.  ``dask`` is a scheduler address, or ``"local"`` for a two-worker local cluster.
    ``batch`` items travel to a local worker in one message (for many small jobs)."""
    if dask is not None:
        yield from _run_dask(func, items, dask, ordered)
    elif workers > 1 and len(items) > 1:
        yield from _run_pool(func, items, workers, ordered, batch)
    else:
        yield from map(func, items)


def _run_pool(func: Callable[[Any], T], items: Sequence[Any], workers: int, ordered: bool,
              batch: int) -> Iterator[T]:
    """A local pool.  Leaving it early (an error, Ctrl-C, SIGTERM) terminates the workers at
    once; ``Pool.terminate`` itself can wait forever for a task it is still feeding to workers
    that are gone (its pipe full), so it gets a second in a daemon thread and the
    exception goes on regardless."""
    import multiprocessing
    import threading

    pool = multiprocessing.Pool(workers, initializer=die_with_parent)
    try:
        mapper = pool.imap if ordered else pool.imap_unordered
        yield from mapper(func, items, chunksize=max(1, batch))
        pool.close()
        pool.join()
    except BaseException:
        for child in multiprocessing.active_children():
            child.terminate()
        stopper = threading.Thread(target=pool.terminate, daemon=True)
        stopper.start()
        stopper.join(timeout=1)
        raise


def _run_dask(func: Callable[[Any], T], items: Iterable[Any], address: str, ordered: bool) -> Iterator[T]:
    try:
        from distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise RuntimeError("running on Dask needs dask.distributed: pip install 'polyloops[dask]'") from None
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           dashboard_address=None) if address == "local" else None
    try:
        with Client(cluster if cluster is not None else address) as client:
            futures = client.map(func, list(items), pure=False)
            if ordered:
                for fut in futures:
                    yield fut.result()
            else:
                for fut in as_completed(futures):
                    yield fut.result()
    finally:
        if cluster is not None:
            cluster.close()
