"""``contactsep modes``: one member's frequencies and mode values at its
contact point, for any beam theory, supports and added mass."""

from __future__ import annotations

import argparse
import sys

from contactsep import output
from contactsep.cli.design_options import add_design_options, design_overrides
from contactsep.cli.help import examples

EXAMPLES = examples(
    "contactsep modes --member 2 --beam2 timoshenko --d 0.75 --json",
    "contactsep modes --member 2 --kr2 2000 --mass2 0.015 --count 3",
    "contactsep modes --member 1 --beam1 timoshenko --csv")


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep modes``."""
    parser = commands.add_parser(
        "modes", help="one member's frequencies and mode values at its "
                      "contact point (any beam theory, supports, masses)",
        description="The first K normal modes of member 1 (upper "
                    "contact), 2 (separator) or 3 (lower contact): p_j "
                    "(rad/s), f_j (cps) and X_j at the contact point, "
                    "with the design's beam theory (--beam2 timoshenko), "
                    "elastic supports (--kr2, --kt2) and point mass "
                    "(--mass2, --x-mass2).",
        **EXAMPLES)
    parser.add_argument("--member", type=int, choices=(1, 2, 3),
                        required=True, help="1, 2 or 3")
    parser.add_argument("--count", type=int, default=None, metavar="K",
                        help="modes (default: the design's n_modes)")
    form = parser.add_mutually_exclusive_group()
    form.add_argument("--json", action="store_true",
                      help="a JSON object (keys p_rad_s, f_hz, X_contact)")
    form.add_argument("--csv", action="store_true",
                      help="CSV: j, p_rad_s, f_hz, X at the contact point "
                         "(and X_lower at --x2-lower on member 2)")
    add_design_options(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from contactsep.model import thesis_design
    from contactsep.model.member_modes import modes
    from contactsep.model.fields import describe

    overrides = design_overrides(args)
    design = thesis_design(**overrides)
    result = modes(design, args.member, args.count)
    if args.json:
        data = {"design": describe(overrides), **result.to_json_dict()}
        output.write_json(sys.stdout, data)
        return 0
    lower = len(result.x_in) > 1
    point = f"x = {result.x_in[0]:.6g} in" + (
        f" (upper contact), x2_lower = {result.x_in[1]:.6g} in (lower "
        f"contact)" if lower else "")
    if args.csv:
        lines = [f"# contactsep modes: member {result.member} "
                 f"({result.theory}), contact point {point}",
                 "j,p_rad_s,f_hz,X_contact" + (",X_lower" if lower else "")]
        lines += [",".join([str(j + 1), repr(p), repr(f)]
                           + [repr(x) for x in row])
                  for j, (p, f, row) in enumerate(zip(
                      result.p_rad_s.tolist(), result.f_hz.tolist(),
                      result.values.tolist()))]
        output.write_text(sys.stdout, "\n".join(lines) + "\n")
        return 0
    print(f"member {result.member} ({result.theory}), contact point "
          f"{point}")
    print(f"{'j':>3} {'p_rad_s':>14} {'f_hz':>12} {'X_contact':>12}"
          + (f" {'X_lower':>12}" if lower else ""))
    for j, (p, f, row) in enumerate(zip(result.p_rad_s, result.f_hz,
                                        result.values)):
        print(f"{j + 1:>3} {p:>14.7g} {f:>12.7g} "
              + " ".join(f"{x:>12.6g}" for x in row))
    return 0
