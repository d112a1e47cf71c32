"""The numerics of a chatter run, chosen from the design in one place:
the time step, the window, the default number of modes, and the checks
every run makes on itself (docs/numerics.md, "How the numerics are
chosen and checked").

* **Step.**  The Hertz and Newton steppers split each step into the
  exact modal flow and a contact kick (fortran/chatter/hertz.f90,
  adaptive*.f90).  The flow is exact, so the highest retained mode does
  not bound the Hertz step: it is at most :data:`CONTACT_PHASE` over
  the contact's own frequency sqrt(k_lin * trace), trace =
  sum_contacts sum_members sum_j X_j(x)^2 / M, k_lin = dF/ddelta =
  (3/2) k^(2/3) F^(1/3) the Hertz stiffness at the force F of the
  upper contact's impact at its largest possible speed (the release's
  modal speeds summed) against the two first modes' effective mass,
  plus the preload; then shrunk until no retained mode sits on a
  resonance of the splitting (:func:`resonance_free`: the kicks alias a
  mode with p_j dt near 2 m pi onto slow motion).  Newton's law keeps
  :data:`STEP_SAFETY` of 2 / p_max.  ``omega`` (reported) bounds the
  closed system's highest frequency (Weyl)::

      omega^2 <= max_j p_j^2 + k_lin * trace.
* **Window.**  :data:`WINDOW_PERIODS` periods of the slowest member's
  first mode after the first impact (of the N-mode release flight).
* **Error control.**  Energy is the error indicator: an elastic run must
  end with ``|energy_ratio - 1| <= ENERGY_TOLERANCE``, a damped one may
  not gain more than that.  A run at the design's step that fails is
  rerun at half the step, at most :data:`MAX_HALVINGS` times; one that
  still fails (or fails at a step the caller gave) is UNCONVERGED
  (status 9).
* **Verification.**  :func:`changes` the relative change of each
  headline quantity between a run and its rerun at half the step and
  twice the modes (``simulate(..., verify=True)``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Modes per member of `contactsep chatter` and of the thesis-free
#: defaults (the one place it is set): the smallest N at which every
#: converging headline quantity (first impact, first impulse, circuit
#: open time) of the family's default runs is within 1 % of a fine-step
#: N = 128 run (benchmarks/default_modes.py: 2.4e-3 at N = 64; at N = 32
#: becu_light's first impulse is 77 % off; docs/numerics.md, "The
#: default N").
DEFAULT_MODES = 64
#: Newton's step as a fraction of 2 / p_max (its velocity-level impulses
#: take the modes' own bound).
STEP_SAFETY = 0.5
#: The resonance test's contact stiffness, as a multiple of the Hertz
#: stiffness at the largest expected force (the unstable band of a mode
#: is kappa dt / p wide: 4 keeps three band widths clear).
RESONANCE_STIFFNESS = 4.0
#: Largest share of the contacts' coupling the kicks may alias onto slow
#: motion (:func:`alias_measure`; the energy error is about a third of
#: it: 1e-7 keeps it a thirtieth of ENERGY_TOLERANCE).
ALIAS_TOLERANCE = 1e-7
#: Factor by which a step failing the resonance test is shrunk.
STEP_SHRINK = 0.997
#: Most phase (rad) of the contact's own linearised oscillation,
#: sqrt(k_lin * trace), a step takes: about 300 steps a contact period,
#: what the energy check asks at few modes, where the contact and not
#: the highest mode is the fastest motion (thesis rig, N = 2: 0.05 rad a
#: step leaves the energy 2e-6 off, 0.025 rad 4e-8).
CONTACT_PHASE = 0.02
#: Periods of the slowest member's first mode the default window runs
#: after the first impact.
WINDOW_PERIODS = 3
#: Largest |energy_ratio - 1| of an elastic run (and largest gain of a
#: damped one) that passes the energy check.
ENERGY_TOLERANCE = 1e-6
#: Most times a design-chosen step that fails the check is halved.
MAX_HALVINGS = 3
#: Headline quantities that --verify compares (field -> its *_change).
HEADLINES = ("first_impact_s", "first_impulse_lb_s", "max_lower_gap_in",
             "first_lift_in", "circuit_open_s", "longest_open_s",
             "n_events")


@dataclass(frozen=True)
class StepChoice:
    """The design's step and what set it."""

    #: The step (s).
    dt: float
    #: Bound on the highest frequency with the contacts closed (rad/s).
    omega: float
    #: Highest retained modal frequency (rad/s).
    p_max: float
    #: Largest expected contact force (lb) and its Hertz stiffness (lb/in).
    force_lb: float
    stiffness_lb_in: float
    #: The contact's accuracy bound CONTACT_PHASE / sqrt(k_lin trace)
    #: (s; the modal bound for Newton's law), before the resonance test.
    contact_dt: float = math.nan
    #: Largest p_j dt of the retained modes at the step (rad).
    largest_phase: float = math.nan
    #: :func:`alias_measure` at the step (0: no mode at p_j dt >= pi).
    alias_share: float = math.nan


