"""The transcribed Appendix G program runs the decks and prints what the
thesis equations say it should.

Expected numbers come from the deck's inputs through the thesis's formulas
evaluated here in float64, or from identities between printed numbers
(the listing's own formulas applied to what it printed); none from the
program under test.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from conftest import THESIS_DECKS, as_precision
from contactsep.errors import DeckError
from contactsep.restored import cards, legacy, listing

G = 386.4  # in/s^2, the listing's g


def run(deck, precision):
    text = legacy.run(deck, precision)
    return text, listing.parse(text)


def assert_printed(printed, expected, precision, single_rtol=2e-6,
                   double_rtol=1e-12):
    """Printed F15.9 values against float64 expectations: half a unit in
    the 9th decimal for the printing, and the working precision's relative
    error for the arithmetic (a few float32 ulp, or float64 ulp)."""
    rtol = single_rtol if precision == "single" else double_rtol
    np.testing.assert_allclose(printed, expected, rtol=rtol, atol=5.1e-10)


@pytest.fixture
def deck_and_listing(thesis_deck, precision):
    data_sets = cards.read_deck(thesis_deck)
    text, parsed = run(thesis_deck, precision)
    return data_sets, text, parsed


def test_thesis_decks_exist():
    names = {p.name for p in THESIS_DECKS}
    for d in ("0125", "0250", "0350", "0500", "0750"):
        assert f"thesis_d{d}.dat" in names


def test_one_listing_per_data_set(deck_and_listing):
    data_sets, text, parsed = deck_and_listing
    assert len(parsed) == len(data_sets)
    assert "".join(p.text for p in parsed) == text


def test_listing_sections(deck_and_listing, precision):
    data_sets, _, parsed = deck_and_listing
    for ds, out in zip(data_sets, parsed):
        assert out.n == ds.n == 4
        np.testing.assert_allclose(
            out.separator_card, as_precision([ds.xl2, ds.b2, ds.h2, ds.rho2],
                                             precision), atol=6e-10)
        for table, names in ((out.modal_table[:, :3], ("v", "c", "alpha")),
                             (out.separator_modes[:, :3], ("v2", "c2", "alph2")),
                             (out.lower_modes[:, :3], ("v3", "c3", "alph3"))):
            expected = np.column_stack([getattr(ds, n) for n in names])
            np.testing.assert_allclose(table, as_precision(expected, precision),
                                       atol=6e-10)
        ed = float(np.float32(9.999)) if precision == "single" else 9.999
        assert out.end_of_search == pytest.approx(ed, abs=6e-10)
        assert out.masses[3] == pytest.approx(
            as_precision(ds.xl2c, precision), abs=6e-10)


def test_impact_search_trace(deck_and_listing, precision):
    data_sets, _, parsed = deck_and_listing
    for ds, out in zip(data_sets, parsed):
        t, ty = out.trace[:, 0], out.trace[:, 1]
        assert t[0] == 0.0
        # the search starts with steps of DELT ...
        np.testing.assert_allclose(np.diff(t[:5]), ds.delt, rtol=1e-5)
        # ... every printed point is above the separator, time increases,
        assert np.all(ty > ds.dely) and np.all(np.diff(t) > 0)
        # and the last one is the impact, within the listing's 1e-8 s
        # stopping step at the tip's own speed, plus rounding: the modal
        # sum's (a few ulps of y_s in the working precision) and the
        # printed F15.9 field's half unit.
        assert out.impact[0] == t[-1]
        eps = np.finfo(np.float32 if precision == "single"
                       else np.float64).eps
        rounding = 8 * eps * ds.ystat + 5e-10
        assert 0 < ty[-1] - ds.dely <= 1e-8 * abs(out.trace[-1, 2]) + rounding
        # it starts from the release point: the modal sum recovers y_s
        assert ty[0] == pytest.approx(ds.ystat, rel=2e-3)


def test_first_frequency_from_beam_formula(deck_and_listing, precision):
    """p_1 = (k_1 L)^2 sqrt(E I g / (A gamma)) / L^2 for each member."""
    data_sets, _, parsed = deck_and_listing
    for ds, out in zip(data_sets, parsed):
        for kl, length, b, h, rho, printed in (
                (ds.v, ds.xl, ds.b, ds.h, ds.rho, out.modal_table[:, 3]),
                (ds.v3, ds.xl3, ds.b3, ds.h3, ds.rho3, out.lower_modes[:, 3])):
            area, inertia, gamma = b * h, b * h**3 / 12.0, rho / 1728.0
            p = kl**2 * np.sqrt(ds.e * inertia * G / (area * gamma)) / length**2
            assert_printed(printed, p, precision)
        # the separator's: nominal length XL2 (quirk 3); wide ones overflow
        kl2 = ds.v2
        area2, inertia2 = ds.b2 * ds.h2, ds.b2 * ds.h2**3 / 12.0
        p2 = kl2**2 * np.sqrt(ds.e * inertia2 * G * 1728.0 /
                              (area2 * ds.rho2)) / ds.xl2**2
        printed = out.separator_modes[:, 3]
        fits = p2 < 99999.9999995
        assert_printed(printed[fits], p2[fits], precision)
        assert np.all(np.isnan(printed[~fits]))


def test_masses_and_ratios(deck_and_listing, precision):
    data_sets, _, parsed = deck_and_listing
    for ds, out in zip(data_sets, parsed):
        mass = lambda rho, b, h, length: rho / 1728.0 * b * h * length / G
        wm = mass(ds.rho, ds.b, ds.h, ds.xl)
        wm2 = mass(ds.rho2, ds.b2, ds.h2, ds.xl2) * ds.xl2c / ds.xl2
        wm3 = mass(ds.rho3, ds.b3, ds.h3, ds.xl3)
        assert_printed(out.masses[:3], [wm, wm2, wm3], precision)
        assert_printed(out.ratios, [ds.h2 / ds.xl2, wm / (wm2 + wm3),
                                    wm2 / wm, wm2 / wm3], precision)


def test_impulse_and_velocities_follow_the_listing_formulas(
        deck_and_listing, precision):
    """EY, TY2DT and the post-impact tip state, recomputed from the printed
    modal table with the listing's formulas (its quirks included).

    The printed numbers carry 9 decimals, so each recomputation is allowed
    the half unit HALF of every printed input, propagated, and HALF for the
    printed result; single precision adds a few dozen float32 ulp."""
    HALF = 5.1e-10
    arithmetic = 3e-6 if precision == "single" else 1e-12
    data_sets, _, parsed = deck_and_listing
    for ds, out in zip(data_sets, parsed):
        v, c, alpha, p, ape = out.modal_table.T
        mass = lambda rho, b, h, length: rho / 1728.0 * b * h * length / G
        wm, wm3 = mass(ds.rho, ds.b, ds.h, ds.xl), \
            mass(ds.rho3, ds.b3, ds.h3, ds.xl3)
        wm2 = mass(ds.rho2, ds.b2, ds.h2, ds.xl2)        # EY: nominal mass
        wm2_corrected = wm2 * ds.xl2c / ds.xl2
        ct, ct2, ct3 = np.sum(c**2), np.sum(ds.c2**2), np.sum(ds.c3**2)
        assert_printed(out.impact[2:], [ct, ct2, ct3], precision)
        act = np.sum(-p * ape * c)                     # quirk 1: no SIN(P*T)
        d_act = np.sum(np.abs(p * c) + np.abs(ape * c)) * HALF
        denominator = ct / wm + ct2 / wm2 + ct3 / wm3
        ey = (1.0 + ds.er) * act / denominator
        assert out.impact[1] == pytest.approx(ey, rel=arithmetic, abs=(
            (1.0 + ds.er) * d_act / denominator + HALF))
        t1 = out.impact[0]
        np.testing.assert_allclose(
            out.coefficients,
            np.column_stack([ape * np.cos(p * t1), -ape * np.sin(p * t1)]),
            rtol=arithmetic, atol=2 * HALF + np.max(np.abs(ape)) * np.max(p)
            * (HALF + (1e-7 * t1 if precision == "single" else 0.0)))
        assert out.ty2dt == pytest.approx(
            out.impact[1] / wm2_corrected * ct2, rel=arithmetic,
            abs=HALF * ct2 / wm2_corrected + HALF)
        # the lower contact starts from rest at its equilibrium
        assert out.history[0, 0] == 0.0 and out.history[0, 1] == 0.0
        # post-impact tip state printed at T = 0: TY = sum A1 C, ACT =
        # sum P B1 C, TYDTL = ACT - EY/WM sum C^2
        a1, b1 = out.coefficients.T
        assert out.tip[0] == 0.0
        assert out.tip[1] == pytest.approx(
            np.sum(a1 * c), rel=arithmetic, abs=ct * HALF + HALF)
        d_tip_act = np.sum(np.abs(p * c)) * HALF + np.sum(np.abs(b1 * c)) * HALF
        assert out.tip[3] == pytest.approx(
            np.sum(p * b1 * c), rel=arithmetic, abs=d_tip_act + HALF)
        assert out.tip[2] == pytest.approx(
            out.tip[3] - out.impact[1] / wm * ct, rel=arithmetic,
            abs=2 * HALF + HALF * ct / wm)


def test_history_grid_runs_to_tau(deck_and_listing, precision):
    """T = 0, DELT, 2 DELT, ... accumulated in the working precision while
    T < 0.060 (the loop at 450-520, simulated here)."""
    data_sets, _, parsed = deck_and_listing
    dtype = np.float32 if precision == "single" else np.float64
    for ds, out in zip(data_sets, parsed):
        t, step, grid = dtype(0.0), dtype(ds.delt), []
        while t < dtype(0.060):
            grid.append(float(t))
            t = dtype(t + step)
        np.testing.assert_allclose(out.history[:, 0], grid, atol=6e-10)


def test_lower_contact_history_is_eq13(deck_and_listing, precision):
    """y3(L3,t) = sum (v0/L3) X_j(L3)^2 / p_j sin p_j t with v0 = TY2DT."""
    data_sets, _, parsed = deck_and_listing
    for ds, out in zip(data_sets, parsed):
        t = out.history[:, 0]
        p3 = out.lower_modes[:, 3]
        y3 = (out.ty2dt / ds.xl3) * np.sum(
            (ds.c3**2 / p3)[:, None] * np.sin(np.outer(p3, t)), axis=0)
        scale = np.max(np.abs(y3))
        np.testing.assert_allclose(out.history[:, 1], y3,
                                   atol=(2e-6 if precision == "single"
                                         else 1e-9) * scale + 6e-10)


def test_several_data_sets_back_to_back(precision):
    """thesis_all.dat is the five single decks in a row: its listing is
    theirs, concatenated."""
    combined = [p for p in THESIS_DECKS if p.stem == "thesis_all"]
    singles = [p for p in THESIS_DECKS if p.stem.startswith("thesis_d")]
    assert combined and len(singles) == 5
    whole = legacy.run(combined[0], precision)
    assert whole == "".join(legacy.run(p, precision) for p in singles)


def test_more_than_four_modes_is_refused(tmp_path, precision):
    from conftest import with_modes, write_deck
    from contactsep.restored import thesis_decks

    deck = write_deck(tmp_path, "n5", [with_modes(thesis_decks.thesis_data_set(0.5), 5)])
    with pytest.raises(DeckError, match="at most 4 modes") as info:
        legacy.run(deck, precision)
    assert info.value.card == 5 and info.value.columns == (16, 17)


def contactsep_cli(*args):
    return subprocess.run([sys.executable, "-m", "contactsep", *args],
                          capture_output=True, text=True, timeout=300)


def test_cli_prints_the_listing_unchanged(precision):
    deck = THESIS_DECKS[0]
    done = contactsep_cli("legacy", str(deck), "--precision", precision)
    assert done.returncode == 0, done.stderr
    assert done.stdout == legacy.run(deck, precision)
    assert done.stderr == ""


def test_cli_refuses_n_above_four_before_running(tmp_path):
    from conftest import with_modes, write_deck
    from contactsep.restored import thesis_decks

    good = thesis_decks.thesis_data_set(0.5)
    deck = write_deck(tmp_path, "n6", [good, with_modes(good, 6)])
    done = contactsep_cli("legacy", str(deck))
    assert done.returncode == 2
    assert done.stderr.startswith("contactsep: error: data set 2, card ")
    assert "Traceback" not in done.stderr
    # the good first data set is still printed
    assert len(listing.parse(done.stdout)) == 1
