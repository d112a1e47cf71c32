"""The convergence study of docs/chatter.md (a few minutes):

    OPENBLAS_NUM_THREADS=1 python benchmarks/chatter_convergence.py

1. dt: the adaptive steppers (Hertz and Newton, the defaults) at
   dt = 2e-7 ... 6.25e-9 s for every thesis separator and N = 4, 16, 32;
   each quantity's largest relative departure from its value at the
   finest dt, per dt (the limit is taken at the finest dt: the printed
   departures of the next finest bound its own error).
2. The independent code: Moreau-Jean (the fixed-step, trapezoidal
   stepper) at 1e-7, 1e-8 and 5e-9 s on the thick separators at N = 32,
   against the adaptive Newton stepper.
3. N: both models at their default dt, N = 4 ... 64 (d = 0.25 in).
4. Appendix E on the rigid stop, N = 1 ... 32.
"""

from __future__ import annotations

import sys
import time

import numpy as np

import contactsep
from contactsep import chatter
from contactsep.chatter.event_driven import rigid_stop_from_design

THICKNESSES = (0.125, 0.25, 0.35, 0.5, 0.75)
MODES = (4, 16, 32)
STEPS = (2e-7, 1e-7, 5e-8, 2.5e-8, 1.25e-8, 6.25e-9)
QUANTITIES = ("first_impulse_lb_s", "max_lower_gap_in", "circuit_open_s")


def run(model, n, d, dt, **options):
    return chatter.simulate(contactsep.thesis_design(n_modes=n, d=d),
                            model=model, dt=dt, samples=1, **options)


def dt_study(model) -> None:
    print(f"\n## {model}: largest |x(dt) / x(finest) - 1| over d = "
          f"{', '.join(map(str, THICKNESSES))} in\n")
    print("| N | " + " | ".join(f"dt = {dt:.3g} s" for dt in STEPS[:-1])
          + " |")
    print("|---|" + "---|" * (len(STEPS) - 1))
    for n in MODES:
        worst = {q: np.zeros(len(STEPS) - 1) for q in QUANTITIES}
        for d in THICKNESSES:
            results = [run(model, n, d, dt) for dt in STEPS]
            for q in QUANTITIES:
                values = np.array([getattr(r, q) for r in results])
                worst[q] = np.maximum(worst[q], np.abs(
                    values[:-1] / values[-1] - 1))
        for q in QUANTITIES:
            print(f"| {n} {q} | " + " | ".join(f"{w:.1e}" for w in worst[q])
                  + " |", flush=True)


def independent_newton() -> None:
    print("\n## Newton at N = 32: adaptive (exact flow) against "
          "Moreau-Jean (trapezoidal)\n")
    print("| d (in) | stepper | dt (s) | first impulse (lb s) | "
          "max lower gap (in) | circuit open (s) | time (s) |")
    print("|---|---|---|---|---|---|---|")
    for d in (0.5, 0.75):
        for stepper, steps in (("adaptive", (1e-7, 6.25e-9)),
                               ("fixed", (1e-7, 1e-8, 5e-9))):
            for dt in steps:
                start = time.perf_counter()
                r = run("newton", 32, d, dt, stepper=stepper)
                print(f"| {d} | {stepper} | {dt:.3g} | "
                      f"{r.first_impulse_lb_s:.5g} | "
                      f"{r.max_lower_gap_in:.5g} | {r.circuit_open_s:.5g} | "
                      f"{time.perf_counter() - start:.2f} |", flush=True)


def n_study() -> None:
    print("\n## N, d = 0.25 in, default dt\n")
    print("| N | Newton first impulse | Newton max lower gap | Newton open "
          "| Hertz first impulse | Hertz max lower gap | Hertz open |")
    print("|---|---|---|---|---|---|---|")
    for n in (4, 8, 16, 32, 64):
        cells = []
        for model in ("newton", "hertz"):
            r = run(model, n, 0.25, None)
            cells += [f"{r.first_impulse_lb_s:.4g}",
                      f"{r.max_lower_gap_in:.4g}",
                      f"{r.circuit_open_s:.5g}"]
        print(f"| {n} | " + " | ".join(cells) + " |", flush=True)


def appendix_e() -> None:
    print("\n## Appendix E on the rigid stop\n")
    print("| N | first impact (s) | first impulse | all impulses | "
          "impacts | rests | resting (s) | energy left |")
    print("|---|---|---|---|---|---|---|---|")
    for n in (1, 2, 4, 8, 16, 32):
        r = rigid_stop_from_design(contactsep.thesis_design(n_modes=n),
                                   t_end=0.06, max_impacts=200_000)
        rest = float(np.sum(np.diff(r.rest_intervals, axis=1))) \
            if len(r.rest_intervals) else 0.0
        print(f"| {n} | {r.impact_t[0]:.6g} | {r.impulse[0]:.4g} | "
              f"{r.impulse.sum():.4g} | {len(r.impact_t)} | "
              f"{len(r.rest_intervals)} | {rest:.4g} | "
              f"{r.final_energy / r.initial_energy:.4g} |", flush=True)


def main(parts) -> None:
    studies = {"dt": lambda: (dt_study("hertz"), dt_study("newton")),
               "independent": independent_newton, "n": n_study,
               "appE": appendix_e}
    for name in parts or studies:
        studies[name]()


if __name__ == "__main__":
    main(sys.argv[1:])
