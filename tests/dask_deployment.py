"""A Dask cluster started as a user starts one, for the tests: ``dask
scheduler --scheduler-file F`` and single-threaded ``dask worker
--scheduler-file F`` processes on 127.0.0.1, each its own process
group, killed at teardown (the ``deployment`` fixture: one a module)."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

#: The dask command of this environment (its workers import this
#: checkout's contactsep).
DASK = shutil.which("dask", path=os.path.dirname(sys.executable))


def _start(*args):
    return subprocess.Popen([DASK, *args], stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL,
                            start_new_session=True)


def _killpg(process) -> None:
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    process.wait(timeout=30)


class Deployment:
    """A scheduler and ``workers`` single-threaded workers sharing the
    scheduler file ``path``; the first worker started with
    ``worker_args`` too."""

    def __init__(self, path: Path, workers: int = 2,
                 worker_args=()) -> None:
        self.path = path
        self.scheduler = _start("scheduler", "--scheduler-file", str(path),
                                "--host", "127.0.0.1", "--port", "0",
                                "--no-dashboard")
        self.workers = []
        deadline = time.monotonic() + 60
        while not path.exists():
            assert time.monotonic() < deadline, "no scheduler file"
            assert self.scheduler.poll() is None, "the scheduler died"
            time.sleep(0.2)
        for _ in range(workers):
            self.workers.append(_start(
                "worker", "--scheduler-file", str(path), "--nthreads", "1",
                "--no-dashboard", "--host", "127.0.0.1",
                *(worker_args if not self.workers else ())))
        import distributed
        with distributed.Client(scheduler_file=str(path),
                                timeout=60) as client:
            client.wait_for_workers(workers, timeout=60)

    @property
    def address(self) -> str:
        return json.loads(self.path.read_text())["address"]

    def close(self) -> None:
        for process in (*self.workers, self.scheduler):
            _killpg(process)


@pytest.fixture(scope="module")
def deployment(tmp_path_factory):
    if DASK is None:
        pytest.skip("no dask command beside this Python")
    cluster = Deployment(tmp_path_factory.mktemp("dask") / "scheduler.json")
    yield cluster
    cluster.close()
