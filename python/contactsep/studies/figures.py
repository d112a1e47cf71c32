"""The thesis's design studies (Figures 5-8, 21, 23 and the convergence in
N) as batched evaluations of the general model.

Each function takes the thesis experiment (contactsep.thesis_design) with
any field overridden by keyword (``n_modes=8``, ``e=0.5``, ...) and returns
a :class:`~contactsep.studies.study.Study`.  Units: in, lb, s.
"""

from __future__ import annotations

import numpy as np

from contactsep.model import evaluate, thesis_design
from contactsep.restored import thesis_decks
from contactsep.studies.study import Study

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


def _notes(design, *extra) -> tuple:
    base = design.replace(h2=0.25)
    return (*extra,
            "model: eq. 23 (contactsep.model), "
            f"impact_velocity={base.impact_velocity}, "
            f"lower_response={base.lower_response}, release={base.release}",
            f"inputs: L1=L3={base.L1} in, b1=b3={base.b1} in, "
            f"h1=h3={base.h1} in, L2={base.L2} in, b2={base.b2} in, "
            f"E={base.E1} psi, gamma={base.gamma1} lb/in^3, "
            f"ys={base.ys} in, e={base.e}, N={base.n_modes}, "
            f"tau={base.tau} s",
            "y3 > 0: the lower contact moves away from the separator; "
            "times from the impact")


def _ok(ev):
    if np.any(ev.status != 0):
        from contactsep.errors import InputError
        raise InputError("a design of the study failed (status "
                         f"{int(np.max(ev.status))}); check the overrides")
    return ev


def fig5(*, backend="compiled", **overrides) -> Study:
    """Figure 5: max y3 against separator thickness d = 0.10..1.00 in, for
    y_s = 0.25, 0.5, 0.75 in."""
    ys = np.array(FIG5_DEFLECTIONS)[:, None]
    d = FIG5_THICKNESSES[None, :]
    overrides.pop("ys", None)
    design = thesis_design(d=d, ys=ys, **overrides)
    ev = _ok(evaluate(design, backend=backend))
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
    r = FIG6_RATIOS
    overrides.setdefault("d", FIG6_THICKNESS)
    base = thesis_design(**overrides)
    length = float(base.L3)
    one = _ok(evaluate(base.replace(x3=r * length), backend=backend))
    two = _ok(evaluate(base.replace(L3=length / r, x3=np.full_like(r, length)),
                       backend=backend))
    return Study("fig6", "Figure 6: maximum lower-contact displacement vs "
                 "x3/L3", {
                     "curve": np.repeat(["I", "II"], r.size),
                     "r": np.concatenate([r, r]),
                     "L3_in": np.concatenate([np.full_like(r, length),
                                              length / r]),
                     "y3_max_in": np.concatenate([one.y3_max, two.y3_max])},
                 _notes(base, "curve I: L3 fixed, x3 = r L3; curve II: "
                        "x3 fixed, L3 = x3/r (the contact point keeps its "
                        "distance from the support)"))


def fig7(*, backend="compiled", **overrides) -> Study:
    """Figure 7: y3(x3, t) for t = 0..0.06 s at r = 0.98 and 0.78 (curve
    I), with each mode's coefficient in the notes."""
    r = np.array(FIG7_RATIOS)
    base = thesis_design(**overrides)
    ev = _ok(evaluate(base.replace(x3=r * float(base.L3)), backend=backend))
    y = ev.y3(FIG7_TIMES)
    notes = [f"r = {ri}: mode coefficients c3_j (in) = "
             + ", ".join(f"{c:.4g}" for c in ev.c3[i])
             for i, ri in enumerate(r)]
    return Study("fig7", "Figure 7: lower-contact displacement vs time", {
        "r": np.repeat(r, FIG7_TIMES.size),
        "t_s": np.tile(FIG7_TIMES, r.size),
        "y3_in": y.ravel()}, _notes(base, *notes))


def fig8(*, backend="compiled", **overrides) -> Study:
    """Figure 8: max y3 against the mass ratio R of eq. 24, changed through
    the separator's density only, symmetric contacts x1/L1 = x3/L3 = 0.98;
    beside it the thesis's law y3_max ~ 1/(1 + 2R)."""
    base = thesis_design(**overrides)
    base = base.replace(x1=FIG8_CONTACT * float(base.L1),
                        x3=FIG8_CONTACT * float(base.L3))
    r0 = float(_ok(evaluate(base, backend=backend)).R)
    gamma2 = float(base.gamma2) * FIG8_RATIOS / r0
    ev = _ok(evaluate(base.replace(gamma2=gamma2), backend=backend))
    anchor = ev.y3_max[0] * (1 + 2 * ev.R[0])
    return Study("fig8", "Figure 8: maximum lower-contact displacement vs "
                 "mass ratio R", {
                     "R": ev.R, "gamma2_lb_in3": gamma2,
                     "y3_max_in": ev.y3_max,
                     "law_in": anchor / (1 + 2 * ev.R)},
                 _notes(base, "R (eq. 24) changed through gamma2 only; "
                        "law_in = y3_max(R1)(1 + 2 R1)/(1 + 2 R)"))


def fig23(*, backend="compiled", lc_reading="listing", **overrides) -> Study:
    """Figures 21 and 23 (the "corrected" theory): the five thesis
    separators with Table III's equivalent lengths L_c; lc_reading as in
    the model ("listing" hybrid by default)."""
    d = np.array(list(TABLE_III))
    lc = np.array(list(TABLE_III.values()))
    overrides.pop("d", None)
    base = thesis_design(d=d, **overrides)
    plain = _ok(evaluate(base, backend=backend))
    ev = _ok(evaluate(base.replace(Lc=lc, lc_reading=lc_reading),
                      backend=backend))
    return Study("fig23", "Figures 21 and 23: maximum lower-contact "
                 "displacement with the Table III equivalent lengths", {
                     "d_in": d, "Lc_in": lc, "y3_max_in": ev.y3_max,
                     "y3_max_uncorrected_in": plain.y3_max},
                 _notes(base, f"L_c from Table III, lc_reading="
                        f"{lc_reading}; e = 0.375 for every separator "
                        "(Figure 23's value; Figure 20's e(d) is not "
                        "tabulated)"))


def convergence(*, backend="compiled", **overrides) -> Study:
    """t1, V, psi, v0 and max y3 for N = 1 ... 50 (docs/model.md)."""
    overrides.pop("n_modes", None)
    n = np.array(CONVERGENCE_MODES)
    design = thesis_design(n_modes=n, **overrides)
    ev = _ok(evaluate(design, backend=backend))
    return Study("convergence", "Convergence in the number of modes N", {
        "N": n, "t1_s": ev.t1, "v_impact_in_s": ev.v_impact,
        "psi_lb_s": ev.psi, "v0_in_s": ev.v0, "y3_max_in": ev.y3_max},
        _notes(design.replace(n_modes=4),
               "psi falls like 1/N (zero effective mass of a point "
               "impact); v0 and y3_max converge like 1/N"))
