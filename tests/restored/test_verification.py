"""The restored core against the independent NumPy reference, quantity by
quantity, and what the listing's float32 arithmetic loses.

Tolerances: the two float64 implementations agree to 1e-9 relative except
where an analytic bound says the listing's own formulas cannot: the D1-D8
integrals subtract terms of size ~ y_s e^{kL}/(kL) to get A_j (absolute
error ~ 12 eps y_s e^{kL}/(kL)), and the listing's search stops within
1e-8 s of the crossing the reference finds exactly.
"""

from __future__ import annotations

import numpy as np
import pytest

from conftest import THESIS_DECKS, variant_data_sets, with_modes
from contactsep.restored import core, reference, thesis_decks

EPS64 = float(np.finfo(np.float64).eps)
EPS32 = float(np.finfo(np.float32).eps)
SEARCH_STEP = 1e-8
RTOL = 1e-9


def amplitude_error(ds, eps) -> np.ndarray:
    """Absolute rounding bound of the listing's A_j at unit roundoff eps."""
    v = np.asarray(ds.v)
    return 12 * eps * abs(ds.ystat) * np.exp(v) / v


def d1_d8_amplitudes(ds, dtype) -> np.ndarray:
    """The listing's loop 60 (D1..D8, A-(7)) term for term in ``dtype``."""
    f = dtype
    xl, ystat = f(ds.xl), f(ds.ystat)
    out = []
    for v, alpha in zip(np.asarray(ds.v, f), np.asarray(ds.alpha, f)):
        sh = (np.exp(v) - np.exp(-v)) / f(2)
        ch = (np.exp(v) + np.exp(-v)) / f(2)
        u = v / xl
        q, r = f(2) / u**3, xl**2 / u
        c, s = np.cos(v), np.sin(v)
        d1 = (q - r) * c + (f(2) * (xl * s)) / u**2 - q
        d2 = (f(2) * xl) * c / u**2 + (r - q) * s
        d3 = f(3) * d2 / u - xl**3 * c / u
        d4 = xl**3 * s / u - f(3) * d1 / u
        d5 = (r + q) * ch - (f(2) * xl) * sh / u**2 - q
        d6 = (r + q) * sh - (f(2) * xl) * ch / u**2
        d7 = xl**3 * ch / u - f(3) * d6 / u
        d8 = xl**3 * sh / u - f(3) * d5 / u
        ap = (f(3) * ystat / xl**3) * ((d6 - d2) - alpha * (d5 - d1))
        pe = (ystat / xl**4) * ((d8 - d4) - alpha * (d7 - d3))
        out.append((ap - pe) / f(2))
    return np.array(out, dtype=f)


def data_sets():
    sets = []
    for deck in THESIS_DECKS:
        sets += [item.data_set for item in core.iter_deck(
            core.read_text(deck), precision="double")]
    for variants in variant_data_sets().values():
        sets += variants
    sets += [with_modes(thesis_decks.thesis_data_set(0.35), n) for n in (6, 8)]
    return sets


def test_restored_double_equals_reference():
    for ds in data_sets():
        ours, ref = core.solve(ds, "double"), reference.run(ds)
        label = f"N={ds.n} h2={ds.h2} e={ds.e:g} dely={ds.dely}"
        for name in ("p", "p2", "p3"):
            np.testing.assert_allclose(getattr(ours, name), getattr(ref, name),
                                       rtol=1e-13, err_msg=label)
        for name in ("wm", "wm2", "wm3", "gr", "beta", "mr1", "mr3", "ct",
                     "ct2", "ct3"):
            assert getattr(ours, name) == pytest.approx(
                getattr(ref, name), rel=1e-13), (label, name)
        d_ape = amplitude_error(ds, EPS64)
        np.testing.assert_array_less(np.abs(ours.ape - ref.ape),
                                     d_ape + RTOL * np.abs(ref.ape),
                                     err_msg=label)
        # the impact: within the listing's search step, on the near side
        assert ref.t_impact - SEARCH_STEP <= ours.t_impact <= ref.t_impact \
            + 1e-15, label
        # what follows from ACT (impulse, separator, lower contact) does not
        # depend on the impact time (quirk 1)
        d_act = np.sum(ours.p * np.abs(ds.c) * d_ape) / abs(ref.impulse_velocity)
        rel = RTOL + d_act
        assert ours.ey == pytest.approx(ref.ey, rel=rel), label
        assert ours.ty2dt == pytest.approx(ref.ty2dt, rel=rel), label
        np.testing.assert_allclose(ours.history_t, ref.history_t, rtol=0,
                                   atol=64 * EPS64 * 0.06, err_msg=label)
        scale = np.max(np.abs(ref.history_ty3))
        np.testing.assert_allclose(ours.history_ty3, ref.history_ty3,
                                   rtol=0, atol=rel * scale, err_msg=label)
        # the post-impact coefficients move with the impact time
        dt = SEARCH_STEP
        np.testing.assert_allclose(
            ours.a1, ref.a1, rtol=0,
            atol=np.max(np.abs(ref.ape) * ref.p) * dt + np.max(d_ape)
            + RTOL * np.max(np.abs(ref.ape)), err_msg=label)
        np.testing.assert_allclose(
            ours.b1, ref.b1, rtol=0,
            atol=np.max(np.abs(ref.ape) * ref.p) * dt + np.max(d_ape)
            + RTOL * np.max(np.abs(ref.ape)), err_msg=label)


