"""The compiled kernel (fortran/model/) against the NumPy twin, which was
written from the equations on its own; and its modes against mpmath."""

from __future__ import annotations

import numpy as np
import pytest

from contactsep import beams
from contactsep.model import Design, compiled, evaluate

SCALARS = ("t1", "v_impact", "psi", "v0", "R", "y3_max", "t_max", "y3_min",
           "t_min", "M1", "M2", "M3")


def random_designs(m, seed, n_max=30):
    rng = np.random.default_rng(seed)
    ends = np.array(beams.END_CONDITIONS)

    def u(lo, hi):
        return rng.uniform(lo, hi, m)

    lengths = {i: u(*span) for i, span in (("1", (5, 25)), ("2", (1, 5)),
                                             ("3", (5, 25)))}
    fields = {}
    for i, (b, h) in (("1", ((0.5, 3), (0.05, 0.3))),
                      ("2", ((0.2, 1), (0.1, 0.8))),
                      ("3", ((0.5, 3), (0.05, 0.3)))):
        fields.update({
            "L" + i: lengths[i], "b" + i: u(*b), "h" + i: u(*h),
            "gamma" + i: u(0.05, 0.35), "E" + i: u(5e6, 3e7),
            "end" + i: ends[rng.integers(0, 4, m)],
            "x" + i: lengths[i] * u(0.5, 1.0)})
    return Design(**fields, ys=u(0.05, 1.0), e=u(0.0, 1.0),
                  n_modes=rng.integers(1, n_max + 1, m), tau=u(0.01, 0.1),
                  release="contact")


def compare(design):
    a = evaluate(design, backend="numpy")
    b = evaluate(design, backend="compiled")
    assert np.array_equal(a.status, b.status)
    ok = a.status == 0
    # Error model: both evaluate the same sums in a different order and
    # with different libm/SIMD sin and cos (a few ulp each); t1 and the
    # extremum times are roots polished to ~1 ulp, so the velocities
    # inherit p_max * dt ~ p_max t eps: 1e-10 covers p t <= 1e5 rad.
    for key in SCALARS:
        x, y = getattr(a, key)[ok], getattr(b, key)[ok]
        floor = 0.0
        if key in ("y3_max", "y3_min"):
            # the extremes can be exactly 0 (at t = 0): an absolute floor
            # of 1e-10 of the response's size
            floor = 1e-10 * np.abs(np.stack([a.y3_max, a.y3_min]))[:, ok] \
                .max(axis=0)
        assert np.all(np.abs(x - y) <= 1e-10 * np.abs(x) + floor), key
    assert np.array_equal(a.at_window_end, b.at_window_end)
    for key in ("p1", "p2", "p3", "c3"):
        x, y = getattr(a, key), getattr(b, key)
        assert np.array_equal(np.isnan(x), np.isnan(y)), key
        live = ~np.isnan(x)
        # frequencies are direct; c3 carries the impact velocity's error
        rtol = 1e-10 if key == "c3" else 1e-12
        assert np.all(np.abs(x[live] - y[live]) <= rtol * np.abs(x[live]))
    return a, b


def test_compiled_equals_twin_on_1000_random_designs():
    compare(random_designs(1000, seed=11, n_max=12))


def test_compiled_equals_twin_on_1000_random_designs_to_n30():
    compare(random_designs(1000, seed=12, n_max=30))


def test_compiled_equals_twin_with_every_option():
    base = random_designs(40, seed=13, n_max=8)
    for changes in (dict(impact_velocity="listing"),
                    dict(lower_response="impulse"),
                    dict(release="tip", end1="clamped-free"),
                    dict(Lc=np.linspace(0.5, 6, 40), lc_reading="listing"),
                    dict(Lc=np.linspace(0.5, 6, 40),
                         lc_reading="frequencies"),
                    dict(Lc=np.linspace(0.5, 6, 40), lc_reading="mass"),
                    dict(gap=-0.05)):
        compare(base.replace(**changes))


def test_invalid_designs_mid_batch_are_statuses():
    design = random_designs(30, seed=14, n_max=6)
    ys = design.ys.copy()
    ys[[3, 17]] = [np.nan, np.inf]
    e = design.e.copy()
    e[9] = -0.5
    h2 = design.h2.copy()
    h2[21] = 0.0
    a, b = compare(design.replace(ys=ys, e=e, h2=h2))
    assert b.status[[3, 9, 17, 21]].tolist() == [2, 2, 2, 2]
    good = np.delete(np.arange(30), [3, 9, 17, 21])
    assert np.all(b.status[good] == 0)


@pytest.mark.parametrize("end", beams.END_CONDITIONS)
def test_fortran_modes_equal_python_modes(end):
    xi = np.linspace(0.0, 1.0, 11)
    kl, values = compiled.mode_values(beams.end_code(end), 50, xi)
    assert np.allclose(kl, beams.eigenvalues(end, 50), rtol=4e-16, atol=0)
    assert np.max(np.abs(values - beams.mode_shapes(end, 50, xi))) < 1e-13
