"""Runs on a real ``dask.distributed`` scheduler (a local cluster of worker processes, reached by
its ``tcp://`` address as a remote one would be): the bytes of one process, and a worker that
dies in the middle of a job has the job run again elsewhere."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def scheduler():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()


def _dies_once(item: tuple[str, int]) -> int:
    """Square ``n``; the first worker to take item 3 dies there (its process ends at once)."""
    marker, n = item
    if n == 3 and not Path(marker).exists():
        Path(marker).write_text(str(os.getpid()))
        os._exit(1)
    return n * n


# Slow: in a loaded test run its restart has waited out a 30 s timeout (the catalog test below
# kills a worker too, and runs by default).
@pytest.mark.slow
def test_a_worker_that_dies_mid_job_has_its_job_run_again(scheduler, tmp_path):
    from polyloops.parallel import run_jobs

    marker = str(tmp_path / "died")
    got = list(run_jobs(_dies_once, [(marker, n) for n in range(8)], dask=scheduler, ordered=True))
    assert got == [n * n for n in range(8)] and Path(marker).exists()


def test_a_catalog_on_a_scheduler_address_is_the_one_process_catalog(scheduler, tmp_path):
    from polyloops.catalog.run import build_catalog

    assert scheduler.startswith("tcp://")
    on_cluster = build_catalog(tmp_path / "d", 18, generator="plantri", dask=scheduler)
    alone = build_catalog(tmp_path / "r", 18, generator="plantri")
    assert (tmp_path / "d" / "catalog.jsonl").read_bytes() == (tmp_path / "r" / "catalog.jsonl").read_bytes()
    assert on_cluster.summary["counts"] == alone.summary["counts"]


class _DieOnce(distributed.WorkerPlugin):
    """A worker plugin: the first worker to begin its ``nth`` task ends its process there and
    then (a marker file makes it happen once in the whole cluster, restarted workers included)."""

    name = "die-once"

    def __init__(self, marker: str, nth: int):
        self.marker, self.nth, self.begun = marker, nth, 0

    def setup(self, worker):
        self.begun = 0

    def transition(self, key, start, finish, **kwargs):
        if finish == "executing":
            self.begun += 1
            if self.begun == self.nth and not Path(self.marker).exists():
                Path(self.marker).write_text(str(os.getpid()))
                os._exit(1)


def test_a_catalog_survives_a_worker_killed_during_the_run(tmp_path):
    """A loops catalog through 26 corners (its top's levels and sixteen shares run as jobs) on a
    cluster of two worker processes, one of which dies in the middle of its third job: the
    job runs again and the records are those of one process, byte for byte."""
    from polyloops.catalog.run import build_catalog

    marker = tmp_path / "died"
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    try:
        with distributed.Client(cluster) as client:
            client.register_plugin(_DieOnce(str(marker), 3))
            on_cluster = build_catalog(tmp_path / "d", 26, generator="loops", workers=2,
                                       dask=cluster.scheduler_address)
    finally:
        cluster.close()
    alone = build_catalog(tmp_path / "r", 26, generator="loops")
    assert marker.exists()  # a worker did die mid-job
    assert (tmp_path / "d" / "catalog.jsonl").read_bytes() == (tmp_path / "r" / "catalog.jsonl").read_bytes()
    assert on_cluster.summary["counts"] == alone.summary["counts"]
