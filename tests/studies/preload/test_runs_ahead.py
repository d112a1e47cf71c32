"""Runs made ahead for idle workers (contactsep.studies.preload.runs_ahead): the
preload search gives the same answer, asks for the same runs in the same
order and logs only those, whatever the number of workers; and more of
the workers are busy.  The simulations are planted (an event below a
threshold, and in a narrow window above it, so that the fine band has
work), on a pool that runs each task in this process as it is handed
one; every W > 1 is held to the search at W = 1 (no runs ahead)."""

from __future__ import annotations

import math
import random

import pytest
from design_family import FAMILY
from test_preload_runs import RecordingPool

from contactsep.chatter.stack import largest_preload
from contactsep.cli import main
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload import scan as preload_scan
from contactsep.studies.preload import search as preload_search
from contactsep.studies.preload.verify import search_design
from contactsep.runs import backend
from contactsep.runs.journal import RunJournal
from contactsep.studies.preload.runs_ahead import RunsAhead

SETTINGS = {"dt": 1e-8, "t_end": 0.01, "damping": "none"}


def threshold(design) -> float:
    """The planted answer: within every family design's ceiling."""
    return 0.2 * largest_preload(design) ** 0.7


def planted_event(task) -> bool:
    """An event below the threshold, and in a window 1.5 % wide at 1.3
    times it (closed around it; wider than the fine band's 0.99 % steps,
    so the band sees it)."""
    t = threshold(task.design)
    return task.preload_lb < t or 1.3 * t < task.preload_lb < 1.32 * t


class SendingPool(RecordingPool):
    """A RecordingPool that records what each batch sent to it (a batch
    begins where :func:`plant`'s map_longest_first opens one)."""

    def submit(self, function, task):
        self.batches[-1].append(task.preload_lb)
        return super().submit(function, task)


def plant(setattr) -> list:
    """The planted simulations on SendingPools (each task run in this
    process as it is handed out); ``setattr(module, name, value)``
    (pytest's monkeypatch, or the builtin).  Returns the pools made, the
    count the busy share is taken from, apart from the Simulations' own
    bookkeeping."""
    pools = []
    real = backend.map_longest_first

    def pool(workers):
        pools.append(SendingPool())
        return pools[-1]

    def batch(pool, *args, **kwargs):
        pool.pool.batches.append([])      # the RestartingPool's pool
        return real(pool, *args, **kwargs)
    setattr(backend, "worker_pool", pool)
    setattr(backend, "map_longest_first", batch)
    setattr(preload, "_simulate_event", planted_event)
    return pools


@pytest.fixture
def planted(monkeypatch):
    return plant(monkeypatch.setattr)


def sent(pool) -> list:
    """How many runs each batch sent to the pool's workers."""
    return [len(b) for b in pool.batches]


def searched(design, workers, journal=None):
    with preload.Simulations(workers, journal=journal) as sims:
        found = search_design(design, "hertz", SETTINGS, sims,
                              largest_preload(design))
    return found, sims


def busy_share(batches, workers: int) -> float:
    """Runs in flight over worker slots, round by round: a batch of b
    runs takes ceil(b / W) rounds of W slots."""
    rounds = sum(math.ceil(b / workers) for b in batches if b)
    return sum(batches) / (rounds * workers)


@pytest.mark.parametrize("name", sorted(FAMILY))
def test_the_answer_and_the_runs_asked_for_do_not_depend_on_w(name,
                                                              planted):
    design = FAMILY[name]
    alone, one = searched(design, 1)
    assert one.ahead.made == 0 and one.batches[0] == 1
    # the planted answer: above the window's events, at most a fine step
    # (0.99 %) above its top end
    assert 1.3 * threshold(design) < alone.min_preload_lb <= \
        1.32 * 1.0099 * threshold(design)
    for workers in (2, 4, 16):
        found, sims = searched(design, workers)
        assert found == alone
        assert sims.log == one.log and sims.runs == one.runs
        assert sims.ahead.used > 0
        # every run made is one asked for or one made ahead, once
        assert sent(planted[-1]) == [b for b in sims.batches if b]
        assert sum(sent(planted[-1])) == \
            len(one.log) - sims.ahead.used + sims.ahead.made
        # fewer rounds than the same batches without runs ahead
        assert sum(math.ceil(b / workers) for b in sent(planted[-1])) < \
            sum(math.ceil(b / workers) for b in one.batches)


