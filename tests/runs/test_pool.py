"""The worker pool of the sweeps and the preload searches (issue 29
item 5): batches handed out costliest first, results in order."""

from __future__ import annotations

import time

from contactsep.runs.pool import map_longest_first, stop_pool, worker_pool


def _started(task):
    return task, time.monotonic()


def test_a_batch_goes_costliest_first_and_comes_back_in_order():
    tasks = [(0.0, "a"), (5.0, "b"), (1.0, "c"), (20.0, "d"), (0.5, "e")]
    pool = worker_pool(1)        # one worker: it runs them as handed out
    try:
        out = map_longest_first(pool, _started, tasks,
                                cost=lambda task: task[0])
    finally:
        stop_pool(pool)
    assert [task for task, _ in out] == tasks
    by_start = [task for task, _ in sorted(out, key=lambda r: r[1])]
    assert by_start == sorted(tasks, key=lambda task: -task[0])


def test_without_a_cost_the_batch_goes_in_order():
    pool = worker_pool(1)
    try:
        out = map_longest_first(pool, _started, [3, 1, 2])
    finally:
        stop_pool(pool)
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
