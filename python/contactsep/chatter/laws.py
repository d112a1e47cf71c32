"""The Hertz family's settings (docs/chatter.md, "Contact laws"): the
dampings and elastic parts ``simulate`` takes, the one-line refusal of a
law that cannot run, and the energy book of a run."""

from __future__ import annotations

import math

import numpy as np

from contactsep.errors import InputError

DAMPINGS = ("none", "flores", "hunt-crossley")
#: Contact buttons: a sphere on a flat, a cylinder across it.
BUTTONS = ("sphere", "cylinder")
#: The Hertz family's elastic parts.
CONTACTS = ("hertz", "thornton")


class ChatterError(InputError):
    """A simulation setting the chatter layer refuses."""


def real(name: str, value, unit: str) -> float:
    """A real number for argument ``name`` (never a bool, None or a
    string), or a ChatterError naming it."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(
            value, (int, float, np.integer, np.floating)):
        raise ChatterError(f"{name}: found {value!r}, expected a number"
                           + (f" ({unit})" if unit else ""))
    try:
        return float(value)
    except OverflowError:
        from contactsep.errors import shown
        raise ChatterError(f"{name}: found {shown(value)}, expected a "
                           f"finite number" + (f" ({unit})" if unit else "")
                           ) from None


def check_law(model, damping, alpha, contact, yield_pressure,
               static_correction):
    """Refuse a contact law that cannot run (the Hertz family's), in one
    line naming the argument; returns alpha and the yield pressure as
    floats (or None)."""
    if contact not in CONTACTS:
        raise ChatterError(f"contact: found {contact!r}, expected one of "
                           f"{', '.join(CONTACTS)}")
    hertz = model == "hertz"
    if alpha is not None:
        alpha = real("alpha", alpha, "s/in")
        if damping != "hunt-crossley":
            raise ChatterError(f"alpha: found {alpha!r}, expected none "
                               f"without damping hunt-crossley")
        if not (alpha > 0.0 and math.isfinite(alpha)):
            raise ChatterError(f"alpha: found {alpha!r}, expected a "
                               f"Hunt-Crossley constant > 0 s/in")
    elif damping == "hunt-crossley":
        raise ChatterError("alpha: hunt-crossley damping needs its "
                           "material constant alpha (s/in; --alpha)")
    if yield_pressure is not None:
        yield_pressure = real("yield_pressure", yield_pressure, "psi")
        if contact != "thornton":
            raise ChatterError(f"yield_pressure: found {yield_pressure!r}, "
                               f"expected none without contact thornton")
        if not (yield_pressure > 0.0 and math.isfinite(yield_pressure)):
            raise ChatterError(f"yield_pressure: found {yield_pressure!r}, "
                               f"expected a pressure > 0 psi")
    elif contact == "thornton":
        raise ChatterError("yield_pressure: thornton contact needs the "
                           "yield pressure (psi; --yield-pressure)")
    if not hertz and (damping != "none" or contact != "hertz"):
        raise ChatterError(f"damping/contact: {damping}/{contact} are Hertz "
                           f"laws; model {model} takes none/hertz")
    return alpha, yield_pressure


def check_button(model, button, length, contact):
    """Refuse a button that cannot run, in one line naming the
    argument; returns the cylinder's length as a float (or None)."""
    from contactsep.model.design_domain import SIZE_RANGE
    if button not in BUTTONS:
        raise ChatterError(f"button: found {button!r}, expected one of "
                           f"{', '.join(BUTTONS)}")
    if button == "cylinder" and model != "hertz":
        raise ChatterError(f"button: a cylinder is a Hertz-family law; "
                           f"model {model} takes sphere")
    if button == "cylinder" and contact == "thornton":
        raise ChatterError("button: thornton's law is a sphere's (give "
                           "button sphere)")
    if length is None:
        return None
    length = real("button_length", length, "in")
    if button != "cylinder":
        raise ChatterError(f"button_length: found {length!r}, expected "
                           f"none without button cylinder")
    low, high = SIZE_RANGE
    if not low <= length <= high:
        raise ChatterError(f"button_length: found {length!r}, expected "
                           f"{low:g} to {high:g} in")
    return length


def energy_book(run, stack, parts) -> dict:
    """The Hertz family's energy book (docs/chatter.md, "Energy book"):
    the energy at the start, the contacts' dissipation (summed by the
    stepper), the vibration energy left in each member's modes and the
    contacts' stored energy at the end (in lb); empty for Newton."""
    if not run.book:
        return {}
    q, v = run.book["q"], run.book["v"]
    modal = 0.5 * stack.m * (v**2 + (stack.p * q)**2)
    ends = np.cumsum([0] + [member.p.size for member in parts])
    return {"energy_initial_lbin": float(run.energy[0]),
            "energy_dissipated_contact_lbin": float(run.book["dissipated"]),
            **{f"energy_member{i + 1}_lbin": float(modal[ends[i]:ends[i + 1]]
                                                   .sum()) for i in range(3)},
            "energy_contact_lbin": float(run.book["stored"])}
