"""The package's Hertz simulation against an independent simulator
(independent_hertz.py: its own modes, release shape, integrator and
crossing search; issue 26) on random designs varying every field that
matters: the three contact points, the end conditions, preload,
damping (Flores), materials, thicknesses, lengths and N.

Window: from the release to the first impact plus 15 % of the upper
contact's fundamental period (the impact, the separator's kick, the
lower contact's first separations and re-contacts): long enough that
every quantity compared has happened, short enough that the contact
dynamics' sensitivity does not amplify round-off into O(1) differences.

The step.  dt is set from the reference's contact dynamics: at most
1/300 of the first contact's duration T_c and 0.05 over the fastest
linearised Hertz frequency or damping rate of any contact phase (a
preloaded light contact rattles far faster than the first impact lasts),
a whole number of steps per sample interval.

The tolerance, derived from the step.  The package integrates by Strang
splitting (second order for the elastic law: its error at dt is
C dt^2 + o(dt^2); with Flores damping, whose force depends on the
velocity the kick changes and is clamped at zero with a kink, A dt +
B dt^2 + o(dt^2)); the reference is an 8th-order adaptive solve at
rtol 1e-11, whose own error is negligible beside it.  The package's
error at dt is estimated from its runs at dt and dt/2 (elastic:
(4/3) |X(dt) - X(dt/2)|, Richardson) or dt, dt/2 and dt/4 (Flores: both
orders, estimated_error); each tolerance is 3x that estimate (a margin
for the higher-order terms), plus a floor for the reference's own error
and round-off.  A bug that moves
the package's limit moves every run alike: their differences stay
O(dt) while the distance to the reference is O(1).  Exceptions, with
their own bounds:
* the first impact: the package reports the start of the first step
  whose starting gap is closed, so it lies in [t*, t* + dt] (t* the
  exact instant) up to the gap error over the impact speed;
* the energy ratio: a bound, ENERGY_FLOOR, beside Richardson (below);
* the open intervals of each contact and of the circuit: wherever the
  package and the reference disagree on whether a contact is open, the
  reference's gap must lie within that contact's gap tolerance of the
  threshold (the only place a gap that close to the reference's can be
  on the other side of it): this bounds every open and close instant by
  the gap tolerance over the gap's rate, and lets a graze of the
  threshold appear in one and not the other only where it is a graze.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import independent_hertz as ih
from contactsep.model import Design
from package_call import run

pytest.importorskip("scipy")

MATERIALS = {"aluminium": (10.0e6, 0.100), "steel": (30.0e6, 0.283),
             "bronze": (16.0e6, 0.320), "becu": (18.5e6, 0.298)}
ENDS = ("clamped-free", "clamped-clamped", "clamped-pinned",
        "pinned-pinned")
#: The reference's residual flexibility in series with each contact
#: (independent_hertz.residual_matrix; issue 25's static correction),
#: off in the random-design comparisons (they have preloads, whose
#: state with the correction the reference does not define); the
#: static tests below switch it on in both, without a preload.
STATIC_CORRECTION = False
#: The energy at a sample is not smooth in dt: the splitting's energy
#: error is bounded and oscillates (a symplectic scheme's modified
#: energy), measured -8e-7, -1.6e-8, -1.4e-9, +1.2e-9 at dt, dt/2,
#: dt/4, dt/8 on one design (seed 9): no Richardson estimate, a bound.
ENERGY_FLOOR = 2e-6


def random_design(seed: int, n_max: int = 4):
    """A random design and preload/damping settings, the thesis rig's
    scale or a relay's."""
    rng = np.random.default_rng(seed)
    scale = rng.choice([1.0, 0.06])          # thesis rig, or a relay
    names = list(MATERIALS)
    (e1, g1), (e2, g2), (e3, g3) = (MATERIALS[names[i]] for i in
                                     rng.integers(0, 4, 3))
    length = scale * rng.uniform(12.0, 20.0)
    l2 = scale * rng.uniform(1.5, 4.0)
    thick = scale * rng.uniform(0.08, 0.16)
    end1 = "clamped-free" if rng.random() < 0.7 else str(rng.choice(ENDS))
    end3 = "clamped-free" if rng.random() < 0.7 else str(rng.choice(ENDS))
    end2 = str(rng.choice(ENDS))

    def point(end, span):
        if end == "clamped-free":
            return span * rng.uniform(0.6, 1.0)
        return span * rng.uniform(0.25, 0.75)
    fields = dict(
        L1=length, b1=scale * 2.0, h1=thick, E1=e1, gamma1=g1, end1=end1,
        L2=l2, b2=scale * 0.5, h2=scale * rng.uniform(0.1, 0.6), E2=e2,
        gamma2=g2, end2=end2,
        L3=length * rng.uniform(0.8, 1.2), b3=scale * 2.0,
        h3=thick * rng.uniform(0.8, 1.25), E3=e3, gamma3=g3, end3=end3,
        ys=length * rng.uniform(0.005, 0.03), e=rng.uniform(0.3, 1.0),
        n_modes=int(rng.integers(1, n_max + 1)),
        release="tip" if end1 == "clamped-free" else "contact")
    fields["x1"] = point(end1, fields["L1"])
    fields["x2"] = point("clamped-clamped", l2)
    fields["x3"] = point(end3, fields["L3"])
    design = Design(**fields)
    damping = "flores" if rng.random() < 0.5 else "none"
    preload_fraction = 0.0 if rng.random() < 0.5 else rng.uniform(0.0005,
                                                                 0.01)
    return design, damping, preload_fraction


