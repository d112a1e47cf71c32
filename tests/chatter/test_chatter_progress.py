"""`contactsep chatter --progress` (issue 30 item 6): a long run's
elapsed time on stderr.  The compiled run reports no steps, so the bar
is ticked by the wait on it: a run long enough to run in a thread calls
the stop checks (output.stop_checks) while it waits."""

from __future__ import annotations

import pytest

from contactsep import output, thesis_design
from contactsep.chatter import simulate
from contactsep.cli.chatter import elapsed


def test_a_threaded_run_ticks_while_it_waits():
    ticks = []
    # 3e6 fixed steps x 48 modes: above the threaded size, below the
    # forked one (runners.STOPPABLE_WORK, limits.FORKED_WORK)
    with output.stop_checks(lambda: ticks.append(1)):
        simulate(thesis_design(n_modes=16), model="hertz", stepper="fixed",
                 dt=1e-8, t_end=0.03, samples=1, single_impulse=False,
                 static_correction=False)
    assert len(ticks) >= 1


def test_never_is_a_no_op_and_always_a_bar(monkeypatch):
    with elapsed("never") as tick:
        assert tick() is None
    pytest.importorskip("tqdm")
    with elapsed("always") as tick:
        tick()
