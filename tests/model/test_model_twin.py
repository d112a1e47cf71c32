"""The NumPy twin of eq. 23 (backend="numpy"): thesis claims, exact
scalings, convergence in N, first impact, extremes, batch statuses."""

from __future__ import annotations

import numpy as np
import pytest

from contactsep import beams
from contactsep.model import (
    DesignError,
    evaluate,
    status,
    thesis_design,
)


def ev(design):
    return evaluate(design, backend="numpy")


def test_thesis_design_is_ok():
    r = ev(thesis_design())
    assert int(r.status) == status.OK
    assert r.t1.shape == ()
    for name in ("t1", "v_impact", "psi", "v0", "y3_max"):
        assert np.isfinite(getattr(r, name)) and getattr(r, name) > 0


def test_tip_cantilever_impact_is_quarter_period_free_vibration():
    """Tip-released cantilever: y1(L,t) = sum A_j X_j(L) cos p_j t with
    A_j X_j(L) = 12 ys/(k_jL)^4 > 0; independent check of t1 by a dense
    scan of the same series with no root finder."""
    d = thesis_design()
    r = ev(d)
    k = beams.eigenvalues("clamped-free", 4)
    p = np.asarray(r.p1)
    w = 12.0 * d.ys / k**4
    t = np.linspace(0.0, float(r.t1), 200001)
    y = (w[:, None] * np.cos(p[:, None] * t)).sum(axis=0)
    assert np.all(y[:-1] > 0.0)          # no earlier crossing
    assert abs(y[-1]) < 1e-9
    v = abs(np.sum(w * p * np.sin(p * float(r.t1))))
    assert float(r.v_impact) == pytest.approx(v, rel=1e-12)


@pytest.mark.parametrize("backend", ["compiled", "numpy"])
def test_extremes_match_dense_brute_force(backend):
    for d in (thesis_design(), thesis_design(x3=0.78 * 19.0, n_modes=20),
              thesis_design(end3="clamped-pinned", x3=9.0, n_modes=8)):
        r = evaluate(d, backend=backend)
        t = np.linspace(0.0, d.tau, 400001)
        y = r.y3(t)
        # the dense grid can only be below the true extremum, by at most
        # ~ max|y''| dt^2/8
        slack = 1e-6 * float(np.max(np.abs(y)))
        assert float(r.y3_max) >= y.max() - 1e-15
        assert float(r.y3_max) <= y.max() + slack
        assert float(r.y3_min) <= y.min() + 1e-15
        assert float(r.y3_min) >= y.min() - slack
        assert float(r.y3(r.t_max)) == pytest.approx(float(r.y3_max),
                                                     rel=1e-12)


def test_y3_max_proportional_to_ys_and_one_plus_e():
    base = ev(thesis_design())
    r = ev(thesis_design(ys=0.8))
    assert float(r.y3_max) == pytest.approx(1.6 * float(base.y3_max),
                                            rel=1e-12)
    r = ev(thesis_design(e=0.9))
    assert float(r.y3_max) == pytest.approx(
        1.9 / 1.375 * float(base.y3_max), rel=1e-12)


def test_y3_max_decreases_with_separator_thickness():
    d = np.linspace(0.0625, 0.5, 8)
    r = ev(thesis_design(d=d, lower_response="as-printed"))
    assert np.all(r.status == status.OK)
    assert np.all(np.diff(r.y3_max) < 0.0)


def test_y3_max_decreases_as_x3_moves_in_from_tip():
    x3 = 19.0 * np.linspace(1.0, 0.7, 7)
    r = ev(thesis_design(x3=x3))
    assert np.all(np.diff(r.y3_max) < 0.0)


