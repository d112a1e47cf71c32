"""The general model (eq. 23): the listing as a special case, the thesis's
claims, analytic identities, and the search for t1 and the extremes held
against brute force."""

from __future__ import annotations

import numpy as np
import pytest

import contactsep
from conftest import THESIS_DECKS
from contactsep import beams
from contactsep.model import DesignError, evaluate, thesis_design
from contactsep.restored import reference

BACKEND = "numpy"


def test_listing_special_case_matches_the_restored_core():
    """With the tip contacts, ACT without sin, the listing's hybrid L_c
    mass and its grid, eq. 23 reproduces the restored core's EY, TY2DT and
    TY3 history.  The only difference is the release amplitudes: the
    listing integrates the deck's mode function, whose ALPHA has 9
    decimals, while the model uses the exact A_j.  The predicted ratio
    comes from the reference's independent closed form with the deck's
    alpha; what is left is the deck's 9-decimal V and C (~1e-9)."""
    for deck in THESIS_DECKS:
        for r in contactsep.replay(deck, precision="double"):
            ds = r.inputs
            design = thesis_design(
                d=ds.h2, Lc=ds.xl2c, impact_velocity="listing",
                ys=ds.ystat, e=ds.er, gamma1=ds.rho / 1728,
                gamma2=ds.rho2 / 1728, gamma3=ds.rho3 / 1728,
                n_modes=ds.n, lower_response="as-printed")
            ev = evaluate(design, backend=BACKEND)
            p = reference.frequencies(ds)[0]
            deck_a = reference.initial_amplitudes(ds, "closed-form")
            exact_a = reference.initial_amplitudes(ds, "exact-mode")
            ratio = np.sum(p * ds.c * deck_a) / np.sum(p * ds.c * exact_a)
            assert abs(abs(r.ey) / ev.psi / ratio - 1) < 5e-9
            assert abs(abs(r.ty2dt) / ev.v0 / ratio - 1) < 5e-9
            history = ev.y3(np.asarray(r.history_t))
            scale = np.max(np.abs(history))
            # the listing's y3 is negative (towards -y): signs mapped
            assert np.max(np.abs(-np.asarray(r.history_ty3) / ratio
                                 - history)) < 5e-9 * scale
            # the deck's alpha is what makes the 3.5e-5: it is no tiny
            # effect the test could miss
            assert abs(ratio - 1) > 1e-6


def test_y3_max_is_proportional_to_ys_and_to_one_plus_e():
    base = evaluate(thesis_design(), backend=BACKEND)
    twice = evaluate(thesis_design(ys=1.0), backend=BACKEND)
    assert np.isclose(twice.y3_max / base.y3_max, 2.0, rtol=1e-12)
    e0 = evaluate(thesis_design(e=0.0), backend=BACKEND)
    e1 = evaluate(thesis_design(e=1.0), backend=BACKEND)
    assert np.isclose(e1.y3_max / e0.y3_max, 2.0, rtol=1e-12)
    assert np.isclose(base.y3_max / e0.y3_max, 1.375, rtol=1e-12)


def test_y3_max_falls_with_separator_thickness():
    # the thesis's claim, eq. 23 as printed (with psi/M3, y3_max rises
    # with d: docs/model.md)
    ev = evaluate(thesis_design(d=np.linspace(0.1, 1.0, 19),
                                lower_response="as-printed"),
                  backend=BACKEND)
    assert np.all(np.diff(ev.y3_max) < 0)


def test_y3_max_falls_as_the_contact_point_moves_in():
    r = np.linspace(1.0, 0.7, 31)
    ev = evaluate(thesis_design(x3=19.0 * r), backend=BACKEND)
    assert np.all(np.diff(ev.y3_max) < 0)


