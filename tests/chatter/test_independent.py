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
rtol 1e-11 (1e-9 on the 200 random designs: below), whose own error is
negligible beside it.  The package's
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

The reference's tolerance on the 200 random designs (RANDOM_RTOL =
1e-9; the slow test).  At rtol 1e-11 DOP853 works near round-off in the
long pressed phases of the preloaded designs (seeds 144 and 179: 99 and
157 s of a reference run; the two tests were half of the slow test's
995 s).  Measured on the ten slowest seeds and 22 others (100, 110,
..., 290, 173, 256): the
reference at 1e-9 against the one at 1e-11, each compared quantity's
change over compare's tolerance for it (the gaps on the sample grid and
at 20,001 instants more, where the open intervals are judged; the first
impact, impulse, largest lower gap and energy ratio); the same window,
step and number of open intervals on every seed; CPU s of the
reference on a loaded machine (both with independent_hertz's scalar
right-hand side, the same equations 1.5x cheaper than the array one):

====  ==  ======  =======  =======  ======  ==========  ==========
seed  N   law     preload  1e-11 s  1e-9 s  ratio 1e-9  ratio 1e-8
====  ==  ======  =======  =======  ======  ==========  ==========
144   8   Flores  yes       99.0     12.7    5.5e-09     2.8e-09
179   8   Flores  yes      157.0      7.0    1.5e-09     2.6e-09
102   8   Flores  yes       19.6     11.7    1.7e-08     6.8e-07
112   7   none    yes       25.9     16.0    1.4e-05     3.2e-04
266   7   none    yes       10.8      7.7    1.4e-06     1.8e-06
254   5   none    yes        9.2      4.6    1.2e-06     2.2e-06
195   6   none    yes        6.9      3.6    9.2e-07     9.0e-06
159   8   none    yes        6.4      4.1    7.0e-06     2.2e-05
104   7   Flores  yes        1.1      0.7    1.9e-08     2.0e-07
154   8   none    no         2.4      1.9    5.0e-09     1.4e-07
22 others (N 1-8, both laws, 11 preloaded)  0.1-3.7 / 0.4-3.2 s;
largest ratio 8.5e-4 (seed 280) at 1e-9, 0.15 (seed 110) at 1e-8
====  ==  ======  =======  =======  ======  ==========  ==========

All 32: 359 CPU s of reference at 1e-11, 88 s at 1e-9.  The largest
ratio at 1e-9, 8.5e-4, is 120x below the 1/10 this change was allowed;
at 1e-8 seed 110 reaches 0.15, so 1e-8 is not used.  The
package-against-reference tolerances are unchanged.
test_the_random_designs_reference_is_the_tight_one repeats the check,
in the default set, on three cheap seeds (100: elastic, preloaded;
140: Flores; 220: Flores, preloaded, N = 7).  The package's own runs
(dt, dt/2, dt/4) take under 0.1 s a seed, so sharing them would save
nothing; the reference's run to the first impact (flight only, exact
flow) is as cheap.
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
#: The reference's DOP853 tolerance on the 200 random designs (the slow
#: test; the module docstring's table).
RANDOM_RTOL = 1e-9
#: Seeds on which the default set checks RANDOM_RTOL against 1e-11.
CHECKED_SEEDS = (100, 140, 220)


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


def reference_window(setup, samples=400, rtol=ih.RTOL):
    """The reference run of ``setup`` over its window (the first impact
    plus 0.15 of the upper contact's first period) and the package's
    step for it: ``(reference, t_end, dt, samples)``, dt a whole number
    of steps a sample, resolving the first contact (300 steps) and the
    stiffest contact's rate (0.05 rad a step); ``rtol``: the reference's
    in contact phases."""
    upper = ih.beam(setup.upper["end"], setup.upper["L"], setup.upper["b"],
                    setup.upper["h"], setup.upper["gamma"],
                    setup.upper["E"], 1)
    period = 2.0 * math.pi / float(upper.p[0])
    first = ih.simulate(setup, 2.0 * period, to_first_impact=True,
                        rtol=rtol)
    assert math.isfinite(first.first_impact_s), "no impact in the window"
    t_end = first.first_impact_s + 0.15 * period
    ref = ih.simulate(setup, t_end, rtol=rtol)
    rate = ref.stiffest_rate(ref.k, ref.chi, ref.m)
    dt = min(ref.first_contact_s / 300.0, 0.05 / rate)
    per_sample = max(1, int(math.ceil(t_end / samples / dt)))
    return ref, t_end, t_end / (samples * per_sample), samples