def setup_of(design, damping, preload, static=STATIC_CORRECTION):
    """The reference's setup: the design's fields written out."""
    def member(i, default_x):
        x = getattr(design, "x" + i)
        return dict(end=str(getattr(design, "end" + i)),
                    L=float(getattr(design, "L" + i)),
                    b=float(getattr(design, "b" + i)),
                    h=float(getattr(design, "h" + i)),
                    gamma=float(getattr(design, "gamma" + i)),
                    E=float(getattr(design, "E" + i)),
                    x=default_x if x is None else float(x))
    return ih.Setup(upper=member("1", float(design.L1)),
                    separator=member("2", float(design.L2) / 2.0),
                    lower=member("3", float(design.L3)),
                    ys=float(design.ys), n_modes=int(design.n_modes),
                    e=float(design.e), preload=float(preload),
                    damping=damping, release=design.release,
                    static_correction=static)


def reference_preload(setup, fraction):
    """A preload that bends the lower contact at x3 by ``fraction`` of
    its length (the reference's own static flexibility at x3, the exact
    point-load deflection of static_shape)."""
    lower = setup.lower
    y = ih.static_shape(lower["end"], lower["L"], lower["x"])
    inertia = lower["b"] * lower["h"]**3 / 12.0
    flexibility = float(y(lower["x"])) / (lower["E"] * inertia)
    return fraction * lower["L"] / flexibility


def reference_window(setup, samples=400):
    """The reference run of ``setup`` over its window (the first impact
    plus 0.15 of the upper contact's first period) and the package's
    step for it: ``(reference, t_end, dt, samples)``, dt a whole number
    of steps a sample, resolving the first contact (300 steps) and the
    stiffest contact's rate (0.05 rad a step)."""
    upper = ih.beam(setup.upper["end"], setup.upper["L"], setup.upper["b"],
                    setup.upper["h"], setup.upper["gamma"],
                    setup.upper["E"], 1)
    period = 2.0 * math.pi / float(upper.p[0])
    first = ih.simulate(setup, 2.0 * period, to_first_impact=True)
    assert math.isfinite(first.first_impact_s), "no impact in the window"
    t_end = first.first_impact_s + 0.15 * period
    ref = ih.simulate(setup, t_end)
    rate = ref.stiffest_rate(ref.k, ref.chi, ref.m)
    dt = min(ref.first_contact_s / 300.0, 0.05 / rate)
    per_sample = max(1, int(math.ceil(t_end / samples / dt)))
    return ref, t_end, t_end / (samples * per_sample), samples


