"""``simulate(..., stop_at_event=True)``: a run that only has to answer
"is there a discontinuity event?" (the preload searches' runs) stops at
its first one.

The compiled adaptive stepper watches the circuit as it goes and
returns at the end of the step where an opening has lasted
``min_open`` (fortran/chatter/adaptive_event.f90; status
STOPPED_AT_EVENT).  Its trajectory up to there is the full run's, bit
for bit (the watch only reads the state), so the answer is the full
run's: decided again here, from the returned crossings, by
:func:`contactsep.chatter.circuit.discontinuity`, the rule every run
uses.  A stopped run whose energy check fails, or that this rule does
not confirm, is run again over the whole window.
"""

from __future__ import annotations

import dataclasses
import math

from contactsep.chatter import circuit, numerics
from contactsep.chatter import status as chatter_status

#: The stepper's argument for "never stop".
NEVER = -1.0


def checked_run(run_at, dt: float, dt_source: str, *args,
                min_open: float, **keywords) -> numerics.CheckedRun:
    """:func:`numerics.checked_run` of ``run_at(step, stop_open)`` that
    stops at the first event: the run at ``dt`` once, kept if its energy
    check passes and it either ran the whole window (it met no event: the
    full run itself) or stopped at an event that
    :func:`circuit.discontinuity` confirms; else the full run's
    ``checked_run`` (its halvings included)."""
    stopped = numerics.checked_run(lambda step: run_at(step, min_open),
                                   dt, "given", *args, **keywords)
    run = stopped.run
    if stopped.converged and (
            run.status == chatter_status.OK or (
                run.status == chatter_status.STOPPED_AT_EVENT
                and circuit.discontinuity(run.upper_open, run.lower_open,
                                          min_open)["chatters"])):
        return dataclasses.replace(stopped, dt_source=dt_source)
    return numerics.checked_run(lambda step: run_at(step, NEVER), dt,
                                dt_source, *args, **keywords)


def stopped_s(status: int, events, min_open: float) -> float:
    """The instant (s) a stopped run's first event was established (its
    start + min_open); NaN for a run of the whole window."""
    if status != chatter_status.STOPPED_AT_EVENT:
        return math.nan
    return float(events[0, 0]) + float(min_open)
