"""Throughput of the general model (issue 11), side by side in one run.

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_model.py

Thesis design family (d from 0.1 to 1.0 in, N = 4, tau = 0.06 s):
the compiled batch, the NumPy twin, and a Python loop of the restored
core's ``contactsep.solve()`` on the equivalent deck data sets; the
time numpy.sin takes for the kernel's count of transcendental calls
(the arithmetic lower bound); and the peak memory of 1e6 designs in a
fresh process.  Prints one table; docs/performance.md quotes it.
"""

from __future__ import annotations

import resource
import subprocess
import sys
import time
import warnings

import numpy as np

import contactsep
from contactsep.model import compiled, pack, twin
from contactsep.restored import thesis_decks

#: Transcendental calls per thesis design (N = 4) in the compiled kernel
#: when nothing is shared with the previous design: mode values at 4
#: points x 4 modes x (2 exp + sin + cos) = 64; first impact ~9 safe steps
#: + 1 Newton x 4 sincos = 40; the extreme search's recurrence set-up
#: 3 x 4 = 12; two polishes (2 slopes + ~3 Newton steps + 2 sums) x 4 = 56;
#: y3(tau) 4.  Total ~176.
TRIG_UNSHARED = 176
#: ... and in a separator sweep, where the upper contact (its impact) and
#: every contact point's mode values are the previous design's: ~72.
TRIG_SHARED = 72


def best_of(fn, repeat=5):
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
    return best


def memory_of_a_million() -> float:
    """Peak RSS (MB) of evaluating 1e6 designs, in a fresh process."""
    code = (
        "import resource, numpy as np, contactsep\n"
        "d = contactsep.thesis_design(d=np.linspace(0.1, 1.0, 1_000_000))\n"
        "r = contactsep.evaluate(d)\n"
        "assert (r.status == 0).all()\n"
        "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)\n")
    out = subprocess.run([sys.executable, "-c", code], check=True,
                         capture_output=True, text=True)
    return float(out.stdout.strip())


def main() -> None:
    # the d sweep runs past d/L2 = 0.3 on purpose: no warning per design
    warnings.simplefilter("ignore", contactsep.ContactsepWarning)
    m = 100_000
    packed = pack(contactsep.thesis_design(d=np.linspace(0.1, 1.0, m)))
    t_compiled = best_of(lambda: compiled.evaluate_packed(packed)) / m
    # every design its own upper contact: nothing to share
    unshared = pack(contactsep.thesis_design(
        d=np.linspace(0.1, 1.0, m), ys=np.linspace(0.4, 0.6, m),
        x1=np.linspace(18.0, 19.0, m), x3=np.linspace(18.0, 19.0, m)))
    t_unshared = best_of(lambda: compiled.evaluate_packed(unshared)) / m
    small = pack(contactsep.thesis_design(d=np.linspace(0.1, 1.0, 5_000)))
    t_twin = best_of(lambda: twin.evaluate_packed(small), 3) / 5_000
    data_sets = [thesis_decks.thesis_data_set(d, equivalent_length=3.6)
                 for d in np.linspace(0.1, 1.0, 200)]

    def loop():
        for ds in data_sets:
            contactsep.solve(ds, "double")

    t_solve = best_of(loop, 3) / len(data_sets)
    x = np.random.default_rng(0).uniform(0, 100, 10_000_000)
    t_sin = best_of(lambda: np.sin(x)) / x.size
    rss = memory_of_a_million()
    print(f"{'what':44} {'us/design':>10} {'designs/s':>11} {'ratio':>8}")
    rows = [("compiled batch, d sweep (contactsep.model._model)", t_compiled),
            ("compiled batch, nothing shared", t_unshared),
            ("NumPy twin (contactsep.model.twin), d sweep", t_twin),
            ("Python loop of contactsep.solve(double)", t_solve),
            (f"numpy.sin x {TRIG_SHARED} (d sweep's trig count)",
             TRIG_SHARED * t_sin),
            (f"numpy.sin x {TRIG_UNSHARED} (unshared trig count)",
             TRIG_UNSHARED * t_sin)]
    for name, t in rows:
        print(f"{name:44} {t * 1e6:10.3f} {1 / t:11.0f} "
              f"{t / t_compiled:8.3g}")
    print(f"peak RSS for 1e6 designs: {rss:.0f} MB")


if __name__ == "__main__":
    main()
