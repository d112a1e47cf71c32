"""The chatter simulation's settings, every check of them in one place:
:func:`check_settings` refuses, before any work and in one line naming
the argument, every :func:`contactsep.chatter.simulate` setting that
cannot run (:func:`checked_arguments`: all of simulate's arguments
checked in order, :class:`Arguments`); :func:`parse_value` reads a setting as inputs name it
(``contactsep chatter --preload``, a chatter sweep's ``--vary
preload=...`` or ``--set``, a sweep file's settings), or a Design field.

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
from contactsep.chatter import laws, stop_event
from contactsep.chatter.laws import ChatterError
from contactsep.chatter.limits import (
    APPE_MAX_MODES,
    MAX_MODES,
    MAX_SAMPLES,
    MAX_T_END,
    MODELS,
    STEPPERS,
)
from contactsep.constants import LISTING_TAU_S
from contactsep.errors import InputError
from contactsep.model import fields
from contactsep.model.design import Design
from contactsep.model.design_domain import SIZE_RANGE

#: The settings a chatter sweep may vary (--vary) and sample (--sample).
VARIABLE_SETTINGS = ("preload", "min_open", "damping", "dt", "alpha",
                     "contact", "yield_pressure")
SAMPLED_SETTINGS = ("preload", "min_open")
#: Settings whose value is one of a few words.
CHOICES = {"damping": laws.DAMPINGS, "contact": laws.CONTACTS,
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


#: A real number for an argument, or a ChatterError naming it.
_real = laws.real


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
    if damping not in laws.DAMPINGS:
        refuse(f"damping: found {damping!r}, expected one of "
               f"{', '.join(laws.DAMPINGS)}")
    if stepper not in STEPPERS:
        refuse(f"stepper: found {stepper!r}, expected one of "
               f"{', '.join(STEPPERS)}")
    preload = _real("preload", preload, "lb")
    theta = _real("theta", theta, "")
    nu = _real("nu", nu, "")
    button_radius = _real("button_radius", button_radius, "in")
    t_end = None if t_end is None else _real("t_end", t_end, "s")
    open_threshold = _real("open_threshold", open_threshold, "in")
    min_open = _real("min_open", min_open, "s")
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
    alpha, yield_pressure = laws.check_law(a.model, a.damping, a.alpha,
                                           a.contact, a.yield_pressure,
                                           static_correction)
    button_length = laws.check_button(a.model, a.button, a.button_length,
                                      a.contact)
    if not isinstance(a.verify, (bool, np.bool_)):
        raise ChatterError(f"verify: found {a.verify!r}, expected True or "
                           f"False")
    stop = stop_event.check(a.stop_at_event, a.model, a.stepper, a.backend,
                            a.verify)
    return dataclasses.replace(a, static_correction=static_correction,
                               alpha=alpha, yield_pressure=yield_pressure,
                               button_length=button_length,
                               stop_at_event=stop)
