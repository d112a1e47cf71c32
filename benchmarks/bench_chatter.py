"""One design of the thesis rig through the chatter layer, side by side
with numpy.sin on 1e6 float64 elements, in one run (issue 16):

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_chatter.py

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

import time

import numpy as np

import contactsep
from contactsep import chatter

REPEATS = 5


def best(fn, repeats=REPEATS) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def main() -> None:
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
    print(f"numpy.sin, 1e6 float64: {sine * 1e3:.2f} ms\n")
    print(f"| {'run (thesis rig, 0-0.06 s)':32} | ms | x numpy.sin | "
          f"work |")
    print("|---|---:|---:|---|")
    for label, seconds, result in rows:
        work = ", ".join(f"{k} {v}" for k, v in result.work.items())
        print(f"| {label:32} | {seconds * 1e3:.1f} | "
              f"{seconds / sine:.2f} | {work} |")
    label, seconds, result = rows[1]
    modes = 3 * result.n_modes
    mode_steps = modes * (result.work["flight_steps"]
                          + result.work["fixed_steps"])
    print(f"\nsummary-only Hertz N = 16: {mode_steps:.3g} mode-steps, "
          f"{seconds / mode_steps * 1e9:.2f} ns each (numpy.sin: "
          f"{sine / 1e6 * 1e9:.2f} ns an element); a 1,000-design sweep: "
          f"{1000 * seconds:.1f} s on one core")


if __name__ == "__main__":
    main()
