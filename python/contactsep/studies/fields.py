"""The Design's fields as a designer names them: units, other names,
output column names, and values read from text.

One convention for every output (docs/studies.md, "Names and units"):
a key or column is the quantity's snake_case name followed by its unit,
``_in``, ``_s``, ``_lb``, ``_lb_s``, ``_in_s``, ``_psi``, ``_lb_in3``,
``_rad_s``, ``_cps``, ``_lb_s2_in`` (mass), ``_lb_in_rad`` and
``_lb_per_in`` (spring stiffnesses); dimensionless names are bare
(``e``, ``R``, ``n_modes``, ``status``).  The separator's thickness is
``d`` in every output (``d_in``), as in the thesis; ``--d`` and
``--h2`` (the Design's field) are both accepted on input.

Everything the command line and the sweeps read about a field is
checked here, once: :func:`parse_value` turns a text into a field's
value or raises an :class:`~contactsep.errors.InputError` naming what
the user typed.

Beside the Design's fields, the chatter sweeps (``contactsep sweep
--model hertz|newton``) fix, vary or sample four settings of the
simulation (:data:`SETTINGS`: ``preload``, ``min_open``, ``damping``,
``dt``; dt is fixed or varied, not sampled); they are named, read and
written the same way, but are not design fields (``--set preload=...``
is refused, naming them).
"""

from __future__ import annotations

import math

import numpy as np

from contactsep import beams, units
from contactsep.beams.member import THEORIES
from contactsep.chatter.simulate import CONTACTS, DAMPINGS
from contactsep.constants import LISTING_TAU_S
from contactsep.errors import InputError, shown
from contactsep.model.design import (
    IMPACT_VELOCITIES,
    LC_READINGS,
    LOWER_RESPONSES,
    REAL_COLUMNS,
    RELEASES,
)
from contactsep.model.names import (
    FIELDS,
    MEMBERS,
    OUTPUT_NAMES,
    SHOWN_WHEN_GIVEN,
)


#: The chatter simulation's settings a chatter sweep may fix, vary or
#: sample (as FIELDS: unit suffix, unit as printed, meaning).
SETTINGS: dict[str, tuple[str, str, str]] = {
    "preload": ("lb", "lb", "force pressing the lower contact on the "
                            "separator at the start"),
    "min_open": ("s", "s", "shortest circuit opening counted as a "
                           "discontinuity event"),
    "damping": ("", "", "Hertz contact damping: none (elastic), flores "
                        "(calibrated to e) or hunt-crossley (alpha)"),
    "alpha": ("s_per_in", "s/in", "Hunt-Crossley's material constant "
                                  "(damping hunt-crossley)"),
    "contact": ("", "", "the Hertz law's elastic part: hertz or thornton "
                        "(elastic-perfectly-plastic)"),
    "yield_pressure": ("psi", "psi", "Thornton's yield pressure (contact "
                                     "thornton)"),
    "dt": ("s", "s", "the adaptive stepper's time step (a convergence "
                     "check: docs/chatter.md)"),
    "static_correction": ("", "", "hertz: the truncated modes' residual "
                                  "flexibility in series with each contact "
                                  "(on or off)"),
    "t_end": ("s", "s", "window of each simulation from the release "
                        "(fixed, not varied)"),
}
#: The settings a chatter sweep may vary (--vary) and sample (--sample).
VARIABLE_SETTINGS = ("preload", "min_open", "damping", "dt", "alpha",
                     "contact", "yield_pressure")
SAMPLED_SETTINGS = ("preload", "min_open")

#: Other names accepted for a field wherever a field is named on input.
ALIASES = {"d": "h2", "restitution": "e"}
#: Fields whose value is one of a few words.
CHOICES = {"end1": beams.END_CONDITIONS, "end2": beams.END_CONDITIONS,
           "end3": beams.END_CONDITIONS,
           "impact_velocity": IMPACT_VELOCITIES,
           "lower_response": LOWER_RESPONSES, "lc_reading": LC_READINGS,
           "release": RELEASES, "damping": DAMPINGS, "contact": CONTACTS,
           "static_correction": ("on", "off"),
           **{f"beam{m}": THEORIES for m in MEMBERS}}
#: Fields that may be None, and what None means.
OPTIONAL = {"x1": "its tip (L1)", "x2": "mid-span (L2/2)",
            "x3": "its tip (L3)", "Lc": "none", "x2_lower": "x2",
            **{f"kappa{m}": "Cowper's 10(1+nu)/(12+11nu)" for m in MEMBERS},
            **{f"kr{m}": "rigid" for m in MEMBERS},
            **{f"kt{m}": "rigid" for m in MEMBERS},
            **{f"x_mass{m}": "the contact point" for m in MEMBERS}}
