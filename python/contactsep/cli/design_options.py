"""The design options every command that takes a design shares (model,
sweep, study, chatter): one option per field of
:class:`contactsep.Design`, ``--set FIELD=VALUE`` and ``--design FILE``.

* ``add_design_options(parser)`` adds them, grouped by member, each with
  its unit and default in the help.  The separator's thickness is
  ``--d`` or ``--h2`` (the Design's field), the coefficient of
  restitution ``--e`` or ``--restitution``.
* ``design_overrides(args) -> dict`` returns the fields the user gave
  (Design field -> value; ``thesis_design(**overrides)`` makes the
  design), checked by building that design; an error names the option
  as typed (``--d: found -0.1, expected a finite number > 0``).

Precedence: ``--design FILE`` (a design file, read by
:mod:`contactsep.model.design_file_read` as ``contactsep.load_design``
reads it: a JSON object of fields, or the output of ``contactsep model
--json`` whose ``design`` it reads) is the starting design; the
command line overrides it, and so do a study's own axes and a sweep's
--vary and --sample (``fields_from_file(args)`` names the
fields only the file gave).  An option given twice: the last one wins
(a base command line with an override appended); two spellings of one
field (``--d`` and ``--h2``, ``--set h2=``) with different values are
refused.  A material preset (``--material2 steel``, ``--material`` for
all three members, ``"material2": "steel"`` in a file) fills E, gamma
and nu of a member in its place among the options: the last given wins,
whether the preset or an explicit ``--E2`` (in a file the explicit
fields win).  Values are read by
:func:`contactsep.model.fields.parse_value`, the one place that reads
a field from text.

A numerics field (n_modes) that only the file gave is used, and said so
in one line on stderr (``contactsep: note: n_modes = 4 from the design
file my.json (the command's default is 64)``); ``with_sources`` puts
``n_modes_source`` ("given", "design file" or "default") in a
command's JSON ``inputs``.
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
import warnings

from contactsep.cli.unit_system import (
    SI_COMMANDS,
    UNIT_SYSTEMS,
    apply_units,
    from_si,
    in_units,
    si_asked,
)
from contactsep.errors import ContactsepWarning, InputError, printable
from contactsep.model import design_file_read
from contactsep.model import fields as F
from contactsep.model.design_file import NUMERICS

#: Where the command line's design values are kept: (field or name,
#: option as typed, text), in command-line order.
_GIVEN = "design_given"
#: Where design_overrides notes the fields only the --design file gave.
_FROM_FILE = "design_from_file"
#: Where design_overrides notes where each numerics field came from:
#: "given" (the command line), "design file" or "default".
_SOURCES = "design_numerics_sources"

#: Option spellings of the fields whose option is not ``--FIELD``.
_SPELLINGS = {"h2": ("--d", "--h2"), "e": ("--e", "--restitution"),
              "n_modes": ("--n-modes",),
              "impact_velocity": ("--impact-velocity",),
              "lower_response": ("--lower-response",),
              "lc_reading": ("--lc-reading",), "release": ("--release",),
              "x2_lower": ("--x2-lower",),
              **{f"x_mass{m}": (f"--x-mass{m}",) for m in "123"}}

#: Material preset options (contactsep.model.materials) -> the members
#: whose E, gamma and nu they fill.
PRESETS = {"--material": "123", "--material1": "1", "--material2": "2",
           "--material3": "3"}


class _Preset(argparse.Action):
    """--materialN NAME: kept in order with the design options (the last
    given wins), expanded by design_overrides."""

    def __call__(self, parser, namespace, values, option_string=None):
        given = list(getattr(namespace, _GIVEN, None) or [])
        given.append((("preset", PRESETS[option_string]), option_string,
                      values))
        setattr(namespace, _GIVEN, given)


class _Given(argparse.Action):
    """Keeps the text and the option as typed; design_overrides reads
    them (so that every error is one line naming the option)."""

    def __call__(self, parser, namespace, values, option_string=None):
        if isinstance(values, list):    # argparse's '--end1=--'
            values = " ".join(values)
        given = list(getattr(namespace, _GIVEN, None) or [])
        given.append((self.const, option_string, values))
        setattr(namespace, _GIVEN, given)


def _help(field: str) -> str:
    """'upper contact length (in; default 19)'."""
    from contactsep.model import Design
    value = {f.name: f.default for f in dataclasses.fields(Design)}[field]
    if value is None:
        value = F.OPTIONAL[field]
    elif isinstance(value, float):
        value = f"{value:.12g}"
    details = [F.unit(field)] if F.unit(field) else []
    details.append(f"default {value}")
    return f"{F.FIELDS[field][2]} ({'; '.join(details)})"


def add_design_options(parser: argparse.ArgumentParser) -> None:
    """One option per Design field, and --set and --design (module
    docstring); design_overrides(args) reads them."""
    parser.set_defaults(**{_GIVEN: None})
    for title, names in F.GROUPS + F.PHYSICS_GROUPS:
        group = parser.add_argument_group(f"design: {title}")
        for field in names:
            options = _SPELLINGS.get(field, (f"--{field}",))
            unit = F.unit(field)
            kwargs = {}
            if field in F.CHOICES:
                kwargs["metavar"] = "{" + ",".join(F.CHOICES[field]) + "}"
            else:
                kwargs["metavar"] = unit.upper() if unit else \
                    ("N" if field == "n_modes" else field.upper())
            group.add_argument(*options, dest=_GIVEN, action=_Given,
                               const=field, default=argparse.SUPPRESS,
                               help=_help(field), **kwargs)
    from contactsep.model.materials import MATERIALS
    group = parser.add_argument_group(
        "design: material presets (E, gamma and nu of a member; the last "
        "option given wins, an explicit --E2 after --material2 too)")
    for option, members in PRESETS.items():
        whose = "all three members" if len(members) == 3 else \
            F.MEMBERS[members]
        group.add_argument(option, dest=_GIVEN, action=_Preset,
                           default=argparse.SUPPRESS,
                           metavar="{" + ",".join(MATERIALS) + "}",
                           help=f"a material preset for {whose} "
                                f"(docs/model.md, \"Material presets\")")
    group = parser.add_argument_group("design: other ways to give it")
    group.add_argument("--set", dest=_GIVEN, action=_Given, const=None,
                       default=argparse.SUPPRESS, metavar="FIELD=VALUE",
                       help="any design field by name (repeatable): "
                            "--set h2=0.3 --set end2=pinned-pinned")
    group.add_argument("--separator", choices=("thesis", "physical"),
                       default="thesis",
                       help="thesis: the clamped Bernoulli-Euler separator "
                            "(default); physical: the supports fitted to "
                            "Table II (study separator-fit: Timoshenko, "
                            "kr2 = 2.19e4 lb in/rad), unless --beam2/--kr2 "
                            "say otherwise")
    group.add_argument("--units", choices=UNIT_SYSTEMS, default="us",
                       help="the unit system of bare numbers on the "
                            "command line and of the output: us (in, lb, "
                            "s, psi, lb/in^3; default) or si (m, N, s, Pa, "
                            "kg/m^3; commands " + ", ".join(SI_COMMANDS)
                            + ")")
    group.add_argument("--design", metavar="FILE",
                       help="a JSON object of design fields (names as in "
                            "--set, or output names such as d_in), or the "
                            "output of `contactsep model --json`; the "
                            "command line overrides it")


def design_overrides(args: argparse.Namespace) -> dict:
    """The design fields the user gave (Design field -> value), checked
    by making the design; errors name the option as typed.  A numerics
    field the --design file alone gave is noted on stderr (note_numerics).
    """
    si = si_asked(args)
    values, labels = {}, {}
    path = getattr(args, "design", None)
    if path:
        values, labels = design_file_read.read_fields(path, f"--design {path}")
    typed = {}
    for field, option, text in getattr(args, _GIVEN, None) or ():
        if isinstance(field, tuple):    # --materialN NAME: E, gamma, nu
            for name, number in design_file_read.preset_fields(
                    text, field[1], option).items():
                typed[name] = option
                values[name] = number
                labels[name] = f"{option} {text}"
            continue
        if field is None:               # --set NAME=VALUE
            name, sep, text = text.partition("=")
            option = f"--set {name.strip()}"
            if not sep:
                raise InputError(f"--set {name}: expected FIELD=VALUE")
            field = F.field_name(name, option)
        value = F.parse_value(field, text, option)
        if si:
            value = from_si(F.FIELDS[field][0], text, value)
        if field in typed and typed[field] != option and \
                typed[field] not in PRESETS and values[field] != value:
            raise InputError(f"{option}: the {F.FIELDS[field][2]} is "
                             f"already given by {typed[field]} "
                             f"(another value)")
        # the same option again: the last one wins (a base command line
        # with an override appended)
        typed[field] = option
        values[field] = value
        labels[field] = option
    apply_units(args, si)
    if getattr(args, "separator", "thesis") == "physical":
        from contactsep.studies.thesis.separator_fit import PHYSICAL_SEPARATOR
        for field, value in PHYSICAL_SEPARATOR.items():
            if field not in values:
                values[field] = value
                labels[field] = "--separator physical"
    design_file_read.make_design(values, labels)
    for message in unit_system_doubts(values, labels):
        warnings.warn(message, ContactsepWarning)
    setattr(args, _FROM_FILE, set(values) - set(typed))
    setattr(args, _SOURCES, {name: "given" if name in typed else
                             "design file" if name in values else "default"
                             for name in NUMERICS})
    note_numerics(args, values)
    return values


#: Beyond these a bare number was probably typed in another unit system:
#: no metal is softer than 1e5 psi (lead: 2e6) or denser than 1 lb/in^3
#: (osmium: 0.816), and a contact spring is not 40 in long.
SOFTEST_PSI = 1e5
DENSEST_LB_IN3 = 1.0
LONGEST_IN = 40.0


def unit_system_doubts(values: dict, labels: dict) -> list[str]:
    """One-line warnings for given numbers that look like another unit
    system's (a modulus in GPa, a density in g/cm^3, a length in mm)."""
    doubts = []
    for field, value in values.items():
        if not isinstance(value, float):
            continue
        label = labels.get(field, field)
        if field[0] == "E" and value < SOFTEST_PSI:
            doubts.append(f"{label}: {value:g} psi is softer than any metal "
                          f"(steel: 30e6 psi = 207 GPa): a modulus in GPa or "
                          f"MPa? Give the unit, e.g. {value:g}GPa")
        elif field.startswith("gamma") and value > DENSEST_LB_IN3:
            doubts.append(f"{label}: {value:g} lb/in^3 is denser than any "
                          f"metal (steel: 0.283 lb/in^3 = 7.85 g/cm^3): a "
                          f"density in g/cm^3? Give the unit, e.g. "
                          f"{value:g}g/cm3")
        elif field[0] == "L" and field[1:] in ("1", "2", "3") and \
                value > LONGEST_IN:
            doubts.append(f"{label}: a member {value:g} in long: a length "
                          f"in mm? Give the unit, e.g. {value:g}mm")
    return doubts


