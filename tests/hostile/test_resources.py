"""Runaway resources (issue 18, class 3): processes, memory and work are
bounded up front, and a pool that cannot start is an error, not a hang."""

from __future__ import annotations

import importlib
import resource
import subprocess
import sys
import textwrap

import pytest
from hostile_cli import main, refusal

from contactsep.chatter import limits, simulate
from contactsep.constants import LISTING_TAU_S
from contactsep.errors import InputError
from contactsep.model import thesis_design
from contactsep.runs import pool
from contactsep.studies.sweep import run as runner
from contactsep.studies.sweep import spec as sweep
simulate_module = importlib.import_module("contactsep.chatter.simulate")


def test_workers_are_bounded_by_the_cores(capsys):
    """--workers 100000 started ~470 processes and +1 GB in 1.5 s."""
    most = pool.max_workers()
    assert most == pool.WORKERS_PER_CORE * pool.usable_cores()
    status, _, err = main(capsys, "sweep", "--vary", "h2=0.1:0.5:5",
                          "--workers", "100000")
    assert refusal(status, err) == (f"--workers: found '100000', expected "
                                    f"an integer from 1 to {most:,}")
    spec = sweep.make_spec(vary=["h2=0.1:0.5:5"])
    with pytest.raises(InputError, match="^--workers: found 100000"):
        runner.run_sweep(spec, workers=100_000)


def test_a_pool_that_cannot_start_is_one_error_not_a_hang():
    """Under a process limit the sweep printed an error and then hung
    (the processes it had started waited for work, and the interpreter's
    exit for them).  Here fork fails after the first worker."""
    script = textwrap.dedent("""
        import os, sys
        real, started = os.fork, []
        def fork():
            if started:
                raise BlockingIOError(11, "Resource temporarily unavailable")
            started.append(1)
            return real()
        os.fork = fork
        from contactsep.cli import main
        sys.exit(main(["sweep", "--vary", "h2=0.1:0.5:400000",
                       "--workers", "3", "--chunk-size", "1000"]))
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True,
                          text=True, timeout=60)
    assert refusal(done.returncode, done.stderr) == (
        "--workers 3: the worker processes could not be started (Resource "
        "temporarily unavailable); try fewer")


def test_chunks_are_sized_by_cost_and_memory():
    """A sweep at --n-modes 100000 tried to allocate 74.5 GiB (chunks of
    100,000 designs, four per-mode arrays each); after Ctrl-C a sweep
    waited minutes for whole chunks."""
    from contactsep.output.pieces import FIRST_PIECE_COST, PIECE_S
    from contactsep.runs.chunks import CHUNK_MEMORY, Chunks
    big = Chunks(10**6, sweep.CHUNK_SIZE, 100_000)
    assert big.limit * 8 * (4 * 100_000 + 64) <= CHUNK_MEMORY
    assert big.next == 1
    small = Chunks(10**6, sweep.CHUNK_SIZE, 4)
    assert small.next == FIRST_PIECE_COST // 4
    # measured: 1 ms a design -> chunks of PIECE_S, grown at most
    # 8 times a chunk, never past chunk_size
    small.record(1000, 1.0)
    assert small.next == int(PIECE_S / 1e-3)
    # a faster chunk moves the estimate half way towards it
    small.record(500, 1e-6)
    assert small.next == int(PIECE_S / ((1e-3 + 2e-9) / 2))
    bounds = list(Chunks(10, 3, 4))
    assert bounds == [(0, 3), (3, 6), (6, 9), (9, 10)]


@pytest.mark.slow
def test_a_sweep_of_a_hundred_thousand_modes_fits_in_a_gigabyte(tmp_path):
    """Two designs at N = 100,000 (6 s each) under a 2 GiB address
    space: the chunk holds one design's arrays, not 74.5 GiB.  Since
    issue 17 the extremum search gives up at such N (status 4: its live
    cells would pass the search's memory budget), so the sweep ends as
    every design failing: one line naming that, exit 2, no MemoryError."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))
    done = subprocess.run(
        [sys.executable, "-m", "contactsep", "sweep", "--vary",
         "h2=0.2:0.3:2", "--n-modes", "100000", "--workers", "1",
         "--json"], capture_output=True, text=True, timeout=600,
        preexec_fn=limit)
    assert done.returncode == 2, done.stderr
    assert done.stderr == (
        "contactsep: error: 2 of 2 designs failed (2 the extremes of y3 "
        "could not be resolved to 1e-12 of sum |c_j| within the search's "
        "work budget): every one; nothing to summarise\n")


@pytest.mark.parametrize("kwargs, message", [
    (dict(model="hertz", n_modes=1024, dt=6.1e-11, t_end=0.06),
     "dt: found 6.1e-11, expected at least 1.84e-08 s at N = 1024 (at most "
     "1e+09 steps and 1e+10 steps x modes a run)"),
    (dict(model="appE", n_modes=1024),
     "n_modes: found 1024, expected at most 128 modes per member for appE"),
    (dict(model="newton", n_modes=1025),
     "n_modes: found 1025, expected at most 1024 modes per member"),
    (dict(model="hertz", n_modes=4, samples=10**9),
     "samples: found 1000000000, expected an integer from 1 to 4,000,000"),
    (dict(model="appE", n_modes=4, t_end=1e6),
     "t_end: found 1000000.0, expected a time > 0 and at most 10 s"),
])
def test_simulation_work_is_bounded_up_front(kwargs, message):
    """Hertz at N = 1024 with dt = 6.1e-11 was accepted (the limit counted
    steps, not steps x modes); appE at N = 1024 ran for 9 minutes;
    samples=10**9 asked for gigabytes."""
    n = kwargs.pop("n_modes")
    with pytest.raises(InputError) as info:
        simulate(thesis_design(n_modes=n), **kwargs)
    assert str(info.value).startswith(message), str(info.value)


def test_the_default_run_at_the_largest_n_is_within_the_work_bound():
    """The bound refuses what the thesis rig does not need: its converged
    step at N = 1024 over the listing's window is inside it (the design's
    own step at N = 1024 is not: test_a_design_step_past_the_budget_...)."""
    steps = LISTING_TAU_S / simulate_module.DEFAULT_DT["hertz"]
    assert steps * 3 * limits.MAX_MODES <= limits.MAX_WORK


def test_a_design_step_past_the_budget_is_refused_naming_what_to_change():
    """At N = 1024 the thesis rig's own step (its highest mode, 5e11
    rad/s) over its own window is far past MAX_WORK: refused at once, in
    one line naming the settings that would fit (fewer modes, a shorter
    window, a larger step); the same run with a given step and window
    that fit is not refused by the budget."""
    with pytest.raises(InputError) as info:
        simulate(thesis_design(n_modes=1024))
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith("n_modes: found 1024 with the design's window")
    assert "lower n_modes" in message and "shorten t_end" in message
    assert "give dt >= " in message and "steps x 3072 modes" in message
