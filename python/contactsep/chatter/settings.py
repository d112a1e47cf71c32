"""The chatter simulation's settings, every check of them in one place:
:func:`check_settings` refuses, before any work and in one line naming
the argument, every :func:`contactsep.chatter.simulate` setting that
cannot run (:func:`checked_arguments`: all of simulate's arguments
checked in order, :class:`Arguments`); :func:`parse_value` reads a setting as inputs name it
(``contactsep chatter --preload``, a chatter sweep's ``--vary
preload=...`` or ``--set``, a sweep file's settings), or a Design field.
The Hertz family's settings are here too: the dampings, buttons and
elastic parts (:data:`DAMPINGS`, :data:`BUTTONS`, :data:`CONTACTS`) and
their checks (:func:`check_law`, :func:`check_button`), with the stop at
an event's (:func:`check_stop_at_event`) and :class:`ChatterError`, the
refusal of them all.

The settings' names, units and output columns are the Design's
vocabulary's (:data:`contactsep.model.fields.SETTINGS`): every reader of
a design refuses them as design fields.  A chatter sweep (``contactsep
sweep --model hertz|newton``) fixes, varies or samples them
(:data:`VARIABLE_SETTINGS`, :data:`SAMPLED_SETTINGS`; dt is fixed or
varied, not sampled).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from contactsep import units
from contactsep.chatter.limits import (
    APPE_MAX_MODES,
    MAX_MODES,
    MAX_SAMPLES,
    MAX_T_END,
    MODELS,
    STEPPERS,
)
from contactsep.constants import LISTING_TAU_S
from contactsep.errors import InputError, shown
from contactsep.model import fields
from contactsep.model.design import Design
from contactsep.model.design_domain import SIZE_RANGE

#: The Hertz family's dampings (docs/chatter.md, "Contact laws").
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


#: The settings a chatter sweep may vary (--vary) and sample (--sample).
VARIABLE_SETTINGS = ("preload", "min_open", "damping", "dt", "alpha",
                     "contact", "yield_pressure")
SAMPLED_SETTINGS = ("preload", "min_open")
#: Settings whose value is one of a few words.
CHOICES = {"damping": DAMPINGS, "contact": CONTACTS,
           "static_correction": ("on", "off")}


def parse_value(name: str, text, label: str):
    """A chatter setting's value (or a Design field's:
    :func:`contactsep.model.fields.parse_value`) from ``text``;
    ``label`` names it in errors ('--preload', 'base: dt').

    preload and min_open take a finite number >= 0, dt one > 0 below the
    window, alpha and yield_pressure one > 0, t_end a window > 0 up to
    MAX_T_END, damping, contact and static_correction one of their words.
    """
    if name in CHOICES:
        return fields.parse_word(text, CHOICES[name], label)
    if name in fields.SETTINGS:
        return _setting(name, text, label)
    return fields.parse_value(name, text, label)


def _setting(field: str, text, label: str) -> float:
    """preload (lb) or min_open (s): a finite number >= 0; dt (s): a
    finite number > 0 and below the window (the chatter layer refuses
    the rest; refused here, it is one line before any work)."""
    unit = fields.unit(field)
    try:
        if isinstance(text, bool):
            raise ValueError
        value = units.convert(text, unit, label) \
            if units.split(text) is not None else float(text)
    except (TypeError, ValueError, OverflowError):
        value = math.nan
    if field == "t_end" and not (0.0 < value <= MAX_T_END):
        raise InputError(f"{label}: found {text!r}, expected a window > 0 "
                         f"and at most {MAX_T_END:g} s")
    if field in ("alpha", "yield_pressure") and not (
            math.isfinite(value) and value > 0.0):
        raise InputError(f"{label}: found {text!r}, expected a "
                         f"{'constant' if field == 'alpha' else 'pressure'}"
                         f" > 0 {unit}")
    if field == "dt" and not (0.0 < value < LISTING_TAU_S):
        raise InputError(f"{label}: found {text!r}, expected a time step "
                         f"> 0 and below the window, {LISTING_TAU_S:g} s")
    if not (math.isfinite(value) and value >= 0.0):
        raise InputError(f"{label}: found {text!r}, expected a "
                         f"{'force' if field == 'preload' else 'time'} "
                         f">= 0 {unit}")
    if field == "min_open" and value > LISTING_TAU_S:
        raise InputError(f"{label}: found {text!r}, expected at most the "
                         f"window, {LISTING_TAU_S:g} s")
    return value


def check_settings(design, model, damping, backend, preload, samples,
                   theta, nu, button_radius, t_end, open_threshold,
                   min_open, stepper):
    """Refuse, before any work, every setting that cannot run."""
    def refuse(message):
        raise ChatterError(message)
    if not isinstance(design, Design):
        refuse(f"design: found {type(design).__name__}, expected a "
               f"contactsep.Design")
    if model not in MODELS:
        refuse(f"model: found {model!r}, expected one of "
               f"{', '.join(MODELS)}")
    if backend not in ("compiled", "numpy"):
        refuse(f"backend: found {backend!r}, expected compiled or numpy")
    if damping not in DAMPINGS:
        refuse(f"damping: found {damping!r}, expected one of "
               f"{', '.join(DAMPINGS)}")
    if stepper not in STEPPERS:
        refuse(f"stepper: found {stepper!r}, expected one of "
               f"{', '.join(STEPPERS)}")
    preload = real("preload", preload, "lb")
    theta = real("theta", theta, "")
    nu = real("nu", nu, "")
    button_radius = real("button_radius", button_radius, "in")
    t_end = None if t_end is None else real("t_end", t_end, "s")
    open_threshold = real("open_threshold", open_threshold, "in")
    min_open = real("min_open", min_open, "s")
    if not (preload >= 0.0 and math.isfinite(preload)):
        refuse(f"preload: found {preload!r}, expected a force >= 0 lb")
    if model == "appE" and preload != 0.0:
        refuse("preload: appE has no lower contact (the upper contact "
               "against a rigid stop); use 0")
    if isinstance(samples, (bool, np.bool_)) or not isinstance(
            samples, (int, np.integer)) or not 1 <= samples <= MAX_SAMPLES:
        refuse(f"samples: found {samples!r}, expected an integer from 1 "
               f"to {MAX_SAMPLES:,}")
    if not 0.5 <= theta <= 1.0:
        refuse(f"theta: found {theta!r}, expected 1/2 <= theta <= 1 "
               f"(Moreau-Jean's theta-method)")
    if not -1.0 < nu <= 0.5:
        refuse(f"nu: found {nu!r}, expected -1 < nu <= 0.5")
    low, high = SIZE_RANGE
    if not low <= button_radius <= high:
        refuse(f"button_radius: found {button_radius!r}, expected {low:g} "
               f"to {high:g} in")
    if t_end is not None and not (0.0 < t_end <= MAX_T_END):
        refuse(f"t_end: found {t_end!r}, expected a time > 0 and at most "
               f"{MAX_T_END:g} s")
    if not 0.0 <= min_open <= (MAX_T_END if t_end is None else t_end):
        refuse(f"min_open: found {min_open!r}, expected 0 to t_end = "
               f"{MAX_T_END if t_end is None else t_end:g} s")
    if design.shape != ():
        refuse("design: chatter simulates one design, not a batch")
    if not float(design.ys) > 0.0:
        refuse(f"ys: found {float(design.ys)!r}, expected a release "
               f"height > 0 above the separator")
    if not 0.0 <= open_threshold < float(design.ys):
        refuse(f"open_threshold: found {open_threshold!r}, expected 0 <= "
               f"open_threshold < ys = {float(design.ys):g} in (a threshold "
               f"at the release height never sees the upper contact open)")
    if isinstance(design.n_modes, tuple):
        refuse("n_modes: one N for all members")
    limit = APPE_MAX_MODES if model == "appE" else MAX_MODES
    if int(design.n_modes) > limit:
        refuse(f"n_modes: found {int(design.n_modes)}, expected at most "
               f"{limit} modes per member for {model} (a run costs steps x "
               f"3N, appE's event search more; N = 64 converges the Hertz "
               f"answers, docs/numerics.md)")
    if float(design.gap) != 0.0:
        refuse(f"gap: found {float(design.gap)!r}, expected 0: the "
               f"simulation releases the upper contact ys above the "
               f"separator's surface (give ys - gap as ys)")
    if design.Lc is not None:
        refuse(f"Lc: found {design.Lc!r}, expected None: the simulation's "
               f"separator is the beam of length L2 (L_c is the single-"
               f"impulse model's equivalent length)")
    if damping == "flores" and not float(design.e) > 0.0:
        refuse("e: found 0.0, expected e > 0 with Flores damping (its "
               "constant is 8(1 - e)/(5 e V))")


def check_stop_at_event(stop_at_event, model: str, stepper: str,
                        backend: str, verify) -> bool:
    """Whether the run stops at its first event
    (:mod:`contactsep.chatter.stop_event`); a request the stop does not
    cover is refused in one line (ChatterError)."""
    if not isinstance(stop_at_event, (bool, np.bool_)):
        raise ChatterError(f"stop_at_event: found {stop_at_event!r}, "
                           f"expected True or False")
    if not stop_at_event:
        return False
    if model == "appE":
        raise ChatterError("stop_at_event: found True with model 'appE', "
                           "expected newton or hertz (appE's lower contact "
                           "never moves: its circuit never opens)")
    if stepper != "adaptive" or backend != "compiled":
        raise ChatterError(f"stop_at_event: found True with stepper "
                           f"{stepper!r} and backend {backend!r}, expected "
                           f"the compiled adaptive stepper (the one that "
                           f"watches the circuit as it goes)")
    if verify:
        raise ChatterError("stop_at_event: found True with verify=True, "
                           "expected one of them (verify compares figures "
                           "of the whole window)")
    return True


@dataclasses.dataclass(frozen=True)
class Arguments:
    """:func:`contactsep.chatter.simulate`'s arguments, by name (its
    docstring documents each); :func:`checked_arguments` checks them."""

    design: object
    model: str
    damping: str
    dt: object
    t_end: object
    open_threshold: object
    min_open: object
    preload: object
    nu: object
    button_radius: object
    backend: str
    samples: object
    theta: object
    stepper: str
    single_impulse: object
    verify: object
    static_correction: object
    alpha: object
    contact: str
    yield_pressure: object
    button: str
    button_length: object
    stop_at_event: object


def checked_arguments(a: Arguments) -> Arguments:
    """``a`` checked before any work, in this order (a bad input is told
    of its first bad setting): the static correction's flag, every
    setting (:func:`check_settings`), the law, the button, verify, the
    stop at an event.  Returned with the law's checked ``alpha``,
    ``yield_pressure`` and ``button_length``, the static correction as
    it acts (hertz only) and ``stop_at_event`` as the run takes it."""
    if not isinstance(a.static_correction, (bool, np.bool_)):
        raise ChatterError(f"static_correction: found "
                           f"{a.static_correction!r}, expected True or "
                           f"False")
    static_correction = bool(a.static_correction) and a.model == "hertz"
    check_settings(a.design, a.model, a.damping, a.backend, a.preload,
                   a.samples, a.theta, a.nu, a.button_radius, a.t_end,
                   a.open_threshold, a.min_open, a.stepper)
    alpha, yield_pressure = check_law(a.model, a.damping, a.alpha,
                                           a.contact, a.yield_pressure,
                                           static_correction)
    button_length = check_button(a.model, a.button, a.button_length,
                                      a.contact)
    if not isinstance(a.verify, (bool, np.bool_)):
        raise ChatterError(f"verify: found {a.verify!r}, expected True or "
                           f"False")
    stop = check_stop_at_event(a.stop_at_event, a.model, a.stepper, a.backend,
                            a.verify)
    return dataclasses.replace(a, static_correction=static_correction,
                               alpha=alpha, yield_pressure=yield_pressure,
                               button_length=button_length,
                               stop_at_event=stop)
