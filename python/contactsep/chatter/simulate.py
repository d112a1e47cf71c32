"""``simulate(design, model=...)``: does the circuit open, when, how long.

Models (docs/chatter.md):

* ``"appE"`` — Appendix E: the upper contact against a rigid, immovable
  separator, event-driven with the exact modal flow (the lower contact
  never moves, so the circuit never opens: the model answers how the
  upper contact chatters);
* ``"newton"`` — the three beams, two unilateral contacts, Newton's
  impact law with restitution e, Moreau-Jean time stepping;
* ``"hertz"`` — the three beams with Hertz contact forces (elastic, or
  Flores damping calibrated to e with V_ref the first impact speed).
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass, field

import numpy as np

from contactsep.chatter import circuit, system
from contactsep.chatter import status as chatter_status
from contactsep.chatter.contacts import HertzLaw
from contactsep.chatter.system import members
from contactsep.constants import LISTING_TAU_S
from contactsep.errors import InputError

MODELS = ("appE", "newton", "hertz")
#: Most modes per member, and most time steps, a run may take.
MAX_MODES = 1024
MAX_STEPS = 1e9
DAMPINGS = ("none", "flores")
#: Default steps: Moreau-Jean 1e-7 s (impulse to 1e-5 against Appendix E);
#: Hertz 2e-8 s (docs/chatter.md: converged to 1e-3 in the first impulse).
DEFAULT_DT = {"appE": None, "newton": 1e-7, "hertz": 2e-8}
#: Samples kept per simulation (the gaps are sampled, not every step).
DEFAULT_SAMPLES = 60_000


class ChatterError(InputError):
    """A simulation setting the chatter layer refuses."""


@dataclass(frozen=True)
class ChatterResult:
    """A simulation of the contact system over 0 <= t <= t_end from the
    release.  Gaps are positive when open (in); times in s; impulses in
    lb s; energies in in lb."""

    model: str
    n_modes: int
    dt: float
    #: Sample times (s) and both gaps (in) at them.
    t: np.ndarray
    gap_upper: np.ndarray
    gap_lower: np.ndarray
    #: Total mechanical energy at the samples (in lb).
    energy: np.ndarray
    #: Open intervals ((k, 2), s) of each contact and of the circuit.
    upper_open_intervals: np.ndarray
    lower_open_intervals: np.ndarray
    circuit_open_intervals: np.ndarray
    #: Total time the circuit is open, and its first opening (NaN: never).
    circuit_open_s: float
    first_circuit_open_s: float
    #: Largest lower gap (in): how far the lower contact separates.
    max_lower_gap_in: float
    #: The first impact of the upper contact: time and impulse (the
    #: impulse of its first contact episode).
    first_impact_s: float
    first_impulse_lb_s: float
    #: Energy at the end over energy at the release.
    energy_ratio: float
    #: The thesis's single-impulse predictions for the same design.
    single_impulse: dict = field(default_factory=dict)
    #: Force pressing the lower contact on the separator at the start (lb);
    #: the energies then include the preload's strain energy.
    preload_lb: float = 0.0
    #: appE only: every event (impact times, impulses, velocities before
    #: and after, energy after each; resting intervals), see
    #: :class:`contactsep.chatter.event_driven.RigidStopResult`.
    rigid_stop: object = field(default=None, repr=False)

    def to_json_dict(self) -> dict:
        """The summary (no sampled arrays), JSON-ready."""
        def clean(x):
            return None if isinstance(x, float) and math.isnan(x) else x
        return {
            "model": self.model, "n_modes": self.n_modes, "dt_s": self.dt,
            "preload_lb": self.preload_lb,
            "first_impact_s": clean(self.first_impact_s),
            "first_impulse_lb_s": clean(self.first_impulse_lb_s),
            "energy_ratio": clean(self.energy_ratio),
            "max_lower_gap_in": clean(self.max_lower_gap_in),
            "circuit_open_s": self.circuit_open_s,
            "first_circuit_open_s": clean(self.first_circuit_open_s),
            "circuit_open_intervals": self.circuit_open_intervals.tolist(),
            "upper_open_s": circuit.total(self.upper_open_intervals),
            "lower_open_s": circuit.total(self.lower_open_intervals),
            "single_impulse": {k: clean(v)
                               for k, v in self.single_impulse.items()},
            **self._events(),
        }

    def _events(self) -> dict:
        """appE: its impacts and rests (times s, impulses lb s, contact
        velocities in/s, energy after each impact in lb)."""
        r = self.rigid_stop
        if r is None:
            return {}
        return {"impacts": [
            {"t_s": float(t), "impulse_lb_s": float(psi),
             "v_before_in_s": float(a), "v_after_in_s": float(b),
             "energy_after_in_lb": float(w)}
            for t, psi, a, b, w in zip(r.impact_t, r.impulse, r.v_before,
                                       r.v_after, r.energy_after)],
            "rest_intervals": r.rest_intervals.tolist()}


def _stack(design):
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


def _single_impulse(design) -> dict:
    from contactsep.model import evaluate
    ev = evaluate(design, backend="numpy")
    impulse = evaluate(design.replace(lower_response="impulse"),
                       backend="numpy")
    return {"t1_s": float(ev.t1) if ev.status == 0 else math.nan,
            "v_impact_in_s": float(ev.v_impact),
            "psi_lb_s": float(ev.psi), "v0_in_s": float(ev.v0),
            "y3_max_in": float(ev.y3_max),
            "y3_max_impulse_form_in": float(impulse.y3_max)}


def simulate(design, model="newton", damping="none", dt=None, *,
             t_end=LISTING_TAU_S, open_threshold=circuit.OPEN_THRESHOLD,
             preload=0.0, nu=0.33, button_radius=0.125,
             backend="compiled", samples=DEFAULT_SAMPLES, theta=0.5
             ) -> ChatterResult:
    """Simulate the contact system of a (single) design from the release.

    ``dt`` defaults per model (DEFAULT_DT); ``preload`` (lb, >= 0) presses
    the lower contact up against the separator at the start (static
    equilibrium of the N-mode models, :func:`system.preload_state`; the
    release height stays y_s above the preloaded separator; appE has no
    lower contact and takes only 0);
    ``nu`` and ``button_radius`` (in) set the Hertz constant;
    ``backend="numpy"`` runs the NumPy twins (slow: tests only).
    """
    if model not in MODELS:
        raise ChatterError(f"model: found {model!r}, expected one of "
                           f"{', '.join(MODELS)}")
    if backend not in ("compiled", "numpy"):
        raise ChatterError(f"backend: found {backend!r}, expected "
                           f"compiled or numpy")
    if damping not in DAMPINGS:
        raise ChatterError(f"damping: found {damping!r}, expected one of "
                           f"{', '.join(DAMPINGS)}")
    if not (preload >= 0.0 and math.isfinite(preload)):
        raise ChatterError(f"preload: found {preload!r}, expected a force "
                           f">= 0 lb")
    if model == "appE" and preload != 0.0:
        raise ChatterError("preload: appE has no lower contact (the upper "
                           "contact against a rigid stop); use 0")
    if not (isinstance(samples, (int, np.integer)) and samples >= 1):
        raise ChatterError(f"samples: found {samples!r}, expected an "
                           f"integer >= 1")
    if not 0.5 <= theta <= 1.0:
        raise ChatterError(f"theta: found {theta!r}, expected 1/2 <= theta "
                           f"<= 1 (Moreau-Jean's theta-method)")
    if not (-1.0 < nu <= 0.5 and button_radius > 0.0
            and math.isfinite(button_radius)):
        raise ChatterError(f"nu, button_radius: found {nu!r}, "
                           f"{button_radius!r}, expected -1 < nu <= 0.5 "
                           f"and a radius > 0 in")
    if not (t_end > 0.0 and math.isfinite(t_end)):
        raise ChatterError(f"t_end: found {t_end!r}, expected a time > 0")
    if design.shape != ():
        raise ChatterError("design: chatter simulates one design, not a "
                           "batch")
    if isinstance(design.n_modes, tuple):
        raise ChatterError("n_modes: one N for all members")
    if int(design.n_modes) > MAX_MODES:
        raise ChatterError(f"n_modes: found {int(design.n_modes)}, expected "
                           f"at most {MAX_MODES} modes per member (a run "
                           f"costs steps x 3N; N = 64 converges the Hertz "
                           f"answers, docs/chatter.md)")
    if not float(design.ys) > 0.0:
        raise ChatterError(f"ys: found {float(design.ys)!r}, expected a "
                           f"release height > 0 above the separator")
    dt = DEFAULT_DT[model] if dt is None else float(dt)
    single = _single_impulse(design)
    if model == "appE":
        return _appendix_e(design, t_end, single, backend, open_threshold)
    if not (dt > 0.0 and dt < t_end):
        raise ChatterError(f"dt: found {dt!r}, expected 0 < dt < t_end")
    if t_end / dt > MAX_STEPS:
        raise ChatterError(f"dt: found {dt!r}, expected at least t_end / "
                           f"{MAX_STEPS:.0e} = {t_end / MAX_STEPS:.3g} s "
                           f"(at most {MAX_STEPS:.0e} steps a run)")
    steps = int(round(t_end / dt))
    stride = max(1, steps // samples)
    m, p, h, q0, v0, parts = _stack(design)
    law = None
    if model == "hertz":
        flores = dict(e=float(design.e), v_ref=single["v_impact_in_s"]) \
            if damping == "flores" else {}
        law = HertzLaw.for_materials(float(design.E1), nu, button_radius,
                                     **flores)
    g0 = np.zeros(2)
    if preload > 0.0:
        upper, sep, lower = parts
        depth = 0.0 if law is None else (preload / law.k) ** (2.0 / 3.0)
        q_sep, q_low, g0 = system.preload_state(sep, lower, preload, depth)
        n1, n2 = upper.p.size, sep.p.size
        q0 = q0.copy()
        q0[n1:n1 + n2] += q_sep
        q0[n1 + n2:] += q_low
    if model == "newton":
        t, g, energy, impulses, first = _run(
            "moreau_jean", backend, m, p, h, g0, q0, v0, float(design.e),
            dt, theta, steps, stride)
    else:
        t, g, energy, impulses, first = _run(
            "hertz", backend, m, p, h, g0, q0, v0, law, dt, steps, stride)
    first_t, first_p = (float(first[0]), float(first[1])) \
        if first[0] >= 0.0 else (math.nan, math.nan)
    found = circuit.discontinuity(t, g[:, 0], g[:, 1], open_threshold)
    return ChatterResult(
        model=model, n_modes=int(design.n_modes), dt=dt, t=t,
        gap_upper=g[:, 0], gap_lower=g[:, 1], energy=energy, **found,
        first_impact_s=first_t, first_impulse_lb_s=first_p,
        energy_ratio=float(energy[-1] / energy[0]), single_impulse=single,
        preload_lb=float(preload))


def _run(kind, backend, m, p, h, g0, q0, v0, *args):
    if backend == "numpy":
        from contactsep.chatter import steppers
        if kind == "moreau_jean":
            e, dt, theta, steps, stride = args
            return steppers.moreau_jean(m, p, h, g0, q0, v0, e=e, dt=dt,
                                        steps=steps, theta=theta,
                                        stride=stride)
        law, dt, steps, stride = args
        return steppers.hertz(m, p, h, g0, q0, v0, law=law, dt=dt,
                              steps=steps, stride=stride)
    api = importlib.import_module("contactsep.chatter._chatter").chatter_api
    if kind == "moreau_jean":
        e, dt, theta, steps, stride = args
        samples = steps // stride + 1
        t, g, energy, impulses, first, status = api.run_moreau_jean(
            m, p, h, g0, q0, v0, e, dt, theta, steps, stride, samples)
        if status != chatter_status.OK:
            raise ChatterError("the contact LCP had no solution")
    else:
        law, dt, steps, stride = args
        samples = steps // stride + 1
        t, g, energy, impulses, first = api.run_hertz(
            m, p, h, g0, q0, v0, law.k, law.chi, dt, steps, stride, samples)
    return t, g.T, energy, impulses.T, first


def _appendix_e(design, t_end, single, backend,
                open_threshold) -> ChatterResult:
    from contactsep.chatter.event_driven import rigid_stop_from_design

    r = rigid_stop_from_design(
        design, t_end=t_end,
        backend="fortran" if backend == "compiled" else "numpy")
    t = np.linspace(0.0, t_end, DEFAULT_SAMPLES + 1)
    gap_upper = r.displacement(t)
    gap_lower = np.zeros_like(t)
    found = circuit.discontinuity(t, gap_upper, gap_lower, open_threshold)
    energy = np.full_like(t, np.nan)
    energy[0], energy[-1] = r.initial_energy, r.final_energy
    return ChatterResult(
        model="appE", n_modes=int(design.n_modes), dt=0.0, t=t,
        gap_upper=gap_upper, gap_lower=gap_lower, energy=energy, **found,
        first_impact_s=float(r.impact_t[0]) if len(r.impact_t)
        else math.nan,
        first_impulse_lb_s=float(r.impulse[0]) if len(r.impulse)
        else math.nan,
        energy_ratio=r.final_energy / r.initial_energy,
        single_impulse=single, rigid_stop=r)
