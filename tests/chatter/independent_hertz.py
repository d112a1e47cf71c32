"""An independent simulator of the three-beam Hertz contact system
(issue 26), written from the equations without importing contactsep, as
tests/extremum_reference.py is for the model.

Nothing is shared with the package but the equations and two documented
conventions (docs/chatter.md): the Hertz constant k = (4/3) E* sqrt(R)
with E* = E1 / (2 (1 - nu^2)) for both contacts (the package's "two
equal materials" convention: it takes the upper contact's modulus for
both), and the thesis's g = 386.4 in/s^2 (Appendix B's listing value).

* **Modes.**  Bernoulli-Euler beams, each end condition's frequency
  equation in a form without overflow (cos x + sech x = 0 clamped-free,
  cos x - sech x = 0 clamped-clamped, sin x - cos x tanh x = 0
  clamped-pinned, x = j pi pinned-pinned), solved by Brent's method on
  brackets one per mode; X_j(x) = cosh kx - cos kx - sigma (sinh kx - sin kx)
  evaluated with the exponentials scaled by exp(-kL) (no cancellation at
  large kL); each shape normalised to int X^2 dx = L by Gauss-Legendre
  quadrature (not assumed).
* **The release.**  The upper contact's static shape under a point load
  at the release point (the tip of a cantilever, or x1), from the beam
  equation EI y'''' = F delta(x - a) solved as two cubics with their
  boundary and matching conditions (an 8 x 8 linear system), scaled to
  y_s at the release point, and projected on the modes by quadrature:
  q_j = (1/L) int y X_j dx.  (The package uses the closed form
  y_s X_j(a) / (k_jL^4 G(a)).)
* **The integrator.**  Where no contact force acts, the exact modal flow
  (each mode a rotation).  Where one does, SciPy's DOP853 (8th order,
  adaptive, rtol 1e-11) on the whole first-order system
  M (q'' + p^2 q) = X F with the Hertz (Flores) force, ending where both
  gaps are open again (a terminal event).  Before the first impact the
  separator and the lower contact stay in their static state (with or
  without a preload it is an exact equilibrium of the N-mode system).
  The package uses Strang splitting with the exact flow (kick, flow,
  kick) on a fixed grid.
* **Crossings.**  In flight, each gap (a sum of sinusoids) is sampled at
  1/16 of the shortest period; a sign change of g - threshold is refined
  by Brent's method, and a sign change of g' (an extremum inside a
  cell) is refined first, so that a crossing pair inside one cell is
  found.  In contact phases, DOP853's event location on its dense output
  (on the physical gaps with the static correction, below).
  The closing of a contact is found the same way in flight.

* **The static correction** (``Setup.static_correction``, optional):
  each member's residual flexibility at its contact point,
  c_i = G_i(x_i) - sum_j X_j^2 / (M p_j^2) (G_i the exact point-load
  flexibility of static_shape), in series with the Hertz contacts:
  C = [[c1 + c2, -c2], [-c2, c2 + c3]], lambda_c = k delta_c^1.5 with
  delta = -(g + C lambda), solved each evaluation (Gauss-Seidel over the
  two contacts, Brent on each); the energy adds lambda C lambda / 2
  (conserved to 2e-14 on the thesis rig at N = 4).  The gaps the
  contacts see are then g + C lambda (``Trajectory.gaps``): a closed
  contact's is minus its element's penetration, and an open one's moves
  with the other contact's force (-c2 lambda_other, the separator's
  spring), so its crossings are located on those.

Units: in, lb, s.  Gaps positive open: g_upper = y1(x1) - y2(x2),
g_lower = y2(x2_lower) - y3(x3) (+ the preload's offsets); the
separator's ``x_lower`` (default its ``x``) is where the lower contact
touches it (issue 28, item 4): the lower gap's Jacobian row, the preload
acting there, and C's off-diagonal the residual cross flexibility
G2(x2, x2_lower) - sum_j X_j(x2) X_j(x2_lower) / (M p_j^2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from independent_beams import (  # noqa: F401  (re-exported)
    GRAVITY,
    Beam,
    beam,
    release_modes,
    static_shape,
    wavenumbers,
)

#: DOP853's tolerances in contact phases.
RTOL = 1e-11
#: Flight samples per shortest period.
SAMPLES_PER_PERIOD = 16


# ------------------------------------------------------------- system

@dataclass(frozen=True)
class Setup:
    """Everything a run needs, written out (in, lb, s)."""

    upper: dict
    separator: dict
    lower: dict
    ys: float
    n_modes: int
    e: float = 1.0
    preload: float = 0.0
    damping: str = "none"
    nu: float = 0.33
    button_radius: float = 0.125
    release: str = "tip"
    #: Residual flexibility in series with each Hertz contact (issue 25's
    #: static correction; no preload).
    static_correction: bool = False


@dataclass
class Trajectory:
    """The reference's answer on [0, t_end]."""

    t_end: float
    first_impact_s: float
    first_impulse_lb_s: float
    v_impact: float
    #: How long the first contact episode of the upper contact lasts (s).
    first_contact_s: float
    energy0: float
    energy_end: float
    crossings: list = field(default_factory=list)   # (t, contact, up)
    open_at_start: tuple = (False, False)
    segments: list = field(default_factory=list)
    h: np.ndarray = None
    g0: np.ndarray = None
    p: np.ndarray = None
    m: np.ndarray = None
    k: float = 0.0
    chi: float = 0.0
    #: The static correction's residual flexibility matrix (None: off).
    cmat: np.ndarray = None

    def gaps(self, t, modal: bool = False) -> np.ndarray:
        """Both physical gaps at times t (2, len(t)): the modal gaps,
        plus C lambda with the static correction (a closed contact's is
        minus its element's penetration; an open one's moves with the
        other contact's force through the separator's residual spring,
        -c2 lambda_other); ``modal``: the modal gaps H q + g0."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.empty((2, t.size))
        starts = np.array([seg[1] for seg in self.segments])
        which = np.clip(np.searchsorted(starts, t, side="right") - 1, 0,
                        len(starts) - 1)
        for k, seg in enumerate(self.segments):
            sel = which == k
            if not sel.any():
                continue
            if seg[0] == "pre":
                q0, n = seg[3], seg[4]
                q = np.repeat(q0[:, None], sel.sum(), axis=1)
                q[:n] = _flow(self.p[:n], q0[:n], np.zeros(n),
                              t[sel] - seg[1])[0]
                out[:, sel] = self.h @ q + self.g0[:, None]
            elif seg[0] == "flow":
                q, v = _flow(self.p, seg[3], seg[4], t[sel] - seg[1])
                out[:, sel] = self.h @ q + self.g0[:, None]
            else:
                y = seg[3](t[sel])
                n = self.p.size
                out[:, sel] = self.h @ y[:n] + self.g0[:, None]
                if self.cmat is not None and not modal:
                    # a force acts only in contact phases
                    u = self.h @ y[n:2 * n]
                    for i in np.flatnonzero(sel):
                        j = int(np.count_nonzero(sel[:i]))
                        out[:, i] += self.cmat @ series_forces(
                            self.k, self.chi, self.cmat, out[:, i], u[:, j])
        return out

    def open_intervals(self, contact: int) -> np.ndarray:
        """(k, 2) open intervals of one contact (0 upper, 1 lower)."""
        state = self.open_at_start[contact]
        start = 0.0 if state else None
        spans = []
        for t, c, up in sorted(self.crossings):
            if c != contact:
                continue
            if up and start is None:
                start = t
            elif not up and start is not None:
                if t > start:
                    spans.append((start, t))
                start = None
        if start is not None and self.t_end > start:
            spans.append((start, self.t_end))
        return np.array(spans, dtype=float).reshape(-1, 2)

    def circuit_intervals(self) -> np.ndarray:
        """Both contacts open: the intersections, by brute pairing."""
        out = []
        for a0, a1 in self.open_intervals(0):
            for b0, b1 in self.open_intervals(1):
                lo, hi = max(a0, b0), min(a1, b1)
                if hi > lo:
                    out.append((lo, hi))
        return np.array(sorted(out), dtype=float).reshape(-1, 2)

    def stiffest_rate(self, k, chi, m, samples=400) -> float:
        """The fastest rate (1/s) of the contact dynamics in the run: over
        every contact phase, each contact's linearised Hertz frequency
        sqrt(1.5 k delta^0.5 w) and damping rate chi k delta^1.5 w
        (w = sum h^2/m, the contact's inverse effective mass) at its
        deepest penetration.  A step well below its inverse resolves
        every contact, preloaded or not.  With the static correction the
        depth is the modal one, -(H q + g0), which exceeds the element's
        own (the series spring takes C lambda of it): a bound."""
        w = (self.h**2 / m).sum(axis=1)
        rate = 0.0
        for seg in self.segments:
            if seg[0] == "flow":
                continue
            t = np.linspace(seg[1], seg[2], samples)
            depth = np.maximum(-self.gaps(t, modal=True), 0.0).max(axis=1)
            rate = max(rate, float(np.max(np.sqrt(1.5 * k * np.sqrt(depth)
                                                  * w))),
                       float(np.max(chi * k * depth**1.5 * w)))
        return rate

    def max_lower_gap(self, per_segment=4000) -> float:
        """Largest lower gap: every segment sampled, the best refined."""
        best = -math.inf
        for seg in self.segments:
            t = np.linspace(seg[1], seg[2], per_segment)
            g = self.gaps(t)[1]
            k = int(np.argmax(g))
            best = max(best, float(g[k]))
            lo, hi = t[max(k - 1, 0)], t[min(k + 1, t.size - 1)]
            fine = np.linspace(lo, hi, 2001)
            best = max(best, float(self.gaps(fine)[1].max()))
        return best


def _flow(p, q, v, s):
    """Exact free motion of every mode over times s (n, len(s))."""
    s = np.atleast_1d(s)
    c, sn = np.cos(np.outer(p, s)), np.sin(np.outer(p, s))
    return (q[:, None] * c + (v / p)[:, None] * sn,
            -(q * p)[:, None] * sn + v[:, None] * c)


def hertz_constant(setup: Setup) -> float:
    """k = (4/3) E* sqrt(R), E* = E1 / (2 (1 - nu^2)) (the package's
    documented two-equal-materials convention)."""
    e_star = setup.upper["E"] / (2.0 * (1.0 - setup.nu**2))
    return 4.0 / 3.0 * e_star * math.sqrt(setup.button_radius)


def _member(d, n):
    b = beam(d["end"], d["L"], d["b"], d["h"], d["gamma"], d["E"], n)
    x = float(d["x"])
    return b, b.shapes([x])[:, 0]


def build(setup: Setup):
    """Stacked masses, frequencies, contact Jacobian, gap offsets and the
    initial displacements."""
    n = setup.n_modes
    b1, x1 = _member(setup.upper, n)
    b2, x2 = _member(setup.separator, n)
    b3, x3 = _member(setup.lower, n)
    x2l = b2.shapes([_lower_point(setup.separator)])[:, 0]
    at = b1.length if (setup.release == "tip"
                       and b1.end == "clamped-free") \
        else float(setup.upper["x"])
    q1 = release_modes(b1, at, setup.ys)
    m = np.concatenate([np.full(n, b1.mass), np.full(n, b2.mass),
                        np.full(n, b3.mass)])
    p = np.concatenate([b1.p, b2.p, b3.p])
    z = np.zeros(n)
    h = np.array([np.concatenate([x1, -x2, z]),
                  np.concatenate([z, x2l, -x3])])
    q = np.concatenate([q1, z, z])
    g0 = np.zeros(2)
    k = hertz_constant(setup)
    if setup.preload > 0.0:
        f = setup.preload
        q2 = f * x2l / (b2.mass * b2.p**2)     # equilibrium: M p^2 q = X F
        q3 = -f * x3 / (b3.mass * b3.p**2)
        q[n:2 * n], q[2 * n:] = q2, q3
        depth = (f / k) ** (2.0 / 3.0)         # F = k depth^1.5
        lift, drop = float(x2l @ q2), float(x3 @ q3)
        # the upper gap's offset: the separator's deflection at x2
        g0 = np.array([float(x2 @ q2), -depth - (lift - drop)])
    return m, p, h, g0, q, k


def point_flexibility(member: dict) -> float:
    """Exact static deflection per unit force at the member's contact
    point (in/lb): static_shape over E I."""
    y = static_shape(member["end"], member["L"], member["x"])
    inertia = member["b"] * member["h"]**3 / 12.0
    return float(y(member["x"])) / (member["E"] * inertia)


def _lower_point(separator: dict) -> float:
    return float(separator.get("x_lower", separator["x"]))


def residual_matrix(setup: Setup) -> np.ndarray:
    """C = [[c1 + c2, -c2], [-c2, c2 + c3]] of the residual flexibilities
    c_i = G_i(x_i) - sum_j X_j(x_i)^2 / (M_i p_j^2) (the part of each
    member's static flexibility its N modes leave out); with the lower
    contact at x2_lower, [[c1 + c2, -c2x], [-c2x, c2l + c3]] (c2l at
    x2_lower, c2x the cross term between x2 and x2_lower)."""
    c = []
    for member in (setup.upper, setup.separator, setup.lower):
        b, x = _member(member, setup.n_modes)
        c.append(point_flexibility(member)
                 - float(np.sum(x**2 / (b.mass * b.p**2))))
    sep = setup.separator
    if _lower_point(sep) == float(sep["x"]):
        return np.array([[c[0] + c[1], -c[1]], [-c[1], c[1] + c[2]]])
    # the separator at the lower contact's point, and between the two
    lower = dict(sep, x=_lower_point(sep))
    b, x = _member(sep, setup.n_modes)
    xl = b.shapes([lower["x"]])[:, 0]
    inertia = sep["b"] * sep["h"]**3 / 12.0
    y = static_shape(sep["end"], sep["L"], sep["x"])
    cross = float(y(lower["x"])) / (sep["E"] * inertia) \
        - float(np.sum(x * xl / (b.mass * b.p**2)))
    c_low = point_flexibility(lower) \
        - float(np.sum(xl**2 / (b.mass * b.p**2)))
    return np.array([[c[0] + c[1], -cross], [-cross, c_low + c[2]]])


def series_forces(k, chi, cmat, g, u):
    """The contact forces lambda >= 0 with the residual springs in
    series: lambda_c = k delta_c^1.5 max(1 - chi u_c, 0), delta =
    -(g + C lambda) (the damping on the modal rate u = g'), by
    Gauss-Seidel over the two contacts, each a scalar root (Brent) of
    an increasing function."""
    lam = np.zeros(2)
    factor = np.maximum(1.0 - chi * np.asarray(u, dtype=float), 0.0)
    for _ in range(200):
        old = lam.copy()
        for c in (0, 1):
            other = cmat[c, 1 - c] * lam[1 - c]

            def excess(x, c=c, other=other):
                d = max(-(g[c] + cmat[c, c] * x + other), 0.0)
                return x - k * d**1.5 * factor[c]
            top = k * max(-(g[c] + other), 0.0)**1.5 * factor[c]
            lam[c] = 0.0 if top <= 0.0 else brentq(
                excess, 0.0, top, xtol=1e-300, rtol=1e-15)
        if np.all(np.abs(lam - old) <= 1e-15 * (np.abs(lam) + 1e-300)):
            break
    return lam


def simulate(setup: Setup, t_end: float, *, threshold: float = 1e-6,
             rtol: float = RTOL, to_first_impact: bool = False
             ) -> Trajectory:
    """Run from the release to t_end (``to_first_impact``: stop at the
    first impact, or t_end if none)."""
    m, p, h, g0, q, k = build(setup)
    n = setup.n_modes
    v = np.zeros_like(q)
    tol_g = 1e-15 * (abs(setup.ys) + 1.0)
    cmat = None
    if setup.static_correction:
        if setup.preload:
            raise NotImplementedError("a preload with the static "
                                      "correction")
        cmat = residual_matrix(setup)

    def gaps(q):
        return h @ q + g0

    def hertz_energy(g):
        if cmat is None:
            d = np.maximum(-g, 0.0)
            return float(np.sum(0.4 * k * d**2.5))
        lam = series_forces(k, 0.0, cmat, g, np.zeros(2))
        d = np.maximum(-(g + cmat @ lam), 0.0)
        return float(np.sum(0.4 * k * d**2.5) + 0.5 * lam @ cmat @ lam)

    def energy(q, v):
        return 0.5 * float(np.sum(m * (v**2 + (p * q)**2))) \
            + hertz_energy(gaps(q))

    energy0 = energy(q, v)
    traj = Trajectory(t_end=t_end, first_impact_s=math.nan, m=m, k=k,
                      first_impulse_lb_s=math.nan, v_impact=math.nan,
                      first_contact_s=math.nan,
                      energy0=energy0, energy_end=math.nan, h=h, g0=g0, p=p,
                      cmat=cmat)
    traj.open_at_start = tuple(bool(x > threshold) for x in gaps(q))

    # --- before the first impact: the upper contact flies, the rest is
    # static (an exact equilibrium of the N-mode system)
    p1, x1 = p[:n], h[0, :n]

    def g_up(s):
        c, sn = np.cos(np.outer(s, p1)), np.sin(np.outer(s, p1))
        return (c * q[:n] + sn * (v[:n] / p1)) @ x1 + gaps(q)[0] \
            - x1 @ q[:n]

    period = 2 * math.pi / p1.max()
    ds = period / SAMPLES_PER_PERIOD
    s_grid = np.arange(0.0, t_end + ds, ds)
    g = g_up(s_grid)
    hit = np.flatnonzero(g < -tol_g)
    t_hit = t_end
    if hit.size:
        j = hit[0]
        # the sample before may itself be within tol_g below zero: bracket
        # g + tol_g / 2, as in flight
        t_hit = brentq(lambda s: float(g_up(np.array([s]))[0]) + tol_g / 2,
                       s_grid[j - 1] if j > 0 else 0.0, s_grid[j],
                       xtol=1e-16, rtol=1e-15)
    t_hit = min(t_hit, t_end)
    for s_cross, up in _flight_crossings(
            lambda s: g_up(s), lambda s: _rate(p1, q[:n], v[:n], x1, s),
            0.0, t_hit, ds, threshold):
        traj.crossings.append((s_cross, 0, up))
    traj.segments.append(("pre", 0.0, t_hit, q.copy(), n))
    qa, va = _flow(p1, q[:n], v[:n], np.array([t_hit]))
    q = q.copy()
    q[:n], v[:n] = qa[:, 0], va[:, 0]
    if t_hit >= t_end or to_first_impact:
        traj.energy_end = energy(q, v)
        if t_hit < t_end:
            traj.first_impact_s = t_hit
        return traj
    traj.first_impact_s = t_hit
    traj.v_impact = -float(h[0] @ v)
    chi = 0.0
    if setup.damping == "flores":
        chi = 8.0 * (1.0 - setup.e) / (5.0 * setup.e * traj.v_impact)
    traj.chi = chi

    def force(g, u):
        if cmat is not None:
            return series_forces(k, chi, cmat, g, u)
        d = np.maximum(-g, 0.0)
        f = k * d**1.5 * (1.0 + chi * (-u))
        return np.where(d > 0.0, np.maximum(f, 0.0), 0.0)

    # the right-hand side, called millions of times in a long pressed
    # phase: its arrays made once and the two contacts' Hertz (Flores)
    # forces in scalars (the same equations as force, without the
    # small-array overhead that was 60 % of a run)
    n3, p2, ht = 3 * n, p**2, np.ascontiguousarray(h.T)

    def rhs(_, y):
        qq, vv = y[:n3], y[n3:2 * n3]
        if cmat is not None:
            f = force(h @ qq + g0, h @ vv)
        else:
            (g_up, g_low), (u_up, u_low) = (h @ qq + g0).tolist(), \
                (h @ vv).tolist()
            f = np.array([_hertz(k, chi, g_up, u_up),
                          _hertz(k, chi, g_low, u_low)])
        res = np.empty(2 * n3 + 2)
        res[:n3] = vv
        np.subtract((ht @ f) / m, p2 * qq, out=res[n3:2 * n3])
        res[2 * n3:] = f
        return res

    t = t_hit
    impulse_before = 0.0
    first_episode_open = True
    while t < t_end:
        # ---- contact phase (DOP853) until both gaps are >= 0 again
        def all_open(_, y):
            return float(np.min(h @ y[:3 * n] + g0))
        all_open.terminal, all_open.direction = True, 1.0

        def physical(y):
            # the gaps the contacts see: with the static correction an
            # open contact's moves with the other's force (-c2 lambda)
            g = h @ y[:3 * n] + g0
            if cmat is None:
                return g
            return g + cmat @ force(g, h @ y[3 * n:6 * n])

        def upper_free(_, y):
            return float(physical(y)[0])
        upper_free.direction = 1.0

        events = [all_open, upper_free]
        for c in (0, 1):
            def cross(_, y, c=c):
                return float(physical(y)[c] - threshold)
            events.append(cross)
        y0 = np.concatenate([q, v, [0.0, 0.0]])
        scale = np.concatenate([np.abs(q) + 1e-12, np.abs(v) + 1e-9,
                                [1e-12, 1e-12]])
        sol = solve_ivp(rhs, (t, t_end), y0, method="DOP853", rtol=rtol,
                        atol=rtol * 1e-3 * np.maximum(scale, scale.max()
                                                      * 1e-6),
                        events=events, dense_output=True)
        if sol.status < 0:
            raise ArithmeticError(sol.message)
        t_stop = float(sol.t[-1])
        y_end = sol.y[:, -1]
        if first_episode_open:
            ends = sol.t_events[1]
            if ends.size:
                traj.first_impulse_lb_s = impulse_before + float(
                    sol.sol(ends[0])[-2])
                traj.first_contact_s = float(ends[0]) - t_hit
                first_episode_open = False
            elif sol.status == 1:
                # the phase ended with both gaps open (the upper
                # contact's release may coincide with the terminal event)
                traj.first_impulse_lb_s = impulse_before + float(y_end[-2])
                traj.first_contact_s = t_stop - t_hit
                first_episode_open = False
            else:
                impulse_before += float(y_end[-2])
        for c in (0, 1):
            for tc in sol.t_events[2 + c]:
                rate = float(h[c] @ sol.sol(tc)[3 * n:6 * n])
                if cmat is not None:
                    # the physical gap's own rate (central difference)
                    d = 1e-9 * (t_stop - t)
                    rate = float(physical(sol.sol(min(tc + d, t_stop)))[c]
                                 - physical(sol.sol(max(tc - d, t)))[c])
                traj.crossings.append((float(tc), c, rate > 0.0))
        traj.segments.append(("ode", t, t_stop, sol.sol))
        q, v = y_end[:3 * n].copy(), y_end[3 * n:6 * n].copy()
        t = t_stop
        if t >= t_end:
            break
        # ---- flight (exact flow) until a gap closes
        ds = 2 * math.pi / p.max() / SAMPLES_PER_PERIOD
        qf, vf = q.copy(), v.copy()

        def g_c(s, c, qf=qf, vf=vf):
            qs, _ = _flow(p, qf, vf, np.atleast_1d(s))
            return h[c] @ qs + g0[c]

        def r_c(s, c, qf=qf, vf=vf):
            _, vs = _flow(p, qf, vf, np.atleast_1d(s))
            return h[c] @ vs

        s_end = t_end - t
        s_close = s_end
        s0 = 0.0
        chunk = 20000 * ds
        while s0 < s_close:
            grid = np.arange(s0, min(s0 + chunk, s_close) + ds, ds)
            grid[-1] = min(grid[-1], s_close)
            closing = math.inf
            for c in (0, 1):
                gc = g_c(grid, c)
                bad = np.flatnonzero((gc < -tol_g) & (grid > 0.0))
                if bad.size:
                    j = bad[0]
                    lo = grid[j - 1] if j > 0 else 0.0
                    root = brentq(lambda s: float(g_c(s, c)[0]) + tol_g / 2,
                                  lo, grid[j], xtol=1e-17, rtol=1e-15)
                    closing = min(closing, root)
            if closing < math.inf:
                s_close = closing
                break
            s0 = grid[-1]
        for c in (0, 1):
            for tc, up in _flight_crossings(
                    lambda s, c=c: g_c(s, c), lambda s, c=c: r_c(s, c),
                    0.0, s_close, ds, threshold):
                traj.crossings.append((t + tc, c, up))
        traj.segments.append(("flow", t, t + s_close, qf, vf))
        qs, vs = _flow(p, qf, vf, np.array([s_close]))
        q, v = qs[:, 0], vs[:, 0]
        t = t + s_close
    traj.energy_end = energy(q, v)
    if first_episode_open:
        traj.first_impulse_lb_s = impulse_before
    return traj


def _hertz(k, chi, g, u):
    """One contact's Hertz (Flores) force, k d^1.5 (1 - chi u) >= 0 at
    depth d = -g > 0 (force's law, for one contact in scalars)."""
    if g >= 0.0:
        return 0.0
    return max(k * (-g)**1.5 * (1.0 + chi * (-u)), 0.0)


def _rate(p1, q1, v1, x1, s):
    c, sn = np.cos(np.outer(s, p1)), np.sin(np.outer(s, p1))
    return (-sn * (q1 * p1) + c * v1) @ x1


def _flight_crossings(g, rate, s0, s1, ds, threshold):
    """Crossings of g(s) = threshold on [s0, s1]: sign changes on a grid
    of step ds refined by Brent's method; an extremum (sign change of
    the rate) inside a cell is located first, so that a pair of
    crossings inside one cell is found.  Yields (s, up)."""
    if s1 <= s0:
        return
    n_cells = int(math.ceil((s1 - s0) / ds))
    block = 20000
    for b in range(0, n_cells, block):
        grid = s0 + ds * np.arange(b, min(b + block, n_cells) + 1)
        grid[-1] = min(grid[-1], s1)
        f = np.atleast_1d(g(grid)) - threshold
        r = np.atleast_1d(rate(grid))
        cells = np.flatnonzero((np.sign(f[:-1]) != np.sign(f[1:]))
                               | (np.sign(r[:-1]) != np.sign(r[1:])))
        for j in cells:
            a, c = grid[j], grid[j + 1]
            points = [a]
            if np.sign(r[j]) != np.sign(r[j + 1]) and r[j] != 0.0 \
                    and r[j + 1] != 0.0:
                points.append(brentq(lambda s: float(rate(np.array([s]))[0]),
                                     a, c, xtol=1e-18, rtol=1e-15))
            points.append(c)
            vals = [float(np.atleast_1d(g(np.array([s])))[0]) - threshold
                    for s in points]
            for (sa, fa), (sb, fb) in zip(zip(points, vals),
                                          zip(points[1:], vals[1:])):
                if (fa > 0.0) != (fb > 0.0):
                    root = brentq(lambda s: float(
                        np.atleast_1d(g(np.array([s])))[0]) - threshold,
                        sa, sb, xtol=1e-18, rtol=1e-15)
                    yield root, fb > 0.0
