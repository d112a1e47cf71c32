"""Values typed with a unit: ``30.5mm``, ``200GPa``, ``7.85g/cm3``,
``10us``, read by pint (``pip install 'contactsep[units]'``) and
converted to the package's units (in, lb, s; psi; lb/in^3).

A bare number keeps the package's unit: units are only ever read from a
value that carries one, so every existing deck, design file and command
line means what it meant.  Conventions:

* a weight density (``gamma``) takes a mass density (``7.85 g/cm^3``:
  the weight under standard gravity, so that 1 lb/in^3 of mass weighs
  1 lbf/in^3) or a weight density (``77 kN/m^3``);
* a force (``preload``) takes a force (``1.5 N``, ``0.3 lbf``) or a mass
  under standard gravity (``0.3 lb`` is read as 0.3 lbf);
* an exponent may follow a unit directly (``cm3``, ``in^3``, ``in**3``);
* a converted value is rounded to 15 significant digits, so that the
  conversion's round-off does not show (``10us`` is 1e-05 s exactly).
"""

from __future__ import annotations

import functools
import re

from contactsep.errors import InputError

#: The package's unit for each kind of quantity, as pint spells it.
TARGETS = {"in": "inch", "s": "second", "lb": "lbf", "psi": "psi",
           "lb/in^3": "lbf / inch**3", "lb s": "lbf * second",
           "in/s": "inch / second", "rad/s": "radian / second"}
#: A number, optionally followed by a unit.
_NUMBER = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)"
                     r"\s*([A-Za-z\u00b5].*?)?\s*$")
#: A unit letter followed directly by its exponent ('cm3' -> 'cm**3').
_EXPONENT = re.compile(r"(?<=[A-Za-z])(\^|\*\*)?(\d+)")


@functools.lru_cache(maxsize=1)
def _registry():
    try:
        import pint
    except ImportError:
        return None
    return pint.UnitRegistry()


def split(text: str) -> tuple[str, str] | None:
    """(number, unit) of a text with a unit after its number, or None
    for a bare number (or anything that is not a number first)."""
    match = _NUMBER.match(text) if isinstance(text, str) else None
    if match is None or not match.group(2):
        return None
    return match.group(1), match.group(2)


def convert(text: str, unit: str, label: str) -> float:
    """The value of ``text`` ('30.5mm') in the package's ``unit`` (a key
    of TARGETS); an InputError naming ``label`` if it has no unit pint
    knows, or a unit of another kind."""
    parts = split(text)
    if parts is None:
        raise InputError(f"{label}: found {text!r}, expected a number "
                         f"with a unit")
    number, typed = parts
    registry = _registry()
    if registry is None:
        raise InputError(f"{label}: found {text!r}: values with units need "
                         f"pint (pip install 'contactsep[units]'); or give "
                         f"a bare number in {unit}")
    if unit not in TARGETS:
        raise InputError(f"{label}: found {text!r}, expected a "
                         f"dimensionless number (no unit)")
    spelled = _EXPONENT.sub(lambda m: f"**{m.group(2)}", typed)
    try:
        quantity = registry.Quantity(float(number), registry.Unit(spelled))
    except Exception:     # pint raises several kinds for a bad unit
        raise InputError(f"{label}: found {text!r}: {typed!r} is not a "
                         f"unit pint knows (e.g. mm, in, GPa, psi, "
                         f"g/cm^3, us)") from None
    target = registry.Unit(TARGETS[unit])
    gravity = registry.Quantity(1.0, "standard_gravity")
    for candidate in (quantity, quantity * gravity):
        if candidate.dimensionality == target.dimensionality:
            return float(f"{candidate.to(target).magnitude:.15g}")
    raise InputError(f"{label}: found {text!r}, expected a quantity in "
                     f"{unit} (or any unit of that kind)")
