"""``--units us|si`` on the commands that take design options: the unit
system of the command line's bare numbers and of the ``--json`` output
(docs/studies.md, "Names and units").

With ``si`` a bare number is read in m, N, s, Pa, kg/m^3 (a value typed
with its unit is read as typed), and every key of the JSON with a unit
suffix becomes its SI twin (:data:`contactsep.model.names.SI_SUFFIXES`,
the one table), and so does the text of ``model``, ``chatter`` and
``preload`` and the CSV of ``preload`` (forces in N, its column
``preload_N``: ``model.names.units_shown``).  Only these commands take
it; ``chatter``'s CSV stays in inch-pound units, so ``si`` is refused
there in one line rather than half done.  With the default ``us``
nothing changes.
"""

from __future__ import annotations

import argparse

from contactsep.errors import InputError

#: --units: the unit system of the command line's bare numbers.
UNIT_SYSTEMS = ("us", "si")
#: The commands whose outputs --units si converts (text and --json).
SI_COMMANDS = ("model", "chatter", "preload")
#: An option's unit as printed -> its suffix in names.SI_SUFFIXES.
_PRINTED = {"in": "in", "s": "s", "lb": "lb", "psi": "psi",
            "lb/in^3": "lb_in3", "s/in": "s_per_in", "lb s": "lb_s",
            "in/s": "in_s"}
#: The commands whose --csv file --units si converts too.
SI_CSV = ("preload",)


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
    for option in ("csv", "png"):
        if getattr(args, option, None) and not (option == "csv"
                                                and command in SI_CSV):
            raise InputError(f"--units si: --{option} stays in in, lb, s "
                             f"(leave it out, or drop --units si)")
    return True


def from_si(suffix: str, text, value):
    """A bare number of the command line read in SI ('0.025' for a
    length is 0.025 m, 0.984... in), rounded as contactsep.units rounds
    a converted value; a value typed with its unit is already converted."""
    from contactsep import units
    from contactsep.model.names import SI_SUFFIXES
    if suffix not in SI_SUFFIXES or not isinstance(value, float) or \
            (isinstance(text, str) and units.split(text) is not None):
        return value
    return float(f"{value / SI_SUFFIXES[suffix][2]:.15g}")


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
    numbers converted, at any depth, and the design's "units" "si"."""
    if getattr(args, "units", "us") != "si":
        return data
    from contactsep.model.names import si_key

    def convert(value, factor):
        if isinstance(value, list):
            return [convert(v, factor) for v in value]
        if isinstance(value, float) or (isinstance(value, int) and
                                        not isinstance(value, bool)):
            return si_number(value, factor) if factor != 1.0 else value
        return value

    def walk(value, bare=None):
        if isinstance(value, list):
            return [walk(v) for v in value]
        if not isinstance(value, dict):
            return value
        out = {}
        for key, item in value.items():
            twin = si_key(key) if isinstance(key, str) else None
            if twin is None and bare and key in bare:
                twin = si_key(bare[key])
            if key == "units" and item == "us":
                out[key] = "si"
            elif twin is None or isinstance(item, dict):
                out[key] = walk(item, _BARE_NAMES.get(key))
            else:
                out[twin[0]] = convert(item, twin[1])
        return out
    return walk(data)


def si_number(value: float, factor: float) -> float:
    """``value`` (in the package's units) times ``factor``, written with
    the fewest significant digits that a design file's
    reader (divide by ``factor``, round to 15 digits, as contactsep.units
    rounds) turns back into ``value`` exactly: 5 mm typed is written
    0.005, not 0.00499999999999999.  A value with more digits than the
    reader keeps is written as the plain product, as before."""
    product = value * factor

    def reads_back(digits: int) -> float | None:
        written = float(f"{product:.{digits}g}")
        return written if float(f"{written / factor:.15g}") == value \
            else None

    if reads_back(15) is None:
        # a computed value (a result, not a typed one): the plain
        # product unless 16 or 17 digits read back
        return reads_back(16) or reads_back(17) or product
    return next(written for written in map(reads_back, range(1, 16))
                if written is not None)


def _bare_names() -> dict:
    """Objects whose keys are bare names of quantities with a unit
    (preload's inputs: "design": {"L1": 19}, "settings": {"dt": ...}) ->
    each name's key with its unit ('L1' -> 'L1_in'), which in_units
    converts as it converts a key with its suffix."""
    from contactsep.studies import fields as F
    design = {f: F.column_name(f) for f in F.FIELDS if F.FIELDS[f][0]}
    settings = {s: F.column_name(s) for s in F.SETTINGS if F.SETTINGS[s][0]}
    settings["open_threshold"] = "open_threshold_in"
    return {"design": design, "settings": settings}


_BARE_NAMES = _bare_names()
