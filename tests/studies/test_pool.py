"""The worker pool of the sweeps and the preload searches (issue 29
item 5): batches handed out costliest first, results in order."""

from __future__ import annotations

import time

from contactsep.studies.pool import map_longest_first, stop_pool, worker_pool


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