def _mobility(member, values=None) -> float:
    """sum_j X_j(x)^2 / M at the member's contact point, or at the point
    of the mode ``values`` given (1/(lb s^2/in))."""
    values = member.x if values is None else values
    return float(np.sum(values**2) / member.mass)


def largest_speed(upper) -> float:
    """An upper bound on the upper contact's speed at its contact point
    after the release (in/s): sum_j |X_j q0_j p_j|."""
    return float(np.sum(np.abs(upper.x * upper.q0 * upper.p)))


def contact_couplings(members):
    """The stacked modes' frequencies ``p`` (rad/s) and their contact
    couplings ``w`` = X_j(x)^2 / M summed over the contacts a mode takes
    part in (1/(lb s^2/in); the separator's modes are in both)."""
    upper, sep, lower = members
    p = np.concatenate([m.p for m in members])
    w = np.concatenate([upper.x**2 / upper.mass,
                        (sep.x**2 + sep.lower_x**2) / sep.mass,
                        lower.x**2 / lower.mass])
    return p, w


def alias_measure(dt, p, w, contact_frequency) -> float:
    """The share of the contacts' coupling held by modes the kicks
    alias onto slow motion: sum_j w_j min(1, (omega_c dt / eps_j)^4) /
    sum_j w_j over the modes with p_j dt >= pi, eps_j the distance of
    p_j dt from the nearest multiple of 2 pi.

    Between two kicks mode j turns by p_j dt exactly, so seen at the
    kicks it turns by eps_j: the kicks drive it as they would a mode of
    frequency eps_j / dt (near an odd multiple of pi they alternate in
    sign against it and see only the force's content at 1/(2 dt): none).
    A contact force of frequency omega_c (its spectrum falling at least
    as (omega_c / Omega)^2 above it, a half-sine pulse's, squared in the
    energy) feeds such a mode, instead of leaving it quasi-static as its
    true p_j would, energy in proportion to its coupling w_j and that
    factor: the energy error of the run, measured on the family, is a
    third of this share (docs/chatter.md)."""
    theta = np.asarray(p) * dt
    high = theta >= math.pi
    if not np.any(high):
        return 0.0
    theta = theta[high]
    eps = np.abs(theta - 2.0 * math.pi * np.round(theta / (2.0 * math.pi)))
    factor = np.minimum(1.0, (contact_frequency * dt
                              / np.maximum(eps, 1e-300))**4)
    return float(np.sum(w[high] * factor) / np.sum(w))


def resonance_free(dt, p, w, stiffness, contact_frequency) -> bool:
    """Whether the step ``dt`` keeps every retained mode off the
    splitting's resonances (docs/numerics.md, "How the numerics are
    chosen and checked"), contacts of linear stiffness ``stiffness``
    (lb/in; both closed) and frequency ``contact_frequency`` (rad/s):

    * stability: one mode of frequency p coupled to a contact by
      kappa = k w (rad^2/s^2) is stable under the splitting iff
      |2 cos(theta) - (kappa dt / p) sin(theta)| <= 2, theta = p dt
      (the trace of its one-step map): unstable in a band of width
      kappa dt / p just below each multiple m pi.  The test takes
      kappa at :data:`RESONANCE_STIFFNESS` times the stiffness (a
      margin of three band widths, and room for a force above the
      estimate).  In the whole system the other modes' compliance sits
      in series with the contact at the aliased (slow) frequency and
      narrows the band further: the test errs on the safe side, and on
      the family it never binds;
    * aliasing: :func:`alias_measure` at most :data:`ALIAS_TOLERANCE`
      (what binds: a mode 0.01 rad below 2 pi a step is linearly
      stable yet takes 1e-3 of the energy, tests/chatter/
      test_step_resonance.py)."""
    theta = p * dt
    kappa = RESONANCE_STIFFNESS * stiffness * w
    trace = 2.0 * np.cos(theta) - kappa * dt / p * np.sin(theta)
    if np.any(np.abs(trace) > 2.0):
        return False
    return alias_measure(dt, p, w, contact_frequency) <= ALIAS_TOLERANCE