def case(seed, n_max=4, static=False):
    """Random design ``seed``'s design, damping, preload and reference
    setup; ``static``: with the static correction (and no preload: the
    reference does not define the preloaded state with it)."""
    design, damping, fraction = random_design(seed, n_max)
    if static:
        # elastic: a closed contact's physical gap, g + C lambda, from
        # the modal one needs the force, which Flores ties to the rate
        fraction, damping = 0.0, "none"
    setup = setup_of(design, damping, 0.0, static)
    preload = reference_preload(setup, fraction) if fraction else 0.0
    return design, damping, preload, setup_of(design, damping, preload,
                                              static)


def package_runs(design, damping, preload, static, t_end, dt, samples):
    """The package at dt and dt/2 (Flores: and dt/4; the error has two
    orders, estimated_error), on one sample grid."""
    steps = (dt, dt / 2) if damping == "none" else (dt, dt / 2, dt / 4)
    runs = [run(design, dt=h, t_end=t_end, samples=samples,
                damping=damping, preload=preload, static_correction=static)
            for h in steps]
    for other in runs[1:]:
        np.testing.assert_array_equal(runs[0].t, other.t)
    return runs


def tolerances(runs, ref, scale, max_lower_gap):
    """Each compared quantity's tolerance (module docstring): 3x its
    error estimate at dt (largest over its samples; estimated_error)
    plus a floor; the first impact's slack (the gap tolerance over the
    impact speed); ``max_lower_gap`` the reference's."""
    def tolerance(name, floor):
        values = [np.asarray(getattr(r, name), dtype=float) for r in runs]
        return 3.0 * float(np.max(estimated_error(*values))) + floor

    gaps = [tolerance(name, 1e-9 * scale)
            for name in ("gap_upper", "gap_lower")]
    return {"gap_upper": gaps[0], "gap_lower": gaps[1],
            "first_impact_s": max(gaps) / ref.v_impact + 1e-12,
            "first_impulse_lb_s": tolerance(
                "first_impulse_lb_s", 1e-8 * ref.first_impulse_lb_s),
            "max_lower_gap_in": tolerance(
                "max_lower_gap_in", max(gaps) + 2e-6 * abs(max_lower_gap)),
            "energy_ratio": tolerance("energy_ratio", ENERGY_FLOOR)}


