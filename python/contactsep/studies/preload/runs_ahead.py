"""Runs made ahead of being asked for: a search's idle workers given the
candidates its next steps may need.

A search asks for its runs in batches (a scan's octave, one bisection
midpoint, a fine band), and a batch smaller than the number of workers
leaves some of them idle for a whole round.  Before such a batch the
search names the runs its next steps would ask for (the next octave of
the scan, the midpoints of the bisection's next levels: most likely
first); as many as fill the batch's last round run beside it, and a
later batch that asks for one of them takes its result from here instead
of running it again.

The answer cannot depend on this: a search asks for exactly the runs it
asks for without it, in the same order, and each run's result is the
same function of the same task wherever and whenever it ran.  A run made
ahead that the search never asks for is in no answer, log or CSV (it is
counted apart: ``made`` less ``used``); a journal keeps it like any other, so that a
resumed search does not run it again.
"""

from __future__ import annotations

from contactsep.runs.task_keys import task_key


class RunsAhead:
    """The results of runs made ahead (by task key) and those queued to
    run with the next batch, for ``capacity`` workers (1: none ahead)."""

    def __init__(self, capacity: int = 1) -> None:
        self.capacity = max(int(capacity), 1)
        self._results = {}
        self._queued = []
        #: Runs made ahead, and how many of them a batch then asked for.
        self.made = 0
        self.used = 0

    def room(self, asked: int) -> int:
        """How many runs fit beside a batch of ``asked`` runs in its last
        round on the workers (none beside an empty batch)."""
        if self.capacity <= 1 or asked <= 0:
            return 0
        return -asked % self.capacity

    def queue(self, function, tasks, asked: int, journal=None) -> None:
        """Queue ``tasks`` (most likely first) for ``function``, as many
        as fit beside the next batch of ``asked`` runs; those already
        made, queued, or held by ``journal`` are skipped."""
        room = self.room(asked) - len(self._queued)
        queued = {key for key, _, _ in self._queued}
        for task in tasks:
            if room <= 0:
                return
            key = task_key(function, task)
            if key in self._results or key in queued or (
                    journal is not None and journal.lookup(key)[0]):
                continue
            self._queued.append((key, function, task))
            queued.add(key)
            room -= 1

    def answered(self, function, tasks) -> tuple[list, list]:
        """(results, indices to run): each task's result where it was
        made ahead (None elsewhere), and the tasks still to run."""
        out, todo = [None] * len(tasks), []
        if not self._results:
            return out, list(range(len(tasks)))
        for i, task in enumerate(tasks):
            key = task_key(function, task)
            if key in self._results:
                out[i] = self._results.pop(key)
                self.used += 1
            else:
                todo.append(i)
        return out, todo

    def take(self, function, tasks) -> list:
        """The tasks queued for ``function`` to run beside ``tasks`` (the
        batch's own runs, none of which is run twice); the queue is then
        empty.  Beside no runs (a batch answered from here), the queue
        waits for the next batch that runs."""
        if not tasks or not self._queued:
            return []
        queued, self._queued = self._queued, []
        asked = {task_key(function, task) for task in tasks}
        return [(key, task) for key, f, task in queued
                if f is function and key not in asked]

    def keep(self, taken: list, results: list) -> None:
        """The results of the tasks :meth:`take` gave, for later
        batches."""
        for (key, _), result in zip(taken, results):
            self._results[key] = result
        self.made += len(taken)
