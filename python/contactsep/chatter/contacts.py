"""Interactions and impact laws: the two unilateral contacts of the three
beams, the Newton impact law, the Hertz force law, the one-step LCP.

Gaps (positive = open; the separator's thickness is not an offset):
g_upper = y1(x1) - y2(x2), g_lower = y2(x2) - y3(x3).  With the stacked
modal coordinates q = [q1, q2, q3], g = H q + g0 with
H = [[X1, -X2, 0], [0, X2, -X3]]; a contact force lambda_c >= 0 acts
along H_c^T (it pushes the gap open).  With the static correction a
Hertz element sits in series with the truncated modes' residual
flexibility C (2 x 2): it carries lambda = k delta^{3/2} on its own
penetration delta = -(g + C lambda) (:func:`series_forces`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

EPS = float(np.finfo(float).eps)


@dataclass(frozen=True)
class NewtonImpactLaw:
    """Newton's impact law with restitution e: at a closing contact
    0 <= u+ + e u- complementary to the impulse P >= 0 (velocity level)."""

    e: float


@dataclass(frozen=True)
class HertzLaw:
    """Hertz contact force F = k delta^{3/2} (1 + chi delta'), F >= 0, with
    k = (4/3) E* sqrt(R), E* = E / (2 (1 - nu^2)) (two equal materials);
    chi = 0 (elastic) or Flores et al. 8 (1 - e) / (5 e V_ref)."""

    k: float
    chi: float = 0.0

    @classmethod
    def for_materials(cls, modulus, nu=0.33, radius=0.125, *, e=None,
                      v_ref=None):
        """k from the materials; chi from e and V_ref when both given."""
        e_star = modulus / (2.0 * (1.0 - nu**2))
        k = 4.0 / 3.0 * e_star * np.sqrt(radius)
        chi = 0.0
        if e is not None and v_ref is not None:
            if not 0.0 < e <= 1.0 or not v_ref > 0.0:
                raise ValueError("Flores damping needs 0 < e <= 1 and "
                                 "V_ref > 0")
            chi = 8.0 * (1.0 - e) / (5.0 * e * v_ref)
        return cls(k=k, chi=chi)

    def force(self, gap, gap_rate):
        """Contact force (lb) for gaps (in) and their rates (in/s)."""
        delta = np.maximum(-gap, 0.0)
        force = self.k * delta**1.5 * (1.0 + self.chi * (-gap_rate))
        return np.where(delta > 0.0, np.maximum(force, 0.0), 0.0)

    def energy(self, gap):
        """Elastic energy (2/5) k delta^{5/2} (in lb)."""
        delta = np.maximum(-gap, 0.0)
        return 0.4 * self.k * delta**2.5


#: Most sweeps of the series solve's coordinate descent, and Newton
#: iterations of one element (as fortran/chatter/hertz_series.f90).
MAX_SWEEPS = 200
MAX_NEWTON = 100


def element_depth(a: float, b: float) -> float:
    """The root delta >= 0 of delta + b delta^{3/2} = a (a > 0, b >= 0):
    Newton's method from the upper bound min(a, (a/b)^{2/3}); the function
    is convex and increasing, so the iterates fall onto the root and stop
    when they stop falling (twin of hertz_series.f90's)."""
    if b <= 0.0:
        return a
    depth = min(a, (a / b) ** (2.0 / 3.0))
    for _ in range(MAX_NEWTON):
        root = math.sqrt(depth)
        step = depth - (depth + b * depth * root - a) / (1.0 + 1.5 * b
                                                          * root)
        if not step < depth:
            break
        depth = max(step, 0.0)
    return depth


def series_forces(stiff, c_matrix, gap) -> np.ndarray:
    """Forces (lb) of Hertz elements (stiffnesses ``stiff``, lb/in^1.5; 0:
    no force) in series with the flexibilities ``c_matrix`` (in/lb) at
    modal gaps ``gap`` (in): the minimiser over lambda >= 0 of
    sum (3/5) s^{-2/3} lambda^{5/3} + lambda^T C lambda / 2 + lambda^T g
    (docs/chatter.md, "The static correction"), by exact coordinate
    descent to 4 ulps (twin of hertz_series.f90's series_forces)."""
    k = len(gap)
    force = [0.0] * k
    if all(float(g) >= 0.0 for g in gap):
        return np.zeros(k)
    eps4 = 4.0 * EPS
    for _ in range(MAX_SWEEPS):
        old = list(force)
        for i in range(k):
            a = -float(gap[i])
            for j in range(k):
                if j != i:
                    a -= float(c_matrix[i][j]) * force[j]
            if a > 0.0 and stiff[i] > 0.0:
                depth = element_depth(a, float(c_matrix[i][i]) * stiff[i])
                force[i] = stiff[i] * depth * math.sqrt(depth)
            else:
                force[i] = 0.0
        if k == 1 or all(abs(f - o) <= eps4 * f for f, o in zip(force,
                                                                 old)):
            break
    return np.array(force)


def series_energy(stiffness: float, c_matrix, gap) -> float:
    """The contacts' elastic energy (in lb) with the series springs:
    sum (2/5) k delta^{5/2} + lambda^T C lambda / 2, undamped forces."""
    force = series_forces([stiffness] * len(gap), c_matrix, gap)
    total = 0.5 * float(force @ (np.asarray(c_matrix) @ force))
    for f in force:
        if f > 0.0:
            total += 0.4 * f * (f / stiffness) ** (2.0 / 3.0)
    return total


def solve_lcp(matrix, vector):
    """z >= 0 with w = matrix z + vector >= 0 and z.w = 0, for 1 or 2
    unknowns, exactly: every active set is tried (2^k of them) and the
    one that satisfies the conditions returned (matrix is symmetric
    positive definite here, so exactly one does)."""
    k = len(vector)
    best = None
    for mask in range(1 << k):
        active = [i for i in range(k) if mask >> i & 1]
        z = np.zeros(k)
        if active:
            sub = matrix[np.ix_(active, active)]
            z[active] = np.linalg.solve(sub, -vector[active])
        w = matrix @ z + vector
        tol = 1e-12 * (np.abs(vector).max() + 1e-300)
        if np.all(z >= -tol) and np.all(w >= -tol):
            best = np.maximum(z, 0.0)
            break
    if best is None:
        raise ArithmeticError("the contact LCP has no solution")
    return best
