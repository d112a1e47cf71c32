"""The backends (contactsep.runs.backend): one contract, so the same
function on each gives the same results in the same order; chosen once
from --workers and --scheduler; a backend's own failures its own
messages."""

from __future__ import annotations

import os

import pytest

from contactsep.errors import InputError
from contactsep.runs import backend


def _square(x):
    return x * x


def _pid(task):
    return task, os.getpid()


ITEMS = [(i, (i,)) for i in range(12)]


def _backends():
    """One of each kind, opened: this process, two local workers, and an
    in-process Dask cluster of two threads (where Dask is installed)."""
    made = [("process", backend.backend_for(workers=1)),
            ("local", backend.backend_for(workers=2))]
    try:
        import distributed
    except ImportError:
        return made, None
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                       processes=False,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    made.append(("dask", backend.backend_for(scheduler=client)))
    return made, (client, cluster)


@pytest.fixture(scope="module")
def backends():
    made, dask = _backends()
    yield made
    for _, each in made:
        each.close()
    if dask is not None:
        client, cluster = dask
        client.close()
        cluster.close()


def test_backend_for_chooses_by_workers_and_scheduler(backends):
    kinds = {name: type(each) for name, each in backends}
    assert kinds["process"] is backend.InProcess
    assert kinds["local"] is backend.LocalPool
    if "dask" in kinds:
        assert kinds["dask"] is backend.DaskCluster
    for name, each in backends:
        assert each.workers == (1 if name == "process" else 2)
        assert each.parallel == (name != "process")


def test_every_backend_streams_the_same_items_in_order(backends):
    # items with no work keep their place in an ordered stream
    items = ITEMS[:5] + [("none", None)] + ITEMS[5:]
    expected = [(tag, None if args is None else args[0] ** 2)
                for tag, args in items]
    for name, each in backends:
        got = list(each.stream(_square, iter(items), window=3))
        assert got == expected, name


def test_every_backend_streams_every_item_unordered(backends):
    for name, each in backends:
        got = list(each.stream(_square, iter(ITEMS), window=4,
                               ordered=False))
        assert sorted(got) == [(i, i * i) for i in range(12)], name


def test_every_backend_maps_in_the_tasks_order(backends):
    tasks = [3.0, 1.0, 7.0, 2.0, 5.0]
    for name, each in backends:
        finished, progress = [], []
        out = each.map(_square, tasks, cost=lambda task: task,
                       finished=lambda i, r: finished.append((i, r)),
                       progress=progress.append)
        assert out == [t * t for t in tasks], name
        # each result told once, as it arrived
        assert sorted(finished) == [(i, t * t) for i, t in
                                    enumerate(tasks)], name
        assert progress == [1] * len(tasks), name


def test_the_local_backend_runs_on_other_processes(backends):
    local = dict(backends)["local"]
    pids = {pid for _, pid in local.map(_pid, list(range(8)))}
    assert os.getpid() not in pids
    here = dict(backends)["process"]
    assert {pid for _, pid in here.map(_pid, [1, 2])} == {os.getpid()}


def test_only_the_local_backend_sends_results_as_files(backends):
    for name, each in backends:
        assert each.results_by_file == (name == "local"), name
    local = dict(backends)["local"]
    directory = local.scratch()
    assert os.path.isdir(directory)


def test_a_local_scratch_directory_goes_with_its_backend():
    local = backend.backend_for(workers=2)
    directory = local.scratch()
    with open(os.path.join(directory, "chunk.npz"), "w") as file:
        file.write("x")
    local.close()
    assert not os.path.exists(directory)


def test_an_unordered_stream_in_process_refuses_an_item_without_work():
    with pytest.raises(ValueError, match="all need work"):
        list(backend.InProcess().stream(_square, iter([("a", None)]), 1,
                                        ordered=False))


class _NoProcesses:
    """A pool whose processes cannot start (a process limit)."""

    def submit(self, function, *args):
        raise OSError(11, "Resource temporarily unavailable")

    def shutdown(self, wait=True):
        pass


def test_workers_that_cannot_start_are_the_options_error(monkeypatch):
    monkeypatch.setattr(backend, "worker_pool",
                        lambda workers: _NoProcesses())
    with backend.backend_for(workers=3) as local:
        with pytest.raises(InputError) as caught:
            list(local.stream(_square, iter(ITEMS), window=2))
    assert str(caught.value) == (
        "--workers 3: the worker processes could not be started (Resource "
        "temporarily unavailable); try fewer")


def test_a_stop_request_ends_a_stream_in_process():
    class Stop(Exception):
        pass

    class Stops:
        calls = 0

        def check(self):
            self.calls += 1
            if self.calls > 2:
                raise Stop

    done = []
    with pytest.raises(Stop):
        for tag, result in backend.InProcess().stream(
                _square, iter(ITEMS), 1, stop=Stops()):
            done.append(tag)
    assert done == [0, 1]
