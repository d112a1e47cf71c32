"""The preload searches' tasks: a journal kept when they were plain
tuples is still answered from (their digests written out here by the
journal's rule of then, on literal tuples), and every batch, the robust
search's included, reaches the pool costliest first (observed by a pool
that runs each task as it is handed one, on planted simulations)."""

from __future__ import annotations

import hashlib
import json
from concurrent.futures import Future

import pytest
from design_family import FAMILY

from contactsep.studies.preload import chart as preload

from contactsep.studies.preload import robust as preload_robust
from contactsep.studies.preload.runs import PreloadRun, SampleRun
from contactsep.runs import backend
from contactsep.runs.journal import RunJournal
from contactsep.runs.task_keys import canonical

SETTINGS = {"dt": 1e-8, "t_end": 0.01, "damping": "none"}
#: The planted threshold: an event below this many lb per inch of the
#: separator's thickness (within every family design's ceiling, at 1.5
#: times its thickness).
PER_IN = 2.0


def tuple_key(function, task: tuple) -> str:
    """A simulation's digest as the journal made it from a plain tuple
    task: SHA-256 of the compact, key-sorted JSON of [the function's
    module.qualname, the task's canonical data]."""
    text = json.dumps([f"{function.__module__}.{function.__qualname__}",
                       canonical(task)], sort_keys=True,
                      separators=(",", ":"), allow_nan=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _refuse(*args, **kwargs):
    raise AssertionError("a task the journal holds was simulated")


@pytest.mark.parametrize("name", ["thesis", "steel_relay", "becu_light"])
def test_a_journal_of_plain_tuple_tasks_answers_the_named_tasks(
        name, tmp_path, monkeypatch):
    design = FAMILY[name]
    fields = {field: getattr(design, field)
              for field in type(design).__dataclass_fields__}
    own = {"min_open": 2e-5}
    # the tasks as the searches built them: (design, model, settings,
    # preload) for the nominal search, (fields, model, settings with
    # the preload) for a sample of the robust search
    nominal = [((design, "hertz", SETTINGS, p), p < 0.1)
               for p in (0.05, 0.2)]
    robust = [((fields, "hertz", {"min_open": 2e-5, "preload": p}),
               (int(p < 0.1), 0)) for p in (0.05, 0.2)]
    inputs = {"test": name}
    with RunJournal(tmp_path / "journal", inputs) as journal:
        for task, result in nominal:
            journal.record(tuple_key(preload._simulate_event, task), result)
        for task, result in robust:
            journal.record(tuple_key(preload_robust._sample_run, task),
                           result)
    monkeypatch.setattr(preload, "simulate", _refuse)
    monkeypatch.setattr(preload_robust, "simulate_design", _refuse)
    with RunJournal(tmp_path / "journal", inputs) as journal, \
            preload.Simulations(1, journal=journal) as sims:
        events = sims.events([PreloadRun(design, "hertz", SETTINGS, p)
                              for p in (0.05, 0.2)])
        samples = sims.map(preload_robust._sample_run,
                           [SampleRun(fields, "hertz", own, p)
                            for p in (0.05, 0.2)])
        assert journal.reused == 4 and journal.recorded == 0
    assert events == [True, False]
    assert samples == [(1, 0), (0, 0)]


class RecordingPool:
    """A pool that runs each task in this process as it is handed one;
    ``batches``: the preloads the simulations received, one list a
    batch, in the order they were handed out."""

    def __init__(self) -> None:
        self.batches: list = []

    def submit(self, function, task) -> Future:
        future = Future()
        future.set_result(function(task))
        return future

    def shutdown(self, wait: bool = True) -> None:
        pass


@pytest.fixture
def pool(monkeypatch):
    """The searches' batches on a RecordingPool (2 workers asked for:
    the pool path), the simulations planted: an event below PER_IN lb
    per inch of the separator's thickness."""
    recorder = RecordingPool()
    real = backend.map_longest_first

    def batch(*args, **kwargs):
        recorder.batches.append([])
        return real(*args, **kwargs)

    def sample(fields, model, settings):
        recorder.batches[-1].append(settings["preload"])
        event = settings["preload"] < PER_IN * fields["h2"]
        return (0.0,) * 5 + (int(event), 0)

    def event(task):
        design, load = task.design, task.preload_lb
        recorder.batches[-1].append(load)
        return load < PER_IN * design.h2

    monkeypatch.setattr(backend, "worker_pool", lambda workers: recorder)
    monkeypatch.setattr(backend, "map_longest_first", batch)
    monkeypatch.setattr(preload_robust, "simulate_design", sample)
    monkeypatch.setattr(preload, "_simulate_event", event)
    return recorder


def _costliest_first(batches) -> int:
    """The batches of several preloads, each checked to reach the pool
    in non-increasing preload order."""
    mixed = [b for b in batches if len(set(b)) > 1]
    for handed in mixed:
        assert handed == sorted(handed, reverse=True)
    return len(mixed)


@pytest.mark.parametrize("name", ["thesis", "steel_relay", "becu_light"])
def test_the_robust_batches_reach_the_pool_costliest_first(name, pool):
    design = FAMILY[name]
    spec = preload_robust.parse_tolerances(
        [f"d=uniform({0.9 * design.h2!r},{1.1 * design.h2!r})"], 100, 1)
    with preload.Simulations(2) as sims:
        robust = preload_robust.robust_preload(
            design, "hertz", dict(SETTINGS), spec, 0.05, sims,
            start=PER_IN * design.h2, ceiling=1e3)
    # a search was run (no sample of the 100 open: the answer at or
    # above the planted threshold of the thickest sample, up to 1.1 d),
    # in batches of several preloads
    assert PER_IN * design.h2 <= robust.min_preload_lb <= \
        1.1 * 1.01 * PER_IN * design.h2
    assert robust.n_open == 0
    assert _costliest_first(pool.batches) >= 2


@pytest.mark.parametrize("name", ["thesis", "steel_relay", "becu_light"])
def test_the_nominal_batches_reach_the_pool_costliest_first(name, pool):
    designs = [FAMILY[name], FAMILY[name].replace(h2=FAMILY[name].h2 * 1.5)]
    with preload.Simulations(2) as sims:
        found = preload.min_preloads(designs, "hertz", dict(SETTINGS),
                                     simulations=sims)
    for design, result in zip(designs, found):
        assert PER_IN * design.h2 <= result.min_preload_lb <= \
            1.01 * PER_IN * design.h2
    assert _costliest_first(pool.batches) >= 2


@pytest.mark.parametrize("study, worker", [("contact_points", "_opening"),
                                           ("materials", "_run")])
def test_the_studies_batches_reach_the_pool_costliest_first(
        study, worker, monkeypatch):
    """The contact-point and materials studies mix free and preloaded
    runs in one batch: the preloaded ones (tens of times slower) are
    handed out first, whatever order the rows are in."""
    import importlib
    module = importlib.import_module(f"contactsep.studies.thesis.{study}")
    recorder = RecordingPool()
    handed = []

    def planted(task):
        handed.append(task.preload_lb)
        return (0.0,) * (4 if study == "contact_points" else 3)

    monkeypatch.setattr(backend, "worker_pool", lambda workers: recorder)
    monkeypatch.setattr(module, worker, planted)
    getattr(module, study)(n_modes=4, preloads=(0.0, 6.0), workers=2)
    assert set(handed) == {0.0, 6.0}
    assert handed == sorted(handed, reverse=True)
