"""The Newton model's defaults converged in dt (issue 16, item 5).

Error model.  One run's largest lower gap and first impulse are smooth
in the step until a branch point (docs/convergence.md, "The Newton
open time"): at the default 5e-8 s the gap lies within 0.25 % of the same
stepper at 3.125e-9 s for N = 4 and 16 and within 0.22 % at N = 32 for
d >= 0.35 in (a convergence study: the fine steps among themselves
agree to 0.2 %), the first impulse within 8e-6; the other code,
Moreau-Jean (trapezoidal, an LCP a step; nothing shared with the
adaptive stepper's flight or impulse), converges to the same gap (N =
32, d = 0.75 in: 0.0085286, 0.0085815, 0.0085914 in at 1e-8, 5e-9,
2.5e-9 s; the adaptive default 0.0085931 in).  The issue asks for 1 %.

One run's open time is ill-conditioned: round-off-sized changes of the
design move it by 1-5 % in both codes, so it has no dt -> 0 limit to
approach.  What converges is its mean over a tolerance band (L2 uniform
within +-0.5 %, seed 0, through `contactsep sweep --dt`): the band means
at 5e-8 s lie within 0.76 % of those at 3.125e-9 s for every thesis
separator and N = 4, 16, 32 (benchmarks/chatter_convergence.py band),
and Moreau-Jean's band means at 1e-8 and 5e-9 s within 0.16 % of the
adaptive stepper's at 3.125e-9 s.  The tests take the three largest
departures of that table; a mean's standard error is 0.13-0.16 % at
N = 4 with 256 designs, so the worst case (N = 4, d = 0.35 in, -0.76 %)
runs 1024 (-0.65 %, standard error of the difference 0.10 %): another
machine's round-off changes the runs, and the mean by about that.
Mutations: the default at 1e-7 s fails the first impulse (N = 32), at
2e-7 s the band tests fail.
"""

from __future__ import annotations

import dataclasses
from concurrent.futures import ProcessPoolExecutor

import pytest

import contactsep
from contactsep import chatter
from contactsep.studies.sweep import run as runner
from contactsep.studies.sweep import spec as sweep
DEFAULT = 5e-8
FINE = 3.125e-9


def run(n, d, dt, stepper="adaptive"):
    return chatter.simulate(contactsep.thesis_design(n_modes=n, d=d),
                            model="newton", dt=dt, samples=1, t_end=0.06,
                            stepper=stepper, single_impulse=False)


def gap(n, d, dt, stepper="adaptive"):
    return run(n, d, dt, stepper).max_lower_gap_in


@pytest.mark.parametrize("n, d", [(n, d) for n in (4, 16)
                                  for d in (0.125, 0.25, 0.35, 0.5, 0.75)]
                         + [(32, 0.35), (32, 0.5), (32, 0.75)])
def test_the_default_largest_lower_gap_is_within_1_percent(n, d):
    """The gap is the quantity the issue asks for; the first impulse is
    what sets the default (at 1e-7 s the first contact episode at N = 32
    takes in a second impact of the separator's fastest modes: 10 % high
    at d = 0.5 in; at 5e-8 s within 8e-6 of the limit)."""
    default, fine = run(n, d, DEFAULT), run(n, d, FINE)
    assert default.max_lower_gap_in == pytest.approx(
        fine.max_lower_gap_in, rel=0.01)
    assert default.first_impulse_lb_s == pytest.approx(
        fine.first_impulse_lb_s, rel=1e-4)


def test_the_default_gap_is_moreau_jeans_limit():
    """The issue's case, N = 32, d = 0.75 in (its 0.00708 in was the
    fixed-step stepper at 1e-7 s), against the other code at 5e-9 s
    (0.14 % below the adaptive default, 0.12 % below its own 2.5e-9 s)."""
    reference = gap(32, 0.75, 5e-9, stepper="fixed")
    assert gap(32, 0.75, DEFAULT) == pytest.approx(reference, rel=0.01)


def band_spec(n, d, dt, samples=256):
    """The band of docs/chatter.md (benchmarks/chatter_convergence.py
    band): L2 uniform within 1e-2 relative (+-0.0125 in), seed 0."""
    assert contactsep.thesis_design().L2 == 2.5
    return sweep.make_spec(sample=["L2=uniform(2.4875,2.5125)"],
                           samples=samples, base={"n_modes": n, "h2": d},
                           model="newton",
                           settings={"dt": dt, "t_end": 0.06})


def _open_time(args):
    n, d, length, dt, stepper = args
    design = dataclasses.replace(contactsep.thesis_design(n_modes=n, d=d),
                                 L2=length)
    return chatter.simulate(design, model="newton", dt=dt, samples=1,
                            stepper=stepper, t_end=0.06,
                            single_impulse=False).circuit_open_s


def _band(n, d, dt, samples):
    summary = runner.run_sweep(band_spec(n, d, dt, samples),
                               progress=False)
    assert summary["n"] == samples and summary["n_failed"] == 0
    return summary


@pytest.mark.slow
@pytest.mark.parametrize("n, d, samples", [(4, 0.35, 1024),
                                           (16, 0.125, 256),
                                           (32, 0.125, 256)])
def test_the_band_mean_open_time_is_within_1_percent(n, d, samples):
    """The three largest departures of the benchmark's table (N = 4,
    d = 0.35 in: -0.65 % over 1024 designs, standard error of the
    difference 0.1 %; N = 16 and 32, d = 0.125 in: -0.29 % and -0.46 %,
    0.03 % and 0.02 %)."""
    default = _band(n, d, DEFAULT, samples)
    fine = _band(n, d, FINE, samples)
    for key in ("circuit_open_mean_s", "max_lower_gap_mean_in"):
        assert default[key] == pytest.approx(fine[key], rel=0.01), key


@pytest.mark.slow
def test_the_band_mean_open_time_is_moreau_jeans():
    """N = 4, d = 0.5 in, the case where narrow ensembles disagreed by
    2.7 %: the other code on the band's first 128 designs, against the
    adaptive default on the same designs."""
    lengths = sweep.chunk_inputs(band_spec(4, 0.5, DEFAULT), 0,
                                 128)["L2"].tolist()
    assert max(lengths) - min(lengths) > 0.02     # the band, sampled
    with ProcessPoolExecutor(2) as pool:
        reference = list(pool.map(_open_time, [
            (4, 0.5, x, 1e-8, "fixed") for x in lengths]))
        default = list(pool.map(_open_time, [
            (4, 0.5, x, DEFAULT, "adaptive") for x in lengths]))
    assert sum(default) / 128 == pytest.approx(sum(reference) / 128,
                                               rel=0.01)
