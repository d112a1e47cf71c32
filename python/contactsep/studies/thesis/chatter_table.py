"""``contactsep study chatter``: the three models for the five thesis
separators and N = 4, 16, 32."""

from __future__ import annotations

import numpy as np

from contactsep.chatter.simulate import DEFAULT_DT, simulate
from contactsep.constants import LISTING_TAU_S
from contactsep.studies.study import Study, thesis_study_design

THICKNESSES = (0.125, 0.25, 0.35, 0.5, 0.75)
MODES = (4, 16, 32)


def chatter_table(thicknesses=THICKNESSES, modes=MODES,
                  models=("appE", "newton", "hertz"), progress=None) -> Study:
    """One row per (model, d, N): first impulse, max lower gap, circuit
    open time, first opening, discontinuity events, energy ratio;
    ``progress(1)`` is called after each simulation (a bar)."""
    rows = {k: [] for k in ("model", "d_in", "N", "first_impulse_lb_s",
                            "max_lower_gap_in", "circuit_open_s",
                            "first_circuit_open_s", "n_events",
                            "energy_ratio")}
    for model in models:
        for d in thicknesses:
            for n in modes:
                # the thesis's step and window, given explicitly
                r = simulate(thesis_study_design(d=d, n_modes=n), model=model,
                             samples=1, t_end=LISTING_TAU_S,
                             dt=DEFAULT_DT[model])
                if progress is not None:
                    progress(1)
                for key, value in (("model", model), ("d_in", d), ("N", n),
                                   ("first_impulse_lb_s",
                                    r.first_impulse_lb_s),
                                   ("max_lower_gap_in", r.max_lower_gap_in),
                                   ("circuit_open_s", r.circuit_open_s),
                                   ("first_circuit_open_s",
                                    r.first_circuit_open_s),
                                   ("n_events", r.n_events),
                                   ("energy_ratio", r.energy_ratio)):
                    rows[key].append(value)
    return Study("chatter", "Repeated impacts: circuit discontinuity of the "
                 "thesis rig by model, separator and N",
                 {k: np.array(v) for k, v in rows.items()},
                 ("window 0-0.060 s from release; open = gap > 1e-6 in; "
                  "events = openings >= 1e-5 s; the adaptive steppers at "
                  "their default dt (newton 5e-8 s, hertz 5e-8 s); hertz "
                  "with the static correction (docs/chatter.md)",
                  "appE: rigid separator, the lower contact never moves"))
