"""Are two trees' Hertz runs the same bits?  The whole result of every
run on the design family, compared by exact equality:

    python benchmarks/step_identity.py --base-python /path/to/venv/bin/python

runs the cases under this interpreter (this tree's contactsep) and under
``--base-python`` (another tree's, e.g. the commit before a change meant
to keep every bit), each in its own subprocess, and compares.  The
cases: every design of tests/design_family.py at N = 16, 32, 64, free
and preloaded (half its largest preload, at most 5 lb), with the laws
the adaptive stepper takes: elastic Hertz, Flores's and Hunt-Crossley's
damping, with the static correction and without, Thornton's plastic law
(without it: trees before Thornton took the correction refused it), and
the cylindrical button (elastic, both).
Each run covers ``--window`` of the design's own window (0.1 by
default, so that the whole set takes minutes) with 40 samples;
``--laws`` and ``--static-only`` narrow the set (a whole-window check).

What is compared: the sampled times, gaps and energies, the contacts'
and the circuit's open intervals, the events, the first impact and
impulse, the largest lower gap, the energy ratio and book, the end
state (q, v) and the stepper's step counts.  ``--tolerance R`` also
prints, for cases that differ, the largest relative difference of the
headline figures (first impulse, open times, energy ratio) and whether
the events are the same, and fails only past R or on other events (a
change allowed to move the last bits).  ``--dump FILE`` writes one
tree's results to an .npz and stops (the subprocesses run that);
``--against FILE`` compares this tree with a saved dump instead of
running the base.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ARRAYS = ("t", "gap_upper", "gap_lower", "energy", "upper_open_intervals",
          "lower_open_intervals", "circuit_open_intervals", "events")
HEADLINE = ("first_impact_s", "first_impulse_lb_s", "circuit_open_s",
            "first_circuit_open_s", "longest_open_s", "max_lower_gap_in",
            "energy_ratio")
SCALARS = HEADLINE + ("n_events", "dt", "status")
LAWS = {
    "elastic": dict(),
    "flores": dict(damping="flores"),
    "hunt-crossley": dict(damping="hunt-crossley", alpha=0.0676),
    "thornton": dict(contact="thornton", yield_pressure=45.0e3),
    "cylinder": dict(button="cylinder"),
}


def cases(quick=False, laws=tuple(LAWS), plain=True):
    """(name, design, settings) of every case."""
    sys.path.insert(0, os.path.join(HERE, "..", "tests"))
    from design_family import FAMILY

    from contactsep.chatter.stack import largest_preload

    for name, design in FAMILY.items():
        for n in (16,) if quick else (16, 32, 64):
            sized = design.replace(n_modes=n)
            for preload in (0.0, min(5.0, 0.5 * largest_preload(sized))):
                for law in laws:
                    settings = LAWS[law]
                    for static in (True, False):
                        if (law == "thornton" and static) or (
                                law != "thornton" and not static
                                and not plain):
                            continue
                        yield (f"{name}/N{n}/P{preload:.4g}/{law}/"
                               f"{'static' if static else 'plain'}",
                               sized, dict(settings, preload=preload,
                                           static_correction=static))


def window(design) -> float:
    """The design's own window (s), as simulate chooses it."""
    from contactsep.chatter import numerics, runners
    from contactsep.chatter.stack import _stack

    m, p, h, q0, v0, parts = _stack(design)
    return numerics.design_window(runners.System(
        m=m, p=p, h=h, g0=np.zeros(2), q0=q0, v0=v0,
        n_upper=parts[0].p.size), parts)


def dump(path, fraction, quick, laws, plain):
    """Run every case in this interpreter and save its results."""
    from contactsep.chatter import simulate

    out, start = {}, time.time()
    for name, design, settings in cases(quick, laws, plain):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                r = simulate(design, model="hertz", samples=40,
                             single_impulse=False,
                             t_end=fraction * window(design), **settings)
            except Exception as error:  # a refusal must match too
                out[f"{name}|refused"] = np.array(str(error))
                continue
        for field in ARRAYS:
            out[f"{name}|{field}"] = np.asarray(getattr(r, field), float)
        for field in SCALARS:
            out[f"{name}|{field}"] = np.asarray(getattr(r, field), float)
        for key, value in sorted(r.work.items()):
            out[f"{name}|work.{key}"] = np.asarray(value, float)
        for key, value in sorted(r.energy_book.items()):
            out[f"{name}|book.{key}"] = np.asarray(value, float)
        for key, value in sorted(r.end_state.items()):
            out[f"{name}|end.{key}"] = np.asarray(value, float)
    np.savez(path, **out)
    print(f"{len({k.split('|')[0] for k in out})} cases in "
          f"{time.time() - start:.0f} s", file=sys.stderr)