def test_symmetric_case_one_plus_two_r_law():
    """x1/L1 = x3/L3 and equal contacts: psi = (1+e)V M2*M3*/(M2*+2M3*)
    and v0 = (1+e)V/(1+2R), so with eq. 23 as printed y3_max (1+2R) is
    the same for every separator density."""
    gamma2 = np.geomspace(0.005, 5.0, 12)
    design = thesis_design(x1=0.98 * 19, x3=0.98 * 19, gamma2=gamma2,
                           release="contact", lower_response="as-printed")
    ev = evaluate(design, backend=BACKEND)
    product = ev.y3_max * (1 + 2 * ev.R)
    assert np.all(np.diff(ev.y3_max) < 0)
    assert np.ptp(product) / product[0] < 1e-12
    # and the impulse form of the lower response does not keep it
    ev = evaluate(design.replace(lower_response="impulse"), backend=BACKEND)
    product = ev.y3_max * (1 + 2 * ev.R)
    assert np.ptp(product) / product[0] > 0.1


def test_tip_loaded_cantilever_amplitudes_and_static_shape():
    """A_j = 3 y_s X_j(L)/(k_jL)^4 synthesises the strength-of-materials
    curve f(x) = y_s (3 xi^2 - xi^3)/2 at 10 points."""
    n = 2000
    kl = beams.eigenvalues("clamped-free", n)
    tip = beams.mode_shapes("clamped-free", n, [1.0])[:, 0]
    amp = 3 * 0.5 * tip / kl**4
    xi = np.linspace(0.1, 1.0, 10)
    shape = (amp[:, None] * beams.mode_shapes("clamped-free", n, xi))[::-1]
    assert np.allclose(shape.sum(axis=0), 0.5 * (3 * xi**2 - xi**3) / 2,
                       rtol=0, atol=1e-10)


def test_first_impact_is_the_first_crossing():
    """y1(x1, t1) = gap to rounding and no sample before t1 below it
    (a grid of 200 points per shortest period)."""
    for design in (thesis_design(n_modes=12),
                   thesis_design(x1=0.8 * 19, n_modes=20, gap=-0.1),
                   thesis_design(end1="clamped-pinned", x1=0.6 * 19)):
        ev = evaluate(design, backend=BACKEND)
        kl = beams.eigenvalues(design.end1, design.n_modes)
        xi1 = (design.x1 or design.L1) / design.L1
        p = ev.p1
        x = beams.mode_shapes(design.end1, design.n_modes, [xi1])[:, 0]
        load = 1.0 if (design.release == "tip"
                       and design.end1 == "clamped-free") else xi1
        xl = beams.mode_shapes(design.end1, design.n_modes, [load])[:, 0]
        amp = design.ys * xl / (kl**4
                                * beams.static_flexibility(design.end1, load))
        t = np.linspace(0, float(ev.t1), int(200 * float(ev.t1)
                                              * p.max() / 2 / np.pi))
        y = (amp * x) @ np.cos(np.outer(p, t))
        assert np.all(y[:-1] > design.gap)
        y1 = np.sum(amp * x * np.cos(p * ev.t1))
        assert abs(y1 - design.gap) < 1e-12 * design.ys


@pytest.mark.parametrize("backend", ["compiled", "numpy"])
@pytest.mark.parametrize("n", [4, 30])
def test_extremes_against_brute_force(n, backend):
    ev = evaluate(thesis_design(n_modes=n, x3=0.9 * 19,
                                lower_response="as-printed"),
                  backend=backend)
    t = np.linspace(0, 0.06, 2_000_001)
    y = ev.y3(t)
    curvature = np.sum(np.abs(ev.c3) * ev.p3**2)
    bound = curvature * (t[1] - t[0])**2 / 8
    assert 0 <= ev.y3_max - y.max() <= bound + 1e-15
    assert 0 <= y.min() - ev.y3_min <= bound + 1e-15
    assert abs(ev.t_max - t[np.argmax(y)]) < 2 * (t[1] - t[0])


def test_maximum_cut_by_the_window_is_flagged():
    ev = evaluate(thesis_design(tau=0.005), backend=BACKEND)
    assert ev.at_window_end and ev.t_max == 0.005
    assert not evaluate(thesis_design(), backend=BACKEND).at_window_end


