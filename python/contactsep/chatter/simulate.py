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
import math
import warnings

import numpy as np

from contactsep import output
from contactsep.chatter import circuit, laws, numerics, runners
from contactsep.chatter import stepper_registry, stop_event
from contactsep.chatter import status as chatter_status
from contactsep.chatter.contacts import HertzLaw
from contactsep.chatter.laws import ChatterError
from contactsep.chatter.result import ChatterResult, blown_up
from contactsep.chatter.system import members
from contactsep.errors import ContactsepWarning
from contactsep.chatter.limits import (  # noqa: F401 (the module's API)
    APPE_MAX_MODES,
    BUTTONS,
    CONTACTS,
    DAMPINGS,
    FORKED_APPE_MODES,
    FORKED_WORK,
    MAX_MODES,
    MAX_SAMPLES,
    MAX_STEPS,
    MAX_T_END,
    MAX_WORK,
    MODELS,
    STEPPERS,
)
from contactsep.chatter.settings import check_settings as _check
from contactsep.chatter.single_impulse import single_impulse as _single_impulse
from contactsep.chatter.stack import (  # noqa: F401 (the module's API)
    COARSE_DT,
    CoarseStepWarning,
    largest_preload,
    smallest_dt,
)
from contactsep.chatter.stack import _system, checked_dt, design_window
from contactsep.chatter.stepper_registry import RunRequest

