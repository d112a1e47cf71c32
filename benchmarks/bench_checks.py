"""The cost of numerics chosen from the design and of the checks (issue
25), side by side in one run:

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_checks.py [--cpu] [--save]

For three designs of tests/design_family.py at N = 32 (the default N),
elastic Hertz, summary only (samples=1): the thesis's old fixed settings
(dt 5e-8 s, window 0.06 s; on the relays that step is unstable), the
design's own step and window (the default; the energy check is one
division, its cost is a rerun when a step is halved), and the default
with verify=True (a second run at 2N and half the step).  Each time is
the best of REPEATS calls; the ratios are to the default.  A preloaded
case shows the cost when the contact is closed at every step.
``--cpu``: CPU time (with the forked children's) instead of the wall
clock; ``--save``: also into benchmarks/results/bench_checks.md, the
run docs/performance.md quotes.
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

import bench_chatter  # noqa: E402 (this folder: a script)
from bench_chatter import best  # noqa: E402
from design_family import FAMILY  # noqa: E402
from results import Report  # noqa: E402

from contactsep import chatter  # noqa: E402

REPEATS = 3


def main(save: bool = False, cpu: bool = False) -> None:
    warnings.simplefilter("ignore")
    if cpu:
        bench_chatter.clock = bench_chatter.cpu_time
    say = Report()
    say(f"clock: {'process CPU time' if cpu else 'wall'}")
    say("| design, N = 32 | old fixed (5e-8 s, 0.06 s) | default | "
          "default + verify | default: dt (s), window (s), energy - 1 |")
    say("|---|---:|---:|---:|---|")
    cases = [("thesis", 0.0), ("steel_relay", 0.0), ("becu_light", 0.0),
             ("steel_relay", 0.35)]
    for name, preload in cases:
        design = FAMILY[name].replace(n_modes=32)
        common = dict(samples=1, single_impulse=False, preload=preload)
        old = best(lambda: chatter.simulate(design, dt=5e-8, t_end=0.06,
                                            **common), REPEATS)
        result = chatter.simulate(design, **common)
        default = best(lambda: chatter.simulate(design, **common), REPEATS)
        verify = best(lambda: chatter.simulate(design, verify=True,
                                               **common), 1)
        label = name + (f", preload {preload:g} lb" if preload else "")
        say(f"| {label} | {old:.3f} s ({old / default:.2f}x) | "
            f"{default:.3f} s (1x) | {verify:.3f} s "
            f"({verify / default:.1f}x) | {result.dt:.3g}, "
            f"{result.t_end_s:.3g}, {result.energy_ratio - 1:.1e} |")
    if save:
        say.save("bench_checks", "OPENBLAS_NUM_THREADS=1 python "
                 "benchmarks/bench_checks.py " + ("--cpu " if cpu else "")
                 + "--save")


if __name__ == "__main__":
    main(save="--save" in sys.argv[1:], cpu="--cpu" in sys.argv[1:])
