"""The thesis's design studies (Figures 5-8, 21, 23 and the convergence in
N) as batched evaluations of the general model.

Each function takes the thesis experiment (contactsep.thesis_design) with
any field overridden by keyword (``n_modes=8``, ``e=0.5``, ...) and returns
a :class:`~contactsep.studies.study.Study`.  Units: in, lb, s.
"""

from __future__ import annotations

import numpy as np

from contactsep.restored import thesis_decks
from contactsep.model.fields import design_lines
from contactsep.studies.study import (
    Study,
    evaluate_all,
    refuse_fixed,
    thesis_study_design,
)

#: Figure 5's grids.
FIG5_THICKNESSES = np.round(np.arange(0.10, 1.0001, 0.05), 10)
FIG5_DEFLECTIONS = (0.25, 0.5, 0.75)
#: Figure 6's contact-point ratios r = x3/L3 and separator thickness.
FIG6_RATIOS = np.round(np.arange(0.70, 1.0001, 0.01), 10)
FIG6_THICKNESS = 0.25
#: Figure 7's times (s) and contact points.
FIG7_TIMES = np.round(np.arange(0.0, 0.06001, 0.0001), 10)
FIG7_RATIOS = (0.98, 0.78)
#: Figure 8's mass ratios and symmetric contact point.
FIG8_RATIOS = np.geomspace(0.05, 5.0, 30)
FIG8_CONTACT = 0.98
#: The convergence study's mode counts.
CONVERGENCE_MODES = (1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 50)
#: Table III: the five separators and their equivalent lengths (in).
TABLE_III = dict(sorted(thesis_decks.EQUIVALENT_LENGTHS.items()))
#: The fields each study sets itself (field -> why): an override of one
#: is refused.
FIXED = {
    "fig5": {"h2": "its x axis, 0.10-1.00 in"},
    "fig6": {"x3": "x3 = r L3 on curve I, L3 on curve II",
             "L3": "19 in on curve I, 19/r on curve II"},
    "fig7": {"x3": "x3/L3 = 0.98 and 0.78"},
    "fig8": {"x1": "symmetric contacts at 0.98 L",
             "x3": "symmetric contacts at 0.98 L",
             "gamma2": "R is changed through it"},
    "fig23": {"h2": "the five thesis separators",
              "Lc": "Table III's values"},
    "convergence": {"n_modes": "its x axis"},
}


def _notes(design, *extra, per_row=()) -> tuple:
    """The study's own notes, the design it evaluated (fields the study
    varies read 'per row'), and the sign convention."""
    return (*extra,
            "model: eq. 23 (contactsep.model); units in each column's name",
            *design_lines(design, per_row),
            "y3 > 0: the lower contact moves away from the separator; "
            "times from the impact")


def fig5(*, backend="compiled", **overrides) -> Study:
    """Figure 5: max y3 against separator thickness d = 0.10..1.00 in, for
    y_s = 0.25, 0.5, 0.75 in (``ys=`` given: that one curve)."""
    refuse_fixed("fig5", overrides, FIXED["fig5"], arrays=("ys",))
    ys = np.atleast_1d(overrides.pop("ys", FIG5_DEFLECTIONS))[:, None]
    d = FIG5_THICKNESSES[None, :]
    design = thesis_study_design(d=d, ys=ys, **overrides)
    ev = evaluate_all(design, backend)
    shape = ev.y3_max.shape
    return Study("fig5", "Figure 5: maximum lower-contact displacement vs "
                 "separator thickness", {
                     "ys_in": np.broadcast_to(ys, shape).ravel(),
                     "d_in": np.broadcast_to(d, shape).ravel(),
                     "y3_max_in": ev.y3_max.ravel(),
                     "t_max_s": ev.t_max.ravel()}, _notes(design))


def fig6(*, backend="compiled", **overrides) -> Study:
    """Figure 6: max y3 against r = x3/L3 = 0.70..1.00 at d = 0.25 in.
    Curve I keeps L3 = 19 in (x3 = r L3); curve II keeps the contact point
    19 in from the support and lengthens the contact, L3 = 19/r."""
    refuse_fixed("fig6", overrides, FIXED["fig6"])
    r = FIG6_RATIOS
    overrides.setdefault("h2", FIG6_THICKNESS)
    base = thesis_study_design(**overrides)
    length = float(base.L3)
    one = evaluate_all(base.replace(x3=r * length), backend)
    two = evaluate_all(base.replace(L3=length / r,
                                    x3=np.full_like(r, length)), backend)
    return Study("fig6", "Figure 6: maximum lower-contact displacement vs "
                 "x3/L3", {
                     "curve": np.repeat(["I", "II"], r.size),
                     "r": np.concatenate([r, r]),
                     "L3_in": np.concatenate([np.full_like(r, length),
                                              length / r]),
                     "y3_max_in": np.concatenate([one.y3_max, two.y3_max])},
                 _notes(base, "curve I: L3 fixed, x3 = r L3; curve II: "
                        "x3 fixed, L3 = x3/r (the contact point keeps its "
                        "distance from the support)",
                        per_row=("L3", "x3")))


