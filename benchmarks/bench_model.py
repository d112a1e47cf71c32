"""Throughput of the general model (issues 11 and 17), side by side in one
run.

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_model.py [--cpu]
        [--targets-only] [--save]

--cpu times by CPU time (user + system of this process and of the
children it waited for: a long design is evaluated in a forked child)
instead of the wall clock, which other processes on a shared machine
disturb less; --targets-only runs issue 17's table
alone; --save writes what it printed to benchmarks/results/bench_model.md
(the run docs/performance.md quotes).

Issue 17's targets: the compiled batch on random designs against the
bound of 38 N numpy.sin element evaluations per design, numpy.sin timed
on 1e6 float64 elements in the same run, interleaved with the kernel and
the best of several rounds kept for each.  "Random designs" are the
thesis rig with the separator thickness, y_s and both contact points
drawn at random (no design shares work with the previous one), N = 4 and
N = 32, tau = 0.06 s; the wide family of the tests (every end condition,
lengths, thicknesses and materials at random, contacts anywhere) is
timed beside them as a harder case.

Issue 11's table: the thesis design family (d from 0.1 to 1.0 in, N = 4):
the compiled batch, with nothing shared, the NumPy twin, a Python loop of
the restored core's solve(), and the peak memory of 1e6 designs in a
fresh process.  docs/performance.md quotes both tables.

The limits: one design of the thesis rig (a batch of one, in process) at
N = 800, 1600 and 3200 modes (tau = 0.06 s), and at N = 4 with windows
tau = 1e4 and 1e5 s: what docs/model.md's "Limits" call seconds.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
import warnings

import numpy as np
from bench_chatter import cpu_time  # this folder: run as a script
from results import Report

import contactsep
from contactsep import beams
from contactsep.model import compiled, pack, twin
from contactsep.restored import thesis_decks

ROUNDS = 7
#: The clock of every measurement (main() may switch it to CPU time).
clock = time.perf_counter
#: Prints, and keeps what it printed for --save.
say = Report()


def best_of(fn, repeat=5):
    best = float("inf")
    for _ in range(repeat):
        start = clock()
        fn()
        best = min(best, clock() - start)
    return best


def thesis_random(m, n, seed=3):
    """The thesis rig with d, y_s, x1, x3 at random (nothing shared)."""
    rng = np.random.default_rng(seed)
    return contactsep.thesis_design(
        d=rng.uniform(0.1, 1.0, m), ys=rng.uniform(0.4, 0.6, m),
        x1=rng.uniform(18.0, 19.0, m), x3=rng.uniform(18.0, 19.0, m),
        n_modes=n)


def wide_random(m, n, seed=5):
    """Every member's end condition, size and material at random, contact
    points anywhere on it (tests/model/test_model_compiled.py's family)."""
    rng = np.random.default_rng(seed)
    ends = np.array(beams.END_CONDITIONS)

    def u(lo, hi):
        return rng.uniform(lo, hi, m)

    fields = {}
    for i, (length, width, thick) in (
            ("1", ((5, 25), (0.5, 3), (0.05, 0.3))),
            ("2", ((1, 5), (0.2, 1), (0.1, 0.8))),
            ("3", ((5, 25), (0.5, 3), (0.05, 0.3)))):
        size = u(*length)
        fields.update({"L" + i: size, "b" + i: u(*width), "h" + i: u(*thick),
                       "gamma" + i: u(0.05, 0.35), "E" + i: u(5e6, 3e7),
                       "end" + i: ends[rng.integers(0, 4, m)],
                       "x" + i: size * u(0.5, 1.0)})
    return contactsep.Design(**fields, ys=u(0.05, 1.0), e=u(0.0, 1.0),
                             n_modes=n, tau=0.06, release="contact")


def targets() -> None:
    """Issue 17: the kernel per design over the 38 N numpy.sin bound."""
    x = np.random.default_rng(0).uniform(0, 100, 1_000_000)
    batches = {}
    for n, m in ((4, 20_000), (32, 4_000)):
        batches[("thesis-like", n)] = pack(thesis_random(m, n))
        batches[("wide", n)] = pack(wide_random(m // 4, n))
    best = {key: float("inf") for key in batches}
    t_sin = float("inf")
    for _ in range(ROUNDS):
        t_sin = min(t_sin, best_of(lambda: np.sin(x), 1) / x.size)
        for key, packed in batches.items():
            t = best_of(lambda: compiled.evaluate_packed(packed), 1)
            best[key] = min(best[key], t / packed.size)
    say(f"numpy.sin: {t_sin * 1e9:.2f} ns an element (1e6 float64)")
    say()
    say("| random designs | N | us/design | bound (us) | ratio |")
    say("|---|---:|---:|---:|---:|")
    for (family, n), t in best.items():
        bound = 38 * n * t_sin
        say(f"| {family} | {n} | {t * 1e6:.2f} | {bound * 1e6:.2f} | "
            f"{t / bound:.2f} |")


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


def family_table() -> None:
    """Issue 11: the thesis design family, every path side by side."""
    m = 100_000
    packed = pack(contactsep.thesis_design(d=np.linspace(0.1, 1.0, m)))
    t_compiled = best_of(lambda: compiled.evaluate_packed(packed)) / m
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
    rss = memory_of_a_million()
    say("| what | us/design | designs/s | ratio |")
    say("|---|---:|---:|---:|")
    rows = [("compiled batch, d sweep (contactsep.model._model)", t_compiled),
            ("compiled batch, nothing shared", t_unshared),
            ("NumPy twin (contactsep.model.twin), d sweep", t_twin),
            ("Python loop of contactsep.solve(double)", t_solve)]
    for name, t in rows:
        say(f"| {name} | {t * 1e6:.3f} | {1 / t:,.0f} | "
            f"{t / t_compiled:.3g} |")
    say()
    say(f"peak RSS for 1e6 designs: {rss:.0f} MB")


def limits() -> None:
    """One design at many modes and over long windows (seconds each)."""
    say("| one thesis design | s | status |")
    say("|---|---:|---:|")
    for label, fields in (("N = 800", {"n_modes": 800}),
                          ("N = 1600", {"n_modes": 1600}),
                          ("N = 3200", {"n_modes": 3200}),
                          ("N = 4, tau = 1e4 s", {"tau": 1e4}),
                          ("N = 4, tau = 1e5 s", {"tau": 1e5})):
        design = contactsep.thesis_design(**fields)
        status = []
        t = best_of(lambda: status.append(
            int(contactsep.evaluate(design).status)), 1)
        say(f"| {label} | {t:.2f} | {status[0]} |")


def main() -> None:
    global clock
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cpu", action="store_true",
                        help="time by process CPU time, not wall clock")
    parser.add_argument("--targets-only", action="store_true",
                        help="only issue 17's table")
    parser.add_argument("--save", action="store_true",
                        help="also write benchmarks/results/bench_model.md")
    args = parser.parse_args()
    if args.cpu:
        # a design of seconds is evaluated in a forked child: its CPU
        # time counts too
        clock = cpu_time
    say(f"clock: {'process CPU time' if args.cpu else 'wall'}")
    # the d sweep runs past d/L2 = 0.3 on purpose: no warning per design
    warnings.simplefilter("ignore", contactsep.ContactsepWarning)
    targets()
    if not args.targets_only:
        say()
        family_table()
        say()
        limits()
    if args.save:
        options = " ".join(a for a in sys.argv[1:])
        say.save("bench_model", f"OPENBLAS_NUM_THREADS=1 python "
                 f"benchmarks/bench_model.py {options}")


if __name__ == "__main__":
    main()
