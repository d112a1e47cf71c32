"""What a sweep specification must satisfy before any work: the model
and its settings, a fixed preload within what the simulation takes, and
steps the simulation takes (one line each, naming the option)."""

from __future__ import annotations

import warnings

import numpy as np

from contactsep.errors import InputError
from contactsep.model import thesis_design
from contactsep.chatter import settings as chatter_settings
from contactsep.model import fields as design_fields

#: What a sweep may evaluate: the general model, or a chatter model.
MODELS = ("eq23", "hertz", "newton")

#: Design fields the largest preload a simulation takes depends on (the
#: separator's and the lower contact's flexibility at the contact; the
#: densities cancel: M p^2 does not depend on them).
_PRELOAD_LIMIT_FIELDS = {"L2", "b2", "h2", "E2", "end2", "x2", "L3", "b3",
                         "h3", "E3", "end3", "x3", "n_modes"}


#: Design fields the three-beam simulation does not read: the single-
#: impulse model's window, impact speed, lower response and L_c reading
#: (a chatter sweep's window is 0-0.06 s from the release).
CHATTER_UNUSED = ("tau", "impact_velocity", "lower_response", "lc_reading")


class SweepError(InputError):
    """A sweep specification the command refuses."""


def check_fixed(base, settings, centres=None) -> tuple[dict, dict]:
    """The fixed design fields (``base``: field or alias -> value) and
    chatter settings, each read as the command line reads it: an unknown
    name, a value of the wrong type or out of range is one line naming
    it (issue 31: {"bogus": 1} was a KeyError, {"dt": nan} ran no
    design, {"dt": "abc"} a TypeError).  The fixed fields are checked as
    one design with the swept fields at ``centres`` (field -> a value
    the sweep takes), not at the thesis's values: a relay 6 mm long
    sweeping its thickness around 0.8 mm is not refused for the
    thesis's 0.25 in.  Returns them by field name."""
    if base is not None and not isinstance(base, dict):
        raise SweepError(f"base: found {type(base).__name__}, expected a "
                         f"dict of design fields")
    if settings is not None and not isinstance(settings, dict):
        raise SweepError(f"settings: found {type(settings).__name__}, "
                         f"expected a dict of chatter settings")
    try:
        return _fixed(base, settings, centres or {})
    except SweepError:
        raise
    except InputError as error:
        raise SweepError(str(error)) from None


def _fixed(base, settings, centres: dict) -> tuple[dict, dict]:
    fields = {}
    for name, value in (base or {}).items():
        if isinstance(value, np.generic):
            value = value.item()
        field = design_fields.field_name(str(name), f"base: {name}")
        fields[field] = design_fields.parse_value(field, value,
                                                  f"base: {name}")
    if fields:
        try:
            thesis_design(**{**centres, **fields})
        except InputError as error:
            raise SweepError(f"base: {error}") from None
    chosen = {}
    for name, value in (settings or {}).items():
        if str(name) not in design_fields.SETTINGS:
            raise SweepError(f"settings: {name}: not a chatter setting "
                             f"(one of {', '.join(design_fields.SETTINGS)})")
        chosen[name] = chatter_settings.parse_value(
            name, value, f"--{name.replace('_', '-')}")
    return fields, chosen


def check_chatter_modes(model: str, fixed) -> None:
    """A chatter sweep's fixed N (``fixed``: one N or three, None when
    varied or the default) within the simulation's limit, before any
    work: every design would be refused on its own.  A varied N past it
    is the status of its rows."""
    from contactsep.chatter.limits import MAX_MODES
    if fixed is None or model == "eq23":
        return
    max_modes = max(fixed) if isinstance(fixed, tuple) else int(fixed)
    if max_modes > MAX_MODES:
        raise SweepError(f"--n-modes: found {max_modes}, expected at most "
                         f"{MAX_MODES} modes per member for the chatter "
                         f"simulation (--model {model})")


