"""The numbers docs/studies.md's "Table II explained" section states
beside the committed separator-fit.csv: the fitted parameters, the bare
separator, Table I under both theories, the separator's Poisson ratio and
Cowper's kappa, Timoshenko with kappa = 5/6 and
the clamp stiffness fitted one row at a time.  Run from the repository
root:

    python docs/studies/make_separator_notes.py > docs/studies/separator_notes.json
"""

from __future__ import annotations

import dataclasses
import json

import numpy as np
from scipy.optimize import brentq

from contactsep.beams.member import cowper_kappa, modal_model
from contactsep.model import thesis_design
from contactsep.studies.tables import (TABLE_I_LOWER, TABLE_I_UPPER,
                                       TABLE_II_D, TABLE_II_EXPERIMENTAL)
from contactsep.studies.thesis import separator_fit as sf

#: Column suffixes of the five separators, as separator-fit.csv's.
ROWS = [name.removeprefix("res_").removesuffix("_pct")
        for name in sf.RESIDUAL_COLUMNS]


def first(d: float, kappa=None, supports=None) -> float:
    """f_1 (cps) of clamped Timoshenko separator d (kappa None: Cowper's)
    on supports (field -> value)."""
    beam = sf.separator(d, "timoshenko-clamped", supports or {})
    if kappa is not None:
        beam = dataclasses.replace(beam, kappa=kappa)
    return float(modal_model(beam, 1, [beam.length / 2]).f_hz[0])


def fits() -> dict:
    """Each fitted model's parameter values (not logs), by data version."""
    out = {}
    for model in sf.MODELS[2:]:
        for data_name, data in sf.DATA.items():
            logs, _ = sf.fit(model, data)
            values = {name: 10.0**log for name, log in
                      zip(sf.PARAMETERS[model], logs)}
            if "mass2" in values:
                values["mass2_g"] = values["mass2"] * sf.GRAMS_PER_LB
            out[f"{model}_{data_name}".replace("-", "_")] = values
    return out


def bare(kr2: float) -> dict:
    """The separator on the fitted clamp without the sensor: its first
    frequencies and equivalent lengths (the clamped Bernoulli-Euler
    length of the same frequency)."""
    length = float(thesis_design().L2)
    out = {"kr2": kr2}
    for row, d in zip(ROWS, TABLE_II_D):
        f_bare = first(d, None, {"kr2": kr2})
        f_be = sf.first_frequency(float(d), sf.MODELS[0], ())
        out[f"f1_{row}_cps"] = f_bare
        out[f"Lc_{row}_in"] = length * float(np.sqrt(f_be / f_bare))
    return out


def table_i() -> dict:
    """The contacts' first four frequencies under both theories, and the
    Timoshenko model's gap to the measured ones (upper and lower)."""
    values = sf.table_i_frequencies()
    shift = 100 * (values["timoshenko"] / values["bernoulli-euler"] - 1)
    gaps = 100 * (values["timoshenko"] / np.array(
        [TABLE_I_UPPER, TABLE_I_LOWER], dtype=float) - 1)
    out = {f"{key}_{k + 1}_cps": float(f) for key, theory in
           (("bernoulli_euler", "bernoulli-euler"),
            ("timoshenko", "timoshenko"))
           for k, f in enumerate(values[theory])}
    out.update(shift_min_pct=float(shift.min()),
               shift_max_pct=float(shift.max()),
               gap_min_pct=float(gaps.min()), gap_max_pct=float(gaps.max()))
    return out


def per_row_kr2() -> dict:
    """The clamp stiffness that fits each row alone (scipy's root
    finder in log10 kr2 within the study's bounds); None where no
    stiffness reaches the measurement."""
    out = {}
    low, high = sf.BOUNDS["kr2"]
    for row, d, f in zip(ROWS, TABLE_II_D, TABLE_II_EXPERIMENTAL):
        def gap(log_kr, d=d, f=f):
            return first(d, None, {"kr2": 10.0**log_kr}) / f - 1

        out[f"kr2_{row}"] = None if gap(low) * gap(high) > 0 else \
            10.0 ** brentq(gap, low, high, xtol=1e-8)
    return out


def notes() -> dict:
    fitted = fits()
    nu = float(thesis_design().nu2)
    return {
        "timoshenko": {"nu": nu, "cowper_kappa": cowper_kappa(nu)},
        "fits": fitted,
        "bare_printed": bare(fitted["timoshenko_kr2_mass2_printed"]["kr2"]),
        "bare_last_9000": bare(
            fitted["timoshenko_kr2_mass2_last_9000"]["kr2"]),
        "table_i": table_i(),
        "kappa_5_6": {f"res_{row}_pct": 100 * (first(d, 5 / 6) / f - 1)
                      for row, d, f in zip(ROWS, TABLE_II_D,
                                           TABLE_II_EXPERIMENTAL)},
        "per_row": per_row_kr2()}


if __name__ == "__main__":
    print(json.dumps(notes(), indent=1))
