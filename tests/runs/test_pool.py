"""The worker pool of the sweeps and the preload searches (issue 29
item 5): batches handed out costliest first, results in order; the one
local loop (pool.stream, issue 46): the items' order or arrival order,
its window held, a dead worker's tasks run again."""

from __future__ import annotations

import time

import pytest

from contactsep.runs.pool import RestartingPool, map_longest_first, stream


def _started(task):
    return task, time.monotonic()


def test_a_batch_goes_costliest_first_and_comes_back_in_order():
    tasks = [(0.0, "a"), (5.0, "b"), (1.0, "c"), (20.0, "d"), (0.5, "e")]
    pool = RestartingPool(1)     # one worker: it runs them as handed out
    try:
        out = map_longest_first(pool, _started, tasks,
                                cost=lambda task: task[0])
    finally:
        pool.stop()
    assert [task for task, _ in out] == tasks
    by_start = [task for task, _ in sorted(out, key=lambda r: r[1])]
    assert by_start == sorted(tasks, key=lambda task: -task[0])


def test_without_a_cost_the_batch_goes_in_order():
    pool = RestartingPool(1)
    try:
        out = map_longest_first(pool, _started, [3, 1, 2])
    finally:
        pool.stop()
    assert [task for task, _ in sorted(out, key=lambda r: r[1])] == [3, 1, 2]


def test_every_worker_gets_twenty_chunks_of_at_least_a_fifth_of_a_second():
    """Chunks from the measured cost (issue 29): about 0.5 s each while
    the work left is large; then each of the workers gets 20 of what is
    left, down to 0.2 s a chunk."""
    from contactsep.runs.chunks import Chunks
    # 1 ms a design measured; 1e6 designs left: 1000 s, 0.5 s chunks
    big = Chunks(10**6, 10**6, 4, workers=4)
    big.record(100, 0.1)
    assert big.next == 500
    # 10,000 designs left on 2 workers: 10 s / 40 chunks = 0.25 s
    mid = Chunks(10_000, 10**6, 4, workers=2)
    mid.record(100, 0.1)
    assert mid.next == 250
    # 2,000 designs on 4 workers: 2 s / 80 = 0.025 s, held at 0.2 s
    small = Chunks(2_000, 10**6, 4, workers=4)
    small.record(100, 0.1)
    assert small.next == 200
    # the designs already handed out are not left: half done, 5 s left
    half = Chunks(10_000, 10**6, 4, workers=1)
    half.next = 5_000
    assert next(half.plan()) == (0, 5_000, False)
    half.record(100, 0.1)
    assert half.next == 250


# --- a worker that dies: the pool is started again ------------------------

def _dies_once(task):
    """``task`` (n, marker file): 3 n, but the worker running n = 5 is
    SIGKILLed the first time (the marker then exists)."""
    import os
    import signal
    n, marker = task
    if n == 5 and not os.path.exists(marker):
        open(marker, "w").close()
        os.kill(os.getpid(), signal.SIGKILL)
    time.sleep(0.01)
    return 3 * n


def _always_dies(task):
    import os
    import signal
    os.kill(os.getpid(), signal.SIGKILL)


def test_a_batch_whose_worker_dies_is_finished_on_a_new_pool(tmp_path):
    """Every result, in order, each handed to ``finished`` once and
    counted done once; the second pool finished it."""
    tasks = [(n, str(tmp_path / "died")) for n in range(12)]
    arrived, done = [], []
    pool = RestartingPool(2)
    try:
        out = map_longest_first(pool, _dies_once, tasks,
                                finished=lambda i, result: arrived.append(i),
                                done=done.append)
    finally:
        pool.stop()
    assert out == [3 * n for n in range(12)]
    assert (tmp_path / "died").exists() and len(pool.pools) == 2
    assert sorted(arrived) == list(range(12))
    assert sum(done) == 12


def test_workers_that_die_every_time_are_one_line():
    from contactsep.errors import InputError
    from contactsep.runs.pool import MAX_POOL_RESTARTS
    pool = RestartingPool(2)
    try:
        with pytest.raises(InputError) as caught:
            map_longest_first(pool, _always_dies, [1, 2, 3])
    finally:
        pool.stop(finished=False)
    assert str(caught.value) == ("a worker process died 4 times (killed, "
                                 "or out of memory)")
    assert len(pool.pools) == MAX_POOL_RESTARTS + 1 == 4