def test_symmetric_case_one_plus_two_R_law():
    """Identical contacts, x1/L1 = x3/L3, R changed via the separator
    density (eq. 24: R = M2*/M3*, M_i* = M_i / sum_j X_ij(x_i)^2).
    Eq. 20 with M1* = M3*: psi = (1+e) V / (2/M3* + 1/M2*), so
    v0 = psi/M2* = (1+e) V/(1+2R): the as-printed y3 (proportional to v0,
    as the thesis's equation after eq. 24) has y3_max (1+2R) exactly
    independent of R.  Under "impulse" y3 is proportional to
    psi = (1+e) V M3* R/(1+2R): y3_max (1+2R)/R is the invariant."""
    gam = np.array([0.02, 0.05, 0.1, 0.3, 1.0])
    for x in (19.0, 0.78 * 19.0):
        r = ev(thesis_design(gamma2=gam, x1=x, x3=x,
                             lower_response="as-printed"))
        R = np.asarray(r.R)
        assert R[-1] / R[0] > 40.0        # R really varies (x50)
        inv = np.asarray(r.y3_max) * (1.0 + 2.0 * R)
        np.testing.assert_allclose(inv, inv[0], rtol=1e-12)
        r = ev(thesis_design(gamma2=gam, x1=x, x3=x,
                             lower_response="impulse"))
        inv = np.asarray(r.y3_max) * (1.0 + 2.0 * R) / R
        np.testing.assert_allclose(inv, inv[0], rtol=1e-12)
    # not true off the symmetric case (x1/L1 != x3/L3)
    r = ev(thesis_design(gamma2=gam, x3=0.78 * 19.0,
                         lower_response="as-printed"))
    inv = np.asarray(r.y3_max) * (1.0 + 2.0 * np.asarray(r.R))
    assert np.ptp(inv) / inv[0] > 1e-3


def test_convergence_in_n():
    """psi falls like 1/N (the separator's mid-span S2 = sum X2j(L/2)^2
    grows like N); v0 and y3_max converge."""
    ns = np.array([8, 16, 32, 50])
    r = ev(thesis_design(n_modes=ns, lower_response="as-printed"))
    psi = np.asarray(r.psi)
    # N psi tends to a constant
    npsi = ns * psi
    assert abs(npsi[-1] / npsi[-2] - 1.0) < 0.05
    assert psi[-1] < 0.25 * psi[0]
    v0, y = np.asarray(r.v0), np.asarray(r.y3_max)
    assert abs(v0[-1] / v0[-2] - 1.0) < 1e-2
    assert abs(y[-1] / y[-2] - 1.0) < 1e-2


def test_bad_design_in_batch_gets_status_others_results():
    x3 = np.array([19.0, 15.0, 19.0])
    e = np.array([0.375, 0.375, 0.375])
    d = thesis_design(x3=x3, e=e)
    good = ev(d)
    # no impact: gap above the release position (y1 never reaches it)
    r = ev(thesis_design(x3=x3, gap=np.array([0.0, 0.7, 0.0])))
    np.testing.assert_array_equal(r.status, [0, status.NO_IMPACT, 0])
    assert np.isnan(r.y3_max[1]) and np.isnan(r.psi[1])
    np.testing.assert_allclose(r.y3_max[[0, 2]], good.y3_max[[0, 2]],
                               rtol=1e-14)


def test_invalid_rows_through_twin_evaluate_packed():
    from contactsep.model.design import pack
    from contactsep.model.twin import evaluate_packed
    p = pack(thesis_design(d=np.array([0.25, 0.25, 0.25])))
    real = np.array(p.real, order="F")
    real[1, 0] = -1.0
    p2 = type(p)(real=real, ints=p.ints, options=p.options, shape=p.shape)
    out = evaluate_packed(p2)
    np.testing.assert_array_equal(out["status"],
                                  [0, status.INVALID_INPUT, 0])
    assert np.isnan(out["t1"][1]) and np.isfinite(out["t1"][0])


@pytest.mark.parametrize("changes, message", [
    (dict(e=1.5), "^e: found 1.5, expected 0 <= e <= 1$"),
    (dict(end2="free-free"), "^end2: found 'free-free', expected one of "),
    (dict(x3=20.0), r"^x3: found 20.0, expected 0 < x3 <= L3 = 19 in$"),
    (dict(n_modes=0), "^n_modes: found 0, expected an integer >= 1"),
    (dict(impact_velocity="fast"),
     "^impact_velocity: found 'fast', expected one of exact, listing$")])
