"""Every column of every study (contactsep.studies) checked against a
formula written here, from the thesis's equations, with mode values from
mpmath (120 digits) and the extremes of y3 from the independent reference
(tests/extremum_reference.py): no number is taken from the model's own
chain unless another column's check confirms it (v0 for Figure 7)."""

from __future__ import annotations

import functools
import math

import extremum_reference as reference
import numpy as np
import pytest

from contactsep import studies
from contactsep.model import evaluate

# the thesis studies' design: eq. 23's lower response as printed
from contactsep.studies.study import thesis_study_design

mpmath = pytest.importorskip("mpmath")

#: The thesis rig (Chapters V-VI), written here on its own.
G = 386.4                       # in/s^2 (Appendix B)
E, GAMMA = 10.0e6, 0.100        # psi, lb/in^3
L, B, H = 19.0, 2.0, 0.125      # contacts (in)
L2, B2 = 2.5, 0.5               # separator (in)
YS, RESTITUTION, TAU = 0.5, 0.375, 0.060
#: Table I-III as printed.
TABLE_I = (10.6, 66.5, 187.0, 366.0)
TABLE_I_UPPER = (10.3, 65.0, 180.0, 360.0)
TABLE_I_LOWER = (10.6, 67.0, 186.0, 371.0)
TABLE_II_D = (0.125, 0.250, 0.350, 0.500, 0.750)
TABLE_II = (4050.0, 8100.0, 11310.0, 16200.0, 24300.0)
TABLE_II_EXPERIMENT = (2000.0, 4000.0, 5000.0, 6250.0, 11100.0)
TABLE_III_P = (12560.0, 25120.0, 31400.0, 39250.0, 70000.0)
TABLE_III_LC = (3.60, 3.60, 3.81, 4.07, 4.15)
#: First clamped-clamped eigenvalue, published (beam-constants.md).
BETA1 = 4.73004074


def constant(thickness, width=B):
    """a = sqrt(E I g / (A gamma)) (III-(1)) of a rectangular section."""
    return math.sqrt(E * (width * thickness**3 / 12.0) * G
                     / (width * thickness * GAMMA))


def mass(length, width, thickness):
    return GAMMA * length * width * thickness / G


@functools.lru_cache(maxsize=None)
def modes(end, n, xi):
    """k_jL and X_j(xi), j = 1..n, of a cantilever or clamped-clamped beam
    normalised to int X^2 = L (roots of the frequency equation divided by
    cosh, from asymptotic guesses; 120 digits outlast the cancellation of
    e^{k_jL} terms to N = 50)."""
    mp = mpmath.mp
    mp.dps = 120
    if end == "clamped-free":
        f = lambda x: mp.cos(x) + 1 / mp.cosh(x)  # noqa: E731
        guess = [1.875] + [(2 * j - 1) * mp.pi / 2 for j in range(2, n + 1)]
    else:
        f = lambda x: mp.cos(x) - 1 / mp.cosh(x)  # noqa: E731
        guess = [(2 * j + 1) * mp.pi / 2 for j in range(1, n + 1)]
    kl, values = [], []
    for g in guess:
        k = mp.findroot(f, g)
        if end == "clamped-free":
            sigma = (mp.sinh(k) - mp.sin(k)) / (mp.cosh(k) + mp.cos(k))
        else:
            sigma = (mp.cosh(k) - mp.cos(k)) / (mp.sinh(k) - mp.sin(k))
        u = k * mp.mpf(xi)
        kl.append(float(k))
        values.append(float(mp.cosh(u) - mp.cos(u)
                            - sigma * (mp.sinh(u) - mp.sin(u))))
    return np.array(kl), np.array(values)


def chain(n, d, ys=YS, xi3=1.0, gamma2=GAMMA):
    """The thesis design's t1, V, psi, v0 and y3's c_j, p_j (tip release,
    tips and mid-span, no L_c), from eqs. 3, 12, 13 and 20."""
    kl, tip = modes("clamped-free", n, 1.0)
    _, x3 = modes("clamped-free", n, xi3)
    _, mid = modes("clamped-clamped", n, 0.5)
    p = kl**2 * constant(H) / L**2
    w = 3.0 * ys * tip**2 / kl**4              # A_j X_j(L)
    # first crossing of y1(L, t) = 0: bisection on a bracket from a scan
    t = np.linspace(0.0, 2 * math.pi / p[0], 20001)
    y = np.cos(np.outer(t, p)) @ w
    k = int(np.argmax(y <= 0.0))
    lo, hi = t[k - 1], t[k]
    for _ in range(200):
        mid_t = 0.5 * (lo + hi)
        if float(np.cos(p * mid_t) @ w) > 0.0:
            lo = mid_t
        else:
            hi = mid_t
    t1 = 0.5 * (lo + hi)
    v = abs(float(np.sin(p * t1) @ (w * p)))
    m1 = mass(L, B, H)
    m2 = GAMMA / GAMMA * gamma2 * L2 * B2 * d / G
    psi = (1 + RESTITUTION) * v / (np.sum(tip**2) / m1 + np.sum(mid**2) / m2
                                   + np.sum(x3**2) / m1)
    v0 = psi * np.sum(mid**2) / m2
    c = (v0 / L) * x3**2 / p
    return dict(t1=t1, v=v, psi=psi, v0=v0, c=c, p=p,
                r=(m2 / np.sum(mid**2)) / (m1 / np.sum(x3**2)))


