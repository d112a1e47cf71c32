"""``contactsep model``: one design's labelled results."""

from __future__ import annotations

import argparse
import sys
import warnings

import numpy as np

from contactsep import output
from contactsep.cli.design_options import add_design_options, design_overrides
from contactsep.cli.help import examples
from contactsep.cli.unit_system import in_units
from contactsep.errors import ContactsepWarning, InputError
from contactsep.model.design_file import NUMERICS
from contactsep.model.names import (
    FLAGS,
    PER_MODE,
    RESULTS,
    si_key,
    si_unit,
)

EXAMPLES = examples(
    "contactsep model --x3 14.82 --n-modes 20           # contact at 0.78 L3",
    "contactsep model --d 0.5 --restitution 0.2 --json  # keys with units",
    "contactsep model --json > my.json && contactsep model --design my.json "
    "--end2 pinned-pinned")


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep model``."""
    parser = commands.add_parser(
        "model", help="evaluate the general model (eq. 23) for one design",
        description="Evaluate the thesis's general model for the thesis "
                    "experiment with any field changed. Units: in, lb, s; "
                    "densities lb/in^3; E psi. x1, x2, x3 are contact "
                    "points in inches from each member's first end "
                    "(defaults: tip, mid-span, tip).",
        **EXAMPLES)
    add_design_options(parser)
    parser.add_argument("--backend", choices=("compiled", "numpy"),
                        default="compiled",
                        help="compiled: the Fortran batch (default); "
                             "numpy: its NumPy twin")
    parser.add_argument("--json", action="store_true",
                        help="print a JSON object (the design and every "
                             "result, each key with its unit) instead of "
                             "a table")
    parser.set_defaults(handler=run)
    # the model layer's other command: one member's modes (issue 27)
    from contactsep.cli import modes
    modes.register(commands)


def results_dict(design, result, numerics=()) -> dict:
    """The design (its design file's object, the form --design and
    contactsep.load_design read back: n_modes only where named in
    ``numerics``, the fields given) and every result under a key that
    carries its unit."""
    from contactsep.model.design_file import file_fields
    data = {"design": file_fields(design, numerics)}
    for name, key, _, _ in RESULTS:
        data[key] = float(getattr(result, name))
    for name, key in FLAGS:
        value = getattr(result, name)
        data[key] = int(value) if name == "status" else bool(value)
    counts = design.n_modes if isinstance(design.n_modes, tuple) \
        else (design.n_modes,) * 3
    for name, key, member in PER_MODE:
        # the batch pads every member to the largest N: its own N only
        data[key] = np.asarray(getattr(result, name))[
            :int(counts[member])].tolist()
    return data


def run(args: argparse.Namespace) -> int:
    """Evaluate and print; status other than 0 is an error (exit 2)."""
    from contactsep.model import evaluate, status, thesis_design

    overrides = design_overrides(args)
    design = thesis_design(**overrides)
    result = evaluate(design, backend=args.backend)
    code = int(result.status)
    if code != status.OK:
        problems = design.problems()
        raise InputError(problems[0] if problems else
                         status.explain(code, design))
    if result.at_window_end:
        warnings.warn("the largest separation is at the end of the window "
                      "(increase --tau)", ContactsepWarning)
    for name in ("max", "min"):
        if bool(getattr(result, f"t_{name}_tied")):
            warnings.warn(f"a later peak comes within 1e-12 of y3_{name}: "
                          f"t_{name} is the earliest", ContactsepWarning)
    if args.json:
        # n_modes only where asked for (issue 49): a file from --json
        # would otherwise fix a simulation's N at eq. 23's default
        output.write_json(sys.stdout, in_units(results_dict(
            design, result, numerics=[n for n in NUMERICS
                                      if n in overrides]), args))
        return 0
    si = getattr(args, "units", "us") == "si"
    for name, key, unit, label in RESULTS:
        value = float(getattr(result, name))
        if si and si_key(key) is not None:
            (key, factor), unit = si_key(key), si_unit(key)
            value *= factor
        print(f"{key:>13} = {value:<13.6g} {unit:<10} {label}")
    return 0