@pytest.mark.parametrize("deck", [p for p in THESIS_DECKS
                                  if p.stem.startswith("thesis_d")],
                         ids=lambda p: p.stem)
def test_what_float32_loses_per_mode(deck):
    """The listing's REAL arithmetic, |single/double - 1| per mode: A_1,
    A_2 good to ~1e-6, A_3 1.05 % and A_4 32 % off (measured 1.4e-7,
    9.3e-7, 1.05e-2, 0.320 on every thesis deck: the upper contact is the
    same in all five), always inside the a priori bound; the impulse
    inherits 0.7 % from A_4 through ACT = sum P A C.  The legacy program
    prints the same digits (test_replay) and the double results agree with
    the NumPy reference (above), so these figures are the listing's."""
    single = core.replay(deck, "single")[0]
    double = core.replay(deck, "double")[0]
    ds = double.inputs
    rel = np.abs(single.ape.astype(float) / double.ape - 1)
    bound = amplitude_error(ds, EPS32) / np.abs(double.ape)
    assert np.all(rel <= bound)
    # the bands from an independent path: the listing's D1..D8 evaluated
    # term for term in np.float32 here (NumPy's libm, not gfortran's);
    # the two float32 evaluations agree to a few ulps of A_j
    ape32 = d1_d8_amplitudes(ds, np.float32).astype(float)
    assert np.all(np.abs(d1_d8_amplitudes(ds, np.float64) / double.ape - 1)
                  < 1e-12)
    np.testing.assert_allclose(single.ape, ape32, rtol=16 * EPS32, atol=0)
    rel32 = np.abs(ape32 / double.ape - 1)
    np.testing.assert_allclose(rel, rel32, rtol=0, atol=16 * EPS32)
    assert rel[0] < 1e-6 and rel[1] < 5e-6 and rel[3] > 0.1
    # the impulse inherits ACT = sum P A C's relative error
    act32 = np.sum(double.p * ape32 * ds.c)
    act64 = np.sum(double.p * double.ape * ds.c)
    impulse = abs(single.ey / double.ey - 1)
    assert impulse == pytest.approx(abs(act32 / act64 - 1), rel=0.05)
    # the lower contact's extreme carries the same relative error (it is
    # proportional to EY)
    extreme = abs(single.extreme_ty3 / double.extreme_ty3 - 1)
    assert extreme == pytest.approx(impulse, rel=1e-3, abs=1e-6)


def test_thesis_options_change_what_they_say():
    """The thesis's eq. (20) impact velocity and the equivalent separator
    mass are named options of the reference; each moves the impulse the
    way its formula says."""
    ds = thesis_decks.thesis_data_set(0.5)
    listing_like = reference.run(ds)
    thesis_velocity = reference.run(ds, impact_velocity="thesis")
    assert thesis_velocity.ey / listing_like.ey == pytest.approx(
        thesis_velocity.impact_velocity / listing_like.impulse_velocity,
        rel=1e-12)
    equivalent = reference.run(ds, separator_mass="equivalent")
    assert equivalent.wm2_impulse == pytest.approx(
        listing_like.wm2_impulse * ds.xl2c / ds.xl2, rel=1e-14)