def test_a_preload_search_survives_a_dead_worker(tmp_path):
    """The searches' Simulations (2 workers: the pool path) with a
    journal: the batch's results, each kept once."""
    from contactsep.runs.journal import RunJournal
    from contactsep.studies.preload.chart import Simulations
    tasks = [(n, str(tmp_path / "died")) for n in range(10)]
    with RunJournal(tmp_path / "j", {}) as journal, \
            Simulations(2, journal=journal) as sims:
        assert sims.map(_dies_once, tasks) == [3 * n for n in range(10)]
        assert (tmp_path / "died").exists()
        assert journal.recorded == 10 == len(journal)


# --- the one local loop: pool.stream ---------------------------------------

def _slept(seconds):
    time.sleep(seconds)
    return seconds


@pytest.mark.parametrize("ordered", [True, False])
def test_the_stream_hands_back_in_order_or_as_they_arrive(ordered):
    """A long first task on two workers: the items' order waits for it
    (an item without work in its place), arrival order gives it last."""
    delays = [1.0, 0.02, 0.02, 0.02]
    items = [(i, (d,)) for i, d in enumerate(delays)]
    if ordered:
        items.insert(2, ("none", None))
    pool = RestartingPool(2)
    try:
        out = list(stream(pool, _slept, items, len(items), ordered=ordered))
    finally:
        pool.stop()
    if ordered:
        assert out == [(0, 1.0), (1, 0.02), ("none", None), (2, 0.02),
                       (3, 0.02)]
    else:
        assert sorted(out) == [(i, d) for i, d in enumerate(delays)]
        assert out[-1] == (0, 1.0)


@pytest.mark.parametrize("ordered", [True, False])
def test_the_stream_holds_its_window(ordered):
    """The items are taken only as the window has room: never more than
    ``window`` ahead of those handed back, and the window filled."""
    window, drawn, handed, ahead = 3, [0], [0], []

    def items():
        for i in range(12):
            drawn[0] += 1
            ahead.append(drawn[0] - handed[0])
            yield i, (0.01 * (i % 3),)

    pool = RestartingPool(2)
    try:
        tags = []
        for tag, _ in stream(pool, _slept, items(), window,
                             ordered=ordered):
            handed[0] += 1
            tags.append(tag)
    finally:
        pool.stop()
    assert sorted(tags) == list(range(12))
    if ordered:
        assert tags == list(range(12))
    assert max(ahead) == window


def test_the_ordered_stream_survives_a_dead_worker(tmp_path):
    """A sweep's stream (the items' order): a worker killed mid-stream
    costs nothing; the chunks in flight run again on a second pool."""
    items = [(n, ((n, str(tmp_path / "died")),)) for n in range(12)]
    pool = RestartingPool(2)
    try:
        out = list(stream(pool, _dies_once, items, 4))
    finally:
        pool.stop()
    assert out == [(n, 3 * n) for n in range(12)]
    assert (tmp_path / "died").exists() and len(pool.pools) == 2


def test_a_stream_whose_workers_always_die_is_one_line_with_advice():
    from contactsep.errors import InputError
    pool = RestartingPool(2)
    try:
        with pytest.raises(InputError) as caught:
            list(stream(pool, _always_dies, [(n, (n,)) for n in range(3)],
                        2, advice=": try less"))
    finally:
        pool.stop(finished=False)
    assert str(caught.value) == ("a worker process died 4 times (killed, "
                                 "or out of memory: try less)")


class _Stop:
    """A stop request that the test sets: check() raises then."""

    def __init__(self) -> None:
        self.asked = False

    def check(self) -> None:
        if self.asked:
            raise KeyboardInterrupt


@pytest.mark.parametrize("ordered", [True, False])
def test_a_stop_ends_the_stream_while_it_waits(ordered):
    """A stop asked while a long task runs ends the stream within a
    wait (LISTEN_S)."""
    import threading
    from contactsep.runs.pool import LISTEN_S
    stop = _Stop()
    pool = RestartingPool(1)
    work = stream(pool, _slept, [(i, (5.0,)) for i in range(3)], 3,
                  ordered=ordered, stop=stop)
    timer = threading.Timer(0.3, lambda: setattr(stop, "asked", True))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            next(work)
    finally:
        timer.cancel()
        pool.stop(finished=False)
    assert time.monotonic() - start < 0.3 + 2 * LISTEN_S + 0.5