def fields_from_file(args: argparse.Namespace) -> set:
    """The fields of design_overrides(args) that only --design gave: a
    study's own axes and a sweep's varied fields take their place."""
    return set(getattr(args, _FROM_FILE, ()))


#: The command whose default N is not the Design's -> where it is kept.
_COMMAND_MODES = {"chatter": "contactsep.chatter.numerics",
                  "preload": "contactsep.studies.preload.chart"}


def _default_modes(command):
    """The N a command runs at unless given (None: each study's own,
    or not one number)."""
    import importlib
    if command in _COMMAND_MODES:
        return importlib.import_module(_COMMAND_MODES[command]).DEFAULT_MODES
    if command in ("model", "sweep"):
        from contactsep.model import Design
        return Design.__dataclass_fields__["n_modes"].default
    return None


def note_numerics(args: argparse.Namespace, values: dict) -> None:
    """One line on stderr for each numerics field the --design file
    alone set: a file's N is a choice of numerics, not of the design,
    and the command would otherwise have run at its own default."""
    for name in NUMERICS:
        if getattr(args, _SOURCES)[name] != "design file":
            continue
        value = values[name]
        text = ",".join(map(str, value)) if isinstance(value, tuple) \
            else str(value)
        default = _default_modes(getattr(args, "command", None))
        own = f"the command's default is {default}" if default is not None \
            else "instead of the command's own default"
        print(printable(f"contactsep: note: {name} = {text} from the "
                        f"design file {args.design} ({own})"),
              file=sys.stderr)


