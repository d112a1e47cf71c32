"""The design options every command that takes a design shares: one
option per field of :class:`contactsep.Design` (a minimal version; the
fuller one, with ``--set`` and ``--design``, comes with the usability
work on the same names and signatures).

* ``add_design_options(parser)`` adds them, grouped by member, each with
  its unit and default in the help.  The separator's thickness is
  ``--d`` or ``--h2`` (the Design's field), the coefficient of
  restitution ``--e`` or ``--restitution``.
* ``design_overrides(args) -> dict`` returns the fields the user gave
  (Design field -> value; ``thesis_design(**overrides)`` makes the
  design), checked by building that design; an error names the option
  as typed (``--d: found -0.1, expected a finite number > 0``).
"""

from __future__ import annotations

import argparse
import dataclasses

from contactsep.beams import END_CONDITIONS
from contactsep.errors import InputError

#: Where the typed options are kept: {field: option as typed}.
_TYPED = "design_typed"

#: (field, description, unit) of every Design field, by member.
_GROUPS = (
    ("upper contact (member 1)", (
        ("L1", "upper contact length", "in"),
        ("b1", "upper contact width", "in"),
        ("h1", "upper contact thickness", "in"),
        ("gamma1", "upper contact weight density", "lb/in^3"),
        ("E1", "upper contact Young's modulus", "psi"),
        ("end1", "upper contact end conditions", ""),
        ("x1", "contact point on the upper contact (default: its tip)",
         "in"),
        ("ys", "release height above the separator", "in"))),
    ("separator (member 2)", (
        ("L2", "separator length", "in"),
        ("b2", "separator width", "in"),
        ("h2", "separator thickness d", "in"),
        ("gamma2", "separator weight density", "lb/in^3"),
        ("E2", "separator Young's modulus", "psi"),
        ("end2", "separator end conditions", ""),
        ("x2", "contact point on the separator (default: mid-span)",
         "in"),
        ("Lc", "separator equivalent length L_c (default: not used)",
         "in"))),
    ("lower contact (member 3)", (
        ("L3", "lower contact length", "in"),
        ("b3", "lower contact width", "in"),
        ("h3", "lower contact thickness", "in"),
        ("gamma3", "lower contact weight density", "lb/in^3"),
        ("E3", "lower contact Young's modulus", "psi"),
        ("end3", "lower contact end conditions", ""),
        ("x3", "contact point on the lower contact (default: its tip)",
         "in"))),
    ("impact and model", (
        ("e", "coefficient of restitution", ""),
        ("n_modes", "modes per member", ""),
        ("tau", "time window of the eq. 23 response, from the impact",
         "s"),
        ("gap", "position of the separator surface seen by the upper "
                "contact", "in"),
        ("impact_velocity", "impact speed: exact, or the listing's",
         ""),
        ("lower_response", "lower-contact response: eq. 23 as printed "
                           "or the impulse form", ""),
        ("lc_reading", "reading of L_c", ""),
        ("release", "static load at the upper contact's tip or at x1",
         ""))),
)

#: Option spellings of the fields whose option is not ``--FIELD``.
_SPELLINGS = {"h2": ("--d", "--h2"), "e": ("--e", "--restitution"),
              "n_modes": ("--n-modes",),
              "impact_velocity": ("--impact-velocity",),
              "lower_response": ("--lower-response",),
              "lc_reading": ("--lc-reading",), "release": ("--release",)}


class _Typed(argparse.Action):
    """Stores the value and remembers the option as typed."""

    def __call__(self, parser, namespace, values, option_string=None):
        typed = dict(getattr(namespace, _TYPED, None) or {})
        typed[self.dest] = option_string
        setattr(namespace, _TYPED, typed)
        setattr(namespace, self.dest, values)


def _kind(field: str, default):
    if field == "n_modes":
        return dict(type=int, metavar="N")
    if field.startswith("end"):
        return dict(choices=END_CONDITIONS)
    if isinstance(default, str):
        return dict(choices=None)
    return dict(type=float, metavar=field.upper())


def add_design_options(parser: argparse.ArgumentParser) -> None:
    """One option per Design field, with its unit and default in the help
    (module docstring); design_overrides(args) reads them."""
    from contactsep.model import Design
    from contactsep.model import design as design_module

    defaults = {f.name: f.default for f in dataclasses.fields(Design)}
    choices = {"impact_velocity": design_module.IMPACT_VELOCITIES,
               "lower_response": design_module.LOWER_RESPONSES,
               "lc_reading": design_module.LC_READINGS,
               "release": design_module.RELEASES}
    parser.set_defaults(**{_TYPED: None})
    for title, fields in _GROUPS:
        group = parser.add_argument_group(f"design: {title}")
        for field, description, unit in fields:
            default = defaults[field]
            shown = "" if default is None else f"default {default:g}" \
                if isinstance(default, float) else f"default {default}"
            details = "; ".join(x for x in (unit, shown) if x)
            kind = _kind(field, default)
            if field in choices:
                kind = dict(choices=choices[field])
            group.add_argument(
                *_SPELLINGS.get(field, (f"--{field}",)), dest=field,
                action=_Typed, default=None,
                help=f"{description} ({details})" if details
                else description, **kind)


def design_overrides(args: argparse.Namespace) -> dict:
    """The design fields the user gave (Design field -> value), checked
    by making the design; errors name the option as typed."""
    from contactsep.model import thesis_design

    typed = getattr(args, _TYPED, None) or {}
    values = {field: getattr(args, field) for field in typed}
    try:
        thesis_design(**values)
    except InputError as error:
        field, sep, rest = str(error).partition(":")
        if sep and field in typed:
            raise InputError(f"{typed[field]}:{rest}") from None
        raise
    return values
