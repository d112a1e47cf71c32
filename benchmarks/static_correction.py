"""Convergence in N of the Hertz chatter answers with and without the
static correction (docs/static-correction.md).

For every design of tests/design_family.py's FAMILY (and the steel relay
preloaded as in issue 25) and N = 4 ... 256 modes per member, the
adaptive Hertz stepper (elastic) with ``static_correction`` off (the
plain N-mode truncation) and on; prints, per design, the first impulse,
the largest lower gap and the circuit's open time, each with its
relative difference to the corrected run at the largest N, and the
energy error |energy_ratio - 1| of every run.

Steps: 5e-8 s on the thesis rigs (the converged default there), 1e-8 s
on the relays (5e-8 s is unstable on their stiff contacts, issue 25),
halved at N = 128 and quartered at N = 256 (with N the contact point's
modal mass shrinks, ~M / 4N, and the contact's frequency grows: at 5e-8
s the thesis rig's N = 256 runs lost 2e-3 of their energy);
windows: 0.06 s (the thesis's) and 0.02 s (several periods of a relay
contact's first mode after its first impact).  Run it niced:

    nice python benchmarks/static_correction.py --json out.json

(about 2 minutes on one core).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))

from design_family import FAMILY  # noqa: E402

from contactsep.chatter import simulate  # noqa: E402

MODES = (4, 8, 16, 32, 64, 128, 256)
QUANTITIES = (("first_impulse_lb_s", "first impulse (lb s)"),
              ("max_lower_gap_in", "largest lower gap (in)"),
              ("circuit_open_s", "circuit open time (s)"))


def cases():
    """(label, design, preload lb, dt s, window s) of the study."""
    out = []
    for name, design in FAMILY.items():
        thesis = name.startswith("thesis")
        out.append((name, design, 0.0, 5e-8 if thesis else 1e-8,
                    0.06 if thesis else 0.02))
    out.append(("steel_relay+0.35lb", FAMILY["steel_relay"], 0.35, 1e-8,
                0.02))
    return out


def step(dt, n) -> float:
    """The case's step at N modes (see the module doc)."""
    return dt / max(1, n // 64)


def run(design, n, correction, preload, dt, t_end) -> dict:
    start = time.perf_counter()
    dt = step(dt, n)
    r = simulate(design.replace(n_modes=n), model="hertz", dt=dt,
                 t_end=t_end, preload=preload, samples=1000,
                 single_impulse=False, static_correction=correction)
    return {"first_impulse_lb_s": r.first_impulse_lb_s,
            "max_lower_gap_in": r.max_lower_gap_in,
            "circuit_open_s": r.circuit_open_s,
            "energy_error": abs(r.energy_ratio - 1.0),
            "seconds": time.perf_counter() - start}


def relative(value, reference) -> str:
    if not (math.isfinite(value) and math.isfinite(reference)):
        return "-"
    if reference == 0.0:
        return "0" if value == 0.0 else "inf"
    return f"{(value - reference) / abs(reference):+.1e}"


def table(label, rows, modes) -> list[str]:
    """Markdown table of one case: each quantity plain / corrected and
    its relative difference to the corrected run at the largest N."""
    reference = rows[(modes[-1], True)]
    lines = [f"#### {label}", "",
             "| N | " + " | ".join(
                 f"{title} plain | corrected" for _, title in QUANTITIES)
             + " | energy error plain / corrected |",
             "|---" * (2 + 2 * len(QUANTITIES)) + "|"]
    for n in modes:
        plain, fixed = rows[(n, False)], rows[(n, True)]
        cells = []
        for key, _ in QUANTITIES:
            for r in (plain, fixed):
                cells.append(f"{r[key]:.6g} ({relative(r[key], reference[key])})")
        cells.append(f"{plain['energy_error']:.0e} / "
                     f"{fixed['energy_error']:.0e}"
                     + (" (!)" if max(plain['energy_error'],
                                      fixed['energy_error']) > 1e-6
                        else ""))
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    lines.append("")
    return lines


def summary(raw) -> list[str]:
    """Per quantity, one row per case: |relative difference| to the
    corrected run at the largest N, plain / corrected, per N; (!) where a
    run's energy error exceeds 1e-6 (that run is not converged in dt)."""
    lines = []
    for key, title in QUANTITIES:
        modes = None
        body = []
        for label, case in raw.items():
            rows = {(r["n_modes"], r["static_correction"]): r
                    for r in case["rows"]}
            modes = sorted({n for n, _ in rows})
            reference = rows[(modes[-1], True)][key]
            cells = []
            for n in modes[:-1]:
                pair = []
                for correction in (False, True):
                    r = rows[(n, correction)]
                    value = r[key]
                    text = "-" if not (math.isfinite(value) and
                                       math.isfinite(reference)
                                       and reference != 0.0) \
                        else f"{abs(value - reference) / abs(reference):.0e}"
                    if r["energy_error"] > 1e-6:
                        text += "(!)"
                    pair.append(text)
                cells.append(" / ".join(pair))
            body.append(f"| {label} | " + " | ".join(cells) + " |")
        lines += [f"{title}: |relative difference| to the corrected "
                  f"N = {modes[-1]}, plain / corrected", "",
                  "| case | " + " | ".join(f"N = {n}" for n in modes[:-1])
                  + " |", "|---" * len(modes) + "|", *body, ""]
    return lines


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n-max", type=int, default=256)
    parser.add_argument("--only", default=None,
                        help="comma-separated case labels")
    parser.add_argument("--json", default=None, help="raw results")
    parser.add_argument("--from-json", default=None,
                        help="print the summary of earlier raw results "
                             "instead of running")
    args = parser.parse_args(argv)
    if args.from_json:
        print("\n".join(summary(json.loads(Path(args.from_json)
                                             .read_text()))))
        return 0
    modes = tuple(n for n in MODES if n <= args.n_max)
    chosen = None if args.only is None else set(args.only.split(","))
    raw = {}
    for label, design, preload, dt, t_end in cases():
        if chosen is not None and label not in chosen:
            continue
        rows = {(n, c): run(design, n, c, preload, dt, t_end)
                for n in modes for c in (False, True)}
        raw[label] = {"dt_s": dt, "t_end_s": t_end, "preload_lb": preload,
                      "rows": [{"n_modes": n, "static_correction": c, **r}
                               for (n, c), r in rows.items()]}
        print("\n".join(table(f"{label} (dt {dt:g} s to N = 64, window "
                              f"{t_end:g} s"
                              + (f", preload {preload:g} lb" if preload
                                 else "") + ")", rows, modes)),
              flush=True)
    print("\n".join(summary(raw)))
    if args.json:
        Path(args.json).write_text(json.dumps(raw, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
