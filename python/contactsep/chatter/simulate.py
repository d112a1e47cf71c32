"""``simulate(design, model=...)``: does the circuit open, when, how long.

Models (docs/chatter.md):

* ``"appE"`` — Appendix E: the upper contact against a rigid, immovable
  separator, event-driven with the exact modal flow (the lower contact
  never moves, so the circuit never opens: the model answers how the
  upper contact chatters);
* ``"newton"`` — the three beams, two unilateral contacts, Newton's
  impact law with restitution e: the adaptive exact-flow stepper by
  default, Moreau-Jean time stepping on request (``stepper="fixed"``);
* ``"hertz"`` — the three beams with Hertz contact forces (elastic, or
  Flores damping calibrated to e with V_ref the first impact speed);
  the adaptive stepper by default, the fixed-step one on request.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from contactsep.chatter import circuit, runners, system
from contactsep.chatter.contacts import HertzLaw
from contactsep.chatter.result import ChatterResult
from contactsep.chatter.system import members
from contactsep.constants import LISTING_TAU_S
from contactsep.errors import InputError

MODELS = ("appE", "newton", "hertz")
#: Most modes per member, and most time steps, a run may take.
MAX_MODES = 1024
MAX_STEPS = 1e9
DAMPINGS = ("none", "flores")
STEPPERS = ("adaptive", "fixed")
#: Default steps of the adaptive steppers (docs/chatter.md,
#: "Convergence"): Hertz 5e-8 s (the thesis rig's first impulse, max
#: lower gap and open time within 1e-6 of the dt -> 0 limit); Newton
#: 5e-8 s (max lower gap within 1 % for d <= 0.75 in, N <= 32).
DEFAULT_DT = {"appE": None, "newton": 5e-8, "hertz": 5e-8}
#: Sample intervals per simulation (the gaps are sampled, not every step).
DEFAULT_SAMPLES = 60_000
#: Poisson's ratio and button radius (in) of the Hertz constant.
DEFAULT_NU = 0.33
DEFAULT_BUTTON_RADIUS = 0.125


#: A dt more than this many times the default is far from converged.
COARSE_DT = 10.0


class ChatterError(InputError):
    """A simulation setting the chatter layer refuses."""


class CoarseStepWarning(UserWarning):
    """A time step far coarser than the converged default."""


def _stack(design):
    """Stacked modes of the three members: (m, p, h, q0, v0, members)."""
    upper, sep, lower = members(design)
    m = np.concatenate([np.full(upper.p.size, upper.mass),
                        np.full(sep.p.size, sep.mass),
                        np.full(lower.p.size, lower.mass)])
    p = np.concatenate([upper.p, sep.p, lower.p])
    zeros1, zeros3 = np.zeros(upper.p.size), np.zeros(lower.p.size)
    h = np.stack([np.concatenate([upper.x, -sep.x, zeros3]),
                  np.concatenate([zeros1, sep.x, -lower.x])])
    q0 = np.concatenate([upper.q0, sep.q0, lower.q0])
    return m, p, h, q0, np.zeros_like(q0), (upper, sep, lower)


def _system(design, preload, law) -> runners.System:
    """The stacked system, the lower contact preloaded if asked."""
    m, p, h, q0, v0, (upper, sep, lower) = _stack(design)
    g0 = np.zeros(2)
    if preload > 0.0:
        depth = 0.0 if law is None else (preload / law.k) ** (2.0 / 3.0)
        q_sep, q_low, g0 = system.preload_state(sep, lower, preload, depth)
        n1, n2 = upper.p.size, sep.p.size
        q0 = q0.copy()
        q0[n1:n1 + n2] += q_sep
        q0[n1 + n2:] += q_low
    return runners.System(m=m, p=p, h=h, g0=g0, q0=q0, v0=v0,
                          n_upper=upper.p.size)


def _single_impulse(design) -> dict:
    """The thesis's single-impulse answer (eq. 23, compiled model) as
    printed and in the impulse form (psi/M3)."""
    from contactsep.model import evaluate
    ev = evaluate(design)
    impulse = evaluate(design.replace(lower_response="impulse"))
    return {"t1_s": float(ev.t1) if ev.status == 0 else math.nan,
            "v_impact_in_s": float(ev.v_impact),
            "psi_lb_s": float(ev.psi), "v0_in_s": float(ev.v0),
            "y3_max_in": float(ev.y3_max),
            "y3_max_impulse_form_in": float(impulse.y3_max)}


def _check(design, model, damping, backend, preload, samples, theta, nu,
           button_radius, t_end, open_threshold, min_open, stepper):
    """Refuse, before any work, every setting that cannot run."""
    def refuse(message):
        raise ChatterError(message)
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
    if not (preload >= 0.0 and math.isfinite(preload)):
        refuse(f"preload: found {preload!r}, expected a force >= 0 lb")
    if model == "appE" and preload != 0.0:
        refuse("preload: appE has no lower contact (the upper contact "
               "against a rigid stop); use 0")
    if not (isinstance(samples, (int, np.integer)) and samples >= 1):
        refuse(f"samples: found {samples!r}, expected an integer >= 1")
    if not 0.5 <= theta <= 1.0:
        refuse(f"theta: found {theta!r}, expected 1/2 <= theta <= 1 "
               f"(Moreau-Jean's theta-method)")
    if not (-1.0 < nu <= 0.5 and button_radius > 0.0
            and math.isfinite(button_radius)):
        refuse(f"nu, button_radius: found {nu!r}, {button_radius!r}, "
               f"expected -1 < nu <= 0.5 and a radius > 0 in")
    if not (t_end > 0.0 and math.isfinite(t_end)):
        refuse(f"t_end: found {t_end!r}, expected a time > 0")
    if not (open_threshold >= 0.0 and math.isfinite(open_threshold)):
        refuse(f"open_threshold: found {open_threshold!r}, expected a "
               f"gap >= 0 in")
    if not (min_open >= 0.0 and math.isfinite(min_open)):
        refuse(f"min_open: found {min_open!r}, expected a time >= 0 s")
    if design.shape != ():
        refuse("design: chatter simulates one design, not a batch")
    if isinstance(design.n_modes, tuple):
        refuse("n_modes: one N for all members")
    if int(design.n_modes) > MAX_MODES:
        refuse(f"n_modes: found {int(design.n_modes)}, expected at most "
               f"{MAX_MODES} modes per member (a run costs steps x 3N; "
               f"N = 64 converges the Hertz answers, docs/chatter.md)")
    if not float(design.ys) > 0.0:
        refuse(f"ys: found {float(design.ys)!r}, expected a release "
               f"height > 0 above the separator")


def simulate(design, model="newton", damping="none", dt=None, *,
             t_end=LISTING_TAU_S, open_threshold=circuit.OPEN_THRESHOLD,
             min_open=circuit.MIN_OPEN, preload=0.0, nu=DEFAULT_NU,
             button_radius=DEFAULT_BUTTON_RADIUS, backend="compiled",
             samples=DEFAULT_SAMPLES, theta=0.5, stepper="adaptive",
             single_impulse=True) -> ChatterResult:
    """Simulate the contact system of a (single) design from the release.

    ``dt`` defaults per model (DEFAULT_DT; it is rounded so that a whole
    number of steps ends at ``t_end``); ``preload`` (lb, >= 0) presses
    the lower contact up against the separator at the start (static
    equilibrium of the N-mode models, :func:`system.preload_state`; the
    release height stays y_s above the preloaded separator; appE has no
    lower contact and takes only 0); ``open_threshold`` (in) is the gap
    above which a contact is open, ``min_open`` (s) the shortest circuit
    opening that counts as a discontinuity event; ``nu`` and
    ``button_radius`` (in) set the Hertz constant; ``samples`` sample
    intervals of the gaps (1: the ends only; the summary does not depend
    on it for hertz and newton); ``stepper="fixed"`` runs Hertz with the
    fixed-step splitting (the reference); ``backend="numpy"`` runs the
    NumPy twins of the fixed-step steppers (slow: tests only);
    ``single_impulse=False`` skips the thesis's eq. 23 figures (two model
    evaluations, ~1 ms: a sweep of chatter runs need not pay them).
    """
    _check(design, model, damping, backend, preload, samples, theta, nu,
           button_radius, t_end, open_threshold, min_open, stepper)
    single = _single_impulse(design) if single_impulse else {}
    settings = dict(t_end_s=float(t_end),
                    open_threshold_in=float(open_threshold),
                    min_open_s=float(min_open), design=design,
                    single_impulse=single)
    if model == "appE":
        return _appendix_e(design, backend, settings)
    dt = DEFAULT_DT[model] if dt is None else float(dt)
    if not (dt > 0.0 and dt < t_end):
        raise ChatterError(f"dt: found {dt!r}, expected 0 < dt < t_end")
    if t_end / dt > MAX_STEPS:
        raise ChatterError(f"dt: found {dt!r}, expected at least "
                           f"{t_end / MAX_STEPS:.3g} s "
                           f"(at most {MAX_STEPS:.0e} steps a run)")
    if dt > COARSE_DT * DEFAULT_DT[model]:
        warnings.warn(f"dt: {dt:g} s is {dt / DEFAULT_DT[model]:.3g} times "
                      f"the converged default {DEFAULT_DT[model]:g} s: the "
                      f"answers may be far from converged (docs/chatter.md)",
                      CoarseStepWarning, stacklevel=2)
    steps = max(1, int(round(t_end / dt)))
    dt = t_end / steps
    stride = max(1, steps // samples)
    law = None
    if model == "hertz":
        flores = dict(e=float(design.e), v_ref=(
            single or _single_impulse(design))["v_impact_in_s"]) \
            if damping == "flores" else {}
        law = HertzLaw.for_materials(float(design.E1), nu, button_radius,
                                     **flores)
    stack = _system(design, preload, law)
    if model == "newton" and stepper == "adaptive" and backend == "compiled":
        run = runners.newton_adaptive(stack, float(design.e), dt, steps,
                                      stride, open_threshold)
    elif model == "newton":
        run = (runners.moreau_jean if backend == "compiled"
               else runners.moreau_jean_numpy)(
            stack, float(design.e), dt, theta, steps, stride,
            open_threshold)
    elif stepper == "adaptive" and backend == "compiled":
        run = runners.hertz_adaptive(stack, law, dt, steps, stride,
                                     open_threshold)
    else:
        run = runners.hertz_fixed(stack, law, dt, steps, stride,
                                  open_threshold, backend)
    found = circuit.discontinuity(run.upper_open, run.lower_open, min_open)
    return ChatterResult(
        model=model, n_modes=int(design.n_modes), dt=dt, t=run.t,
        gap_upper=run.gaps[:, 0], gap_lower=run.gaps[:, 1],
        energy=run.energy, **found,
        max_lower_gap_in=run.max_lower_gap_in,
        first_impact_s=run.first[0], first_impulse_lb_s=run.first[1],
        energy_ratio=float(run.energy[-1] / run.energy[0]),
        preload_lb=float(preload), damping=damping,
        stepper=stepper if backend == "compiled" else "fixed",
        work=run.work, **settings)


def _appendix_e(design, backend, settings) -> ChatterResult:
    from contactsep.chatter.event_driven import rigid_stop_from_design

    t_end = settings["t_end_s"]
    r = rigid_stop_from_design(
        design, t_end=t_end,
        backend="fortran" if backend == "compiled" else "numpy")
    t = np.linspace(0.0, t_end, DEFAULT_SAMPLES + 1)
    gap_upper = r.displacement(t)
    gap_lower = np.zeros_like(t)
    threshold = settings["open_threshold_in"]
    found = circuit.discontinuity(
        circuit.open_from_samples(t, gap_upper, t_end, threshold),
        circuit.open_from_samples(t, gap_lower, t_end, threshold),
        settings["min_open_s"])
    energy = np.full_like(t, np.nan)
    energy[0], energy[-1] = r.initial_energy, r.final_energy
    return ChatterResult(
        model="appE", n_modes=int(design.n_modes), dt=0.0, t=t,
        gap_upper=gap_upper, gap_lower=gap_lower, energy=energy, **found,
        max_lower_gap_in=0.0,
        first_impact_s=float(r.impact_t[0]) if len(r.impact_t)
        else math.nan,
        first_impulse_lb_s=float(r.impulse[0]) if len(r.impulse)
        else math.nan,
        energy_ratio=r.final_energy / r.initial_energy,
        rigid_stop=r, work={"impacts": len(r.impact_t)}, **settings)