def run_dump(python, path, args):
    command = [python, os.path.abspath(__file__), "--dump", path,
               "--window", repr(args.window), "--laws", args.laws] + \
        (["--quick"] if args.quick else []) + \
        (["--static-only"] if args.static_only else [])
    return subprocess.Popen(command, env=dict(
        os.environ, OPENBLAS_NUM_THREADS="1"))


def relative(a, b) -> float:
    a, b = float(a), float(b)
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def compare(base_path, new_path, tolerance) -> int:
    base, new = np.load(base_path), np.load(new_path)
    names = sorted({k.split("|")[0] for k in base.files}
                   | {k.split("|")[0] for k in new.files})
    same, differ, failed = 0, [], 0
    for name in names:
        keys = sorted({k for k in base.files if k.startswith(name + "|")}
                      | {k for k in new.files if k.startswith(name + "|")})
        odd = [k.split("|")[1] for k in keys
               if k not in base.files or k not in new.files
               or base[k].shape != new[k].shape
               or not np.array_equal(base[k], new[k], equal_nan=True)]
        if not odd:
            same += 1
            continue
        differ.append(name)
        worst = max((relative(base[f"{name}|{f}"], new[f"{name}|{f}"])
                     for f in HEADLINE if f"{name}|{f}" in base.files
                     and f"{name}|{f}" in new.files), default=math.inf)
        events = f"{name}|events" in base.files and \
            base[f"{name}|events"].shape == new[f"{name}|events"].shape
        if events:
            # the event times (and open intervals) count as headline too
            for f in ("events", "circuit_open_intervals"):
                a, b = base[f"{name}|{f}"].ravel(), new[f"{name}|{f}"].ravel()
                if a.shape == b.shape:
                    worst = max([worst] + [relative(x, y)
                                           for x, y in zip(a, b)])
        bad = tolerance is None or worst > tolerance or not events
        failed += bad
        print(f"{'FAIL' if bad else 'near'} {name}: differ in "
              f"{', '.join(odd[:6])}{' ...' if len(odd) > 6 else ''}; "
              f"headline rel {worst:.3g}, events "
              f"{'same count' if events else 'DIFFER in count'}")
    print(f"{len(names)} cases: {same} identical in every array, "
          f"{len(differ)} differ, {failed} fail")
    return 1 if failed else 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base-python", help="the other tree's python")
    parser.add_argument("--against", help="a saved dump to compare with")
    parser.add_argument("--dump", help="write this tree's results, stop")
    parser.add_argument("--save", help="keep this tree's dump here")
    parser.add_argument("--window", type=float, default=0.1,
                        help="share of each design's window (0.1)")
    parser.add_argument("--quick", action="store_true", help="N = 16 only")
    parser.add_argument("--laws", default=",".join(LAWS),
                        help=f"comma-separated, of {', '.join(LAWS)}")
    parser.add_argument("--static-only", action="store_true",
                        help="no plain-truncation runs (but Thornton's)")
    parser.add_argument("--tolerance", type=float, default=None,
                        help="allow headline figures this close (relative)")
    args = parser.parse_args()
    laws = tuple(args.laws.split(","))
    if not set(laws) <= set(LAWS):
        parser.error(f"--laws: expected some of {', '.join(LAWS)}")
    if args.dump:
        dump(args.dump, args.window, args.quick, laws, not args.static_only)
        return 0
    if not (args.base_python or args.against):
        parser.error("give --base-python or --against")
    with tempfile.TemporaryDirectory() as scratch:
        new_path = args.save or os.path.join(scratch, "new.npz")
        jobs = [run_dump(sys.executable, new_path, args)]
        base_path = args.against
        if not base_path:
            base_path = os.path.join(scratch, "base.npz")
            jobs.append(run_dump(args.base_python, base_path, args))
        if any(job.wait() != 0 for job in jobs):
            print("a dump failed", file=sys.stderr)
            return 2
        return compare(base_path, new_path, args.tolerance)


if __name__ == "__main__":
    sys.exit(main())