def test_validation_errors_name_the_field(changes, message):
    """The whole message, from its start: the field's name first."""
    with pytest.raises(DesignError, match=message):
        thesis_design(**changes)


def test_compiled_backend_is_built_and_agrees():
    """The compiled backend must be there (CI builds it): an import error
    fails this test instead of skipping it."""
    from contactsep.model import compiled  # noqa: F401
    r = evaluate(thesis_design(), backend="compiled")
    t = ev(thesis_design())
    assert float(r.y3_max) == pytest.approx(float(t.y3_max), rel=1e-12)
    assert float(r.psi) == pytest.approx(float(t.psi), rel=1e-12)


# Strength-of-materials static shapes y(x)/y(a) (Roark), load at a:
def _cantilever_tip(xi):          # y = F x^2 (3L - x) / (6 EI)
    return xi**2 * (3.0 - xi) / 2.0


def _fixed_mid(xi):               # x <= L/2: y = F x^2 (3L - 4x)/(48 EI)
    u = np.minimum(xi, 1.0 - xi)
    return 4.0 * u**2 * (3.0 - 4.0 * u)


def _pinned_mid(xi):              # x <= L/2: y = F x (3L^2 - 4x^2)/(48 EI)
    u = np.minimum(xi, 1.0 - xi)
    return u * (3.0 - 4.0 * u**2)


@pytest.mark.parametrize("end,a,shape", [
    ("clamped-free", 1.0, _cantilever_tip),
    ("clamped-clamped", 0.5, _fixed_mid),
    ("pinned-pinned", 0.5, _pinned_mid)])
def test_static_shape_synthesised_from_release_amplitudes(end, a, shape):
    """y(x, 0) = sum_j A_j X_j(x) with the twin's A_j, 400 modes, against
    the textbook shape at 10 points.  Tail: |A_j X_j| <= 4 ys/(G k_j^4),
    so the truncation is below 4 ys / (G 3 pi^4 n^3)."""
    from contactsep.model import twin
    n, ys = 400, 0.5
    kl = beams.eigenvalues(end, n)[None, :]
    g = beams.static_flexibility(end, np.array([a]))
    xa = beams.mode_shapes(end, n, [a])[:, 0][None, :]
    amp = twin.release_amplitudes(np.array([ys]), xa, kl, g)[0]
    xi = np.linspace(0.1, 1.0, 10)
    y = amp @ beams.mode_shapes(end, n, xi)
    tail = 4.0 * ys / (float(g[0]) * 3.0 * np.pi**4 * n**3)
    np.testing.assert_allclose(y, ys * shape(xi), rtol=0, atol=tail)


def test_first_impact_no_earlier_crossing_other_ends():
    """Varied end conditions, contact points and gaps: y1(x1, t) computed
    here from modes + the twin's amplitudes stays above the gap on a dense
    grid before t1 and equals it at t1."""
    from contactsep.model import twin
    cases = [("clamped-free", 0.7, 0.0, "tip"),
             ("clamped-free", 0.9, 0.1, "contact"),
             ("clamped-clamped", 0.5, 0.0, "contact"),
             ("clamped-pinned", 0.6, -0.05, "contact"),
             ("pinned-pinned", 0.3, 0.0, "contact")]
    for end, xi1, gap, rel in cases:
        n = 12
        d = thesis_design(end1=end, x1=xi1 * 19.0, gap=gap, n_modes=n,
                          release=rel)
        r = ev(d)
        assert int(r.status) == status.OK, (end, xi1)
        xl = 1.0 if rel == "tip" else xi1
        kl = beams.eigenvalues(end, n)
        g = beams.static_flexibility(end, np.array([xl]))
        amp = twin.release_amplitudes(
            np.array([0.5]), beams.mode_shapes(end, n, [xl])[:, 0][None],
            kl[None], g)[0]
        w = amp * beams.mode_shapes(end, n, [xi1])[:, 0]
        p = np.asarray(r.p1)
        t = np.linspace(0.0, float(r.t1), 100001)
        y = (w[:, None] * np.cos(p[:, None] * t)).sum(axis=0)
        assert np.all(y[:-1] > gap), (end, xi1)
        assert abs(y[-1] - gap) < 1e-10
