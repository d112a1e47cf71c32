"""Appendix E as a model: one beam's contact point against a rigid stop,
event-driven with the exact modal flow between impacts.

Between events every mode moves exactly, q_j(t) = q_j cos p_j t +
(v_j/p_j) sin p_j t.  An impact applies the Newton impulse
psi_n = (1+e) M v_n^- / sum X_j^2 (Appendix E, eq. 9) in modal space,
v_j += X_j psi_n / M.  The next contact is found by safe steps: with
B = sum |X_j| p_j^2 a_j (a_j each mode's amplitude) bounding |y''|, the
lower bound y + y' s - B s^2/2 cannot reach the stop before its own first
root, so stepping to that root never passes a contact, grazing ones
included; right after an impact y = 0 and y' = -e v^- > 0 give a first
step of 2y'/B > 0, so round-off cannot create a false re-contact.

Impacts of a beam on a stop accumulate (Zeno): the rebound speeds fall
geometrically.  When a rebound speed falls below ``zeno_speed`` times the
first impact speed, the contact is taken as closed (the remaining normal
velocity removed: at most (1e-4)^2 of the first impact's energy at the
contact for the default) and
the beam moves as a constrained (propped) system, exactly in the modes
of that system, until the contact force turns tensile; then it flies
again.  The printed recursion (eq. 7) writes B_j1 where B_j(n-1) belongs
and drops the previous impulse's own term; docs/chatter.md derives the
exact continuation this code implements.
"""

from __future__ import annotations

import math

import numpy as np

from contactsep.chatter import circuit
from contactsep.chatter.event_driven_compiled import constrained_basis
from contactsep.chatter.result import ChatterResult
from contactsep.chatter.rigid_stop import ZENO_SPEED, RigidStopResult, _flow
from contactsep.constants import LISTING_TAU_S

#: Safe steps allowed per search before a grazing approach is taken as a
#: contact.
MAX_STEPS = 200_000


def _bound(kind, q, v, p, basis, x):
    """B >= |y''| for all later times of the segment."""
    if kind == "free":
        amp = np.sqrt(q**2 + (v / p)**2)
        return float(np.sum(np.abs(x) * p**2 * amp))
    vectors, omega = basis
    a, b = q @ vectors, v @ vectors
    w = np.where(omega > 0, omega, 1.0)
    amp = np.where(omega > 0, np.sqrt(a**2 + (b / w)**2), 0.0)
    return float(np.sum(np.abs(x @ vectors) * omega**2 * amp))


def _first_root(value, slope, bound, scale, horizon):
    """First tau in (0, horizon] where value(tau) reaches 0 from above, by
    safe steps; None if none.  value, slope: callables of tau."""
    tau = 0.0
    for _ in range(MAX_STEPS):
        f, d = value(tau), slope(tau)
        if f <= 0.0:
            return tau
        root = np.sqrt(d * d + 2.0 * bound * f)
        step = (d + root) / bound if d >= 0.0 else 2.0 * f / (root - d)
        small = step <= 1e-15 * max(tau, 1e-9)
        # converged on a crossing; the Newton step -f/d only where the
        # safe step agrees with it (f and d both at round-off, as at a
        # release from rest, would otherwise jump over real contacts)
        if d < 0.0 and (small or f <= 1e-15 * scale) and -f / d <= 2 * step:
            return tau - f / d
        if small and f <= 1e-12 * scale:
            return tau               # a tangency at the stop: grazing
        tau += step
        if tau > horizon:
            return None
    return tau   # a grazing approach: taken as the contact


def simulate_rigid_stop(p, x, mass, q0, v0, e, t_end, *, stop=0.0,
                        zeno_speed=ZENO_SPEED, max_impacts=1_000_000,
                        backend="numpy") -> RigidStopResult:
    """Appendix E: the beam (p_j, X_j at the contact, mass M) from state
    (q0, v0) against a rigid stop at ``stop`` (the beam above it).
    ``backend="fortran"``: the compiled twin (event_driven_compiled.py).
    The NumPy run's steps are :class:`_StopRun`'s methods."""
    if backend == "fortran":
        from contactsep.chatter.event_driven_compiled import (
            simulate_rigid_stop_compiled,
        )
        return simulate_rigid_stop_compiled(
            p, x, mass, q0, v0, e, t_end, stop=stop, zeno_speed=zeno_speed,
            max_impacts=max_impacts)
    if backend != "numpy":
        raise ValueError(f"backend: found {backend!r}, expected numpy or "
                         f"fortran")
    p, x = np.asarray(p, float), np.asarray(x, float)
    q, v = np.array(q0, dtype=float), np.array(v0, dtype=float)
    if stop != 0.0:
        raise ValueError("the stop is at y = 0 (shift the initial state)")
    run = _StopRun(p, x, mass, e, t_end, zeno_speed, q, v)
    # each pass: fly to the next contact, strike it, rest if the impacts
    # have accumulated.  A pass strikes at most once; the cap on passes
    # also ends runs whose passes strike nothing (contacts that leave)
    events = 0
    while run.t < t_end and len(run.impacts) < max_impacts \
            and events < 4 * max_impacts:
        events += 1
        if not run.fly_to_contact():
            break                    # the window ended in flight
        if run.strike() and run.rest_until_release():
            break                    # the window ended at rest
    return run.result()