#: The thesis rig's converged steps (docs/numerics.md, "Convergence"):
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
    if not isinstance(static_correction, (bool, np.bool_)):
        raise ChatterError(f"static_correction: found "
                           f"{static_correction!r}, expected True or False")
    static_correction = bool(static_correction) and model == "hertz"
    _check(design, model, damping, backend, preload, samples, theta, nu,
           button_radius, t_end, open_threshold, min_open, stepper)
    alpha, yield_pressure = laws.check_law(model, damping, alpha, contact,
                                           yield_pressure,
                                           static_correction)
    button_length = laws.check_button(model, button, button_length,
                                      contact)
    if not isinstance(verify, (bool, np.bool_)):
        raise ChatterError(f"verify: found {verify!r}, expected True or "
                           f"False")
    stop = stop_event.check(stop_at_event, model, stepper, backend, verify)
    single = _single_impulse(design) if single_impulse else {}
    t_end_source = "given" if t_end is not None else "design"
    if t_end is None:
        t_end = design_window(design, min_open)
    settings = dict(t_end_s=float(t_end),
                    open_threshold_in=float(open_threshold),
                    min_open_s=float(min_open), design=design,
                    single_impulse=single, t_end_source=t_end_source,
                    static_correction=static_correction, contact=contact,
                    alpha_s_per_in=alpha, yield_pressure_psi=yield_pressure,
                    button=button, button_radius_in=float(button_radius))
    if model == "appE":
        if dt is not None:
            raise ChatterError(f"dt: found {dt!r}, expected None: appE is "
                               f"event-driven (the exact modal flow "
                               f"between impacts) and takes no step")
        return output.interruptible(
            int(design.n_modes) > FORKED_APPE_MODES, _appendix_e, design,
            backend, settings)
    law = None
    if model == "hertz":
        flores = dict(e=float(design.e), v_ref=(
            single or _single_impulse(design))["v_impact_in_s"]) \
            if damping == "flores" else {}
        law = HertzLaw.for_materials(float(design.E1), nu, button_radius,
                                     alpha=alpha,
                                     yield_pressure=yield_pressure,
                                     button=button, length=button_length,
                                     **flores)
    stack = _system(design, preload, law, static_correction)
    parts = members(design)
    choice = numerics.design_step(parts,
                                  None if law is None else law.k, preload,
                                  linear=law is not None and law.linear)
    dt_source = "given" if dt is not None else "design"
    dt = choice.dt if dt is None else laws.real("dt", dt, "s")
    least = checked_dt(design, dt, dt_source, t_end, t_end_source,
                       choice.dt, stack.m.size)
    damped = (model == "hertz" and (damping != "none"
                                    or contact != "hertz")) or (
        model == "newton" and float(design.e) < 1.0)

    def run_at(step, stop_open=stop_event.NEVER):
        steps = max(1, int(round(t_end / step)))
        return t_end / steps, _run(RunRequest(
            model, stepper, backend, stack, law, design, theta, t_end / steps,
            steps, max(1, steps // samples), open_threshold, stop_open))
    refine = None if law is None else (
        lambda step: numerics.design_step(parts, law.k, preload,
                                          largest=step,
                                          linear=law.linear).dt)
    checked = (functools.partial(stop_event.checked_run, min_open=min_open)
               if stop else numerics.checked_run)(
        run_at, dt, dt_source, damped, least, refine,
        book=model == "hertz" and (damping == "hunt-crossley"
                                   or contact == "thornton"))
    run, ratio, halvings = checked.run, checked.ratio, checked.halvings
    if run.status not in (chatter_status.OK,
                          chatter_status.STOPPED_AT_EVENT):
        return blown_up(run, model, design, checked.dt, preload, damping,
                        stepper if backend == "compiled" else "fixed",
                        dict(settings, dt_source=dt_source))
    status = run.status if checked.converged \
        else chatter_status.UNCONVERGED
    if not checked.converged:
        warnings.warn(checked.message(), UnconvergedWarning, stacklevel=2)
    found = circuit.discontinuity(run.upper_open, run.lower_open, min_open)
    result = ChatterResult(
        model=model, n_modes=int(design.n_modes), dt=checked.dt, t=run.t,
        gap_upper=run.gaps[:, 0], gap_lower=run.gaps[:, 1],
        energy=run.energy, **found,
        max_lower_gap_in=run.max_lower_gap_in,
        first_lift_in=circuit.first_lift(
            run.t, run.gaps[:, 1], run.first[0],
            math.pi / float(parts[2].p[0])),
        first_impact_s=run.first[0], first_impulse_lb_s=run.first[1],
        energy_ratio=ratio, preload_lb=float(preload), damping=damping,
        stepper=stepper if backend == "compiled" else "fixed",
        work=run.work, status=status, dt_source=dt_source,
        energy_book=laws.energy_book(run, stack, parts),
        stopped_s=stop_event.stopped_s(status, found["events"], min_open),
        end_state={"q": run.book["q"], "v": run.book["v"]}
        if run.book else {},
        numerics={"design_dt_s": choice.dt, "omega_bound_rad_s":
                  choice.omega, "p_max_rad_s": choice.p_max,
                  "contact_force_bound_lb": choice.force_lb,
                  "contact_stiffness_lb_per_in": choice.stiffness_lb_in,
                  "contact_dt_s": choice.contact_dt,
                  "alias_share": choice.alias_share,
                  "dt_halvings": halvings,
                  "energy_tolerance": numerics.ENERGY_TOLERANCE},
        **settings)
    if verify:
        result = _verified(result, design, model, damping, dict(
            t_end=t_end, open_threshold=open_threshold, min_open=min_open,
            preload=preload, nu=nu, button_radius=button_radius,
            backend=backend, samples=samples, theta=theta, stepper=stepper,
            single_impulse=False, static_correction=static_correction,
            alpha=alpha, contact=contact, yield_pressure=yield_pressure,
            button=button, button_length=button_length))
    return result


def _run(request: RunRequest) -> runners.Run:
    """One run of the registry's stepper for the request's (model,
    stepper, backend) (:mod:`contactsep.chatter.stepper_registry`); a
    long one in a child process that Ctrl-C stops."""
    step = stepper_registry.lookup(*request.key)
    return output.interruptible(
        request.steps * request.stack.m.size >= FORKED_WORK, step, request)


def _verified(result, design, model, damping, settings) -> ChatterResult:
    """``result`` with ``changes``: the relative change of each headline
    quantity at half the step and twice the modes (moved down off the
    2N design's resonances: a step free of them for N modes need not be
    for 2N)."""
    n = 2 * int(design.n_modes)
    if n > MAX_MODES:
        raise ChatterError(f"verify: twice N = {int(design.n_modes)} is "
                           f"more than {MAX_MODES} modes")
    finer = design.replace(n_modes=n)
    law = None if model != "hertz" else HertzLaw.for_materials(
        float(design.E1), settings["nu"], settings["button_radius"],
        button=settings["button"], length=settings["button_length"])
    step = numerics.design_step(
        members(finer), None if law is None else law.k,
        settings["preload"], largest=result.dt / 2.0,
        linear=law is not None and law.linear).dt
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UnconvergedWarning)
        check = simulate(finer, model=model, damping=damping, dt=step,
                         **settings)
    changes = numerics.changes(result, check)
    changes["verify_dt_s"] = check.dt
    changes["verify_n_modes"] = n
    changes["verify_status"] = check.status
    return dataclasses.replace(result, changes=changes)


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
        energy_ratio=r.final_energy / r.initial_energy, dt_source="none",
        rigid_stop=r, work={"impacts": len(r.impact_t)}, **settings)
