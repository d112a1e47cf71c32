"""``contactsep chatter``: does the circuit open, when, for how long."""

from __future__ import annotations

import argparse
import json
import sys


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep chatter``."""
    parser = commands.add_parser(
        "chatter", help="simulate repeated impacts and circuit opening",
        description="Simulate the thesis rig (any field changed) from the "
                    "release: Appendix E against a rigid separator (appE), "
                    "the three beams with Newton's impact law by "
                    "Moreau-Jean (newton), or with Hertz contact (hertz). "
                    "Prints when and for how long the circuit opens.")
    parser.add_argument("--d", type=float, default=0.25,
                        help="separator thickness (in)")
    parser.add_argument("--n-modes", type=int, default=4)
    parser.add_argument("--model", choices=("appE", "newton", "hertz"),
                        default="newton")
    parser.add_argument("--damping", choices=("none", "flores"),
                        default="none", help="Hertz damping")
    parser.add_argument("--dt", type=float, default=None,
                        help="time step (s); default per model")
    parser.add_argument("--t-end", type=float, default=0.060,
                        help="window from the release (s)")
    parser.add_argument("--e", type=float, default=None,
                        help="coefficient of restitution (thesis: 0.375)")
    parser.add_argument("--ys", type=float, default=None,
                        help="release height above the separator (in)")
    parser.add_argument("--preload", type=float, default=0.0,
                        help="force pressing the lower contact against "
                             "the separator at the start (lb; default 0)")
    parser.add_argument("--json", action="store_true")
    parser.add_argument("--png", metavar="FILE",
                        help="plot both gaps, open-circuit intervals shaded")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from contactsep.chatter import simulate
    from contactsep.model import thesis_design

    overrides = {k: getattr(args, k) for k in ("e", "ys")
                 if getattr(args, k) is not None}
    design = thesis_design(d=args.d, n_modes=args.n_modes, **overrides)
    result = simulate(design, model=args.model, damping=args.damping,
                      dt=args.dt, t_end=args.t_end, preload=args.preload)
    summary = result.to_json_dict()
    if args.json:
        json.dump(summary, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        lists = ("circuit_open_intervals", "impacts", "rest_intervals")
        for key, value in summary.items():
            if key not in lists:
                print(f"{key:>22} = {value}")
        print(f"{'open intervals':>22} = "
              f"{len(result.circuit_open_intervals)}")
        for key in lists[1:]:
            if key in summary:
                print(f"{key:>22} = {len(summary[key])} (--json lists "
                      f"them)")
    if args.png:
        plot(result, args.png)
    return 0


def plot(result, path: str) -> None:
    """Both gaps against time, the open-circuit intervals shaded."""
    from contactsep.studies.plots import _pyplot

    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 4.0), dpi=80)
    ax.plot(result.t, result.gap_upper, lw=0.8, label="upper gap")
    ax.plot(result.t, result.gap_lower, lw=0.8, label="lower gap")
    for start, end in result.circuit_open_intervals:
        ax.axvspan(start, end, color="red", alpha=0.15, lw=0)
    ax.set(xlabel="time from release (s)", ylabel="gap (in)",
           title=f"{result.model}, N = {result.n_modes}: circuit open "
                 f"{result.circuit_open_s * 1e3:.2f} ms (shaded)")
    ax.legend(fontsize=8)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