def test_bad_design_in_a_batch_keeps_the_others():
    ys = np.array([0.5, -1.0, 0.5, np.nan, 0.25])
    e = np.array([0.375, 0.375, 2.0, 0.375, 0.375])
    ev = evaluate(thesis_design(ys=ys, e=e), backend=BACKEND)
    assert ev.status.tolist() == [0, 1, 2, 2, 0]
    assert np.isnan(ev.psi[1:4]).all()
    one = evaluate(thesis_design(), backend=BACKEND)
    assert ev.psi[0] == one.psi
    assert np.isclose(ev.y3_max[4], one.y3_max / 2, rtol=1e-12)


@pytest.mark.parametrize("changes, message", [
    (dict(h2=-0.25), "h2: found -0.25, expected a finite number > 0"),
    (dict(e=1.5), "e: found 1.5, expected 0 <= e <= 1"),
    (dict(x3=20.0), "x3: found 20.0, expected 0 < x3 <= L3"),
    (dict(end2="free-free"), "end2: found 'free-free'"),
    (dict(n_modes=0), "n_modes: found 0"),
    (dict(impact_velocity="fast"), "impact_velocity: found 'fast'"),
    (dict(L1="long"), "L1: found 'long', expected a number"),
])
def test_design_errors_name_the_field(changes, message):
    with pytest.raises(DesignError, match=message.replace("(", r"\(")):
        thesis_design(**changes)


def test_design_batches_broadcast():
    d = thesis_design(d=np.array([0.125, 0.25]), ys=np.array([[0.25], [0.5]]))
    assert d.shape == (2, 2)
    ev = evaluate(d, backend=BACKEND)
    assert ev.y3_max.shape == (2, 2) and ev.p3.shape == (2, 2, 4)
    assert ev.y3([0.0, 0.01]).shape == (2, 2, 2)


def test_deck_data_sets_convert_both_ways():
    from contactsep.model import data_set_from_design, design_from_data_set
    from contactsep.restored import thesis_decks

    ds = thesis_decks.thesis_data_set(0.35)
    design = design_from_data_set(ds)
    assert design.gamma2 == ds.rho2 / 1728 and design.Lc == ds.xl2c
    back = data_set_from_design(design)
    assert back == ds
    # the converted design runs the listing's numbers (see the special
    # case above) and refuses what a deck cannot say
    with pytest.raises(DesignError, match="x3: a deck's contacts"):
        data_set_from_design(design.replace(x3=15.0))
    with pytest.raises(DesignError, match="E1, E2, E3"):
        data_set_from_design(design.replace(E2=3e7))


def test_convergence_in_n():
    """The point impact's effective mass is zero (sum X_j(L)^2 = 4N), so
    psi falls like 1/N; v0 and y3_max converge, their changes halving as
    N doubles (O(1/N), docs/model.md)."""
    n = np.array([50, 100, 200, 400])
    ev = evaluate(thesis_design(n_modes=n, lower_response="as-printed"),
                  backend="compiled")
    deviation = np.abs(ev.psi[1:] / ev.psi[:-1] - 0.5)
    assert np.all(deviation < 2e-3) and np.all(np.diff(deviation) < 0)
    for values in (ev.v0, ev.y3_max):
        steps = np.abs(np.diff(values))
        assert np.all(steps[1:] / steps[:-1] < 0.6)
        assert steps[-1] / values[-1] < 2e-3


def test_model_command_prints_labelled_results(capsys):
    from contactsep.cli import main

    assert main(["model", "--x3", str(0.78 * 19), "--n-modes", "20",
                 "--json"]) == 0
    import json
    data = json.loads(capsys.readouterr().out)
    ev = evaluate(thesis_design(x3=0.78 * 19, n_modes=20))
    assert data["y3_max_in"] == float(ev.y3_max)
    assert main(["model", "--e", "3"]) == 2
    assert "e: found 3.0, expected 0 <= e <= 1" in capsys.readouterr().err