def compare(seed, n_max=4, static=False, intervals=True):
    """The package against the reference on random design ``seed``;
    ``static``: both with the static correction (and no preload: the
    reference does not define the preloaded state with it)."""
    design, damping, fraction = random_design(seed, n_max)
    if static:
        # elastic: a closed contact's physical gap, g + C lambda, from
        # the modal one needs the force, which Flores ties to the rate
        fraction, damping = 0.0, "none"
    setup = setup_of(design, damping, 0.0, static)
    preload = reference_preload(setup, fraction) if fraction else 0.0
    setup = setup_of(design, damping, preload, static)
    ref, t_end, dt, samples = reference_window(setup)
    # Flores: a third run at dt/4 (the error has two orders, below)
    steps = (dt, dt / 2) if damping == "none" else (dt, dt / 2, dt / 4)
    runs = [run(design, dt=h, t_end=t_end, samples=samples,
                damping=damping, preload=preload, static_correction=static)
            for h in steps]
    coarse, fine = runs[:2]
    for other in runs[1:]:
        np.testing.assert_array_equal(coarse.t, other.t)
    # both report the physical gaps (with the static correction a closed
    # contact's is minus its Hertz element's penetration, and an open
    # one's moves with the other's force through the separator's spring)
    g_ref = ref.gaps(coarse.t)
    scale = float(setup.ys)

    def tolerance(name, floor):
        """3x the error estimate of quantity ``name`` at dt (largest over
        its samples) plus ``floor``: see estimated_error."""
        values = [np.asarray(getattr(r, name), dtype=float) for r in runs]
        return 3.0 * float(np.max(estimated_error(*values))) + floor

    # the gap histories
    gap_tols = []
    for c, name in ((0, "gap_upper"), (1, "gap_lower")):
        err = np.abs(getattr(coarse, name) - g_ref[c])
        tol = tolerance(name, 1e-9 * scale)
        assert err.max() <= tol, (seed, name, err.max(), tol)
        gap_tols.append(tol)
    gap_tol = max(gap_tols)
    # the first impact: in [t*, t* + dt], up to the gap error / speed
    slack = gap_tol / ref.v_impact + 1e-12
    assert ref.first_impact_s - slack <= coarse.first_impact_s \
        <= ref.first_impact_s + dt + slack, (seed, coarse.first_impact_s,
                                             ref.first_impact_s, dt)
    # the first impulse and the largest lower gap
    assert abs(coarse.first_impulse_lb_s - ref.first_impulse_lb_s) <= \
        tolerance("first_impulse_lb_s", 1e-8 * ref.first_impulse_lb_s), (
        seed, coarse.first_impulse_lb_s, fine.first_impulse_lb_s,
        ref.first_impulse_lb_s)
    assert abs(coarse.max_lower_gap_in - ref.max_lower_gap()) <= tolerance(
        "max_lower_gap_in", gap_tol + 2e-6 * abs(ref.max_lower_gap())), (
        seed, coarse.max_lower_gap_in, fine.max_lower_gap_in,
        ref.max_lower_gap())
    # the energy ratio (elastic: 1; Flores: what the damping removed)
    ref_ratio = ref.energy_end / ref.energy0
    assert abs(coarse.energy_ratio - ref_ratio) <= tolerance(
        "energy_ratio", ENERGY_FLOOR), (
        seed, coarse.energy_ratio, fine.energy_ratio, ref_ratio)
    # each contact's and the circuit's open intervals: where the package
    # and the reference disagree on whether a contact is open, the
    # reference's gap must be within that contact's gap tolerance of the
    # threshold (a package gap within the tolerance of the reference's
    # can be on the other side of the threshold only there); for the
    # circuit, one of the two contacts' must be
    threshold = 1e-6
    for contact, a, r in ((0, coarse.upper_open_intervals,
                           ref.open_intervals(0)),
                          (1, coarse.lower_open_intervals,
                           ref.open_intervals(1)),
                          (None, coarse.circuit_open_intervals,
                           ref.circuit_intervals())):
        if not intervals:
            continue
        for t in _disagreements(a, r):
            near = np.abs(ref.gaps(t) - threshold) <= np.array(
                gap_tols)[:, None]
            ok = near.any(axis=0) if contact is None else near[contact]
            if static and not ok.all():
                # with the correction, a crossing in a step where a force
                # acts at either end is found on the grid's physical gaps,
                # linear between them (docs/static-correction.md): its
                # instant is good to that step, not to the gap tolerance
                # (seed 1: the first closing, 0.06 dt)
                piece = (t[-1] - t[0]) * (len(t) + 1) / (len(t) - 1)
                assert piece <= dt, (seed, contact, t, piece / dt, a, r)
                continue
            assert ok.all(), (seed, contact, t[~ok], a, r)
    return design, damping, preload


