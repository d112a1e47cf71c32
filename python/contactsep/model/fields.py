"""The Design's fields as inputs and outputs name them, in one place:
each field's name, unit, meaning, other names, output column, words, and
its value read from text (docs/names-and-units.md).

One convention for every JSON, CSV, Parquet, ``to_dict()`` and DataFrame
the package writes: a key or column is the quantity's snake_case name
followed by its unit's suffix, ``_in``, ``_s``, ``_lb``, ``_lb_s``,
``_in_s``, ``_psi``, ``_lb_in3``, ``_rad_s``, ``_cps``, ``_lb_s2_in``
(mass), ``_lb_in_rad`` and ``_lb_per_in`` (spring stiffnesses);
dimensionless names are bare (``e``, ``R``, ``n_modes``, ``status``).
Units are the package's: in, lb, s, psi, lb/in^3.  The separator's
thickness is ``d`` in every output (``d_in``), as in the thesis; ``--d``
and ``--h2`` (the Design's field) are both accepted on input.

Everything the command line, the design files and the sweeps read about
a field is checked here, once: :func:`parse_value` turns a text into a
field's value or raises an :class:`~contactsep.errors.InputError` naming
what the user typed.

The chatter simulation's settings (:data:`SETTINGS`: ``preload``,
``min_open``, ``damping``, ``dt``, ...) are named and written the same
way, and every reader of a design knows their names, so as to refuse
them as design fields in one line naming where they go (``--set
preload=...``, a design file's ``preload_lb``); their values are read and
checked by :mod:`contactsep.chatter.settings`.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from contactsep import beams, units
from contactsep.beams.member import THEORIES
from contactsep.errors import InputError, shown
from contactsep.model.design_domain import REAL_COLUMNS

#: field -> (unit suffix of its column, unit as printed, meaning).
FIELDS: dict[str, tuple[str, str, str]] = {}
MEMBERS = {"1": "upper contact", "2": "separator", "3": "lower contact"}
for _m, _member in MEMBERS.items():
    FIELDS.update({
        f"L{_m}": ("in", "in", f"{_member} length"),
        f"b{_m}": ("in", "in", f"{_member} width"),
        f"h{_m}": ("in", "in", f"{_member} thickness"
                   + (" d" if _m == "2" else "")),
        f"gamma{_m}": ("lb_in3", "lb/in^3", f"{_member} weight density"),
        f"E{_m}": ("psi", "psi", f"{_member} Young's modulus"),
        f"end{_m}": ("", "", f"{_member} end conditions (x = 0 first)"),
    })
FIELDS.update({
    "x1": ("in", "in", "contact point on the upper contact, from x = 0"),
    "x2": ("in", "in", "contact point on the separator, from x = 0"),
    "x3": ("in", "in", "contact point on the lower contact, from x = 0"),
    "x2_lower": ("in", "in", "where the lower contact touches the "
                             "separator, from x = 0 (default: x2)"),
    "Lc": ("in", "in", "separator equivalent length L_c (Table III)"),
    "ys": ("in", "in", "static deflection of the upper contact before "
                       "release"),
    "e": ("", "", "coefficient of restitution, 0 <= e <= 1"),
    "n_modes": ("", "", "modes per member: N, or N1,N2,N3"),
    "tau": ("s", "s", "window of the lower-contact response, from the "
                      "impact"),
    "gap": ("in", "in", "position of the separator surface seen by the "
                        "upper contact"),
    "impact_velocity": ("", "", "exact: abs(dy1/dt) at t1; listing: "
                                "Appendix G's ACT (no sin)"),
    "lower_response": ("", "", "as-printed: eq. 13/23 with v0/L3; "
                               "impulse: psi/M3 (eq. 19)"),
    "lc_reading": ("", "", "reading of L_c: listing (hybrid), "
                           "frequencies, or mass"),
    "release": ("", "", "tip: the cantilever's tip is deflected; "
                        "contact: the contact point x1"),
})
for _m, _member in MEMBERS.items():
    FIELDS.update({
        f"beam{_m}": ("", "", f"{_member} beam theory"),
        f"nu{_m}": ("", "", f"{_member} Poisson's ratio"),
        f"kappa{_m}": ("", "", f"{_member} shear coefficient"),
        f"kr{_m}": ("lb_in_rad", "lb in/rad", f"{_member} rotational "
                    f"spring at each clamped end"),
        f"kt{_m}": ("lb_per_in", "lb/in", f"{_member} translational spring "
                    f"at each supported end"),
        f"mass{_m}": ("lb", "lb", f"{_member} added point mass (weight)"),
        f"x_mass{_m}": ("in", "in", f"where the {_member}'s point mass "
                        f"sits, from x = 0"),
    })

#: The chatter simulation's settings an input may name (as FIELDS: unit
#: suffix, unit as printed, meaning); not design fields.
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
                     "check: docs/convergence.md)"),
    "static_correction": ("", "", "hertz: the truncated modes' residual "
                                  "flexibility in series with each contact "
                                  "(on or off)"),
    "t_end": ("s", "s", "window of each simulation from the release "
                        "(fixed, not varied)"),
}

#: The name a field has in outputs, where it is not the field's own.
OUTPUT_NAMES = {"h2": "d"}
#: Fields an output shows only when given (None, their default, is
#: left out, so that the outputs of designs without them are unchanged).
SHOWN_WHEN_GIVEN = ("x2_lower",)
#: Other names accepted for a field wherever a field is named on input.
ALIASES = {"d": "h2", "restitution": "e"}

#: The model's options, their values in the order of their codes (the
#: first is the default, except for lower_response: "impulse", the
#: physically consistent form; the thesis studies, decks and replay keep
#: "as-printed" explicitly).
IMPACT_VELOCITIES = ("exact", "listing")
LOWER_RESPONSES = ("as-printed", "impulse")
LC_READINGS = ("listing", "frequencies", "mass")
RELEASES = ("tip", "contact")
#: Fields whose value is one of a few words.
CHOICES = {"end1": beams.END_CONDITIONS, "end2": beams.END_CONDITIONS,
           "end3": beams.END_CONDITIONS,
           "impact_velocity": IMPACT_VELOCITIES,
           "lower_response": LOWER_RESPONSES, "lc_reading": LC_READINGS,
           "release": RELEASES, **{f"beam{m}": THEORIES for m in MEMBERS}}
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


def _entry(name: str) -> tuple[str, str, str]:
    return FIELDS[name] if name in FIELDS else SETTINGS[name]


def column_name(name: str) -> str:
    """A field's (or setting's) key in every output: 'h2' -> 'd_in',
    'e' -> 'e', 'gamma2' -> 'gamma2_lb_in3', 'preload' -> 'preload_lb'."""
    suffix = _entry(name)[0]
    name = OUTPUT_NAMES.get(name, name)
    return f"{name}_{suffix}" if suffix else name


def unit(name: str) -> str:
    """A field's (or setting's) unit as printed ('lb/in^3'); '' for
    dimensionless."""
    return _entry(name)[1]


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


def parse_word(text, allowed, label: str, aliases=None) -> str:
    """One of the words ``allowed`` from ``text`` (``aliases``: other
    words for them), or an InputError naming ``label``."""
    word = text.strip() if isinstance(text, str) else None
    word = (aliases or {}).get(word, word)
    if word not in allowed:
        raise InputError(f"{label}: found {text!r}, expected one of "
                         f"{', '.join(allowed)}")
    return word


def parse_number(text, suffix_unit: str, label: str) -> float:
    """A number from ``text`` (a str, maybe with a unit, ``'30.5mm'``,
    converted by :mod:`contactsep.units` to ``suffix_unit``; or a JSON
    number), or an InputError naming ``label``: any float, its range
    checked by whoever takes it."""
    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise InputError(f"{label}: found {text!r}, expected a number "
                         f"({suffix_unit or 'dimensionless'})")
    if units.split(text) is not None:
        return units.convert(text, suffix_unit, label)
    try:
        value = float(text)
    except (ValueError, OverflowError):
        raise InputError(f"{label}: found {shown(text)}, expected a number "
                         f"({suffix_unit or 'dimensionless'})") from None
    return value


def parse_value(field: str, text, label: str):
    """A Design field's value from ``text`` (a str, or a number or list
    from a JSON file); ``label`` names it in errors ('--d',
    'design.json: d_in').

    Real fields take a number (any float; the Design checks its range; a
    text may carry a unit, ``'30.5mm'``, converted by
    :mod:`contactsep.units`; the fields of :data:`OPTIONAL` also None,
    their default), end conditions and the options one of their words,
    ``n_modes`` an integer >= 1 or three of them ('4,16,4').  A chatter
    setting's value: :func:`contactsep.chatter.settings.parse_value`.
    """
    if field in CHOICES:
        return parse_word(text, CHOICES[field], label,
                          beams.ALIASES if field.startswith("end") else None)
    if field == "n_modes":
        return _modes(text, label)
    if text is None and field in OPTIONAL:
        return None
    return parse_number(text, FIELDS[field][1], label)


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


def describe(values: dict) -> dict:
    """Fields (and chatter settings) as an output shows them: column
    names, plain values."""
    out = {}
    for name, value in values.items():
        if isinstance(value, tuple):
            value = list(value)
        out[column_name(name)] = value
    return out


def design_keys(design) -> dict:
    """Every field of a single Design under its output key, plain values
    (a tuple of mode counts as a list; a field of SHOWN_WHEN_GIVEN only
    when given)."""
    out = {}
    for f in dataclasses.fields(design):
        value = getattr(design, f.name)
        if value is None and f.name in SHOWN_WHEN_GIVEN:
            continue
        if isinstance(value, tuple):
            value = list(value)
        elif isinstance(value, np.ndarray) and value.ndim == 0:
            value = value.item()
        out[column_name(f.name)] = value
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
