"""One three-beam run of the thesis rig, N = 16, side by side (issue 8).

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_chatter.py

Compiled steppers (contactsep.chatter._chatter) over the whole 0.06 s window
against their NumPy twins timed on 1/50 of the steps (per-step cost is
constant, so the ratio is per step), and Appendix E's event-driven
solver on the rigid stop, compiled against NumPy (best of 5 each).
"""

from __future__ import annotations

import time

import numpy as np

import contactsep
import contactsep.chatter._chatter as compiled_module
from contactsep.chatter import steppers
from contactsep.chatter.contacts import HertzLaw
from contactsep.chatter.event_driven import rigid_stop_from_design
from contactsep.chatter.event_driven_compiled import (
    simulate_rigid_stop_compiled,
)
from contactsep.chatter.simulate import _stack
from contactsep.chatter.system import members

API = compiled_module.chatter_api


def timed(fn):
    start = time.perf_counter()
    fn()
    return time.perf_counter() - start


def main() -> None:
    design = contactsep.thesis_design(n_modes=16)
    m, p, h, q0, v0, _ = _stack(design)
    g0 = np.zeros(2)
    law = HertzLaw.for_materials(10.0e6)
    rows = []
    for name, dt in (("newton (Moreau-Jean)", 1e-7), ("hertz", 2e-8)):
        steps = int(round(0.06 / dt))
        stride = steps // 60_000
        samples = steps // stride + 1
        if name == "hertz":
            full = timed(lambda: API.run_hertz(
                m, p, h, g0, q0, v0, law.k, law.chi, dt, steps, stride,
                samples))
            part = timed(lambda: steppers.hertz(
                m, p, h, g0, q0, v0, law=law, dt=dt, steps=steps // 50,
                stride=stride)) * 50
        else:
            full = timed(lambda: API.run_moreau_jean(
                m, p, h, g0, q0, v0, 0.375, dt, 0.5, steps, stride,
                samples))
            part = timed(lambda: steppers.moreau_jean(
                m, p, h, g0, q0, v0, e=0.375, dt=dt, steps=steps // 50,
                stride=stride)) * 50
        rows.append((name, dt, steps, full, part))
    appe = min(timed(lambda: rigid_stop_from_design(design, t_end=0.06))
               for _ in range(5))
    appe_compiled = min(timed(lambda: rigid_stop_from_design(
        design, t_end=0.06, backend="fortran")) for _ in range(5))
    upper = members(design)[0]
    appe_events = min(timed(lambda: simulate_rigid_stop_compiled(
        upper.p, upper.x, upper.mass, upper.q0, upper.v0, 0.375, 0.06,
        segments=False)) for _ in range(5))
    print(f"{'run (N = 16, 0-0.06 s)':28} {'dt':>7} {'steps':>9} "
          f"{'compiled s':>10} {'NumPy s':>9} {'ratio':>6}")
    for name, dt, steps, full, part in rows:
        print(f"{name:28} {dt:7.0e} {steps:9d} {full:10.2f} {part:9.1f} "
              f"{part / full:6.0f}")
    print(f"{'appE event-driven':28} {'-':>7} {'-':>9} "
          f"{appe_compiled:10.4f} {appe:9.4f} {appe / appe_compiled:6.0f}")
    print(f"{'appE, events only (no replay)':28} {'-':>7} {'-':>9} "
          f"{appe_events:10.4f} {appe:9.4f} {appe / appe_events:6.0f}")


if __name__ == "__main__":
    main()
