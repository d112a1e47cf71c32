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

import dataclasses
import functools
import warnings
from typing import NamedTuple

from contactsep import output
from contactsep.chatter import circuit, numerics, runners
from contactsep.chatter import stepper_registry, stop_event
from contactsep.chatter import status as chatter_status
from contactsep.chatter.event_driven import chatter_result
from contactsep.chatter.laws import HertzLaw
from contactsep.chatter.result import ChatterResult, blown_up, from_run
from contactsep.chatter.system import members
from contactsep.errors import ContactsepWarning
from contactsep.chatter.limits import FORKED_APPE_MODES, FORKED_WORK, MAX_MODES
from contactsep.chatter.settings import (
    Arguments,
    ChatterError,
    checked_arguments,
    real,
)
from contactsep.chatter.single_impulse import single_impulse as _single_impulse
from contactsep.chatter.stack import _system, checked_dt, design_window
from contactsep.chatter.stepper_registry import RunRequest

#: The thesis rig's converged steps (docs/convergence.md, "The
#: thesis rig in dt and N"):
#: Hertz 5e-8 s (the thesis rig's first impulse, max lower gap and open
#: time within 1e-6 of the dt -> 0 limit); Newton 5e-8 s (max lower gap
#: within 1 % for d <= 0.75 in, N <= 32).  The thesis studies pass them
#: explicitly; a run without ``dt`` takes its design's own step
#: (:func:`contactsep.chatter.numerics.design_step`).
DEFAULT_DT = {"appE": None, "newton": 5e-8, "hertz": 5e-8}
#: Sample intervals per simulation (the gaps are sampled, not every step).
DEFAULT_SAMPLES = 60_000
#: Poisson's ratio and button radius (in) of the Hertz constant.
DEFAULT_NU = 0.33
DEFAULT_BUTTON_RADIUS = 0.125


class UnconvergedWarning(ContactsepWarning):
    """A run that failed its energy check (status 9, UNCONVERGED)."""


