"""A batch of short simulations packed into Dask tasks
(contactsep.runs.dask_packs): the packs sized by the one chunk rule, the
results those of one run a task, in the tasks' order, and a run that
fails inside a pack that run's failure, the pack's other runs kept."""

from __future__ import annotations

import pytest

from contactsep.runs.chunks import MIN_PACK_S, chunk_seconds
from contactsep.runs.dask_packs import Pack, Packs, run_pack

distributed = pytest.importorskip("distributed")


def _timed(workers: int, seconds_a_run: float) -> Packs:
    packs = Packs(workers)
    packs.record(10, 10 * seconds_a_run)
    return packs


def test_a_pack_is_sized_by_the_chunk_rule():
    """One run a pack before any is timed; then the rule's seconds
    (chunk_seconds, down to MIN_PACK_S) over the time a run took, grown
    at most eightfold a batch, and a worker's share of a batch at most."""
    assert Packs(2).cut([4, 2, 0, 1, 3]) == [[4], [2], [0], [1], [3]]
    packs = _timed(2, 1e-3)
    order = list(range(100_000))
    sizes = [len(packs.cut(order)[0]) for _ in range(4)]
    # 100 s of work on 2 workers: PIECE_S a pack, 500 runs of 1 ms
    target = chunk_seconds(100.0, 2, MIN_PACK_S)
    assert target == 0.5
    assert sizes == [8, 64, 500, 500]
    # a short batch: MIN_PACK_S a pack (50 runs), its order kept
    cut = packs.cut(list(range(99, -1, -1)))
    assert [len(pack) for pack in cut] == [50, 50]
    assert sum(cut, []) == list(range(99, -1, -1))
    # never fewer packs than workers
    assert [len(p) for p in packs.cut([7, 8, 9])] == [1, 1, 1]
    assert [len(p) for p in packs.cut([1, 2, 3, 4, 5])] == [2, 2, 1]


def _fails_on_three(task):
    if task == 3:
        raise ValueError("run 3 fails")
    return 10 * task


def test_a_failing_run_is_a_status_inside_its_pack():
    out, seconds = run_pack(Pack(_fails_on_three, [1, 3, 5]))
    assert out[0] == (True, 10) and out[2] == (True, 50)
    assert out[1][0] is False and str(out[1][1]) == "run 3 fails"
    assert seconds >= 0


def _cluster():
    return distributed.LocalCluster(n_workers=1, threads_per_worker=1,
                                    processes=False, dashboard_address=":0")


def test_packed_results_are_the_unpacked_ones_in_order():
    """The same batch one run a task and packed (a timed Packs): the
    same results in the tasks' order, each handed to ``finished`` once
    and counted once; the scheduler saw one task a pack."""
    from contactsep.runs.dask_map import run_tasks
    tasks = list(range(40))
    order = sorted(tasks, key=lambda i: (i * 7) % 40)
    with _cluster() as cluster, distributed.Client(cluster) as client:
        plain = run_tasks(client, _fails_on_three, [t + 4 for t in tasks],
                          order=order)
        seen, counted = {}, []
        packs = _timed(1, 1e-3)
        expected = packs.cut(order)
        packs = _timed(1, 1e-3)
        with distributed.get_task_stream(client) as stream:
            packed = run_tasks(client, _fails_on_three,
                               [t + 4 for t in tasks], order=order,
                               finished=seen.__setitem__,
                               progress=counted.append, packs=packs)
    assert packed == plain == [10 * (t + 4) for t in tasks]
    assert seen == dict(enumerate(packed)) and counted == [1] * 40
    assert len(expected) == 5        # 8 runs a pack (the first growth)
    ran = [t for t in stream.data if str(t["key"]).startswith("run_pack")]
    assert len(ran) == len(expected)


def test_a_failing_run_in_a_pack_keeps_the_packs_other_runs():
    """The failing run's error is raised (as a one-run task's would be)
    after every other run of its pack is handed to ``finished`` (a
    journal keeps them): the pack is not lost."""
    from contactsep.runs.dask_map import run_tasks
    tasks = [1, 2, 3, 4, 5, 6]
    seen = {}
    with _cluster() as cluster, distributed.Client(cluster) as client:
        packs = _timed(1, 1e-3)
        with pytest.raises(ValueError, match="run 3 fails"):
            run_tasks(client, _fails_on_three, tasks,
                      finished=seen.__setitem__, packs=packs)
    assert seen == {0: 10, 1: 20, 3: 40, 4: 50, 5: 60}
