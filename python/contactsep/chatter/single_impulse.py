"""The single-impulse figures (eq. 23) a simulation reports beside its
own answer, and a second path to the impact speed for the tests."""

from __future__ import annotations

import math
import warnings

import numpy as np

from contactsep.chatter import system
from contactsep.errors import ContactsepWarning


def single_impulse(design) -> dict:
    """The thesis's single-impulse answer (eq. 23, compiled model) as
    printed and in the impulse form (psi/M3), with the members' own
    beam physics (issue 27: eq. 23 takes their modes)."""
    from contactsep.model import evaluate
    from contactsep.model.energy import EnergyBoundWarning
    from contactsep.model.status import explain
    from contactsep.model.contact_points import lower_point_differs
    with warnings.catch_warnings():
        # both forms are reported, labelled; the as-printed one may
        # exceed the release's energy (docs/model.md)
        warnings.simplefilter("ignore", EnergyBoundWarning)
        ev = evaluate(design.replace(lower_response="as-printed",
                                     x2_lower=None))
    if lower_point_differs(design):
        # eq. 23 passes the impulse through one separator point: only the
        # release flight (t1, the impact speed) holds at x2
        return {"t1_s": float(ev.t1) if ev.status == 0 else math.nan,
                "v_impact_in_s": float(ev.v_impact), "psi_lb_s": math.nan,
                "v0_in_s": math.nan, "y3_max_in": math.nan,
                "y3_max_impulse_form_in": math.nan}
    impulse = evaluate(design.replace(lower_response="impulse",
                                      x2_lower=None))
    if ev.status != 0:
        # the figures are null: say why, once (issue 31: tau = 1e300
        # gave them all null and nothing on stderr)
        warnings.warn(f"single impulse (eq. 23): "
                      f"{explain(int(ev.status), design)}; its figures are "
                      f"null (the simulation does not depend on them)",
                      ContactsepWarning, stacklevel=3)
    return {"t1_s": float(ev.t1) if ev.status == 0 else math.nan,
            "v_impact_in_s": float(ev.v_impact),
            "psi_lb_s": float(ev.psi), "v0_in_s": float(ev.v0),
            "y3_max_in": float(ev.y3_max),
            "y3_max_impulse_form_in": float(impulse.y3_max)}


def modal_impact_speed(design) -> float:
    """(A second path, for tests: eq. 23 gives it too.)  |dy1/dt| when
    the released upper contact's modal model (its beam physics) first
    reaches the gap: y1 = sum X_j q_j cos p_j t sampled
    at 1/64 of its shortest period, the crossing bisected."""
    upper = system.members(design)[0]
    amplitude = upper.x * upper.q0
    gap = float(design.gap)

    def height(t):
        return float(np.sum(amplitude * np.cos(upper.p * t))) - gap

    step = 2.0 * math.pi / float(np.max(upper.p)) / 64.0
    t, limit = 0.0, 8.0 * math.pi / float(np.min(upper.p))
    while height(t + step) > 0.0:
        t += step
        if t > limit:
            return math.nan
    lo, hi = t, t + step
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if height(mid) > 0.0 else (lo, mid)
    return float(abs(np.sum(amplitude * upper.p * np.sin(upper.p * hi))))