def design_step(members, hertz_k=None, preload=0.0,
                largest=None, linear=False) -> StepChoice:
    """The step (s) for the stacked members (upper, separator, lower).

    Hertz (``hertz_k``, lb/in^1.5, the Hertz constant): the contact's
    accuracy bound CONTACT_PHASE / sqrt(k_lin trace) (module doc), or
    ``largest`` where smaller, shrunk by :data:`STEP_SHRINK` until
    :func:`resonance_free` holds (the retained modes' p_j dt may exceed
    pi: the flow between kicks is exact, so the highest mode does not
    bound the step; the shrinking stops at p_max dt = 1, where no mode
    can resonate).  None (Newton's rigid law): :data:`STEP_SAFETY` of
    2 / p_max, or ``largest`` where smaller.  With ``linear`` (a
    cylindrical button) ``hertz_k`` is a linear spring's k (lb/in), the
    stiffness itself."""
    upper, sep, lower = members
    p_max = float(max(m.p.max() for m in members))
    if hertz_k is None:
        dt = STEP_SAFETY * 2.0 / p_max
        if largest is not None:
            dt = min(dt, float(largest))
        return StepChoice(dt=dt, omega=p_max, p_max=p_max, force_lb=0.0,
                          stiffness_lb_in=0.0, contact_dt=dt,
                          largest_phase=p_max * dt, alias_share=math.nan)
    # the first modes' effective mass at the upper contact (the most
    # a slow impact can push against: the largest force)
    first = upper.x[0]**2 / upper.mass + sep.x[0]**2 / sep.mass
    mass = 1.0 / first
    speed = largest_speed(upper)
    if linear:
        force = math.sqrt(mass * hertz_k) * speed + float(preload)
        stiffness = hertz_k
    else:
        depth = (1.25 * mass * speed**2 / hertz_k) ** 0.4
        force = hertz_k * depth**1.5 + float(preload)
        stiffness = 1.5 * hertz_k ** (2.0 / 3.0) * force ** (1.0 / 3.0)
    # the separator at each contact's point (x2, x2_lower; at one point
    # the sum is 2 mobility exactly)
    trace = (_mobility(upper) + (_mobility(sep) + _mobility(
        sep, sep.lower_x)) + _mobility(lower))
    omega = math.sqrt(p_max**2 + stiffness * trace)
    contact_dt = CONTACT_PHASE / math.sqrt(stiffness * trace)
    start = contact_dt if largest is None else min(contact_dt,
                                                   float(largest))
    p, w = contact_couplings(members)
    floor = 1.0 / p_max     # below it no p_j dt reaches 1: no resonance
    dt = start
    frequency = CONTACT_PHASE / contact_dt
    while dt > floor and not resonance_free(dt, p, w, stiffness,
                                            frequency):
        dt *= STEP_SHRINK
    dt = max(dt, min(floor, start))
    return StepChoice(dt=dt, omega=omega, p_max=p_max, force_lb=force,
                      stiffness_lb_in=stiffness, contact_dt=contact_dt,
                      largest_phase=p_max * dt,
                      alias_share=alias_measure(dt, p, w, frequency))


def first_impact_estimate(system) -> float:
    """The first time (s) the upper gap closes in the release flight of
    the N-mode system (separator and lower contact at rest): the first
    sign change of the sampled gap, refined by bisection; the upper
    contact's first half period if it never closes (a release away from
    the separator)."""
    n1 = system.n_upper
    p, x, q = system.p[:n1], system.h[0, :n1], system.q0[:n1]
    rest = float(system.h[0, n1:] @ system.q0[n1:] + system.g0[0])

    def gap(t):
        return np.cos(np.multiply.outer(t, p)) @ (x * q) + rest

    half = math.pi / float(p.min())
    t = np.linspace(0.0, half, 4097)
    closed = np.nonzero(gap(t) <= 0.0)[0]
    if not closed.size:
        return half
    hi = float(t[closed[0]])
    lo = float(t[closed[0] - 1]) if closed[0] else 0.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if gap(np.array([mid]))[0] > 0.0 else (lo, mid)
    return hi


def design_window(system, members) -> float:
    """The window (s): the first impact and :data:`WINDOW_PERIODS`
    periods of the slowest member's first mode."""
    slowest = min(float(m.p[0]) for m in members)
    return (first_impact_estimate(system)
            + WINDOW_PERIODS * 2.0 * math.pi / slowest)


