"""The default N of `contactsep chatter` from a measured convergence
study (issue 25; docs/numerics.md, "The default N"):

    OPENBLAS_NUM_THREADS=1 nice python benchmarks/default_modes.py [--json F]

For every design of tests/design_family.py (FAMILY, and UNSEEN as the
check after the choice), elastic Hertz with the default command's
numerics (the design's own step and window, the static correction on),
N = 16, 32, 64, 128, and the reference: N = 128 at half its design step
(or the finest step the work budget allows over the window: 0.68 of it
on the thesis rigs) over the same window (a fine-step, high-N run;
N = 256 over the design's window exceeds the work budget).  Prints
the |relative difference| to the reference of the quantities that
converge (first impact, first impulse, circuit open time, the lower
contact's first lift, read at the command's default samples) and of the
largest lower gap (which does not: a chaotic rattle, docs/chatter.md),
the energy error and the seconds of each default run (a few minutes on
one loaded core).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from design_family import FAMILY, UNSEEN  # noqa: E402

from contactsep import chatter  # noqa: E402
from contactsep.chatter import numerics  # noqa: E402
from contactsep.chatter.stack import smallest_dt  # noqa: E402

MODES = (16, 32, 64, 128)
CONVERGING = ("first_impact_s", "first_impulse_lb_s", "circuit_open_s",
              "first_lift_in")
QUANTITIES = CONVERGING + ("max_lower_gap_in",)


def run(design, **options):
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = chatter.simulate(design, single_impulse=False, **options)
    return r, time.perf_counter() - start


def study(designs):
    rows = {}
    for name, design in designs.items():
        runs = {n: run(design.replace(n_modes=n)) for n in MODES}
        top, _ = runs[MODES[-1]]
        # half the step, or the finest the work budget allows
        least = smallest_dt(MODES[-1], top.t_end_s)
        reference, _ = run(design.replace(n_modes=MODES[-1]),
                           dt=max(top.dt / 2, 1.01 * least),
                           t_end=top.t_end_s)
        rows[name] = {
            "reference": {q: getattr(reference, q) for q in QUANTITIES}
            | {"dt_s": reference.dt,
               "energy_error": reference.energy_ratio - 1},
            "runs": {n: {q: numerics.relative_change(getattr(r, q),
                                                     getattr(reference, q))
                         for q in QUANTITIES}
                     | {"dt_s": r.dt, "t_end_s": r.t_end_s,
                        "energy_error": r.energy_ratio - 1,
                        "status": r.status, "seconds": seconds}
                     for n, (r, seconds) in runs.items()}}
        print(f"# {name} done", file=sys.stderr, flush=True)
    return rows


def table(rows, quantity, title):
    print(f"\n{title}\n")
    print("| design | " + " | ".join(f"N = {n}" for n in MODES) + " |")
    print("|---|" + "---|" * len(MODES))
    for name, row in rows.items():
        cells = []
        for n in MODES:
            r = row["runs"][n]
            mark = "" if abs(r["energy_error"]) <= 1e-6 else "(!)"
            cells.append(f"{r[quantity]:.1e}{mark}")
        print(f"| {name} | " + " | ".join(cells) + " |")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--json")
    args = parser.parse_args(argv)
    rows = study({**FAMILY, **UNSEEN})
    for quantity, title in (
            ("first_impact_s", "first impact"),
            ("first_impulse_lb_s", "first impulse"),
            ("circuit_open_s", "circuit open time"),
            ("first_lift_in", "first lift (the lower contact's first "
                              "swing)"),
            ("max_lower_gap_in", "largest lower gap (does not converge)")):
        table(rows, quantity, f"{title}: |relative difference| to N = "
              f"{MODES[-1]} at half its step ((!): energy off by > 1e-6)")
    print("\nthe default run: dt (s), window (s), seconds\n")
    print("| design | " + " | ".join(f"N = {n}" for n in MODES) + " |")
    print("|---|" + "---|" * len(MODES))
    for name, row in rows.items():
        print(f"| {name} | " + " | ".join(
            f"{row['runs'][n]['dt_s']:.2e}, {row['runs'][n]['t_end_s']:.3g}"
            f", {row['runs'][n]['seconds']:.2f} s" for n in MODES) + " |")
    worst = {n: max(row["runs"][n][q] for row in rows.values()
                    for q in CONVERGING) for n in MODES}
    print("\nlargest difference of a converging quantity: " + ", ".join(
        f"N = {n}: {w:.1e}" for n, w in worst.items()))
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1, default=str))


if __name__ == "__main__":
    main()