@pytest.mark.parametrize("name", sorted(FAMILY))
@pytest.mark.parametrize("workers", [8, 16])
def test_eight_and_sixteen_workers_are_kept_busy(name, workers, planted):
    """At least 80 % of 8 or 16 workers' slots hold a run, and at least
    20 points more than the same search without runs ahead (its
    bisection steps are one run each, its scans four: 61-65 % at 8
    workers, 39-44 % at 16), and most runs made ahead are asked for."""
    design = FAMILY[name]
    _, alone = searched(design, 1)
    _, sims = searched(design, workers)
    share = busy_share(sent(planted[-1]), workers)
    assert share >= 0.8
    assert share >= busy_share(alone.batches, workers) + 0.2
    assert sims.ahead.used >= 0.75 * sims.ahead.made


def test_a_journal_keeps_the_runs_made_ahead(planted, tmp_path):
    design = FAMILY["steel_relay"]
    alone, _ = searched(design, 1)
    with RunJournal(tmp_path / "j", {"t": 1}) as journal:
        found, sims = searched(design, 4, journal)
        assert journal.recorded == sum(sims.batches)
    assert found == alone
    with RunJournal(tmp_path / "j", {"t": 1}) as journal:
        again, _ = searched(design, 1, journal)
        assert journal.recorded == 0
    assert again == alone


def test_the_midpoints_ahead_hold_every_later_bisection_step():
    """Brute force: a plain bisection to 1 % on random brackets and
    thresholds; its steps 2 to 6 are all among the midpoints named at
    step 1, and the first level comes first."""
    rng = random.Random(3)
    for _ in range(200):
        lo = rng.uniform(0.01, 10.0)
        hi = lo * rng.uniform(1.05, 1.4)
        t = rng.uniform(lo, hi)
        mid = math.sqrt(lo * hi)
        ahead = preload_scan.midpoints_ahead([(0, (lo, hi), mid)], 0.01)
        assert sorted(ahead[:2]) == [(0, math.sqrt(lo * mid)),
                                     (0, math.sqrt(mid * hi))]
        a, b, steps = lo, hi, []
        while b > a * 1.01:
            m = math.sqrt(a * b)
            steps.append(m)
            a, b = (m, b) if m < t else (a, m)
        named = {p for _, p in ahead}
        assert set(steps[1:6]) <= named


def test_the_scan_s_last_batch_names_the_first_midpoint():
    """Brute force over random thresholds and ceilings: the search's
    batch after its last scan batch (the bisection's first midpoint) is
    among the runs named ahead of that scan batch."""
    rng = random.Random(5)
    for _ in range(300):
        t = math.exp(rng.uniform(math.log(0.01), math.log(50.0)))
        ceiling = t * rng.uniform(1.5, 40.0)
        batches, named = [], []

        def has_event(tasks):
            batches.append([p for _, p in tasks])
            return [p < t for _, p in tasks]

        def speculate(asked, tasks):
            named.append((len(batches), {p for _, p in tasks}))
        preload_search.search(1, has_event, ceilings=[ceiling],
                              ceiling_first=True, band=False,
                              speculate=speculate)
        on_grid = [i for i, b in enumerate(batches)
                   if all(p == 0.0 or abs(4 * math.log2(p) -
                          round(4 * math.log2(p))) < 1e-9 for p in b)]
        last_scan = max(on_grid)
        if last_scan + 1 >= len(batches):
            continue                    # no bisection (answer on the grid)
        ahead = dict(named)[last_scan]
        assert set(batches[last_scan + 1]) <= ahead, (t, ceiling)


def test_room_fills_the_last_round():
    for capacity in (1, 2, 3, 8, 16):
        ahead = RunsAhead(capacity)
        for asked in range(0, 40):
            room = ahead.room(asked)
            assert 0 <= room < max(capacity, 1)
            if capacity > 1 and asked:
                assert (asked + room) % capacity == 0
            else:
                assert room == 0


def test_the_command_s_csv_is_the_same_on_one_and_two_workers(
        planted_preload, tmp_path, capsys):
    """On real worker processes (the planted physics of the preload
    command's tests): the CSV and the text are byte for byte those of
    one worker."""
    outs = []
    for workers in ("1", "2"):
        path = tmp_path / f"w{workers}.csv"
        assert main(["preload", "--n-modes", "4", "--workers", workers,
                     "--progress", "never", "--csv", str(path)]) == 0
        outs.append((path.read_bytes(), capsys.readouterr().out))
    assert outs[0] == outs[1]
