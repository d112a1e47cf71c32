"""The preload search's cost: answers, simulations and CPU time of
``contactsep.preload(design)`` at its defaults (verify, the check at 4N
where the answer moves more than 2 %) on a few designs of
tests/design_family.py, for this tree and, given ``--base-python``,
for another install (another commit's code) with the same settings:

    OPENBLAS_NUM_THREADS=1 nice python benchmarks/bench_search.py \\
        [--base-python PATH] [--designs NAME:N,NAME:N] [--json F] [--save]

Each search runs in one process (workers=1), so its CPU time is the
process's and that of its finished children (a long simulation runs in
a forked child: contactsep.output.interruptible), from getrusage.  The table prints one row a design and install: the answer
(lb), the answer at 2N and half the step and the change, the
simulations (nominal, at 2N, total with the checks) and the CPU
seconds.  ``--json F`` writes the rows (strict JSON) as well;
``--save`` the table to benchmarks/results/bench_search.md, the run
docs/performance.md quotes.  ``--rows-only`` prints one install's rows
as JSON (what ``--base-python`` runs); ``--rows F`` and ``--base-rows
F`` take such rows (one JSON list a line) from earlier runs instead of
running them, the designs searched one process each, side by side.
"""

from __future__ import annotations

import argparse
import json
import math
import resource
import subprocess
import sys
import time
import warnings
from pathlib import Path

HERE = Path(__file__).resolve()
#: (design, N): small N, so that each search takes minutes on two cores.
DEFAULT_DESIGNS = "steel_relay:8,becu_light:8,thesis:4"


def _rows(designs: str, settings=None) -> list:
    """Run the searches in this process (this interpreter's install)."""
    sys.path.insert(0, str(HERE.parents[1] / "tests"))
    from design_family import FAMILY

    from contactsep.studies.preload.command import preload
    rows = []
    for item in designs.split(","):
        name, n = item.split(":")
        design = FAMILY[name].replace(n_modes=int(n))
        cpu, wall = _cpu(), time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            answer = preload(design, workers=1, **(settings or {}))
        rows.append({
            "design": name, "n_modes": int(n), "settings": settings or {},
            "min_preload_lb": _finite(answer.min_preload_lb),
            "verify_min_preload_lb": _finite(answer.verify_min_preload_lb),
            "min_preload_change": answer.min_preload_change,
            "converged": answer.converged,
            "nominal_runs": len(answer.tested),
            "verify_runs": len(answer.verify_tested),
            "simulations": answer.simulations,
            "cpu_s": _cpu() - cpu,
            "wall_s": time.perf_counter() - wall})
    return rows


def _cpu() -> float:
    """CPU seconds of this process and of its finished children."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (own.ru_utime + own.ru_stime + children.ru_utime
            + children.ru_stime)


def _read_rows(path: str) -> list:
    rows = []
    for line in Path(path).read_text().splitlines():
        if line.strip():
            rows += json.loads(line)
    return rows


def _finite(value):
    return value if isinstance(value, float) and math.isfinite(value) \
        else None


def _g(value, fmt="{:.5g}") -> str:
    return "none" if value is None else fmt.format(value)


def table(results: dict) -> str:
    """The rows of every install as a Markdown table."""
    lines = ["| design, N | code | answer (lb) | at 2N, dt/2 (lb) | change "
             "| runs at N | at 2N | all | CPU (s) |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    # each design's rows together, this tree's first
    pairs = [(label, r) for label, rows in results.items()
             for r in rows]
    order = list(dict.fromkeys((r["design"], r["n_modes"])
                               for _, r in pairs))
    pairs.sort(key=lambda lr: order.index((lr[1]["design"],
                                           lr[1]["n_modes"])))
    for label, r in pairs:
        change = r["min_preload_change"]
        given = ", ".join(f"{k} {v}" for k, v in
                          r.get("settings", {}).items())
        lines.append(
            f"| {r['design']}, {r['n_modes']}"
            f"{f' ({given})' if given else ''} | {label} | "
            f"{_g(r['min_preload_lb'])} | "
            f"{_g(r['verify_min_preload_lb'])} | "
            f"{_g(change, '{:+.2%}')} | {r['nominal_runs']} | "
            f"{r['verify_runs']} | {r['simulations']} | "
            f"{r['cpu_s']:.0f} |")
    return "\n".join(lines)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base-python", help="another install's python")
    parser.add_argument("--designs", default=DEFAULT_DESIGNS,
                        help="NAME:N,... of tests/design_family.py")
    parser.add_argument("--settings", type=json.loads, default=None,
                        help="simulate()'s keywords for every search, as "
                             "a JSON object")
    parser.add_argument("--json", help="also write the rows here")
    parser.add_argument("--save", action="store_true",
                        help="also into benchmarks/results/bench_search.md")
    parser.add_argument("--rows", help="this tree's rows, from --rows-only")
    parser.add_argument("--base-rows", help="the base's, from --rows-only")
    parser.add_argument("--rows-only", action="store_true",
                        help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.rows_only:
        print(json.dumps(_rows(args.designs, args.settings),
                         allow_nan=False))
        return
    results = {"this tree": _read_rows(args.rows) if args.rows
               else _rows(args.designs, args.settings)}
    if args.base_rows:
        results["base"] = _read_rows(args.base_rows)
    elif args.base_python:
        done = subprocess.run(
            [args.base_python, str(HERE), "--rows-only", "--designs",
             args.designs, *(["--settings", json.dumps(args.settings)]
                             if args.settings else [])], check=True, capture_output=True, text=True,
            cwd=str(HERE.parents[1]))
        results["base"] = json.loads(done.stdout.splitlines()[-1])
    sys.path.insert(0, str(HERE.parent))
    from results import Report
    say = Report()
    say(table(results))
    if args.save:
        say.save("bench_search", "OPENBLAS_NUM_THREADS=1 nice python "
                 "benchmarks/bench_search.py " + " ".join(
                     sys.argv[1:] if argv is None else argv))
    if args.json:
        text = json.dumps(results, allow_nan=False, indent=1)
        Path(args.json).write_text(text + "\n")


if __name__ == "__main__":
    main()
