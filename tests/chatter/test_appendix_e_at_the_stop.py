"""Appendix E's twins (fortran/chatter/event_driven.f90 and
contactsep/chatter/event_driven.py) on starts placed at the stop to
within rounding (issue 26).

Why they disagreed.  A start with y = X.q at round-off (+-1e-18 in) and
a clear approach (u = X.v < 0) was decided on the sign of that
round-off: y > 0 met the stop at once (the root finder's Newton step,
y/|u| ~ 1e-18 s), y <= 0 was taken as "leaving a rest" (the rule for
y and u both at round-off) and flew into the stop for up to 1e-3 of
the shortest period before the impact (1.7e-6 s at N = 5, penetrating
all the while).  The two twins sum X.q in different orders, so they
fell on different sides on 7 of these 300 starts (22 of the issue's),
and their impact sequences then diverged (10 impacts against 353).
Both now take a start at the stop that approaches beyond the round-off
of u (64 eps sum |X_j v_j|) as an impact now, as they already did after
an impact.

What is well-conditioned, and tested: the impact and rest counts (one
to one), the first impact's time (measured within 3.3e-16 s) and
impulse (6.2e-9 relative: the impulse is computed from velocities summed
in different orders after flows of different lengths, 0 against
1e-18 s), the energy at the end (1.8e-12).  What is not: the later
impulses of a Zeno sequence near a graze, where y and u both approach
round-off, differ by up to 2.2e-6 of the first (not tested).
"""

from __future__ import annotations

import numpy as np
import pytest

import contactsep
from contactsep.chatter.event_driven import simulate_rigid_stop
from contactsep.chatter.system import members

pytest.importorskip("contactsep.chatter._chatter")


def _start(rng):
    n = int(rng.integers(1, 9))
    upper = members(contactsep.thesis_design(n_modes=n))[0]
    q0 = rng.normal(size=n) * 0.01
    q0 = q0 - upper.x * (q0 @ upper.x) / (upper.x @ upper.x)
    return upper, q0, rng.normal(size=n)


def _check_twins(seed, count):
    rng = np.random.default_rng(seed)
    for _ in range(count):
        upper, q0, v0 = _start(rng)
        runs = [simulate_rigid_stop(upper.p, upper.x, upper.mass, q0, v0,
                                    0.375, 0.01, backend=backend)
                for backend in ("numpy", "fortran")]
        a, b = runs
        assert len(a.impact_t) == len(b.impact_t)
        assert a.rest_intervals.shape == b.rest_intervals.shape
        if len(a.impact_t) == 0:
            continue
        assert abs(a.impact_t[0] - b.impact_t[0]) <= 1e-14
        assert a.impulse[0] == pytest.approx(b.impulse[0], rel=1e-7)
        assert a.final_energy == pytest.approx(b.final_energy, rel=1e-10)


def test_the_twins_decide_alike_at_the_stop():
    # seed 1's starts 66 and 69 were two of the 7 that disagreed
    _check_twins(1, 70)


def test_the_twins_decide_alike_on_300_starts_at_the_stop():
    _check_twins(2, 300)


@pytest.mark.parametrize("backend", ["numpy", "fortran"])
@pytest.mark.parametrize("y0", [-1e-18, 0.0, 1e-18])
def test_a_start_at_the_stop_that_approaches_strikes_at_once(backend, y0):
    """One mode, X = 2 at the tip: y within rounding of the stop either
    side, u = -1 in/s: the impact is at t <= y/|u|, its impulse the
    Newton impulse (1 + e) M |u| / X^2, whatever the sign of y."""
    upper = members(contactsep.thesis_design(n_modes=1))[0]
    x = upper.x
    q0 = np.array([y0 / x[0]])
    v0 = np.array([-1.0 / x[0]])
    r = simulate_rigid_stop(upper.p, x, upper.mass, q0, v0, 0.375, 0.001,
                            backend=backend)
    assert r.impact_t[0] <= max(y0, 0.0) / 1.0 + 1e-30
    assert r.impulse[0] == pytest.approx(
        1.375 * upper.mass * 1.0 / float(x @ x), rel=1e-12)
