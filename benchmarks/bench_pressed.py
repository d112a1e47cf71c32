"""Preloaded against free Hertz runs on the design family (issue 29,
item 4), and what the preloaded lower contact does meanwhile:

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_pressed.py [--save]

Each design of tests/design_family.py at N = 16, its own step and
window, summary only (samples=1), free and with a 5 lb preload (or half
its largest preload, if smaller): the CPU time of ``simulate`` (best of
two), the preloaded run's over the free run's, and the adaptive
stepper's fixed steps of each.  Then the preloaded run again with
samples through its window: the lower contact's depth (-gap) over the
second half of the window, its range and the strongest frequency of its
spectrum: a lower contact that stays pressed rings on its Hertz spring
for the whole window (the elastic law has no damping), so its force is
not smooth between impacts and the steps must follow the ringing
(docs/performance-contact.md, "Preloaded runs"); the last column is the depth
range with Flores damping calibrated to the design's e.

CPU time of this process (``time.process_time``), so that other work on
the machine does not count; ``--save``: also into
benchmarks/results/bench_pressed.md.
"""

from __future__ import annotations

import math
import os
import sys
import time
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))

from design_family import FAMILY  # noqa: E402
from results import Report  # noqa: E402

from contactsep.chatter import simulate  # noqa: E402
from contactsep.chatter.stack import largest_preload  # noqa: E402

N_MODES = 16
PRELOAD_LB = 5.0
REPEATS = 2
SAMPLES = 200_001


def run(design, preload, samples=1, damping="none"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return simulate(design, model="hertz", preload=preload,
                        samples=samples, single_impulse=False,
                        damping=damping)


def cpu_best(design, preload):
    best, result = math.inf, None
    for _ in range(REPEATS):
        start = time.process_time()
        result = run(design, preload)
        best = min(best, time.process_time() - start)
    return best, result


def ringing(design, preload, damping="none"):
    """Depth range (in) over the second half of the window, its
    strongest frequency (Hz), and the run's circuit openings."""
    r = run(design, preload, SAMPLES, damping)
    half = len(r.t) // 2
    depth = -np.asarray(r.gap_lower[half:])
    spectrum = np.abs(np.fft.rfft(depth - depth.mean()))
    freqs = np.fft.rfftfreq(depth.size, float(r.t[1] - r.t[0]))
    # the strongest oscillation, not the drift of the mean (bin 0)
    return (float(depth.min()), float(depth.max()),
            float(freqs[1 + int(np.argmax(spectrum[1:]))]),
            len(r.circuit_open_intervals))


def main(save: bool = False) -> None:
    say = Report()
    say("clock: process CPU time")
    say(f"| design, N = {N_MODES} | preload (lb) | free (s) | preloaded "
        f"(s) | ratio | fixed steps, free / preloaded | lower depth, "
        f"2nd half (in) | its strongest frequency (Hz) | circuit "
        f"openings | the same depth with Flores damping (in) |")
    say("|---|---:|---:|---:|---:|---|---|---:|---:|---|")
    for name, design in FAMILY.items():
        design = design.replace(n_modes=N_MODES)
        load = min(PRELOAD_LB, 0.5 * largest_preload(design))
        free, r_free = cpu_best(design, 0.0)
        pressed, r_load = cpu_best(design, load)
        low, high, hz, openings = ringing(design, load)
        damped = ringing(design, load, "flores")
        say(f"| {name} | {load:.3g} | {free:.3f} | {pressed:.3f} | "
            f"{pressed / free:.1f} | {r_free.work['fixed_steps']:,} / "
            f"{r_load.work['fixed_steps']:,} | {low:.3g} to {high:.3g} | "
            f"{hz:.3g} | {openings} | {damped[0]:.3g} to "
            f"{damped[1]:.3g} |")
    if save:
        say.save("bench_pressed", "OPENBLAS_NUM_THREADS=1 python "
                 "benchmarks/bench_pressed.py --save")


if __name__ == "__main__":
    main(save="--save" in sys.argv[1:])