def with_sources(data: dict, args: argparse.Namespace) -> dict:
    """A command's JSON with ``n_modes_source`` ("given", "design file"
    or "default") beside ``n_modes`` in its ``inputs``, as ``dt_source``
    is beside ``dt_s``; in SI with ``--units si`` (in_units)."""
    sources = getattr(args, _SOURCES, None) or {}
    inputs = data.get("inputs")
    if not isinstance(inputs, dict):
        return in_units(data, args)
    out = {}
    for key, value in inputs.items():
        out[key] = value
        if key in sources:
            out[f"{key}_source"] = sources[key]
    return in_units({**data, "inputs": out}, args)


def damping_law(args: argparse.Namespace, overrides: dict, model: str):
    """The Hertz contact's damping law a simulation runs with: the one
    named by --damping; where none is named and the user gave e (--e,
    --set e=, or a --design file whose e is not an echo of the rig's),
    "flores", calibrated to that e, said in one line on stderr (an
    elastic law would drop the e without a word); else None (the
    simulation's default, elastic "none").  Only Hertz contact has a
    damping law: Newton's impact law reads e itself."""
    named = getattr(args, "damping", None)
    if named is not None or model != "hertz":
        return named
    from contactsep.model import thesis_design
    # as guards.drop_echoes reads it: the file's e at the rig's is an echo
    echo = "e" in fields_from_file(args) and \
        overrides.get("e") == thesis_design().e
    if "e" not in overrides or echo:
        return None
    print(printable(f"contactsep: note: damping flores, calibrated to the "
                    f"given e = {overrides['e']:g} (--damping none: elastic "
                    f"Hertz contact, e unused)"), file=sys.stderr)
    return "flores"