#: Fields a sweep may vary (--vary) and sample (--sample).
VARIABLE = REAL_COLUMNS + ("end1", "end2", "end3", "n_modes")
SAMPLED = REAL_COLUMNS


def _entry(field: str) -> tuple[str, str, str]:
    return FIELDS[field] if field in FIELDS else SETTINGS[field]


def column_name(field: str) -> str:
    """The field's (or setting's) key in every output: 'h2' -> 'd_in',
    'e' -> 'e', 'gamma2' -> 'gamma2_lb_in3', 'preload' -> 'preload_lb'."""
    suffix = _entry(field)[0]
    name = OUTPUT_NAMES.get(field, field)
    return f"{name}_{suffix}" if suffix else name


_BY_COLUMN = {column_name(f): f for f in FIELDS}
_SETTING_NAMES = {**{s: s for s in SETTINGS},
                  **{column_name(s): s for s in SETTINGS}}


def field_name(name: str, label: str | None = None,
               settings: bool = False) -> str:
    """The Design field a name stands for: the field itself, an alias
    ('d', 'restitution') or an output column name ('d_in'); with
    ``settings``, also a chatter setting ('preload' or 'preload_lb').
    ``label`` (default: the name) is how an error names it."""
    name = name.strip()
    field = name if name in FIELDS else ALIASES.get(name) or \
        _BY_COLUMN.get(name)
    if field is None and name in _SETTING_NAMES:
        if settings:
            return _SETTING_NAMES[name]
        option = "--" + _SETTING_NAMES[name].replace("_", "-")
        raise InputError(f"{label or name}: a setting of the chatter "
                         f"simulation, not a design field: give it as "
                         f"{option} (contactsep chatter, and contactsep "
                         f"sweep --model hertz or newton, take it)")
    if field is None:
        also = f"; the chatter settings {', '.join(SETTINGS)}" \
            if settings else ""
        raise InputError(f"{label or name}: not a design field (one of "
                         f"{', '.join(FIELDS)}; also d, restitution"
                         f"{also})")
    return field


def unit(field: str) -> str:
    """The unit as printed ('lb/in^3'); '' for dimensionless."""
    return _entry(field)[1]


def parse_value(field: str, text, label: str):
    """A field's value from ``text`` (a str, or a number or list from a
    JSON file); ``label`` names it in errors ('--d', 'design.json: d_in').

    Real fields take a number (any float; the Design checks its range;
    a text may carry a unit, ``'30.5mm'``, converted by
    :mod:`contactsep.units`;
    x1, x2, x3, x2_lower and Lc also None, their default), the settings preload
    and min_open a finite number >= 0, dt one > 0 below the window,
    damping none or flores,
    end conditions and the options one of their words, ``n_modes`` an
    integer >= 1 or three of them ('4,16,4').
    """
    if field in CHOICES:
        allowed = CHOICES[field]
        word = text.strip() if isinstance(text, str) else None
        if field.startswith("end"):
            word = beams.ALIASES.get(word, word)
        if word not in allowed:
            raise InputError(f"{label}: found {text!r}, expected one of "
                             f"{', '.join(allowed)}")
        return word
    if field == "n_modes":
        return _modes(text, label)
    if text is None and field in OPTIONAL:
        return None
    if field in SETTINGS:
        return _setting(field, text, label)
    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise InputError(f"{label}: found {text!r}, expected a number "
                         f"({unit(field) or 'dimensionless'})")
    if units.split(text) is not None:
        return units.convert(text, unit(field), label)
    try:
        value = float(text)
    except (ValueError, OverflowError):
        raise InputError(f"{label}: found {shown(text)}, expected a number "
                         f"({unit(field) or 'dimensionless'})") from None
    return value


#: The longest window of a chatter simulation (s; its MAX_T_END).
MAX_WINDOW_S = 10.0


