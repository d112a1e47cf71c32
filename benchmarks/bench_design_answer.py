"""Nanoseconds a Hertz step, free and preloaded, this tree against
another (docs/performance-contact.md, "The preloaded step"):

    OPENBLAS_NUM_THREADS=1 python benchmarks/bench_design_answer.py \\
        --base-python /path/to/base/venv/bin/python [--quick]

For the designs thesis, steel_relay and becu_light of
tests/design_family.py at N = 16, 32, 64, 128 (``--quick``: N = 32),
free and with the lower contact preloaded (5 lb, or half the design's
largest preload if smaller), the default ``simulate`` (Hertz, adaptive
stepper, static correction) over the design's own window, summary only
(samples=1): the CPU time of the call (``time.process_time`` plus the
CPU time of the child a long run is forked into; best of ``--repeats``,
2 by default) over the adaptive stepper's fixed steps (``work``'s
``fixed_steps``: its flight steps are few and cheap, but the call's
Python setup counts, which is most of a free run's figure).  The
yardstick, measured in the same process: ``numpy.sin`` on 1e6 doubles,
best of 3, in ns an element; a step's cost in those elements is the
figure to compare across machines.  Then one preloaded relay run
(steel_relay, N = 32, 0.2 lb): its CPU time.

``--base-python`` runs the same measurement under another tree's
interpreter (its editable install of contactsep: e.g. a worktree of
the commit before a change) in a subprocess, one tree after the other;
without it, this tree alone.  ``--measure`` prints one tree's figures
as JSON and stops (what the subprocess runs); ``--base-json FILE`` takes
the base's figures from such a saved print instead of measuring them
(with ``--base-python``, which names the base's tree), and
``--this-json FILE`` this tree's (both measured at once on a loaded
machine, each in its own process: the CPU time counts each alone).
The output is
a markdown table: each tree's ns a step, the ratio base / this, and
this tree's ns a step in numpy.sin elements; ``--save``: also into
benchmarks/results/bench_design_answer.md (docs/performance.md quotes
it).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import subprocess
import sys
import time
import warnings

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

from results import Report  # noqa: E402

DESIGNS = ("thesis", "steel_relay", "becu_light")
SIZES = (16, 32, 64, 128)
PRELOAD_LB = 5.0
RELAY_PRELOAD_LB = 0.2


def cpu() -> float:
    """CPU seconds of this process and its waited-for children."""
    times = os.times()
    return time.process_time() + times.children_user + times.children_system


def sin_ns() -> float:
    """numpy.sin's ns an element on 1e6 doubles, best of 3."""
    import numpy as np

    x = np.random.default_rng(1).uniform(0.0, 10.0, 1_000_000)
    best = math.inf
    for _ in range(3):
        start = time.process_time()
        np.sin(x)
        best = min(best, time.process_time() - start)
    return best * 1e9 / x.size


def timed(design, preload, repeats):
    """Best CPU time (s) of the default simulate, and its work."""
    from contactsep.chatter import simulate

    best, work = math.inf, None
    for _ in range(repeats):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            start = cpu()
            r = simulate(design, model="hertz", preload=preload, samples=1,
                         single_impulse=False)
            best = min(best, cpu() - start)
        work = dict(r.work, halvings=r.numerics.get("dt_halvings", 0),
                    n_events=r.n_events)
    return best, work


def measure(sizes, repeats) -> dict:
    """This interpreter's figures (its tree's contactsep)."""
    sys.path.insert(0, os.path.join(HERE, "..", "tests"))
    from design_family import FAMILY

    try:
        from contactsep.chatter.stack import largest_preload
    except ImportError:     # the base commit's home of it
        from contactsep.chatter.simulate import largest_preload

    rows = []
    yardstick = sin_ns()
    for name in DESIGNS:
        for n in sizes:
            design = FAMILY[name].replace(n_modes=n)
            for preload in (0.0, min(PRELOAD_LB,
                                     0.5 * largest_preload(design))):
                seconds, work = timed(design, preload, repeats)
                rows.append(dict(design=name, n=n, preload=preload,
                                 seconds=seconds, **work))
    relay = FAMILY["steel_relay"].replace(n_modes=32)
    seconds, work = timed(relay, RELAY_PRELOAD_LB, repeats)
    return dict(sin_ns=min(yardstick, sin_ns()), rows=rows,
                relay=dict(seconds=seconds, **work))


