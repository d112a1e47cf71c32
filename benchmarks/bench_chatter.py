"""One design of the thesis rig through the chatter layer, side by side
with numpy.sin on 1e6 float64 elements, in one run (issue 16):

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_chatter.py [--cpu] [--save]

(``--cpu``: time by the CPU time of the process and its children, which
the other processes of a shared machine disturb less than the wall
clock; ``--save``: also into
benchmarks/results/bench_chatter.md, the run docs/performance.md
quotes.)

Every time is the best of REPEATS in-process calls of
``contactsep.chatter.simulate`` (the whole call: design, modes, the
single-impulse figures, the stepper, the circuit) and is printed with
its ratio to numpy.sin.  The adaptive steppers are the defaults; the
fixed-step ones are the references they are tested against.  The last
column counts the work: flight steps, fixed steps and flow evaluations
of the searches (adaptive), or steps (fixed).  Every run takes the
thesis's window (0.06 s) and, unless it names one, the thesis's step
(5e-8 s), given: the settings these figures were first measured with
("default" in a label means the default stepper; the design's own step
and window, issue 25: benchmarks/bench_checks.py).
"""

from __future__ import annotations

import resource
import sys
import time

import numpy as np
from results import Report  # this folder: run as a script

import contactsep
from contactsep import chatter

REPEATS = 5
#: The clock of every measurement (--cpu: cpu_time).
clock = time.perf_counter


def cpu_time() -> float:
    """CPU seconds of this process and of its finished children (a long
    simulation runs in a forked child: contactsep.output.interruptible),
    to the microsecond (getrusage)."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (own.ru_utime + own.ru_stime + children.ru_utime
            + children.ru_stime)


def best(fn, repeats=REPEATS) -> float:
    times = []
    for _ in range(repeats):
        start = clock()
        fn()
        times.append(clock() - start)
    return min(times)


def main(save: bool = False, cpu: bool = False) -> None:
    global clock
    if cpu:
        clock = cpu_time
    say = Report()
    say(f"clock: {'process CPU time' if cpu else 'wall'}")
    x = np.random.default_rng(0).random(1_000_000)
    sine = best(lambda: np.sin(x), 20)
    rows = []

    def case(label, design, repeats=REPEATS, **options):
        options = {"t_end": 0.06, **options}
        if options.get("model") != "appE":
            options.setdefault("dt", 5e-8)
        result = chatter.simulate(design, **options)
        seconds = best(lambda: chatter.simulate(design, **options),
                       repeats)
        rows.append((label, seconds, result))

    rig16 = contactsep.thesis_design(n_modes=16)
    rig32 = contactsep.thesis_design(n_modes=32)
    case("hertz N=16 (default)", rig16, model="hertz")
    case("hertz N=16, summary only", rig16, model="hertz", samples=1)
    # the static correction (default since issue 28) is the Hertz law's
    # largest cost: the same runs without it
    case("hertz N=16, no static correction", rig16, model="hertz",
         static_correction=False)
    case("hertz N=16, summary, no static corr.", rig16, model="hertz",
         samples=1, static_correction=False)
    case("hertz N=16, preload 0.1 lb", rig16, model="hertz", preload=0.1)
    case("hertz N=32 (default)", rig32, model="hertz")
    case("hertz N=16 fixed-step", rig16, 1, model="hertz",
         stepper="fixed")
    case("newton N=16 (default)", rig16, model="newton")
    case("newton N=32 d=0.75 (default)",
         contactsep.thesis_design(n_modes=32, d=0.75), model="newton")
    case("newton N=16 Moreau-Jean 1e-7", rig16, 1, model="newton",
         stepper="fixed", dt=1e-7)
    case("appE N=16", rig16, model="appE")
    say(f"numpy.sin, 1e6 float64: {sine * 1e3:.2f} ms\n")
    say(f"| {'run (thesis rig, 0-0.06 s)':36} | ms | x numpy.sin | "
        f"work |")
    say("|---|---:|---:|---|")
    for label, seconds, result in rows:
        work = ", ".join(f"{k} {v}" for k, v in result.work.items())
        say(f"| {label:36} | {seconds * 1e3:.1f} | "
            f"{seconds / sine:.2f} | {work} |")
    label, seconds, result = rows[1]
    modes = 3 * result.n_modes
    mode_steps = modes * (result.work["flight_steps"]
                          + result.work["fixed_steps"])
    say(f"\nsummary-only Hertz N = 16: {mode_steps:.3g} mode-steps, "
        f"{seconds / mode_steps * 1e9:.2f} ns each (numpy.sin: "
        f"{sine / 1e6 * 1e9:.2f} ns an element); a 1,000-design sweep: "
        f"{1000 * seconds:.1f} s on one core")
    if save:
        say.save("bench_chatter",
                 "OPENBLAS_NUM_THREADS=1 python benchmarks/bench_chatter.py "
                 + ("--cpu " if cpu else "") + "--save")


if __name__ == "__main__":
    main(save="--save" in sys.argv[1:], cpu="--cpu" in sys.argv[1:])