def simulate(design, model="hertz", damping="none", dt=None, *,
             t_end=None, open_threshold=circuit.OPEN_THRESHOLD,
             min_open=circuit.MIN_OPEN, preload=0.0, nu=DEFAULT_NU,
             button_radius=DEFAULT_BUTTON_RADIUS, backend="compiled",
             samples=DEFAULT_SAMPLES, theta=0.5, stepper="adaptive",
             single_impulse=True, verify=False,
             static_correction=True, alpha=None, contact="hertz",
             yield_pressure=None, button="sphere",
             button_length=None, stop_at_event=False) -> ChatterResult:
    """Simulate the contact system of a (single) design from the release.

    Parameters
    ----------
    design : Design
        A single design (inches, pounds, seconds).  It carries N
        (``n_modes``; ``contactsep chatter`` uses
        :data:`contactsep.chatter.numerics.DEFAULT_MODES` unless given).
    model : {"hertz", "newton", "appE"}
        Hertz contact (the default), Newton's impact law (both: the three
        beams), or Appendix E's rigid separator (module docstring).
    damping : {"none", "flores", "hunt-crossley"}
        Hertz contact damping: Flores (calibrated to the design's e and
        its own impact speed), or Hunt-Crossley with the material
        constant ``alpha`` (never calibrated: e emerges); the elastic
        Hertz law does not use ``e``.
    dt : float, optional
        Time step (s); by default the design's own
        (:func:`contactsep.chatter.numerics.design_step`), rounded so
        that a whole number of steps ends at ``t_end``.  appE takes none.
    t_end : float, optional
        Window from the release (s); by default the design's own (its
        slowest member's first periods after the first impact).
    open_threshold : float
        Gap (in) above which a contact is open.
    min_open : float
        Shortest circuit opening (s) that counts as a discontinuity
        event.
    preload : float
        Force (lb, >= 0) pressing the lower contact up against the
        separator at the start (static equilibrium; with the static
        correction the exact point-load deflections,
        :func:`system.preload_state`; the release height stays y_s above
        the preloaded separator; appE takes only 0).
    nu, button_radius : float
        Poisson's ratio and contact button radius (in) of the Hertz
        constant.
    backend : {"compiled", "numpy"}
        ``"numpy"`` runs the NumPy twins of the fixed-step steppers
        (slow: tests only).
    samples : int
        Sample intervals of the gaps (1: the ends only).  The adaptive
        stepper's trajectory and summary do not depend on it (hertz and
        newton: its flight steps do not stop at the samples), except
        ``energy_ratio``, the last sample's, which is at ``t_end`` where
        the samples divide the steps; the fixed-step reference takes its
        largest lower gap and crossings from the samples.
    theta : float
        Moreau-Jean's theta (fixed stepper).
    stepper : {"adaptive", "fixed"}
        ``"fixed"`` runs the fixed-step reference (Moreau-Jean, Hertz
        splitting).
    single_impulse : bool
        ``False`` skips the thesis's eq. 23 figures (two model
        evaluations, ~1 ms: a sweep of chatter runs need not pay them).
    verify : bool
        Rerun at half the step and twice the modes and record the
        relative change of each headline quantity (``result.changes``:
        ``first_impulse_change``, ...).
    static_correction : bool
        Hertz: the truncated modes' residual flexibility in series with
        each contact and in the preload's static state (docs/numerics.md,
        "The static correction"); False is the plain N-mode truncation.
        Newton's rigid law cannot take a series compliance: for it (and
        appE) the option changes nothing.

    alpha : float, optional
        Hunt-Crossley's constant (s/in): F = k delta^{3/2} (1 + alpha
        delta'); only with ``damping="hunt-crossley"``.
    contact : {"hertz", "thornton"}
        The elastic part of the law: Hertz, or Thornton's (1997)
        elastic-perfectly-plastic sphere on a flat (needs
        ``yield_pressure``; it takes the static correction too;
        docs/chatter.md, "Contact laws").
    yield_pressure : float, optional
        Thornton's limiting contact pressure p_y (psi).
    button : {"sphere", "cylinder"}
        The contact button: a sphere of ``button_radius`` on a flat
        (Hertz, k = (4/3) E* sqrt(R)), or a cylinder of that radius
        across the flat (a line contact, F = (pi/4) E* L delta).
    button_length : float, optional
        The cylinder's length L (in; default its diameter).
    stop_at_event : bool
        Stop at the first discontinuity event (status 10,
        STOPPED_AT_EVENT, ``stopped_s``): for a run that only answers
        "is there an event?"; the same answer as the whole window's
        (:mod:`contactsep.chatter.stop_event`).  The compiled adaptive
        stepper only; not with ``verify``.

    Returns
    -------
    ChatterResult
        The sampled gaps (in) and the summary: ``circuit_open_s``,
        ``first_circuit_open_s``, ``n_events``, ``chatters``,
        ``max_lower_gap_in``, ``first_impulse_lb_s``, ...; ``status`` 0,
        7 (stopped at the energy bound: no circuit figures), 9
        (unconverged: its energy check failed, with a warning,
        :class:`UnconvergedWarning`) or 10 (stopped at its first event:
        figures up to there, ChatterResult.stopped_s); ``dt_source`` and
        ``t_end_source`` say whether the step and window were chosen
        from the design or given.  Every newton or hertz run checks its
        energy (elastic within 1e-6 of the start, damped never gaining);
        a design-chosen step that fails is halved (at most
        numerics.MAX_HALVINGS times).

    Raises
    ------
    ChatterError
        A setting the chatter layer refuses (one line naming it).

    Examples
    --------
    >>> import contactsep
    >>> from contactsep import chatter
    >>> r = chatter.simulate(contactsep.thesis_design(n_modes=16),
    ...                      preload=0.2, t_end=0.06)
    >>> r.status, r.static_correction
    (0, True)
    """
    a = checked_arguments(Arguments(
        design=design, model=model, damping=damping, dt=dt, t_end=t_end,
        open_threshold=open_threshold, min_open=min_open, preload=preload,
        nu=nu, button_radius=button_radius, backend=backend,
        samples=samples, theta=theta, stepper=stepper,
        single_impulse=single_impulse, verify=verify,
        static_correction=static_correction, alpha=alpha, contact=contact,
        yield_pressure=yield_pressure, button=button,
        button_length=button_length, stop_at_event=stop_at_event))
    # eq. 23 runs here, not in a step, so that its warning names the caller
    single = _single_impulse(design) if single_impulse else {}
    a, settings = _gathered(a, single)
    if model == "appE":
        return _appendix_e_run(a, settings)
    law = _law(a, (single or _single_impulse(design))
               if model == "hertz" and damping == "flores" else {})
    plan = _plan(a, law, settings["t_end_source"])
    checked = _checked_run(a, law, plan)
    if checked.run.status not in (chatter_status.OK,
                                  chatter_status.STOPPED_AT_EVENT):
        return blown_up(checked.run, model, design, checked.dt, preload,
                        damping, _stepper(a),
                        dict(settings, dt_source=plan.dt_source))
    status = checked.run.status if checked.converged \
        else chatter_status.UNCONVERGED
    if not checked.converged:
        warnings.warn(checked.message(), UnconvergedWarning, stacklevel=2)
    result = from_run(checked, plan.stack, plan.parts, plan.choice, status,
                      model=model, design=design, preload=preload,
                      damping=damping, stepper=_stepper(a),
                      dt_source=plan.dt_source, min_open=min_open,
                      settings=settings)
    return _verified(result, a) if verify else result