def check_elastic(model: str, swept: set, settings: dict) -> None:
    """Elastic Hertz contact (damping none, not varied) reads no e: a
    sweep of e would give equal rows."""
    if model == "hertz" and "e" in swept and "damping" not in swept and \
            settings.get("damping", "none") == "none":
        raise SweepError("e: not used by elastic Hertz contact (--model "
                         "hertz, damping none); with --damping flores it "
                         "sets the damping, with --model newton the "
                         "impact law")


def check_used(model: str, given: set) -> None:
    """A chatter sweep refuses the design fields its simulation does
    not read (CHATTER_UNUSED): fixed or varied, every row would be the
    same, and a note would name a value nothing used."""
    unused = sorted(given & set(CHATTER_UNUSED)) if model != "eq23" else []
    if unused:
        raise SweepError(f"{', '.join(unused)}: not used by the chatter "
                         f"simulation (--model {model}; its window is "
                         f"0-0.06 s from the release): a field of the "
                         f"single-impulse model (--model eq23)")


def check_preload(preload, base: dict, swept: set) -> None:
    """A fixed preload above what the simulation takes for every design
    (the limit depends on no swept field) is refused before any work;
    otherwise a design above its limit is its row's status 2."""
    if preload is None or swept & _PRELOAD_LIMIT_FIELDS:
        return
    from contactsep.chatter.stack import largest_preload
    most = largest_preload(thesis_design(**base))
    if preload > most:
        raise SweepError(f"--preload: found {preload!r}, expected at most "
                         f"{most:.6g} lb for this design (it would bend "
                         f"the lower contact or the separator by more "
                         f"than its length)")


def check_dt(steps, max_modes: int, option: str, model: str) -> None:
    """Every step (fixed or varied) is one the simulation takes at the
    sweep's largest N: a sweep that would fail every design is refused
    before any work.  A coarse step is warned of here, once, not by
    every design."""
    from contactsep.chatter.limits import MAX_MODES, MAX_STEPS, MAX_WORK
    from contactsep.chatter.simulate import DEFAULT_DT
    from contactsep.chatter.stack import (
        COARSE_DT,
        CoarseStepWarning,
        smallest_dt,
    )
    least = smallest_dt(min(max_modes, MAX_MODES))
    for dt in steps:
        if dt < least:
            raise SweepError(f"{option}: found {dt!r}, expected at least "
                             f"{least:.3g} s at N = {max_modes} (a run "
                             f"takes at most {MAX_STEPS:.0e} steps and "
                             f"{MAX_WORK:.0e} steps x modes)")
    coarse = [dt for dt in steps if dt > COARSE_DT * DEFAULT_DT[model]]
    if coarse:
        warnings.warn(f"{option}: {max(coarse):g} s is more than "
                      f"{COARSE_DT:g} times the converged default "
                      f"{DEFAULT_DT[model]:g} s: the answers may be far "
                      f"from converged (docs/convergence.md)",
                      CoarseStepWarning, stacklevel=3)


def check_model(model: str, backend: str, used: set) -> None:
    """The settings belong to the chatter models, damping to Hertz; the
    chatter models run compiled."""
    if model not in MODELS:
        raise SweepError(f"--model: found {model!r}, expected one of "
                         f"{', '.join(MODELS)}")
    settings = sorted(used & set(design_fields.SETTINGS))
    if model == "eq23" and settings:
        raise SweepError(f"{', '.join(settings)}: a setting of the chatter "
                         f"simulation; needs --model hertz or newton")
    if model == "newton" and "damping" in used:
        raise SweepError("damping: the Hertz contact's (--model hertz); "
                         "Newton's impact law has e")
    hertz_only = sorted(used & {"alpha", "contact", "yield_pressure"})
    if model == "newton" and hertz_only:
        raise SweepError(f"{', '.join(hertz_only)}: the Hertz contact's "
                         f"(--model hertz)")
    if model != "eq23" and backend != "compiled":
        raise SweepError(f"--backend {backend}: the chatter sweeps run the "
                         f"compiled steppers")