def extremes(c, p, tau=TAU):
    return reference.extremes(c, p, tau)


def model_extremes(design):
    """The reference's extremes of the model's y3 (c3, p3) per design."""
    ev = evaluate(design)
    c3 = ev.c3.reshape(-1, ev.c3.shape[-1])
    p3 = ev.p3.reshape(-1, ev.p3.shape[-1])
    return np.array([extremes(c[~np.isnan(p)], p[~np.isnan(p)])
                     for c, p in zip(c3, p3)])


def test_fig5_columns():
    s = studies.fig5()
    d = np.round(np.arange(0.10, 1.0001, 0.05), 10)
    ys = np.repeat([0.25, 0.5, 0.75], d.size)
    np.testing.assert_array_equal(s["ys_in"], ys)
    np.testing.assert_allclose(s["d_in"], np.tile(d, 3), rtol=1e-15)
    for k, (y, t) in enumerate(zip(s["y3_max_in"], s["t_max_s"])):
        one = chain(4, s["d_in"][k], ys=s["ys_in"][k])
        want = extremes(one["c"], one["p"])
        assert y == pytest.approx(want[0], rel=1e-9)
        assert t == pytest.approx(want[1], rel=1e-6)


def test_fig6_columns():
    s = studies.fig6()
    r = np.round(np.arange(0.70, 1.0001, 0.01), 10)
    assert s["curve"].tolist() == ["I"] * r.size + ["II"] * r.size
    np.testing.assert_array_equal(s["r"], np.concatenate([r, r]))
    np.testing.assert_allclose(s["L3_in"], np.concatenate(
        [np.full(r.size, L), L / r]), rtol=1e-15)
    one = thesis_study_design(x3=r * L)
    two = thesis_study_design(L3=L / r, x3=np.full(r.size, L))
    want = np.concatenate([model_extremes(one)[:, 0],
                           model_extremes(two)[:, 0]])
    np.testing.assert_allclose(s["y3_max_in"], want, rtol=1e-12)


def test_fig7_columns():
    """y3(t) of the two contact points from c_j = (v0/L3) X_j(x3)^2/p_j
    (eq. 13 as printed), X_j and p_j computed here; v0 the model's (its
    value is checked in test_convergence_columns)."""
    s = studies.fig7()
    t = np.round(np.arange(0.0, 0.06001, 0.0001), 10)
    np.testing.assert_array_equal(s["t_s"], np.tile(t, 2))
    np.testing.assert_array_equal(s["r"], np.repeat([0.98, 0.78], t.size))
    for k, ratio in enumerate((0.98, 0.78)):
        v0 = float(evaluate(thesis_study_design(x3=ratio * L)).v0)
        kl, x3 = modes("clamped-free", 4, ratio)
        p = kl**2 * constant(H) / L**2
        c = (v0 / L) * x3**2 / p
        y = np.sin(np.outer(t, p)) @ c
        np.testing.assert_allclose(s["y3_in"][k * t.size:(k + 1) * t.size],
                                   y, rtol=0, atol=1e-14)


def test_fig8_columns():
    s = studies.fig8()
    np.testing.assert_allclose(s["R"], np.geomspace(0.05, 5.0, 30),
                               rtol=1e-12)
    # eq. 24 from masses and mode values computed here
    for rr, gamma2 in zip(s["R"], s["gamma2_lb_in3"]):
        assert chain(4, 0.25, xi3=0.98, gamma2=gamma2)["r"] == \
            pytest.approx(rr, rel=1e-10)
    want = model_extremes(thesis_study_design(gamma2=s["gamma2_lb_in3"],
                                        x1=0.98 * L, x3=0.98 * L))[:, 0]
    np.testing.assert_allclose(s["y3_max_in"], want, rtol=1e-12)
    law = want[0] * (1 + 2 * s["R"][0]) / (1 + 2 * s["R"])
    np.testing.assert_allclose(s["law_in"], law, rtol=1e-12)


def test_fig23_columns():
    """With the listing's L_c (M2 L_c/L2 in v0 only) y3 as printed scales
    with v0, so the corrected curve is the uncorrected one times L2/L_c."""
    s = studies.fig23()
    assert s["d_in"].tolist() == list(TABLE_II_D)
    assert s["Lc_in"].tolist() == list(TABLE_III_LC)
    for d, lc, y, y_plain in zip(s["d_in"], s["Lc_in"], s["y3_max_in"],
                                 s["y3_max_uncorrected_in"]):
        one = chain(4, d)
        assert y_plain == pytest.approx(extremes(one["c"], one["p"])[0],
                                        rel=1e-9)
        assert y == pytest.approx(y_plain * L2 / lc, rel=1e-12)