class _Plan(NamedTuple):
    """A stepped run's system and step: the stacked system, its members,
    the design's step choice (numerics.design_step), the step that runs
    (s), whether it was given or chosen, and the least step allowed."""

    stack: object
    parts: tuple
    choice: object
    dt: float
    dt_source: str
    least: float


def _gathered(a: Arguments, single: dict) -> tuple:
    """``a`` with its window (the design's unless given) and the
    settings every result carries."""
    t_end_source = "given" if a.t_end is not None else "design"
    t_end = a.t_end if a.t_end is not None else design_window(a.design,
                                                              a.min_open)
    settings = dict(t_end_s=float(t_end),
                    open_threshold_in=float(a.open_threshold),
                    min_open_s=float(a.min_open), design=a.design,
                    single_impulse=single, t_end_source=t_end_source,
                    static_correction=a.static_correction,
                    contact=a.contact, alpha_s_per_in=a.alpha,
                    yield_pressure_psi=a.yield_pressure, button=a.button,
                    button_radius_in=float(a.button_radius))
    return dataclasses.replace(a, t_end=t_end), settings


def _appendix_e_run(a: Arguments, settings: dict) -> ChatterResult:
    """appE: no step to take (dt must be None); a run of many modes in a
    child process that Ctrl-C stops."""
    if a.dt is not None:
        raise ChatterError(f"dt: found {a.dt!r}, expected None: appE is "
                           f"event-driven (the exact modal flow between "
                           f"impacts) and takes no step")
    return output.interruptible(
        int(a.design.n_modes) > FORKED_APPE_MODES, chatter_result, a.design,
        a.backend, settings, DEFAULT_SAMPLES)


def _law(a: Arguments, impact: dict):
    """The Hertz family's contact law (None for newton); Flores damping
    calibrated to e and ``impact``'s speed (eq. 23's first impact)."""
    if a.model != "hertz":
        return None
    flores = dict(e=float(a.design.e), v_ref=impact["v_impact_in_s"]) \
        if a.damping == "flores" else {}
    return HertzLaw.for_materials(float(a.design.E1), a.nu, a.button_radius,
                                  alpha=a.alpha,
                                  yield_pressure=a.yield_pressure,
                                  button=a.button, length=a.button_length,
                                  **flores)