def energy_converged(ratio: float, damped: bool) -> bool:
    """The energy check: elastic |ratio - 1| <= ENERGY_TOLERANCE, damped
    ratio <= 1 + ENERGY_TOLERANCE (damping only removes energy)."""
    if not math.isfinite(ratio):
        return False
    if damped:
        return ratio <= 1.0 + ENERGY_TOLERANCE
    return abs(ratio - 1.0) <= ENERGY_TOLERANCE


@dataclass(frozen=True)
class CheckedRun:
    """A stepper's run that passed its energy check, or the last one
    tried: the run, its step (s), its energy ratio, how often the step
    was halved, whether it converged, and what set the step."""

    run: object
    dt: float
    ratio: float
    halvings: int
    converged: bool
    damped: bool
    dt_source: str
    #: Whether the energy book had to close too (checked_run's book).
    book: bool = False

    def message(self) -> str:
        """The one-line warning of an unconverged run."""
        rule = ("a damped run must not gain energy" if self.damped
                else "an elastic run must keep it within 1e-6")
        if self.book:
            rule += (", and its energy book (end + dissipated) must close "
                     "within 1e-6")
        return (f"unconverged: energy end/start {self.ratio:.10g} at dt "
                f"{self.dt:.3g} s ({self.dt_source}"
                + (f", halved {self.halvings} times" if self.halvings
                   else "")
                + f"; {rule}): status 9, the figures are not to be "
                f"trusted"
                + (" (give a smaller dt)" if self.dt_source == "given"
                   else ""))


def checked_run(run_at, dt: float, dt_source: str, damped: bool,
                least: float, refine=None, book: bool = False) -> CheckedRun:
    """Run ``run_at(dt) -> (step, run)`` and check its energy; a step the
    design chose (``dt_source`` "design") that fails is halved, at most
    :data:`MAX_HALVINGS` times and never below ``least`` (the work
    budget's smallest step); a given one is run once.  ``refine(step)``
    (optional) moves a halved step down off the splitting's resonances
    (:func:`design_step` with ``largest``): half a resonance-free step
    need not be one.  With ``book`` (the Hunt-Crossley and Thornton
    laws) a damped run's energy book must close too: |ratio + dissipated
    / start - 1| <= ENERGY_TOLERANCE (``run.book``, the dissipation the
    stepper summed)."""
    halvings = 0
    while True:
        step, run = run_at(dt)
        # the energy at the end: the book's where the stepper kept one
        # (the last sample may fall a few steps before the end)
        end = run.book["end"] if getattr(run, "book", None) else \
            run.energy[-1]
        if math.isfinite(getattr(run, "stopped_at", math.nan)) and \
                not getattr(run, "book", None):
            end = run.energy_end     # a Newton run stopped at its event
        ratio = float(end / run.energy[0])
        converged = energy_converged(ratio, damped)
        if book and converged and run.book:
            converged = energy_converged(ratio + run.book["dissipated"]
                                         / float(run.energy[0]), False)
        if converged or dt_source != "design" or \
                halvings == MAX_HALVINGS or dt / 2.0 < least:
            return CheckedRun(run=run, dt=step, ratio=ratio,
                              halvings=halvings, converged=converged,
                              damped=damped, dt_source=dt_source,
                              book=book)
        dt, halvings = dt / 2.0, halvings + 1
        if refine is not None:
            dt = max(float(refine(dt)), least)


def relative_change(coarse, fine) -> float:
    """|fine - coarse| / |fine| (0 when both are 0; NaN when either is
    NaN or only fine is 0)."""
    coarse, fine = float(coarse), float(fine)
    if math.isnan(coarse) and math.isnan(fine):
        return 0.0      # e.g. no impact, or never open, in both
    if math.isnan(coarse) or math.isnan(fine):
        return math.nan
    if fine == coarse:
        return 0.0
    if fine == 0.0:
        return math.inf
    return abs(fine - coarse) / abs(fine)


def changes(result, check) -> dict:
    """``{quantity + "_change": relative change}`` of the headline
    quantities from ``result`` to ``check`` (its rerun at half the step
    and twice the modes); ``circuit_open_change`` names the total open
    time's."""
    out = {}
    for name in HEADLINES:
        key = {"circuit_open_s": "circuit_open_change"}.get(
            name, name.removesuffix("_s").removesuffix("_in")
            .removesuffix("_lb") + "_change")
        out[key] = relative_change(getattr(result, name),
                                   getattr(check, name))
    return out