def test_convergence_columns():
    """t1 (y1 = 0 by bisection), V, psi (eq. 20), v0 (eq. 12) and y3_max
    (the reference's, of c_j from eq. 13) for every N, from mode values
    computed here."""
    s = studies.convergence()
    assert s["N"].tolist() == [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 50]
    for k, n in enumerate(s["N"]):
        one = chain(int(n), 0.25)
        assert s["t1_s"][k] == pytest.approx(one["t1"], rel=1e-12)
        assert s["v_impact_in_s"][k] == pytest.approx(one["v"], rel=1e-10)
        assert s["psi_lb_s"][k] == pytest.approx(one["psi"], rel=1e-10)
        assert s["v0_in_s"][k] == pytest.approx(one["v0"], rel=1e-10)
        assert s["y3_max_in"][k] == pytest.approx(
            extremes(one["c"], one["p"])[0], rel=1e-9)
    # psi falls like 1/N (zero effective mass of a point impact)
    npsi = s["N"] * s["psi_lb_s"]
    assert abs(npsi[-1] / npsi[-2] - 1) < 0.01


def test_table1_columns():
    s = studies.table1()
    kl = np.array([1.87510407, 4.69409113, 7.85475744, 10.99554073])
    model = kl**2 * constant(H) / L**2 / (2 * math.pi)
    assert s["mode"].tolist() == [1, 2, 3, 4]
    assert s["printed_theoretical_cps"].tolist() == list(TABLE_I)
    np.testing.assert_allclose(s["model_cps"], model, rtol=1e-8)
    # the published k_jL carry 9 digits: ~1e-8 in a ratio of frequencies
    np.testing.assert_allclose(s["relative_difference"],
                               model / np.array(TABLE_I) - 1, rtol=0,
                               atol=2e-8)
    assert s["experimental_upper_cps"].tolist() == list(TABLE_I_UPPER)
    assert s["experimental_lower_cps"].tolist() == list(TABLE_I_LOWER)


def test_table2_columns():
    s = studies.table2()
    d = np.array(TABLE_II_D)
    model = np.array([BETA1**2 * constant(h, B2) / L2**2 / (2 * math.pi)
                      for h in d])
    assert s["d_in"].tolist() == list(TABLE_II_D)
    assert s["printed_theoretical_cps"].tolist() == list(TABLE_II)
    np.testing.assert_allclose(s["model_cps"], model, rtol=1e-8)
    np.testing.assert_allclose(s["relative_difference"],
                               model / np.array(TABLE_II) - 1, rtol=0,
                               atol=2e-8)
    assert s["experimental_cps"].tolist() == list(TABLE_II_EXPERIMENT)


def test_table3_columns():
    """L_c where the clamped-clamped separator has the printed p:
    p = beta1^2 a / L_c^2, so L_c = beta1 sqrt(a / p)."""
    s = studies.table3()
    d, p = np.array(TABLE_II_D), np.array(TABLE_III_P)
    formula = np.sqrt(1.3e6 * d / p)
    model = np.array([BETA1 * math.sqrt(constant(h, B2) / q)
                      for h, q in zip(d, p)])
    assert s["d_in"].tolist() == list(TABLE_II_D)
    assert s["p_rad_s"].tolist() == list(TABLE_III_P)
    assert s["printed_Lc_in"].tolist() == list(TABLE_III_LC)
    np.testing.assert_allclose(s["Lc_formula_in"], formula, rtol=1e-14)
    np.testing.assert_allclose(s["relative_difference"],
                               formula / np.array(TABLE_III_LC) - 1,
                               rtol=1e-12)
    np.testing.assert_allclose(s["Lc_model_in"], model, rtol=1e-8)


def test_every_column_is_checked_here():
    """A column added to a study needs its check in this file."""
    checked = {
        "fig5": ["ys_in", "d_in", "y3_max_in", "t_max_s"],
        "fig6": ["curve", "r", "L3_in", "y3_max_in"],
        "fig7": ["r", "t_s", "y3_in"],
        "fig8": ["R", "gamma2_lb_in3", "y3_max_in", "law_in"],
        "fig23": ["d_in", "Lc_in", "y3_max_in", "y3_max_uncorrected_in"],
        "convergence": ["N", "t1_s", "v_impact_in_s", "psi_lb_s",
                        "v0_in_s", "y3_max_in"],
        "table1": ["mode", "printed_theoretical_cps", "model_cps",
                   "relative_difference", "experimental_upper_cps",
                   "experimental_lower_cps"],
        "table2": ["d_in", "printed_theoretical_cps", "model_cps",
                   "relative_difference", "experimental_cps"],
        "table3": ["d_in", "p_rad_s", "printed_Lc_in", "Lc_formula_in",
                   "relative_difference", "Lc_model_in"],
        # checked in tests/studies/thesis/test_conclusion8.py (the share against
        # the cantilever's formulas, the swings against a naive count)
        "conclusion8": ["r", "x3_in", "first_mode_share", "n_maxima",
                        "y3_max_in"]}
    assert set(checked) == set(studies.STUDIES) - {"chatter"}
    for name, columns in checked.items():
        assert list(getattr(studies, name)().columns) == columns, name
