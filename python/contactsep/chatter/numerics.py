"""The numerics of a chatter run, chosen from the design in one place:
the time step, the window, the default number of modes, and the checks
every run makes on itself (docs/chatter.md, "How the numerics are
chosen and checked").

* **Step.**  The Hertz and Newton steppers split each step into the
  exact modal flow and a contact kick (fortran/chatter/hertz.f90,
  adaptive*.f90).  Linearised, one step of such a splitting is stable
  while ``omega dt < 2`` for the system's highest frequency ``omega``
  (and a kick resonates with a mode of ``p dt`` near a multiple of pi).
  With the contact linearised at the largest force it can carry, the
  squared frequencies of the modal system with the contacts closed are
  bounded by (Weyl: the contact adds a positive semidefinite matrix
  whose trace bounds its largest eigenvalue)::

      omega^2 <= max_j p_j^2 + k_lin * sum_contacts sum_members
                                       sum_j X_j(x)^2 / M,

  k_lin = dF/ddelta = (3/2) k^(2/3) F^(1/3) the Hertz stiffness at the
  force F.  F is the Hertz force of the upper contact's impact at its
  largest possible speed (the release's modal speeds summed, an upper
  bound) against the two first modes' effective mass at the contact,
  plus the preload.  The step is :data:`STEP_SAFETY` of ``2/omega``,
  and at most :data:`CONTACT_PHASE` over the contact's own frequency
  ``sqrt(k_lin * trace)`` (accuracy: at few modes the contact, not the
  highest mode, is the fastest motion).
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
#: defaults (the one place it is set; the static-correction study sets
#: its value).
DEFAULT_MODES = 32
#: The step as a fraction of the splitting's stability limit 2/omega.
STEP_SAFETY = 0.5
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
             "circuit_open_s", "longest_open_s", "n_events")


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


def _mobility(member, values=None) -> float:
    """sum_j X_j(x)^2 / M at the member's contact point, or at the point
    of the mode ``values`` given (1/(lb s^2/in))."""
    values = member.x if values is None else values
    return float(np.sum(values**2) / member.mass)


def largest_speed(upper) -> float:
    """An upper bound on the upper contact's speed at its contact point
    after the release (in/s): sum_j |X_j q0_j p_j|."""
    return float(np.sum(np.abs(upper.x * upper.q0 * upper.p)))


def design_step(members, hertz_k=None, preload=0.0,
                linear=False) -> StepChoice:
    """The step (s) for the stacked members (upper, separator, lower):
    :data:`STEP_SAFETY` of 2/omega with omega bounded as in the module
    doc.  ``hertz_k`` (lb/in^1.5) is the Hertz constant; None (Newton's
    rigid law) bounds omega by the modes alone; with ``linear`` (a
    cylindrical button) it is a linear spring's k (lb/in), the
    stiffness itself."""
    upper, sep, lower = members
    p_max = float(max(m.p.max() for m in members))
    force = stiffness = 0.0
    if hertz_k is not None:
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
            stiffness = 1.5 * hertz_k ** (2.0 / 3.0) * force ** (1.0
                                                                 / 3.0)
    # the separator at each contact's point (x2, x2_lower; at one point
    # the sum is 2 mobility exactly)
    trace = (_mobility(upper) + (_mobility(sep) + _mobility(
        sep, sep.lower_x)) + _mobility(lower))
    omega = math.sqrt(p_max**2 + stiffness * trace)
    dt = STEP_SAFETY * 2.0 / omega
    if stiffness > 0.0:
        dt = min(dt, CONTACT_PHASE / math.sqrt(stiffness * trace))
    return StepChoice(dt=dt, omega=omega,
                      p_max=p_max, force_lb=force,
                      stiffness_lb_in=stiffness)


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
                least: float, book: bool = False) -> CheckedRun:
    """Run ``run_at(dt) -> (step, run)`` and check its energy; a step the
    design chose (``dt_source`` "design") that fails is halved, at most
    :data:`MAX_HALVINGS` times and never below ``least`` (the work
    budget's smallest step); a given one is run once.  With ``book``
    (the Hunt-Crossley and Thornton laws) a damped run's energy book
    must close too: |ratio + dissipated / start - 1| <= ENERGY_TOLERANCE
    (``run.book``, the dissipation the stepper summed)."""
    halvings = 0
    while True:
        step, run = run_at(dt)
        # the energy at the end: the book's where the stepper kept one
        # (the last sample may fall a few steps before the end)
        end = run.book["end"] if getattr(run, "book", None) else \
            run.energy[-1]
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