class _StopRun:
    """One NumPy run of :func:`simulate_rigid_stop`: the time, the modal
    state (q, v) and the events so far, advanced by its steps."""

    def __init__(self, p, x, mass, e, t_end, zeno_speed, q, v):
        self.p, self.x, self.mass, self.e = p, x, mass, e
        self.t_end, self.zeno_speed = t_end, zeno_speed
        self.q, self.v = q, v
        self.sx = float(x @ x)
        # the contact search's tolerances are relative to the first gap
        self.scale = max(abs(float(q @ x)), 1e-300)
        self.t = 0.0
        self.e0 = self.energy(q, v)
        self.impacts, self.rests = [], []
        self.segments = [(0.0, "free", q.copy(), v.copy(), None)]
        self.first_speed = None
        # at the stop with no approach: the next flight leaves it
        self.leaving = False

    def energy(self, q, v):
        return 0.5 * self.mass * float(np.sum(v**2 + (self.p * q)**2))

    def fly_to_contact(self) -> bool:
        """Fly free to the next contact (True) or to the window's end
        (False)."""
        p, x = self.p, self.x
        bound = _bound("free", self.q, self.v, p, None, x)
        q_base, v_base = self.q.copy(), self.v.copy()
        y, yd = _free_gap(q_base, v_base, p, x)
        tau = self._contact_time(y, yd, q_base, v_base, bound)
        self.leaving = False
        if tau is None:
            self.q, self.v = _flow("free", q_base, v_base, p, None,
                                   self.t_end - self.t)
            self.t = self.t_end
            return False
        self.q, self.v = _flow("free", q_base, v_base, p, None, tau)
        self.t += tau
        return True

    def _contact_time(self, y, yd, q_base, v_base, bound):
        """The flight's time to the next contact, None past the window."""
        x = self.x
        # approaching beyond the round-off of the modal sum u = sum X v
        closing = yd(0.0) < -64.0 * np.finfo(float).eps * float(
            np.sum(np.abs(x * v_base)))
        if y(0.0) <= 0.0 and yd(0.0) <= 0.0 and not self.leaving and (
                self.impacts or closing):
            # still closing (or a start at the stop, to within rounding,
            # that approaches it): an impact now.  A start whose y is
            # -1e-18 and whose u is clearly negative would otherwise be
            # taken as leaving a rest and fly into the stop for up to
            # 1e-3 of the shortest period, while y = +1e-18 meets it at
            # once: a decision on the sign of round-off (issue 26)
            return 0.0
        start = 0.0
        if self.leaving or y(0.0) <= 0.0:
            start = self._clear_start(y, q_base, v_base)
        tau = _first_root(lambda s: y(start + s), lambda s: yd(start + s),
                          bound, self.scale, self.t_end - self.t - start)
        return None if tau is None else start + tau

    def _clear_start(self, y, q_base, v_base):
        """Where a flight from the stop with (almost) no normal velocity
        is clear of it: it leaves as y ~ tau^2 or tau^3; the search
        starts where y exceeds the round-off of the modal sum (else that
        round-off is found as a contact with no approach)."""
        p, x = self.p, self.x
        noise = 64.0 * np.finfo(float).eps * float(
            np.sum(np.abs(x * q_base) + np.abs(x * v_base) / p))
        start = 1e-12 * 2.0 * np.pi / p.max()
        while y(start) <= noise and start < 1e-3 * 2 * np.pi / p.max():
            start *= 2.0
        return start

    def strike(self) -> bool:
        """The Newton impulse at a contact that approaches; True when
        the impacts have accumulated (the rebound below zeno_speed of
        the first impact's speed)."""
        x, mass = self.x, self.mass
        u_minus = float(self.v @ x)
        if u_minus >= 0.0:
            # at the stop but not approaching it (leaving a rest, or the
            # modal sum's round-off near y = 0): no impact; fly on
            self._fly_from_here()
            return False
        psi = -(1.0 + self.e) * mass * u_minus / self.sx
        self.v = self.v + x * psi / mass
        u_plus = float(self.v @ x)
        self.first_speed = self.first_speed or abs(u_minus)
        self.impacts.append((self.t, psi, u_minus, u_plus,
                             self.energy(self.q, self.v)))
        self.segments.append((self.t, "free", self.q.copy(), self.v.copy(),
                              None))
        return u_plus < self.zeno_speed * self.first_speed

    def _fly_from_here(self):
        # the next flight leaves the stop from the present state
        self.leaving = True
        self.segments.append((self.t, "free", self.q.copy(), self.v.copy(),
                              None))

    def rest_until_release(self) -> bool:
        """Close the contact (accumulation) and move constrained until
        the contact force turns tensile; True when the window ends at
        rest."""
        x, p, mass, sx = self.x, self.p, self.mass, self.sx
        self.v = self.v - x * float(self.v @ x) / sx
        basis = constrained_basis(p, x)
        self.q = self.q - x * float(self.q @ x) / sx
        self.segments.append((self.t, "rest", self.q.copy(), self.v.copy(),
                              basis))
        qr, vr = self.q.copy(), self.v.copy()
        kx = x * p**2   # contact force = M sum X_j p_j^2 q_j / sum X^2
        force, force_rate = _rest_force(qr, vr, p, basis, kx, mass, sx)
        force_bound = mass * _bound("rest", qr, vr, p, basis, kx) / sx
        if force(0.0) <= 0.0:
            # the stop pulls: the contact opens at once, no rest
            self.segments.pop()
            self._fly_from_here()
            return False
        release = _first_root(force, force_rate, max(force_bound, 1e-300),
                              max(abs(force(0.0)), 1e-300),
                              self.t_end - self.t)
        end = self.t_end if release is None else self.t + release
        self.rests.append((self.t, end))
        self.q, self.v = _flow("rest", qr, vr, p, basis, end - self.t)
        self.t = end
        if release is None:
            return True
        self._fly_from_here()
        return False

    def result(self) -> RigidStopResult:
        table = np.array(self.impacts) if self.impacts else np.zeros((0, 5))
        return RigidStopResult(
            impact_t=table[:, 0], impulse=table[:, 1], v_before=table[:, 2],
            v_after=table[:, 3], energy_after=table[:, 4],
            rest_intervals=np.array(self.rests).reshape(-1, 2),
            initial_energy=self.e0, final_energy=self.energy(self.q, self.v),
            segments=self.segments, p=self.p, x=self.x)