def estimated_error(*values):
    """The package's error at dt, estimated from its values at dt, dt/2
    (and dt/4): elastic, the splitting is second order, the error C dt^2
    is (4/3) (X(dt) - X(dt/2)) (Richardson).  Flores, the error is
    A dt + B dt^2: the damping's first-order part (its force depends on
    the velocity the kick changes, its clamp at zero has a kink) and the
    elastic splitting's second-order part, which can be as large and of
    the other sign; then, with d1 = X(dt) - X(dt/2), d2 = X(dt/2) -
    X(dt/4), A dt + B dt^2 = (2 d1 + 8 d2) / 3 (2 d1 where B = 0, the
    former two-run estimate, which stays a floor).  Seed 173 (e = 0.92, so little damping)
    is why: the upper gap's error at t_end is 5.22, 5.02, 3.24, 1.82,
    0.96e-5 in at dt ... dt/16, successive ratios 1.04, 1.55, 1.78, 1.89
    (-> 2): A dt + B dt^2 with B dt / A = -0.65, nearly cancelling
    between dt and dt/2, so that 2 d1 (4e-6) fell 13x short of the
    error; (2 d1 + 8 d2) / 3 = 4.9e-5 (the reference moves by 4e-12
    from rtol 1e-11 to 1e-12)."""
    if len(values) == 2:
        return 4.0 / 3.0 * np.abs(values[0] - values[1])
    d1, d2 = values[0] - values[1], values[1] - values[2]
    # the larger of the two models' estimates: where the convergence is
    # not yet of either form, the three-step one can fall short (seed
    # 256's energy ratio, errors +1.8e-3, -0.9e-3, -0.2e-3 at dt, dt/2,
    # dt/4: (2 d1 + 8 d2) / 3 = 1.5e-5, 2 |d1| = 5.4e-3)
    return np.maximum(np.abs(2.0 * d1 + 8.0 * d2) / 3.0, 2.0 * np.abs(d1))


def _disagreements(a, b, points=5):
    """Sample instants inside every piece of [0, t_end] where exactly one
    of two lists of intervals ((k, 2)) holds."""
    ends = np.unique(np.concatenate([a.ravel(), b.ravel()]))
    out = []
    for lo, hi in zip(ends[:-1], ends[1:]):
        if hi - lo <= 1e-12 * hi:
            continue        # the round-off of an instant (t_end = steps dt)
        mid = 0.5 * (lo + hi)
        inside_a = bool(np.any((a[:, 0] <= mid) & (mid < a[:, 1])))
        inside_b = bool(np.any((b[:, 0] <= mid) & (mid < b[:, 1])))
        if inside_a != inside_b:
            out.append(np.linspace(lo, hi, points + 2)[1:-1])
    return out


@pytest.mark.parametrize("seed", range(5))
def test_the_package_agrees_with_the_independent_simulator(seed):
    compare(seed)


@pytest.mark.parametrize("seed", range(5))
def test_the_static_correction_agrees_with_the_independent_simulator(seed):
    """Issue 25's static correction: the reference's own residual
    flexibilities (G from its static beam, less its own mode sum) in
    series with each contact, against the package's: the gap
    histories, the first impact and impulse, the largest lower gap and
    the energy (the open instants: the next test)."""
    compare(seed, static=True, intervals=False)


@pytest.mark.parametrize("seed", range(5))
def test_the_static_corrections_open_instants_agree_to_a_step(seed):
    """The open instants with the static correction.  An open contact's
    physical gap is not its modal one while the other contact presses:
    the separator's residual spring moves it by -c2 lambda_other.  The
    reference once located its crossings in contact phases on the modal
    gaps, and disagreed with the package by 14 steps (seed 1: the lower
    contact "opened" while its element was still 2e-6 in deep, with
    0.015 lb on it) and 3 steps (seed 2); on the physical gaps every
    instant agrees to the gap tolerance, or within a step where the
    package interpolates (see compare)."""
    compare(seed, static=True)


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(100, 300))
def test_the_package_agrees_on_a_few_hundred_random_designs(seed):
    """200 designs up to N = 8: 3-25 s each on two loaded cores (a
    preloaded N = 8 Flores design 140 s: the reference integrates the
    pressed contact's every mode).  Seed 173 was an xfail while Flores
    runs were estimated first order from two steps (estimated_error)."""
    compare(seed, n_max=8)


def test_the_random_designs_vary_every_field_that_matters():
    """The default seeds cover off-tip, off-mid-span contact points,
    other end conditions, both damping laws, preloads and several N."""
    seen = [random_design(seed) for seed in range(5)]
    designs = [d for d, _, _ in seen]
    assert {damping for (_, damping, _) in seen} == {"none", "flores"}
    assert any(f > 0 for (_, _, f) in seen) and any(f == 0 for
                                                    (_, _, f) in seen)
    assert len({int(d.n_modes) for d in designs}) >= 2
    assert any(abs(float(d.x2) - float(d.L2) / 2) > 0.05 * float(d.L2)
               for d in designs)
    assert len({(d.end1, d.end2, d.end3) for d in designs}) >= 3
