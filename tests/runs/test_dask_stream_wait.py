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
