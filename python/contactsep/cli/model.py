"""``contactsep model``: one design's labelled results."""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np

from contactsep.errors import InputError

#: (attribute, label, unit) of the printed results, in order.
RESULTS = (
    ("t1", "first impact after release", "s"),
    ("v_impact", "impact speed of the upper contact", "in/s"),
    ("psi", "impulse", "lb s"),
    ("v0", "separator velocity after the impact", "in/s"),
    ("R", "mass ratio (eq. 24)", "-"),
    ("y3_max", "largest lower-contact separation", "in"),
    ("t_max", "its time after the impact", "s"),
    ("y3_min", "smallest lower-contact displacement", "in"),
    ("t_min", "its time after the impact", "s"),
    ("M1", "upper contact mass", "lb s^2/in"),
    ("M2", "separator mass", "lb s^2/in"),
    ("M3", "lower contact mass", "lb s^2/in"),
)

#: Design fields settable from the command line: option, field, type.
_FIELDS = [("--d", "h2", float), ("--x1", "x1", float),
           ("--x2", "x2", float), ("--x3", "x3", float),
           ("--ys", "ys", float), ("--e", "e", float),
           ("--tau", "tau", float), ("--gap", "gap", float),
           ("--Lc", "Lc", float),
           ("--end1", "end1", str), ("--end2", "end2", str),
           ("--end3", "end3", str)]
for _member in "123":
    for _name in ("L", "b", "h", "gamma", "E"):
        _FIELDS.append((f"--{_name}{_member}", _name + _member, float))


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep model``."""
    parser = commands.add_parser(
        "model", help="evaluate the general model (eq. 23) for one design",
        description="Evaluate the thesis's general model for the thesis "
                    "experiment with any field changed. Units: in, lb, s; "
                    "densities lb/in^3; E psi. x1, x2, x3 are contact "
                    "points in inches from each member's first end "
                    "(defaults: tip, mid-span, tip).")
    seen = set()
    for option, field, kind in _FIELDS:
        if field in seen:
            continue
        seen.add(field)
        parser.add_argument(option, dest=field, type=kind, default=None,
                            metavar=field.upper() if kind is float else None)
    parser.add_argument("--n-modes", type=int, default=None,
                        help="modes per member (default 4)")
    parser.add_argument("--impact-velocity", choices=("exact", "listing"))
    parser.add_argument("--lower-response", choices=("as-printed",
                                                     "impulse"))
    parser.add_argument("--lc-reading", choices=("listing", "frequencies",
                                                 "mass"))
    parser.add_argument("--release", choices=("tip", "contact"))
    parser.add_argument("--backend", choices=("compiled", "numpy"),
                        default="compiled")
    parser.add_argument("--json", action="store_true",
                        help="print a JSON object instead of a table")
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """Evaluate and print; status other than 0 is an error (exit 2)."""
    from contactsep.model import evaluate, status, thesis_design

    overrides = {field: getattr(args, field) for _, field, _ in _FIELDS
                 if getattr(args, field, None) is not None}
    for option in ("n_modes", "impact_velocity", "lower_response",
                   "lc_reading", "release"):
        if getattr(args, option) is not None:
            overrides[option] = getattr(args, option)
    result = evaluate(thesis_design(**overrides), backend=args.backend)
    code = int(result.status)
    if code != status.OK:
        raise InputError(status.MESSAGES[code])
    if args.json:
        data = {name: float(getattr(result, name)) for name, _, _ in RESULTS}
        data["at_window_end"] = bool(result.at_window_end)
        data["t_max_tied"] = bool(result.t_max_tied)
        data["t_min_tied"] = bool(result.t_min_tied)
        for key in ("p1", "p2", "p3", "c3"):
            data[key] = np.asarray(getattr(result, key)).tolist()
        json.dump(data, sys.stdout, indent=2)
        sys.stdout.write("\n")
        return 0
    for name, label, unit in RESULTS:
        print(f"{name:>8} = {float(getattr(result, name)):14.6e}  {unit:<10}"
              f" {label}")
    if result.at_window_end:
        print("warning: the largest separation is at the end of the window "
              "(increase --tau)", file=sys.stderr)
    for name in ("max", "min"):
        if getattr(result, f"t_{name}_tied"):
            print(f"note: a later peak comes within 1e-12 of y3_{name}; "
                  f"t_{name} is the earliest", file=sys.stderr)
    return 0