def _setting(field: str, text, label: str) -> float:
    """preload (lb) or min_open (s): a finite number >= 0; dt (s): a
    finite number > 0 and below the window (the chatter layer refuses
    the rest; refused here, it is one line before any work)."""
    try:
        if isinstance(text, bool):
            raise ValueError
        value = units.convert(text, unit(field), label) \
            if units.split(text) is not None else float(text)
    except (TypeError, ValueError, OverflowError):
        value = math.nan
    if field == "t_end" and not (0.0 < value <= MAX_WINDOW_S):
        raise InputError(f"{label}: found {text!r}, expected a window > 0 "
                         f"and at most {MAX_WINDOW_S:g} s")
    if field in ("alpha", "yield_pressure") and not (
            math.isfinite(value) and value > 0.0):
        raise InputError(f"{label}: found {text!r}, expected a "
                         f"{'constant' if field == 'alpha' else 'pressure'}"
                         f" > 0 {unit(field)}")
    if field == "dt" and not (0.0 < value < LISTING_TAU_S):
        raise InputError(f"{label}: found {text!r}, expected a time step "
                         f"> 0 and below the window, {LISTING_TAU_S:g} s")
    if not (math.isfinite(value) and value >= 0.0):
        raise InputError(f"{label}: found {text!r}, expected a "
                         f"{'force' if field == 'preload' else 'time'} "
                         f">= 0 {unit(field)}")
    if field == "min_open" and value > LISTING_TAU_S:
        raise InputError(f"{label}: found {text!r}, expected at most the "
                         f"window, {LISTING_TAU_S:g} s")
    return value


def _modes(text, label: str):
    parts = text.split(",") if isinstance(text, str) else (
        list(text) if isinstance(text, (list, tuple)) else [text])
    counts = []
    for part in parts:
        try:
            if isinstance(part, bool):
                raise ValueError
            number = float(part)
            count = int(number)
            if count != number or not math.isfinite(number):
                raise ValueError
        except (TypeError, ValueError, OverflowError):
            count = None
        if count is None or count < 1 or len(parts) not in (1, 3):
            raise InputError(f"{label}: found {text!r}, expected an "
                             f"integer >= 1, or three of them (N1,N2,N3)")
        counts.append(count)
    return counts[0] if len(counts) == 1 else tuple(counts)


def describe(design_fields: dict) -> dict:
    """Fields (and chatter settings) as an output shows them: column
    names, plain values."""
    out = {}
    for field, value in design_fields.items():
        if isinstance(value, tuple):
            value = list(value)
        out[column_name(field)] = value
    return out


#: The fields by member, as help and notes group them.
GROUPS = (("upper contact (member 1)", ("L1", "b1", "h1", "gamma1", "E1",
                                        "end1", "x1", "ys")),
          ("separator (member 2)", ("L2", "b2", "h2", "gamma2", "E2",
                                    "end2", "x2", "x2_lower", "Lc")),
          ("lower contact (member 3)", ("L3", "b3", "h3", "gamma3", "E3",
                                        "end3", "x3")),
          ("impact and model", ("e", "n_modes", "tau", "gap",
                                "impact_velocity", "lower_response",
                                "lc_reading", "release")))


#: Each member's beam physics (contactsep.model.physics): options, and a
#: line of design_lines where one differs from the thesis's.
PHYSICS_GROUPS = tuple(
    (f"{title} beam physics", tuple(f"{kind}{m}" for kind in (
        "beam", "nu", "kappa", "kr", "kt", "mass", "x_mass")))
    for (title, _), m in zip(GROUPS[:3], "123"))


def _value_text(design, field: str, per_row) -> str:
    value = getattr(design, field)
    if field in per_row:
        return "per row"
    if value is None:
        return OPTIONAL[field]
    if isinstance(value, tuple):
        return ",".join(str(v) for v in value)
    values = np.unique(np.asarray(value))
    if values.size > 1:
        return "per row"
    value = values.item()
    text = f"{value:.12g}" if isinstance(value, float) else str(value)
    return f"{text} {unit(field)}".rstrip()


def design_lines(design, per_row=()) -> list[str]:
    """The design a study or output was computed for, in four lines
    (upper contact, separator, lower contact, impact and model), each
    field under its output name with its unit; a field that varies
    across the batch, or is named in ``per_row``, reads 'per row' (the
    study's columns and notes give it)."""
    lines = []
    physics = [(title, names) for title, names in PHYSICS_GROUPS
               if any(getattr(design, name, None) not in (
                   None, 0.0, "bernoulli-euler", 0.33) for name in names)]
    for title, names in GROUPS + tuple(physics):
        parts = [f"{OUTPUT_NAMES.get(name, name)} = "
                 f"{_value_text(design, name, per_row)}" for name in names
                 if not (name in SHOWN_WHEN_GIVEN and name not in per_row
                         and getattr(design, name, None) is None)]
        lines.append(f"{title}: " + ", ".join(parts))
    return lines
