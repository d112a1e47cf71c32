"""The Dask loop's wait for a result (runs/dask_map._arrival): on
distributed's as_completed it waits on its condition until a result has
arrived; on one without that condition (not distributed's documented
API, so a later release may drop it) it polls after FETCH_GAP_S."""

from __future__ import annotations

import threading
import time

from contactsep.runs import dask_map


class _Arrivals:
    """An as_completed's two parts the wait uses."""

    def __init__(self, condition=True):
        self.ready = False
        if condition:
            self.thread_condition = threading.Condition()

    def has_ready(self):
        return self.ready


def test_without_the_condition_it_polls_after_the_fetch_gap(monkeypatch):
    # a listening limit far above the gap: a wait on it would show
    monkeypatch.setattr(dask_map, "LISTEN_S", 30.0)
    start = time.monotonic()
    dask_map._arrival(_Arrivals(condition=False), None)
    waited = time.monotonic() - start
    assert dask_map.FETCH_GAP_S <= waited < 10.0


def test_with_the_condition_a_result_ends_the_wait_early(monkeypatch):
    monkeypatch.setattr(dask_map, "LISTEN_S", 30.0)
    arrivals = _Arrivals()

    def arrive():
        time.sleep(0.02)
        with arrivals.thread_condition:
            arrivals.ready = True
            arrivals.thread_condition.notify_all()

    threading.Thread(target=arrive).start()
    start = time.monotonic()
    dask_map._arrival(arrivals, None)
    assert time.monotonic() - start < 10.0


def test_with_the_condition_and_nothing_arriving_it_listens_its_limit():
    start = time.monotonic()
    dask_map._arrival(_Arrivals(), None)
    assert time.monotonic() - start >= dask_map.LISTEN_S * 0.9


def test_the_fetch_gap_is_waited_only_while_tasks_are_in_flight(
        monkeypatch):
    """After a fetch, the next waits FETCH_GAP_S (results arriving fast
    come in one gather) while some task is still in flight; once every
    task has arrived (as_completed's ``futures`` empty) it fetches at
    once: a batch's last result is not held back."""
    monkeypatch.setattr(dask_map, "FETCH_GAP_S", 5.0)
    arrivals = _Arrivals()
    arrivals.ready = True
    arrivals.futures = {}
    start = time.monotonic()
    dask_map._arrival(arrivals, time.monotonic())
    assert time.monotonic() - start < 2.0
    monkeypatch.setattr(dask_map, "FETCH_GAP_S", 0.3)
    arrivals.futures = {"in flight": 1}
    start = time.monotonic()
    dask_map._arrival(arrivals, time.monotonic())
    assert time.monotonic() - start >= 0.25