def _plan(a: Arguments, law, t_end_source: str) -> _Plan:
    """The stacked system and the step: the given one, or the design's;
    a step too coarse warns (at simulate's caller), one too fine for the
    window is refused."""
    stack = _system(a.design, a.preload, law, a.static_correction)
    parts = members(a.design)
    choice = numerics.design_step(parts,
                                  None if law is None else law.k, a.preload,
                                  linear=law is not None and law.linear)
    dt_source = "given" if a.dt is not None else "design"
    dt = choice.dt if a.dt is None else real("dt", a.dt, "s")
    least = checked_dt(a.design, dt, dt_source, a.t_end, t_end_source,
                       choice.dt, stack.m.size, stacklevel=3)
    return _Plan(stack, parts, choice, dt, dt_source, least)


def _checked_run(a: Arguments, law, plan: _Plan) -> numerics.CheckedRun:
    """The run at the plan's step with its energy checked (a chosen step
    that fails halved), or stopped at its first event when asked."""
    damped = (a.model == "hertz" and (a.damping != "none"
                                      or a.contact != "hertz")) or (
        a.model == "newton" and float(a.design.e) < 1.0)
    t_end = a.t_end

    def run_at(step, stop_open=stop_event.NEVER):
        steps = max(1, int(round(t_end / step)))
        return t_end / steps, _run(RunRequest(
            a.model, a.stepper, a.backend, plan.stack, law, a.design,
            a.theta, t_end / steps, steps, max(1, steps // a.samples),
            a.open_threshold, stop_open))
    refine = None if law is None else (
        lambda step: numerics.design_step(plan.parts, law.k, a.preload,
                                          largest=step,
                                          linear=law.linear).dt)
    return (functools.partial(stop_event.checked_run, min_open=a.min_open)
            if a.stop_at_event else numerics.checked_run)(
        run_at, plan.dt, plan.dt_source, damped, plan.least, refine,
        book=a.model == "hertz" and (a.damping == "hunt-crossley"
                                     or a.contact == "thornton"))


def _run(request: RunRequest) -> runners.Run:
    """One run of the registry's stepper for the request's (model,
    stepper, backend) (:mod:`contactsep.chatter.stepper_registry`); a
    long one in a child process that Ctrl-C stops."""
    step = stepper_registry.lookup(*request.key)
    return output.interruptible(
        request.steps * request.stack.m.size >= FORKED_WORK, step, request)


def _stepper(a: Arguments) -> str:
    """The stepper that ran: the NumPy backend's is the fixed one."""
    return a.stepper if a.backend == "compiled" else "fixed"


def _verified(result, a: Arguments) -> ChatterResult:
    """``result`` with ``changes``: the relative change of each headline
    quantity at half the step and twice the modes (moved down off the
    2N design's resonances: a step free of them for N modes need not be
    for 2N)."""
    design = a.design
    n = 2 * int(design.n_modes)
    if n > MAX_MODES:
        raise ChatterError(f"verify: twice N = {int(design.n_modes)} is "
                           f"more than {MAX_MODES} modes")
    finer = design.replace(n_modes=n)
    law = None if a.model != "hertz" else HertzLaw.for_materials(
        float(design.E1), a.nu, a.button_radius, button=a.button,
        length=a.button_length)
    step = numerics.design_step(
        members(finer), None if law is None else law.k, a.preload,
        largest=result.dt / 2.0, linear=law is not None and law.linear).dt
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnconvergedWarning)
        check = simulate(
            finer, model=a.model, damping=a.damping, dt=step, t_end=a.t_end,
            open_threshold=a.open_threshold, min_open=a.min_open,
            preload=a.preload, nu=a.nu, button_radius=a.button_radius,
            backend=a.backend, samples=a.samples, theta=a.theta,
            stepper=a.stepper, single_impulse=False,
            static_correction=a.static_correction, alpha=a.alpha,
            contact=a.contact, yield_pressure=a.yield_pressure,
            button=a.button, button_length=a.button_length)
    changes = numerics.changes(result, check)
    changes["verify_dt_s"] = check.dt
    changes["verify_n_modes"] = n
    changes["verify_status"] = check.status
    return dataclasses.replace(result, changes=changes)