def compare(seed, n_max=4, static=False, intervals=True, rtol=ih.RTOL):
    """The package against the reference on random design ``seed``;
    ``static``: both with the static correction (and no preload: the
    reference does not define the preloaded state with it); ``rtol``:
    the reference's (RANDOM_RTOL: the evidence in the module
    docstring)."""
    design, damping, preload, setup = case(seed, n_max, static)
    ref, t_end, dt, samples = reference_window(setup, rtol=rtol)
    runs = package_runs(design, damping, preload, static, t_end, dt,
                        samples)
    coarse, fine = runs[:2]
    # both report the physical gaps (with the static correction a closed
    # contact's is minus its Hertz element's penetration, and an open
    # one's moves with the other's force through the separator's spring)
    g_ref = ref.gaps(coarse.t)
    max_lower_gap = ref.max_lower_gap()
    tol = tolerances(runs, ref, float(setup.ys), max_lower_gap)

    # the gap histories
    gap_tols = [tol["gap_upper"], tol["gap_lower"]]
    for c, name in ((0, "gap_upper"), (1, "gap_lower")):
        err = np.abs(getattr(coarse, name) - g_ref[c])
        assert err.max() <= tol[name], (seed, name, err.max(), tol[name])
    # the first impact: in [t*, t* + dt], up to the gap error / speed
    slack = tol["first_impact_s"]
    assert ref.first_impact_s - slack <= coarse.first_impact_s \
        <= ref.first_impact_s + dt + slack, (seed, coarse.first_impact_s,
                                             ref.first_impact_s, dt)
    # the first impulse and the largest lower gap
    assert abs(coarse.first_impulse_lb_s - ref.first_impulse_lb_s) <= \
        tol["first_impulse_lb_s"], (
        seed, coarse.first_impulse_lb_s, fine.first_impulse_lb_s,
        ref.first_impulse_lb_s)
    assert abs(coarse.max_lower_gap_in - max_lower_gap) <= \
        tol["max_lower_gap_in"], (
        seed, coarse.max_lower_gap_in, fine.max_lower_gap_in,
        max_lower_gap)
    # the energy ratio (elastic: 1; Flores: what the damping removed)
    ref_ratio = ref.energy_end / ref.energy0
    assert abs(coarse.energy_ratio - ref_ratio) <= tol["energy_ratio"], (
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


def reference_change(seed, rtol, n_max=8):
    """How far the reference at ``rtol`` lies from the one at ih.RTOL
    (1e-11) on random design ``seed``, in each compared quantity over
    compare's tolerance for it (the package's runs at the tight
    reference's step): {quantity: ratio}.  The gaps on the sample grid
    and between (20,001 instants more: where the open intervals are
    judged).  Also asserts the same window, step and count of open
    intervals."""
    design, damping, preload, setup = case(seed, n_max)
    tight, t_end, dt, samples = reference_window(setup)
    loose, t_end_loose, dt_loose, _ = reference_window(setup, rtol=rtol)
    assert (t_end_loose, dt_loose) == pytest.approx((t_end, dt), rel=1e-9)
    for c in (0, 1):
        assert len(loose.open_intervals(c)) == len(tight.open_intervals(c))
    runs = package_runs(design, damping, preload, False, t_end, dt,
                        samples)
    tight_gap = tight.max_lower_gap()
    tol = tolerances(runs, tight, float(setup.ys), tight_gap)
    t = np.union1d(runs[0].t, np.linspace(0.0, t_end, 20001))
    change = np.abs(loose.gaps(t) - tight.gaps(t)).max(axis=1)
    ratio = {"gap_upper": change[0] / tol["gap_upper"],
             "gap_lower": change[1] / tol["gap_lower"]}
    for name, tight_value, loose_value in (
            ("first_impact_s", tight.first_impact_s, loose.first_impact_s),
            ("first_impulse_lb_s", tight.first_impulse_lb_s,
             loose.first_impulse_lb_s),
            ("max_lower_gap_in", tight_gap, loose.max_lower_gap()),
            ("energy_ratio", tight.energy_end / tight.energy0,
             loose.energy_end / loose.energy0)):
        ratio[name] = abs(loose_value - tight_value) / tol[name]
    return ratio


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
    """200 designs up to N = 8, the reference at RANDOM_RTOL (at 1e-11
    a preloaded N = 8 Flores design took 140-265 s, the reference
    integrating the pressed contact's every mode).  Seed 173 was an
    xfail while Flores runs were estimated first order from two steps
    (estimated_error)."""
    compare(seed, n_max=8, rtol=RANDOM_RTOL)


@pytest.mark.parametrize("seed", CHECKED_SEEDS)
def test_the_random_designs_reference_is_the_tight_one(seed):
    """RANDOM_RTOL's reference within a tenth of every tolerance of the
    one at 1e-11 (the module docstring's table, on cheap seeds)."""
    ratio = reference_change(seed, RANDOM_RTOL)
    assert max(ratio.values()) <= 0.1, (seed, ratio)


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
