"""``--units us|si`` on the commands that take design options: the unit
system of the command line's bare numbers and of every output
(docs/names-and-units.md).

With ``si`` a bare number is read in m, N, s, Pa, kg/m^3 (a value typed
with its unit is read as typed), and every key of the JSON with a unit
suffix becomes its SI twin (:data:`contactsep.model.names.SI_SUFFIXES`,
the one table); the text, CSV, Parquet, PNG and HTML outputs of the
commands that take it show SI too (``model.names.units_shown``).  The
other commands (the thesis's studies, the restored program) refuse it
in one line.  With the default ``us`` nothing changes.
"""

from __future__ import annotations

import argparse

from contactsep.errors import InputError

#: --units: the unit system of the command line's bare numbers.
UNIT_SYSTEMS = ("us", "si")
#: The commands whose outputs --units si converts (text and --json).
SI_COMMANDS = ("model", "chatter", "preload", "sweep", "report")
#: An option's unit as printed -> its suffix in names.SI_SUFFIXES.
_PRINTED = {"in": "in", "s": "s", "lb": "lb", "psi": "psi",
            "lb/in^3": "lb_in3", "s/in": "s_per_in", "lb s": "lb_s",
            "in/s": "in_s"}


def si_shown(value, unit: str, si: bool):
    """A number shown in the text with its printed unit ('in', 'lb s')
    -> (value, unit) in the unit system asked for: unchanged for us, or
    for a unit with no SI twin ('' or 's')."""
    from contactsep.model.names import SI_SUFFIXES
    suffix = _PRINTED.get(unit)
    if not si or suffix is None or not isinstance(value, (int, float)) \
            or isinstance(value, bool):
        return value, unit
    _, printed, factor = SI_SUFFIXES[suffix]
    return value * factor, printed


def si_asked(args: argparse.Namespace) -> bool:
    """Whether --units si is asked for, refused in one line where the
    command's outputs would stay in inch-pound units."""
    if getattr(args, "units", "us") != "si":
        return False
    command = getattr(args, "command", None)
    if command not in SI_COMMANDS:
        raise InputError(f"--units si: {command} writes in, lb, s; the "
                         f"commands that take it are "
                         f"{', '.join(SI_COMMANDS)} (or give each value "
                         f"its unit: --L1 25mm)")
    return True


def from_si(suffix: str, text, value):
    """A bare number of the command line read in SI ('0.025' for a
    length is 0.025 m, 0.984... in), rounded as contactsep.units rounds
    a converted value; a value typed with its unit is already converted."""
    from contactsep import units
    from contactsep.model.names import SI_SUFFIXES, from_si_number
    if suffix not in SI_SUFFIXES or not isinstance(value, float) or \
            (isinstance(text, str) and units.split(text) is not None):
        return value
    return from_si_number(value, suffix)


def apply_units(args: argparse.Namespace, si: bool) -> None:
    """The command's own options read as bare numbers (--preload 0.7,
    --t-end 0.01: values.Bare) in SI where --units si is asked for;
    plain floats either way."""
    from contactsep.cli.values import Bare
    for name, value in list(vars(args).items()):
        if isinstance(value, Bare):
            setattr(args, name, from_si(_PRINTED.get(value.unit, ""),
                                         None, float(value))
                    if si else float(value))


def in_units(data, args: argparse.Namespace):
    """A command's JSON in the unit system of --units: unchanged for us;
    for si every key with a unit suffix renamed to its SI twin
    (model.names.SI_SUFFIXES: 'y3_max_in' -> 'y3_max_m') and its
    numbers converted, at any depth, and the design's "units" "si"
    (:func:`contactsep.model.names.si_data`)."""
    if getattr(args, "units", "us") != "si":
        return data
    from contactsep.model.names import si_data
    return si_data(data, _BARE_NAMES)


def _bare_names() -> dict:
    """Objects whose keys are bare names of quantities with a unit
    (preload's inputs: "design": {"L1": 19}, "settings": {"dt": ...}) ->
    each name's key with its unit ('L1' -> 'L1_in'), which in_units
    converts as it converts a key with its suffix."""
    from contactsep.model import fields as F
    design = {f: F.column_name(f) for f in F.FIELDS if F.FIELDS[f][0]}
    settings = {s: F.column_name(s) for s in F.SETTINGS if F.SETTINGS[s][0]}
    settings["open_threshold"] = "open_threshold_in"
    return {"design": design, "settings": settings}


_BARE_NAMES = _bare_names()