def commit(path) -> str:
    try:
        return subprocess.run(
            ["git", "-C", path, "log", "-1", "--format=%h"],
            capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "?"


def tree_of(python) -> str:
    """The source tree of an interpreter's contactsep."""
    found = subprocess.run(
        [python, "-c", "import contactsep, os; "
         "print(os.path.dirname(contactsep.__file__))"],
        capture_output=True, text=True, check=True).stdout.strip()
    return os.path.normpath(os.path.join(found, "..", ".."))


def machine() -> str:
    try:
        with open("/proc/cpuinfo") as info:
            for line in info:
                if line.startswith("model name"):
                    return f"{line.split(':', 1)[1].strip()}, " \
                           f"{os.cpu_count()} cores"
    except OSError:
        pass
    return platform.processor() or platform.machine()


def ns(row) -> float:
    return row["seconds"] * 1e9 / max(row["fixed_steps"], 1)


def table(new, base) -> str:
    head = ["design", "N", "preload (lb)", "fixed steps"]
    head += ["base ns/step", "ns/step", "base/this"] if base else \
        ["ns/step"]
    head += ["in sin elements"]
    lines = ["| " + " | ".join(head) + " |",
             "|" + "|".join("---" for _ in head) + "|"]
    for i, row in enumerate(new["rows"]):
        cells = [row["design"], str(row["n"]), f"{row['preload']:.3g}",
                 f"{row['fixed_steps']:,}"]
        if base:
            old = base["rows"][i]
            cells += [f"{ns(old):.0f}", f"{ns(row):.0f}",
                      f"{ns(old) / ns(row):.2f}"]
        else:
            cells += [f"{ns(row):.0f}"]
        cells += [f"{ns(row) / new['sin_ns']:.1f}"]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base-python", help="the other tree's python")
    parser.add_argument("--quick", action="store_true", help="N = 32 only")
    parser.add_argument("--repeats", type=int, default=2)
    parser.add_argument("--base-json",
                        help="the base's saved --measure output")
    parser.add_argument("--this-json",
                        help="this tree's saved --measure output")
    parser.add_argument("--save", action="store_true",
                        help="also into benchmarks/results/")
    parser.add_argument("--measure", action="store_true",
                        help="print this tree's figures as JSON, stop")
    args = parser.parse_args()
    sizes = (32,) if args.quick else SIZES
    if args.measure:
        print(json.dumps(measure(sizes, args.repeats)))
        return 0
    base = None
    if args.base_json:
        with open(args.base_json) as saved:
            base = json.load(saved)
    elif args.base_python:
        command = [args.base_python, os.path.abspath(__file__), "--measure",
                   "--repeats", str(args.repeats)] + \
            (["--quick"] if args.quick else [])
        base = json.loads(subprocess.run(
            command, capture_output=True, text=True, check=True,
            env=dict(os.environ, OPENBLAS_NUM_THREADS="1")).stdout)
    if args.this_json:
        with open(args.this_json) as saved:
            new = json.load(saved)
    else:
        new = measure(sizes, args.repeats)
    say = Report()
    command = ("OPENBLAS_NUM_THREADS=1 python benchmarks/"
               "bench_design_answer.py"
               + (" --base-python BASE" if base else "")
               + (" --base-json BASE.json" if args.base_json else "")
               + (" --this-json THIS.json" if args.this_json else "")
               + (" --quick" if args.quick else "")
               + (" --save" if args.save else ""))
    say(f"this tree: commit {commit(os.path.join(HERE, '..'))}"
        + (f"; base (BASE): commit {commit(tree_of(args.base_python))}"
           if base and args.base_python else "") + f"; {machine()}")
    say(f"numpy.sin: {new['sin_ns']:.2f} ns an element"
        + (f" (base's process: {base['sin_ns']:.2f})" if base else ""))
    say()
    say(table(new, base))
    say()
    relay = new["relay"]
    line = (f"steel_relay, N = 32, preload {RELAY_PRELOAD_LB} lb: "
            f"{relay['seconds']:.2f} s CPU, {relay['fixed_steps']:,} fixed "
            f"steps, {ns(relay):.0f} ns a step "
            f"({ns(relay) / new['sin_ns']:.1f} sin elements)")
    if base:
        line += (f"; base {base['relay']['seconds']:.2f} s, "
                 f"{ns(base['relay']):.0f} ns a step "
                 f"({base['relay']['seconds'] / relay['seconds']:.2f}x)")
    say(line)
    halved = [f"{r['design']} N = {r['n']}" for r in new["rows"]
              if r["halvings"]]
    if halved:
        say(f"(the step was halved, and the time covers every try, in: "
            f"{', '.join(halved)})")
    if args.save:
        say.save("bench_design_answer", command)
    return 0


if __name__ == "__main__":
    sys.exit(main())
