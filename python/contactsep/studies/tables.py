"""The thesis's Tables I-III recomputed beside the printed values.

The printed values are the thesis's (Chapter VI), kept here as the data
the recomputation is compared with.  Known disagreements (docs/studies.md,
docs/reference.md): Table I is 3.2-3.7 % below the model with the
handbook aluminium that reproduces Table II to 0.22 % (the two tables were
not computed with one E/gamma); Table III's d = 0.750 row does not follow
its own formula (3.73 in, printed 4.15).
"""

from __future__ import annotations

import numpy as np

from contactsep.model.fields import design_lines
from contactsep.studies.study import (
    Study,
    evaluate_all,
    refuse_fixed,
    thesis_study_design,
)

#: Table I (cps): theoretical and experimental, upper and lower contact.
TABLE_I_THEORETICAL = (10.6, 66.5, 187.0, 366.0)
TABLE_I_UPPER = (10.3, 65.0, 180.0, 360.0)
TABLE_I_LOWER = (10.6, 67.0, 186.0, 371.0)
#: Table II: separator thickness (in), theoretical and experimental (cps).
TABLE_II_D = (0.125, 0.250, 0.350, 0.500, 0.750)
TABLE_II_THEORETICAL = (4050.0, 8100.0, 11310.0, 16200.0, 24300.0)
TABLE_II_EXPERIMENTAL = (2000.0, 4000.0, 5000.0, 6250.0, 11100.0)
#: Table III: p (rad/s) and L_c (in), from L_c^2 = 1.3e6 d/p.
TABLE_III_P = (12560.0, 25120.0, 31400.0, 39250.0, 70000.0)
TABLE_III_LC = (3.60, 3.60, 3.81, 4.07, 4.15)
#: The fields each table sets itself (field -> why): an override of one
#: is refused.
FIXED = {"table1": {"n_modes": "the table's four modes"},
         "table2": {"h2": "the table's five separators"},
         "table3": {"h2": "the table's five separators"}}


def _relative(model, printed):
    return np.asarray(model) / np.asarray(printed) - 1.0


def table1(*, backend="compiled", **overrides) -> Study:
    """Table I: the contacts' first four natural frequencies (cps)."""
    refuse_fixed("table1", overrides, FIXED["table1"])
    design = thesis_study_design(n_modes=4, **overrides)
    ev = evaluate_all(design, backend)
    model = ev.p1 / (2 * np.pi)
    return Study("table1", "Table I: contact natural frequencies", {
        "mode": np.arange(1, 5),
        "printed_theoretical_cps": np.array(TABLE_I_THEORETICAL),
        "model_cps": model,
        "relative_difference": _relative(model, TABLE_I_THEORETICAL),
        "experimental_upper_cps": np.array(TABLE_I_UPPER),
        "experimental_lower_cps": np.array(TABLE_I_LOWER)}, (
        "model_cps: the upper contact's frequencies (end1, L1, h1, E1 and "
        "gamma1 below)", *design_lines(design),
        "known disagreement: the printed theory is 3.2-3.7 % low; it "
        "implies E/gamma = 9.34e7 in, not the 1e8 in that reproduces "
        "Table II"))


def table2(*, backend="compiled", **overrides) -> Study:
    """Table II: the separator's first natural frequency (cps)."""
    refuse_fixed("table2", overrides, FIXED["table2"])
    d = np.array(TABLE_II_D)
    design = thesis_study_design(d=d, **overrides)
    ev = evaluate_all(design, backend)
    model = ev.p2[:, 0] / (2 * np.pi)
    return Study("table2", "Table II: separator natural frequency", {
        "d_in": d, "printed_theoretical_cps": np.array(TABLE_II_THEORETICAL),
        "model_cps": model,
        "relative_difference": _relative(model, TABLE_II_THEORETICAL),
        "experimental_cps": np.array(TABLE_II_EXPERIMENTAL)}, (
        "model_cps: the separator's first frequency (the thesis rig: the "
        "printed theory to 0.22 %)", *design_lines(design),
        "the experiment is 2-2.6 times lower: support compliance, shear "
        "and rotatory inertia (Chapter VI)"))


def table3(*, backend="compiled", **overrides) -> Study:
    """Table III: equivalent separator lengths L_c (in).

    ``Lc_formula_in`` is the printed formula sqrt(1.3e6 d/p) with the
    printed p; ``Lc_model_in`` the length at which the model's
    clamped-clamped separator has the printed p (the same idea without
    the formula's rounded constant, which is 2.4 % off)."""
    refuse_fixed("table3", overrides, FIXED["table3"])
    d = np.array(TABLE_II_D)
    p = np.array(TABLE_III_P)
    design = thesis_study_design(d=d, **overrides)
    ev = evaluate_all(design, backend)
    formula = np.sqrt(1.3e6 * d / p)
    model = float(design.L2) * np.sqrt(ev.p2[:, 0] / p)
    return Study("table3", "Table III: equivalent length of the separators",
                 {"d_in": d, "p_rad_s": p,
                  "printed_Lc_in": np.array(TABLE_III_LC),
                  "Lc_formula_in": formula,
                  "relative_difference": _relative(formula, TABLE_III_LC),
                  "Lc_model_in": model}, (
                     "Lc_formula_in = sqrt(1.3e6 d/p) with the printed p; "
                     "Lc_model_in from the separator below",
                     *design_lines(design),
                     "known disagreement: the d = 0.750 row gives 3.73 in, "
                     "printed 4.15 (what p = 6.28 x 9000 would give)"))
