"""The simulations (NumPy twins of fortran/chatter/): Moreau-Jean time
stepping with the Newton law, and Hertz contact by splitting with the
exact modal flow.  Simulation side of the Siconos split.

State: stacked modal coordinates q, v of every member (mode j of member
i has mass m_j = M_i and frequency p_j); H (k x n) the contacts' Jacobian,
g0 their gap offsets.  Output is sampled every ``stride`` steps.
"""

from __future__ import annotations

import numpy as np

from contactsep.chatter.contacts import (
    series_energy,
    series_forces,
    series_law_energy,
    series_law_forces,
    solve_lcp,
)
from contactsep.chatter.laws import ContactMemory, HertzLaw

EPS = float(np.finfo(float).eps)


def moreau_jean(m, p, h_matrix, g0, q, v, *, e, dt, steps, theta=0.5,
                stride=1):
    """Moreau-Jean on M q'' + K q = H^T lambda (theta-method, velocity-level
    Newton law, the k-contact LCP solved exactly each step).

    With theta = 1/2 the free flight is the trapezoidal rule: energy is
    conserved for every step size (the modes far above 1/dt keep their
    energy but not their phase); a contact is taken as active when its
    predicted gap g + (dt/2) u is closed and it is not separating.
    Returns sampled (t, gaps,
    energy) and the impulses summed over each sample's steps
    (samples, k; row s holds steps (s-1) stride + 1 .. s stride).
    """
    q, v = q.astype(float).copy(), v.astype(float).copy()
    k = m * p**2
    w = 1.0 / (m + dt**2 * theta**2 * k)
    d_full = (h_matrix * w) @ h_matrix.T
    samples = steps // stride + 1
    t_out = np.empty(samples)
    g_out = np.empty((samples, len(g0)))
    e_out = np.empty(samples)
    impulses = np.zeros((samples, len(g0)))
    t_out[0], g_out[0] = 0.0, h_matrix @ q + g0
    e_out[0] = 0.5 * np.sum(m * v**2 + k * q**2)
    first, episode = [-1.0, -1.0], 0
    for step in range(steps):
        u = h_matrix @ v
        gap = h_matrix @ q + g0
        v_free = w * (m * v - dt * k * q - dt**2 * theta * (1 - theta)
                      * k * v)
        # closed and not separating: the impulse's work, P (1-e) u_k / 2,
        # is then never positive (energy never grows).  "Separating" is
        # beyond round-off: a closed contact at rest has u = 0 +- the
        # round-off of v_free + impulse, which cancel (a contact skipped
        # for a step sinks by dt^2 F / M)
        noise = 64.0 * EPS * (np.abs(h_matrix) @ np.abs(v_free))
        active = np.flatnonzero((gap + 0.5 * dt * u <= 0.0) & (u <= noise))
        v_new = v_free
        touched = 0.0
        if active.size:
            lcp_q = h_matrix[active] @ v_free + e * u[active]
            impulse = solve_lcp(d_full[np.ix_(active, active)], lcp_q)
            touched = float(impulse[0]) if active[0] == 0 else 0.0
            if step // stride + 1 < samples:
                impulses[step // stride + 1, active] += impulse
            v_new = v_free + w * (h_matrix[active].T @ impulse)
        if touched > 0.0 and episode == 0:
            episode, first = 1, [(step + 1) * dt, 0.0]
        if episode == 1:
            if touched > 0.0:
                first[1] += touched
            else:
                episode = 2
        q = q + dt * (theta * v_new + (1 - theta) * v)
        v = v_new
        if (step + 1) % stride == 0:
            s = (step + 1) // stride
            t_out[s] = (step + 1) * dt
            g_out[s] = h_matrix @ q + g0
            e_out[s] = 0.5 * np.sum(m * v**2 + k * q**2)
    return t_out, g_out, e_out, impulses, np.array(first)


def hertz(m, p, h_matrix, g0, q, v, *, law: HertzLaw, dt, steps, stride=1,
          c_matrix=None, book=False):
    """Hertz contact by Strang splitting: half kick of the contact forces,
    the exact modal flow over dt (every mode, however stiff), half kick.
    Symplectic for chi = 0; the step resolves the contact, not the modes.
    ``c_matrix`` (k x k, in/lb): the static correction's series
    flexibilities (None or 0: the plain truncation; Thornton's law
    takes the series solve of its own force and remembers the elements'
    depths).  Returns sampled (t, gaps, energy incl. the contact's) and the
    impulses (force at each step's start x dt) summed per sample; with
    ``book``, also the energy book: a dict of the final ``q``, ``v``,
    the ``dissipated`` energy (the damping's work, each kick's exact
    change of kinetic energy, its damping part, and the plastic work)
    and the contacts' ``stored`` energy at the end (in lb).  The
    contacts' part of each step is :class:`_HertzContacts`'s."""
    q, v = q.astype(float).copy(), v.astype(float).copy()
    contacts = _HertzContacts(m, p, h_matrix, g0, law, dt, c_matrix)
    c, s = np.cos(p * dt), np.sin(p * dt)
    samples = steps // stride + 1
    t_out = np.empty(samples)
    g_out = np.empty((samples, len(g0)))
    e_out = np.empty(samples)
    impulses = np.zeros((samples, len(g0)))
    contacts.remember(q)
    t_out[0], e_out[0] = 0.0, contacts.energy(q, v)
    g_out[0] = contacts.sampled(q, contacts.forces(h_matrix @ q + g0, v,
                                                   law.chi))
    first = _FirstEpisode()
    for step in range(steps):
        force, v = contacts.kick(q, v)
        if step // stride + 1 < samples:
            impulses[step // stride + 1] += force * dt
        first.record(step, force[0], dt)
        q, v = q * c + v / p * s, -q * p * s + v * c
        contacts.remember(q)
        force, v = contacts.kick(q, v)
        if (step + 1) % stride == 0:
            k = (step + 1) // stride
            t_out[k] = (step + 1) * dt
            g_out[k] = contacts.sampled(q, force)
            e_out[k] = contacts.energy(q, v)
    out = (t_out, g_out, e_out, impulses, np.array(first.first))
    if not book:
        return out
    return out + (contacts.book(q, v),)


class _FirstEpisode:
    """The upper contact's first episode of contact in :func:`hertz`:
    [its start (s), its summed impulse (lb s)], [-1, -1] until it
    begins; the episode ends at the first step without force."""

    def __init__(self):
        self.first, self.episode = [-1.0, -1.0], 0

    def record(self, step, force, dt):
        # force: the upper contact's at the step's start
        if force > 0.0 and self.episode == 0:
            self.episode, self.first = 1, [step * dt, 0.0]
        if self.episode == 1:
            if force > 0.0:
                self.first[1] += force * dt
            else:
                self.episode = 2


class _HertzContacts:
    """The contacts of one :func:`hertz` run (twin of hertz.f90): their
    forces under the law (plain, or in series with the static
    correction's flexibilities), the half kicks, the depths Thornton's
    law remembers, the energy they store and the damping's work."""

    def __init__(self, m, p, h_matrix, g0, law, dt, c_matrix):
        self.m, self.p, self.h_matrix, self.g0 = m, p, h_matrix, g0
        self.law, self.dt, self.c_matrix = law, dt, c_matrix
        self.series = c_matrix is not None and bool(
            np.any(np.asarray(c_matrix) != 0.0))
        self.memory = ContactMemory(law, len(g0))
        #: The damping's work so far (in lb), from the kicks.
        self.damped = 0.0

    def remember(self, q):
        law, memory = self.law, self.memory
        if self.series and law.plastic:
            # Thornton's elements' own depths, undamped: those the
            # elastic energy reads (hertz.f90's remember)
            gap = self.h_matrix @ q + self.g0
            _, depth = series_law_forces(memory, [1.0] * len(gap),
                                         self.c_matrix, gap)
            for j, d in enumerate(depth):
                if d > 0.0:
                    memory.remember(j, float(d))
            return
        for j, gap in enumerate(self.h_matrix @ q + self.g0):
            if gap < 0.0:
                memory.remember(j, -float(gap))

    def stored(self, q):
        law, memory, c_matrix = self.law, self.memory, self.c_matrix
        gap = self.h_matrix @ q + self.g0
        if self.series and law.plastic:
            return series_law_energy(memory, c_matrix, gap)
        if self.series:
            return series_energy(law.k, c_matrix, gap, law.linear)
        return sum(memory.energy(j, -float(g)) for j, g in enumerate(gap))

    def energy(self, q, v):
        m, p = self.m, self.p
        return 0.5 * np.sum(m * (v**2 + (p * q)**2)) + self.stored(q)

    def _series_force(self, gap, v, chi):
        # Flores's factor on each element's stiffness (hertz.f90)
        law = self.law
        stiff = [law.k] * len(gap)
        if chi != 0.0 and np.any(gap < 0.0):
            stiff = [law.k * max(1.0 - chi * float(r), 0.0)
                     for r in self.h_matrix @ v]
        return series_forces(stiff, self.c_matrix, gap, law.linear)

    def _factors(self, gap, v, chi):
        # Flores's factor max(1 - chi u, 0) of each Thornton element
        if chi != 0.0 and np.any(gap < 0.0):
            return [max(1.0 - chi * float(r), 0.0)
                    for r in self.h_matrix @ v]
        return [1.0] * len(gap)

    def forces(self, gap, v, chi):
        law, memory, h_matrix = self.law, self.memory, self.h_matrix
        if self.series and law.plastic:
            return series_law_forces(memory, self._factors(gap, v, chi),
                                     self.c_matrix, gap)[0]
        if self.series:
            return self._series_force(gap, v, chi)
        if not law.plastic and chi == law.chi:
            return law.force(gap, h_matrix @ v)
        rates = h_matrix @ v
        return np.array([
            (memory.force(j, -float(g), float(r)) if chi != 0.0 else
             memory.elastic_force(j, -float(g))) if g < 0.0 else 0.0
            for j, (g, r) in enumerate(zip(gap, rates))])

    def kick(self, q, v):
        """A half kick of the contact forces: (the force, v after)."""
        h_matrix, dt, law = self.h_matrix, self.dt, self.law
        gap = h_matrix @ q + self.g0
        force = self.forces(gap, v, law.chi)
        after = v + 0.5 * dt * (h_matrix.T @ force) / self.m
        if law.chi != 0.0 and np.any(gap < 0.0):
            # the damping's part of the kick's exact work
            elastic = self.forces(gap, v, 0.0)
            self.damped -= 0.25 * dt * float((force - elastic) @ (
                h_matrix @ v + h_matrix @ after))
        return force, after

    def sampled(self, q, force):
        # with the correction, the physical gaps g + C lambda
        gap = self.h_matrix @ q + self.g0
        return gap + np.asarray(self.c_matrix) @ force if self.series \
            else gap

    def book(self, q, v):
        """The energy book at the end (see :func:`hertz`)."""
        return {"q": q, "v": v,
                "dissipated": self.damped + self.memory.plastic_work(),
                "stored": float(self.stored(q))}
