"""The upper and lower contacts touching the separator at different
points (issue 28, item 4: the thesis's recommendation 3): ``x2`` for the
upper contact, ``x2_lower`` for the lower one.

* Against the independent simulator (tests/chatter/independent_hertz.py,
  nothing imported from contactsep; its separator's ``x_lower``): the gap
  histories, first impulse, largest lower gap, energy and open
  intervals, with a preload (plain truncation) and with the static
  correction (whose off-diagonal is the separator's residual cross
  flexibility between the two points), to the package's own Richardson
  error at dt and dt/2 (as tests/chatter/test_independent.py).
* x2_lower = x2 given is the one-point system bit for bit (the default,
  None, is today's code path: checked against the pre-change branch when
  it was written).
* The mirror identity: on a symmetric (clamped-clamped, uniform)
  separator, (x2, x2_lower) = (a, b) and (L2 - a, L2 - b) are the same
  system (each mode is symmetric or antisymmetric about mid-span; the
  antisymmetric coordinates change sign), so every answer agrees to
  round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import independent_hertz as ih
from contactsep import chatter
from contactsep.model import Design, DesignError, evaluate, thesis_design
from contactsep.model.contact_points import separator_points
from package_call import run
from test_independent import (
    ENERGY_FLOOR,
    _disagreements,
    random_design,
    reference_preload,
    reference_window,
    setup_of,
)

pytest.importorskip("scipy")

#: Elastic runs: 3x the second-order Richardson estimate
#: (4/3) |X(dt) - X(dt/2)| (test_independent.estimated_error), as a
#: factor of the |X(dt) - X(dt/2)| the comparisons below take.
MARGIN = 3.0 * 4.0 / 3.0


def _with_lower_point(seed):
    """A random design of test_independent with the lower contact at
    another point of the separator (a quarter to three quarters of L2,
    at least a tenth of L2 from x2)."""
    design, damping, fraction = random_design(seed)
    rng = np.random.default_rng(1000 + seed)
    length = float(design.L2)
    x2 = separator_points(design)[0]
    while True:
        lower = length * rng.uniform(0.25, 0.75)
        if abs(lower - x2) >= 0.1 * length:
            return design.replace(x2_lower=lower), damping, fraction


def _setup(design, damping, preload, static):
    setup = setup_of(design, damping, preload, static)
    separator = dict(setup.separator, x_lower=float(design.x2_lower))
    return ih.Setup(**{**setup.__dict__, "separator": separator})


def compare(seed, static):
    design, damping, fraction = _with_lower_point(seed)
    if static:
        fraction, damping = 0.0, "none"
    preload = reference_preload(_setup(design, damping, 0.0, static),
                                fraction) if fraction else 0.0
    setup = _setup(design, damping, preload, static)
    ref, t_end, dt, samples = reference_window(setup)
    coarse, fine = (run(design, dt=h, t_end=t_end, samples=samples,
                        damping=damping, preload=preload,
                        static_correction=static) for h in (dt, dt / 2))
    # the reference's physical gaps (with the static correction: the
    # modal gaps plus C lambda, independent_hertz.Trajectory.gaps)
    g_ref = ref.gaps(coarse.t)
    scale = float(setup.ys)
    margin = MARGIN if damping == "none" else 6.0
    tols = []
    for c, name in ((0, "gap_upper"), (1, "gap_lower")):
        err = np.abs(getattr(coarse, name) - g_ref[c])
        tol = margin * np.max(np.abs(getattr(coarse, name)
                                     - getattr(fine, name))) + 1e-9 * scale
        assert err.max() <= tol, (seed, name, err.max(), tol)
        tols.append(tol)
    assert abs(coarse.first_impulse_lb_s - ref.first_impulse_lb_s) <= \
        margin * abs(coarse.first_impulse_lb_s - fine.first_impulse_lb_s) \
        + 1e-8 * ref.first_impulse_lb_s
    assert abs(coarse.max_lower_gap_in - ref.max_lower_gap()) <= \
        margin * abs(coarse.max_lower_gap_in - fine.max_lower_gap_in) \
        + max(tols) + 2e-6 * abs(ref.max_lower_gap())
    assert abs(coarse.energy_ratio - ref.energy_end / ref.energy0) <= \
        margin * abs(coarse.energy_ratio - fine.energy_ratio) + ENERGY_FLOOR
    if not static:
        threshold = 1e-6
        for contact, a, r in ((0, coarse.upper_open_intervals,
                               ref.open_intervals(0)),
                              (1, coarse.lower_open_intervals,
                               ref.open_intervals(1))):
            for t in _disagreements(a, r):
                near = np.abs(ref.gaps(t)[contact] - threshold) <= \
                    tols[contact]
                assert near.all(), (seed, contact, t, a, r)
    return design, fraction


#: Seeds of test_independent's random designs: a clamped-pinned
#: separator without preload; clamped-clamped with a preload and Flores
#: damping; a cantilever separator, preloaded, elastic.
SEEDS = (0, 3, 7)
#: With the static correction (no preload, elastic): clamped-pinned,
#: clamped-clamped, pinned-pinned separators.
STATIC_SEEDS = (0, 1, 6)


@pytest.mark.parametrize("seed", SEEDS)
def test_a_lower_point_off_x2_agrees_with_the_independent_simulator(seed):
    design, _ = compare(seed, static=False)
    assert float(design.x2_lower) != separator_points(design)[0]


@pytest.mark.parametrize("seed", [
    seed
    for seed in STATIC_SEEDS])        # 5-10 s each
def test_the_cross_flexibility_agrees_with_the_independent_simulator(seed):
    compare(seed, static=True)


def test_the_seeds_cover_a_preload_and_both_dampings():
    seen = [_with_lower_point(seed) for seed in SEEDS]
    assert any(f > 0 for _, _, f in seen)
    assert {damping for _, damping, _ in seen} == {"none", "flores"}
    ends = {d.end2 for d, _, _ in seen} | {
        _with_lower_point(seed)[0].end2 for seed in STATIC_SEEDS}
    assert len(ends) >= 3


# ------------------------------------------------------------ bit for bit

def _answers(result):
    return (result.t, result.gap_upper, result.gap_lower, result.energy,
            result.circuit_open_intervals, result.first_impulse_lb_s,
            result.max_lower_gap_in, result.dt)


@pytest.mark.parametrize("settings", [
    dict(model="hertz", preload=0.05),
    dict(model="hertz", preload=0.05, static_correction=False),
    dict(model="newton", preload=0.02)])
def test_x2_lower_equal_to_x2_is_the_one_point_system_bit_for_bit(settings):
    for design in (thesis_design(n_modes=6),
                   thesis_design(n_modes=6, x2=0.8, d=0.35)):
        given = design.replace(x2_lower=separator_points(design)[0])
        a = chatter.simulate(design, t_end=0.01, samples=100, **settings)
        b = chatter.simulate(given, t_end=0.01, samples=100, **settings)
        for x, y in zip(_answers(a), _answers(b)):
            assert np.array_equal(x, y, equal_nan=True)


# ------------------------------------------------------------------ mirror

def _mirror_pair(a, b, **fields):
    base = thesis_design(n_modes=8, **fields)
    length = float(base.L2)
    return (base.replace(x2=a, x2_lower=b),
            base.replace(x2=length - a, x2_lower=length - b))


@pytest.mark.parametrize("settings", [
    dict(model="hertz", preload=0.05),
    dict(model="hertz", preload=0.0, static_correction=False),
    dict(model="newton", preload=0.02)])
@pytest.mark.parametrize("a,b", [(0.8, 1.6), (1.0, None), (0.6, 0.6)])
def test_the_mirror_identity_of_a_symmetric_separator(settings, a, b):
    """x2 = a, x2_lower = b against L2 - a, L2 - b (b None: x2_lower at
    x2, the issue's item 8 mirror x2 = a and L2 - a): the same gaps,
    impulse and openings to round-off, over the first contact episodes
    (a short window, 7.6 ms past the first impact: a long chattering
    run amplifies round-off)."""
    left, right = _mirror_pair(a, a if b is None else b)
    if b is None:
        left, right = (d.replace(x2_lower=None) for d in (left, right))
    runs = [chatter.simulate(d, t_end=0.03, dt=1e-7, samples=300,
                             **settings) for d in (left, right)]
    one, two = runs
    assert one.n_events == two.n_events
    assert one.first_impact_s < 0.025 and one.n_events >= 1
    scale = float(left.ys)
    for name in ("gap_upper", "gap_lower"):
        assert np.max(np.abs(getattr(one, name) - getattr(two, name))) \
            <= 1e-12 * scale
    assert one.first_impulse_lb_s == pytest.approx(two.first_impulse_lb_s,
                                                   rel=1e-12)
    assert one.circuit_open_s == pytest.approx(two.circuit_open_s,
                                               rel=1e-9, abs=1e-15)
    assert one.max_lower_gap_in == pytest.approx(two.max_lower_gap_in,
                                                 rel=1e-9, abs=1e-15)


def test_the_mirror_identity_of_a_timoshenko_separator_on_springs():
    """The general beam path (transfer-matrix modes, the cross
    flexibility with shear and elastic clamps): the Table II fit's
    separator (Timoshenko, kr2 = 2.19e4 lb in/rad at both ends) is
    symmetric too."""
    left, right = _mirror_pair(0.8, 1.6, beam2="timoshenko", kr2=2.19e4)
    one, two = (chatter.simulate(d, t_end=0.03, dt=1e-7, samples=300,
                                 preload=0.05) for d in (left, right))
    assert one.n_events == two.n_events >= 1
    for name in ("gap_upper", "gap_lower"):
        assert np.max(np.abs(getattr(one, name) - getattr(two, name))) \
            <= 1e-12 * float(left.ys)
    assert one.circuit_open_s == pytest.approx(two.circuit_open_s,
                                               rel=1e-9)


def test_the_mirror_is_not_the_identity_off_the_mirror():
    """The identity is not empty: moving only the lower point changes
    the answers."""
    design = thesis_design(n_modes=8, x2=0.8)
    runs = [chatter.simulate(design.replace(x2_lower=x), t_end=0.03,
                             dt=1e-7, samples=300, preload=0.05)
            for x in (0.8, 1.6)]
    assert np.max(np.abs(runs[0].gap_lower - runs[1].gap_lower)) > \
        1e-4 * float(design.ys)


@pytest.mark.parametrize("static", [True, False])
def test_a_preload_at_x2_lower_is_a_static_state(static):
    """The preload pushes the separator up at x2_lower: nothing moves
    before the upper contact arrives (the lower gap keeps its start
    value, the Hertz penetration), and the upper gap starts where it
    starts without a preload (the release height kept above the
    preloaded separator at x2: the cross flexibility)."""
    design = thesis_design(n_modes=8, x2=0.7, x2_lower=1.9)
    r = chatter.simulate(design, t_end=0.03, dt=1e-7, samples=300,
                         preload=2.0, static_correction=static)
    before = r.t < 0.9 * r.first_impact_s
    assert before.sum() > 100
    lower = r.gap_lower[before]
    assert np.max(np.abs(lower - lower[0])) <= 1e-12 * float(design.ys)
    assert lower[0] < 0.0          # pressed: the Hertz penetration
    # the release height of the unpreloaded run (the N-mode release
    # shape's own, 4e-5 below y_s at N = 8)
    free = chatter.simulate(design, t_end=0.03, dt=1e-7, samples=300,
                            static_correction=static)
    assert r.gap_upper[0] == pytest.approx(free.gap_upper[0], rel=1e-12)


# ---------------------------------------------------------------- refusals

def test_eq23_refuses_a_lower_point_off_x2_in_one_line():
    with pytest.raises(DesignError, match="x2_lower.*eq. 23") as info:
        evaluate(thesis_design(x2_lower=1.0))
    assert "\n" not in str(info.value)
    # equal to x2 (mid-span by default) it is the thesis's model
    assert float(evaluate(thesis_design(x2_lower=1.25)).y3_max) == \
        float(evaluate(thesis_design()).y3_max)


@pytest.mark.parametrize("value,match", [
    (0.0, "x2_lower: found 0.0, expected 0.0025 < x2_lower < 2.4975 in"),
    (2.5, "inside the span"), ("1", "expected one number"),
    (True, "expected one number"), (math.nan, "expected")])
def test_a_lower_point_outside_the_separator_is_refused(value, match):
    with pytest.raises(DesignError, match=match):
        Design(x2_lower=value)