def fig7(*, backend="compiled", **overrides) -> Study:
    """Figure 7: y3(x3, t) for t = 0..0.06 s at r = 0.98 and 0.78 (curve
    I), with each mode's coefficient in the notes."""
    refuse_fixed("fig7", overrides, FIXED["fig7"])
    r = np.array(FIG7_RATIOS)
    base = thesis_study_design(**overrides)
    ev = evaluate_all(base.replace(x3=r * float(base.L3)), backend)
    y = ev.y3(FIG7_TIMES)
    notes = [f"r = {ri}: mode coefficients c3_j (in) = "
             + ", ".join(f"{c:.4g}" for c in ev.c3[i])
             for i, ri in enumerate(r)]
    return Study("fig7", "Figure 7: lower-contact displacement vs time", {
        "r": np.repeat(r, FIG7_TIMES.size),
        "t_s": np.tile(FIG7_TIMES, r.size),
        "y3_in": y.ravel()}, _notes(base, *notes, per_row=("x3",)))


def fig8(*, backend="compiled", **overrides) -> Study:
    """Figure 8: max y3 against the mass ratio R of eq. 24, changed through
    the separator's density only, symmetric contacts x1/L1 = x3/L3 = 0.98;
    beside it the thesis's law y3_max ~ 1/(1 + 2R)."""
    refuse_fixed("fig8", overrides, FIXED["fig8"])
    base = thesis_study_design(**overrides)
    base = base.replace(x1=FIG8_CONTACT * float(base.L1),
                        x3=FIG8_CONTACT * float(base.L3))
    r0 = float(evaluate_all(base, backend).R)
    gamma2 = float(base.gamma2) * FIG8_RATIOS / r0
    ev = evaluate_all(base.replace(gamma2=gamma2), backend)
    anchor = ev.y3_max[0] * (1 + 2 * ev.R[0])
    return Study("fig8", "Figure 8: maximum lower-contact displacement vs "
                 "mass ratio R", {
                     "R": ev.R, "gamma2_lb_in3": gamma2,
                     "y3_max_in": ev.y3_max,
                     "law_in": anchor / (1 + 2 * ev.R)},
                 _notes(base, "R (eq. 24) changed through gamma2 only; "
                        "law_in = y3_max(R1)(1 + 2 R1)/(1 + 2 R)",
                        per_row=("gamma2",)))


def fig23(*, backend="compiled", lc_reading="listing", **overrides) -> Study:
    """Figures 21 and 23 (the "corrected" theory): the five thesis
    separators with Table III's equivalent lengths L_c; lc_reading as in
    the model ("listing" hybrid by default)."""
    refuse_fixed("fig23", overrides, FIXED["fig23"])
    d = np.array(list(TABLE_III))
    lc = np.array(list(TABLE_III.values()))
    base = thesis_study_design(d=d, **overrides)
    plain = evaluate_all(base, backend)
    corrected = base.replace(Lc=lc, lc_reading=lc_reading)
    ev = evaluate_all(corrected, backend)
    return Study("fig23", "Figures 21 and 23: maximum lower-contact "
                 "displacement with the Table III equivalent lengths", {
                     "d_in": d, "Lc_in": lc, "y3_max_in": ev.y3_max,
                     "y3_max_uncorrected_in": plain.y3_max},
                 _notes(corrected, "L_c from Table III (y3_max_in; "
                        "y3_max_uncorrected_in without it); one e for "
                        "every separator (Figure 23's 0.375 by default; "
                        "Figure 20's e(d) is not tabulated)"))


def convergence(*, backend="compiled", **overrides) -> Study:
    """t1, V, psi, v0 and max y3 for N = 1 ... 50 (docs/model.md)."""
    refuse_fixed("convergence", overrides, FIXED["convergence"])
    n = np.array(CONVERGENCE_MODES)
    design = thesis_study_design(n_modes=n, **overrides)
    ev = evaluate_all(design, backend)
    return Study("convergence", "Convergence in the number of modes N", {
        "N": n, "t1_s": ev.t1, "v_impact_in_s": ev.v_impact,
        "psi_lb_s": ev.psi, "v0_in_s": ev.v0, "y3_max_in": ev.y3_max},
        _notes(design,
               "psi falls like 1/N (zero effective mass of a point "
               "impact); v0 and y3_max converge like 1/N"))
