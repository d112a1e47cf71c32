"""``contactsep chatter``: does the circuit open, when, for how long."""

from __future__ import annotations

import argparse
import json
import sys

from contactsep.constants import LISTING_TAU_S


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
    parser.add_argument("--t-end", type=float, default=LISTING_TAU_S,
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
        from contactsep.studies.plots import save_chatter_png
        save_chatter_png(result, args.png)
    return 0