def _free_gap(q_base, v_base, p, x):
    """y(tau) and y'(tau) of a free flight from (q_base, v_base)."""

    def y(tau):
        return float(_flow("free", q_base, v_base, p, None, tau)[0] @ x)

    def yd(tau):
        return float(_flow("free", q_base, v_base, p, None, tau)[1] @ x)

    return y, yd


def _rest_force(qr, vr, p, basis, kx, mass, sx):
    """The contact force at rest and its rate, as functions of the time
    since the rest began."""

    def force(tau):
        return mass * float(_flow("rest", qr, vr, p, basis, tau)[0] @ kx) / sx

    def force_rate(tau):
        return mass * float(_flow("rest", qr, vr, p, basis, tau)[1] @ kx) / sx

    return force, force_rate


def rigid_stop_from_design(design, *, t_end=LISTING_TAU_S, **options
                           ) -> RigidStopResult:
    """The upper contact of a Design released onto a rigid separator
    (options as simulate_rigid_stop's, backend included)."""
    from contactsep.chatter.system import members

    upper = members(design)[0]
    return simulate_rigid_stop(upper.p, upper.x, upper.mass, upper.q0,
                               upper.v0, float(design.e), t_end, **options)


def chatter_result(design, backend, settings, samples):
    """appE's run as a :class:`contactsep.chatter.result.ChatterResult`:
    the upper gap at ``samples`` intervals, the lower contact at rest,
    the energy at the ends; ``settings`` the ones every result carries."""
    t_end = settings["t_end_s"]
    r = rigid_stop_from_design(
        design, t_end=t_end,
        backend="fortran" if backend == "compiled" else "numpy")
    t = np.linspace(0.0, t_end, samples + 1)
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
