"""How far the pressed step can grow: preloaded Hertz runs of the design
family at multiples of the design's own step, near each design's
answer, and what each headline quantity does:

    OPENBLAS_NUM_THREADS=1 python benchmarks/pressed_step.py [--save]

Each design at N = 32 and 64 (elastic Hertz, the design's own window,
static correction on, summary only), preloaded at its converged minimum
preload (docs/studies/preload_family.csv), run at 1/2, 1, 2, 4, 8 and
16 times the design's step.  Printed per run: the steps a period of the
pressed lower contact's ringing (its strongest frequency, from a
sampled run at the design's step: a rough scale, the strongest peak
is not always the contact's own ringing), |energy_ratio - 1|, the relative
change against the run at half the design's step of the first impact
time, the first impulse and the circuit's open time, the number of
discontinuity events, and the adaptive stepper's fixed steps.

What it showed (docs/records/2026-12-pressed-step.md): the first impact
and the first impulse hold to 1.4e-4 up to 16x the step; energy holds
to 1e-6 at 2x on the family and fails at 4x-8x on three of the four
relays, earlier as N grows; the circuit's open time near the answer is
not converged even between 1/2 and 1 times the design's step, and the
event itself can flip with the step.
``--save``: also into benchmarks/results/pressed_step.md.
"""

from __future__ import annotations

import csv
import os
import sys
import time
import warnings

import numpy as np

HERE = os.path.dirname(__file__)
sys.path.insert(0, os.path.join(HERE, "..", "tests"))

from design_family import FAMILY
from results import Report

from contactsep.chatter import simulate

MODES = (32, 64)
MULTIPLES = (0.5, 1.0, 2.0, 4.0, 8.0, 16.0)
SAMPLES = 200_001


def answers() -> dict:
    """Each family design's converged minimum preload (lb)."""
    path = os.path.join(HERE, "..", "docs", "studies",
                        "preload_family.csv")
    with open(path, newline="") as handle:
        rows = csv.DictReader(line for line in handle
                              if not line.startswith("#"))
        return {row["design"]: float(row["converged_min_preload_lb"])
                for row in rows}


def run(design, preload, dt=None, t_end=None, samples=1):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return simulate(design, preload=preload, dt=dt, t_end=t_end,
                        samples=samples)


def ring_hz(design, preload) -> float:
    """The strongest frequency (Hz) of the lower contact's depth over
    the second half of the window, at the design's step."""
    r = run(design, preload, samples=SAMPLES)
    half = len(r.t) // 2
    depth = -np.asarray(r.gap_lower[half:])
    spectrum = np.abs(np.fft.rfft(depth - depth.mean()))
    freqs = np.fft.rfftfreq(depth.size, float(r.t[1] - r.t[0]))
    return float(freqs[1 + int(np.argmax(spectrum[1:]))])


def change(value, reference) -> float:
    return abs(value - reference) / abs(reference) if reference else \
        float(value != reference)


def main(save: bool = False) -> None:
    say = Report()
    say("| design | N | preload (lb) | step x | steps a ring period | "
        "energy error | first impact | first impulse | open time | "
        "events | fixed steps | wall (s) |")
    say("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for name, preload in answers().items():
        for n in MODES:
            design = FAMILY[name].replace(n_modes=n)
            own = run(design, preload)
            period = 1.0 / ring_hz(design, preload)
            runs = {}
            for multiple in MULTIPLES:
                start = time.perf_counter()
                runs[multiple] = (run(design, preload, own.dt * multiple,
                                      own.t_end_s),
                                  time.perf_counter() - start)
            ref = runs[0.5][0]
            for multiple, (r, wall) in runs.items():
                say(f"| {name} | {n} | {preload:.4g} | {multiple:g} | "
                    f"{period / r.dt:.0f} | {abs(r.energy_ratio - 1):.1e} "
                    f"| {change(r.first_impact_s, ref.first_impact_s):.1e}"
                    f" | {change(r.first_impulse_lb_s, ref.first_impulse_lb_s):.1e}"
                    f" | {change(r.circuit_open_s, ref.circuit_open_s):.2f}"
                    f" | {r.n_events} | {r.work['fixed_steps']:,} | "
                    f"{wall:.2f} |")
    if save:
        say.save("pressed_step", "OPENBLAS_NUM_THREADS=1 python "
                 "benchmarks/pressed_step.py --save")


if __name__ == "__main__":
    main(save="--save" in sys.argv[1:])
