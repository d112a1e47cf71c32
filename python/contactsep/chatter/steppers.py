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
    ContactMemory,
    HertzLaw,
    series_energy,
    series_forces,
    series_law_energy,
    series_law_forces,
    solve_lcp,
)

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
    and the contacts' ``stored`` energy at the end (in lb)."""
    q, v = q.astype(float).copy(), v.astype(float).copy()
    series = c_matrix is not None and bool(np.any(np.asarray(c_matrix)
                                                  != 0.0))
    memory = ContactMemory(law, len(g0))
    c, s = np.cos(p * dt), np.sin(p * dt)
    samples = steps // stride + 1
    t_out = np.empty(samples)
    g_out = np.empty((samples, len(g0)))
    e_out = np.empty(samples)
    impulses = np.zeros((samples, len(g0)))
    damped = [0.0]

    def remember(q):
        if series and law.plastic:
            # Thornton's elements' own depths, undamped: those the
            # elastic energy reads (hertz.f90's remember)
            gap = h_matrix @ q + g0
            _, depth = series_law_forces(memory, [1.0] * len(gap),
                                         c_matrix, gap)
            for j, d in enumerate(depth):
                if d > 0.0:
                    memory.remember(j, float(d))
            return
        for j, gap in enumerate(h_matrix @ q + g0):
            if gap < 0.0:
                memory.remember(j, -float(gap))

    def stored(q):
        gap = h_matrix @ q + g0
        if series and law.plastic:
            return series_law_energy(memory, c_matrix, gap)
        if series:
            return series_energy(law.k, c_matrix, gap, law.linear)
        return sum(memory.energy(j, -float(g)) for j, g in enumerate(gap))

    def energy(q, v):
        return 0.5 * np.sum(m * (v**2 + (p * q)**2)) + stored(q)

    def series_force(gap, v, chi):
        # Flores's factor on each element's stiffness (hertz.f90)
        stiff = [law.k] * len(gap)
        if chi != 0.0 and np.any(gap < 0.0):
            stiff = [law.k * max(1.0 - chi * float(r), 0.0)
                     for r in h_matrix @ v]
        return series_forces(stiff, c_matrix, gap, law.linear)

    def factors(gap, v, chi):
        # Flores's factor max(1 - chi u, 0) of each Thornton element
        if chi != 0.0 and np.any(gap < 0.0):
            return [max(1.0 - chi * float(r), 0.0) for r in h_matrix @ v]
        return [1.0] * len(gap)

    def forces(gap, v, chi):
        if series and law.plastic:
            return series_law_forces(memory, factors(gap, v, chi),
                                     c_matrix, gap)[0]
        if series:
            return series_force(gap, v, chi)
        if not law.plastic and chi == law.chi:
            return law.force(gap, h_matrix @ v)
        rates = h_matrix @ v
        return np.array([
            (memory.force(j, -float(g), float(r)) if chi != 0.0 else
             memory.elastic_force(j, -float(g))) if g < 0.0 else 0.0
            for j, (g, r) in enumerate(zip(gap, rates))])

    def kick(q, v):
        gap = h_matrix @ q + g0
        force = forces(gap, v, law.chi)
        after = v + 0.5 * dt * (h_matrix.T @ force) / m
        if law.chi != 0.0 and np.any(gap < 0.0):
            # the damping's part of the kick's exact work
            elastic = forces(gap, v, 0.0)
            damped[0] -= 0.25 * dt * float((force - elastic) @ (
                h_matrix @ v + h_matrix @ after))
        return force, after

    def sampled(q, force):
        # with the correction, the physical gaps g + C lambda
        gap = h_matrix @ q + g0
        return gap + np.asarray(c_matrix) @ force if series else gap

    remember(q)
    t_out[0], e_out[0] = 0.0, energy(q, v)
    g_out[0] = sampled(q, forces(h_matrix @ q + g0, v, law.chi))
    first, episode = [-1.0, -1.0], 0
    for step in range(steps):
        force, v = kick(q, v)
        if step // stride + 1 < samples:
            impulses[step // stride + 1] += force * dt
        if force[0] > 0.0 and episode == 0:
            episode, first = 1, [step * dt, 0.0]
        if episode == 1:
            if force[0] > 0.0:
                first[1] += force[0] * dt
            else:
                episode = 2
        q, v = q * c + v / p * s, -q * p * s + v * c
        remember(q)
        force, v = kick(q, v)
        if (step + 1) % stride == 0:
            k = (step + 1) // stride
            t_out[k] = (step + 1) * dt
            g_out[k] = sampled(q, force)
            e_out[k] = energy(q, v)
    out = (t_out, g_out, e_out, impulses, np.array(first))
    if not book:
        return out
    return out + ({"q": q, "v": v,
                   "dissipated": damped[0] + memory.plastic_work(),
                   "stored": float(stored(q))},)
