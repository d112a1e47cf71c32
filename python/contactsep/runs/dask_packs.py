"""Many short simulations in one Dask task: a batch of
:func:`contactsep.runs.dask_map.run_tasks` cut into packs (:class:`Pack`,
the function and a list of the batch's tasks), each one task on the
cluster, sized by the one chunk rule (:func:`contactsep.runs.chunks.
chunk_seconds`) from the seconds a run took in the packs before
(:class:`Packs`; the first batch one run a pack, as a costly sweep's
first chunk).  Each run's failure stays that run's: a pack hands back
every run's result or error, in its order.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

from contactsep.output.pieces import PieceSizes
from contactsep.runs.chunks import MIN_PACK_S, chunk_seconds


@dataclass(frozen=True)
class Pack:
    """The typed task of one pack: ``function(task)`` for each of
    ``tasks``, in order, on one worker."""

    function: Callable
    tasks: list


def run_pack(pack: Pack) -> tuple[list, float]:
    """On a Dask worker (glibc's own heap thresholds: the Dask loop's
    :class:`~contactsep.runs.dask_map.OnWorker`): ([(True, result) or
    (False, the exception)] of each of the pack's runs, in order; the
    seconds they took together)."""
    start = time.perf_counter()
    out = []
    for task in pack.tasks:
        try:
            out.append((True, pack.function(task)))
        except Exception as error:   # noqa: BLE001 - the run's own status
            out.append((False, error))
    return out, time.perf_counter() - start


class Packs:
    """The packs of each batch on ``workers`` worker threads, sized from
    the runs timed so far (one object for a search: its batches are
    alike)."""

    def __init__(self, workers: int = 1) -> None:
        self.workers = max(1, workers)
        self._sizes = PieceSizes(1)

    def cut(self, order: list) -> list[list]:
        """``order`` (the batch's indices, costliest first) in packs of
        consecutive indices: each the rule's seconds of the batch on
        the workers (down to MIN_PACK_S, but a worker's share of the
        batch at most), one run a pack before any is timed."""
        rate = self._sizes.seconds_per_item
        if not rate:
            return [[i] for i in order]
        self._sizes.resize(chunk_seconds(len(order) * rate, self.workers,
                                         MIN_PACK_S))
        # and never fewer packs than workers: the floor would idle some
        size = max(1, min(self._sizes.next, len(order) // self.workers))
        return [order[at:at + size] for at in range(0, len(order), size)]

    def record(self, runs: int, seconds: float) -> None:
        """A pack of ``runs`` took ``seconds`` on its worker."""
        self._sizes.observe(runs, seconds)
