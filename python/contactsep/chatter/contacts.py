"""Interactions and impact laws: the two unilateral contacts of the three
beams, the Newton impact law, the Hertz force law, the one-step LCP.

Gaps (positive = open; the separator's thickness is not an offset):
g_upper = y1(x1) - y2(x2), g_lower = y2(x2) - y3(x3).  With the stacked
modal coordinates q = [q1, q2, q3], g = H q + g0 with
H = [[X1, -X2, 0], [0, X2, -X3]]; a contact force lambda_c >= 0 acts
along H_c^T (it pushes the gap open).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


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
