"""The chatter layer's limits (modes, steps, work, window, samples) and
the refusal, before any work and in one line naming the argument, of
every :func:`contactsep.chatter.simulate` setting that cannot run."""

from __future__ import annotations

import math

import numpy as np

from contactsep.chatter import laws
from contactsep.chatter.laws import ChatterError
from contactsep.model.design import SIZE_RANGE

#: The models simulate() runs.
MODELS = ("appE", "newton", "hertz")
#: Most modes per member, and most time steps, a run may take.
MAX_MODES = 1024
MAX_STEPS = 1e9
#: Most steps x modes (all three members) a newton or hertz run may take:
#: the default run at N = 1024 is 3.7e9 (about a minute).
MAX_WORK = 1e10
#: Most modes appE takes: its event search grows steeply with N (0.7 s
#: at N = 64, 1.9 s at 96, 25 s at 128; N = 1024 ran for 9 minutes).
APPE_MAX_MODES = 128
#: Longest window (s): 170 times the listing's TAU.
MAX_T_END = 10.0
#: Most sample intervals of the gaps (each sample holds t, two gaps and
#: the energy, and more on their way out: about 200 MB at the limit;
#: 10^9 asked for gigabytes).
MAX_SAMPLES = 4_000_000
#: A run of at least this many steps x modes (or appE with more modes
#: than FORKED_APPE_MODES) runs in a child process, so that Ctrl-C and
#: SIGTERM stop it at once instead of after the compiled call returns.
FORKED_WORK = 3e8
FORKED_APPE_MODES = 48
DAMPINGS = laws.DAMPINGS
CONTACTS = laws.CONTACTS
BUTTONS = laws.BUTTONS
STEPPERS = ("adaptive", "fixed")

#: A real number for an argument, or a ChatterError naming it.
_real = laws.real


def check_settings(design, model, damping, backend, preload, samples,
                   theta, nu, button_radius, t_end, open_threshold,
                   min_open, stepper):
    """Refuse, before any work, every setting that cannot run."""
    def refuse(message):
        raise ChatterError(message)
    from contactsep.model import Design
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
               f"answers, docs/chatter.md)")
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
