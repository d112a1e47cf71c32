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
    """A contact force law of the Hertz family (docs/chatter.md, "Contact
    laws"): F = F_e (1 + chi delta'), F >= 0, with F_e = k delta^{3/2},
    k = (4/3) E* sqrt(R), E* = E / (2 (1 - nu^2)) (two equal materials);
    chi = 0 (elastic), Flores et al. 8 (1 - e) / (5 e V_ref) (calibrated
    to e), or Hunt and Crossley's alpha (a material constant).  With a
    yield pressure p_y > 0, F_e is Thornton's elastic-perfectly-plastic
    law (:class:`ContactMemory`; twin of fortran/chatter/contact_law.f90).
    """

    k: float
    chi: float = 0.0
    #: Thornton: the yield pressure (psi; 0: elastic Hertz), the
    #: effective modulus E* (psi) and the button radius R (in).
    yield_pressure: float = 0.0
    e_star: float = 0.0
    radius: float = 0.0
    #: A line contact (a cylindrical button): F_e = k delta with k =
    #: (pi/4) E* L (lb/in), L the cylinder's length.
    linear: bool = False

    @classmethod
    def for_materials(cls, modulus, nu=0.33, radius=0.125, *, e=None,
                      v_ref=None, alpha=None, yield_pressure=None,
                      button="sphere", length=None):
        """k from the materials; chi from e and V_ref when both given
        (Flores), or alpha (Hunt-Crossley, s/in); Thornton's law with a
        yield pressure (psi); a cylindrical ``button`` of ``length`` (in;
        default its diameter 2R) a line contact."""
        e_star = modulus / (2.0 * (1.0 - nu**2))
        k = 4.0 / 3.0 * e_star * np.sqrt(radius)
        linear = button == "cylinder"
        if linear:
            k = math.pi / 4.0 * e_star * (2.0 * radius if length is None
                                          else length)
        chi = 0.0
        if e is not None and v_ref is not None:
            if not 0.0 < e <= 1.0 or not v_ref > 0.0:
                raise ValueError("Flores damping needs 0 < e <= 1 and "
                                 "V_ref > 0")
            chi = 8.0 * (1.0 - e) / (5.0 * e * v_ref)
        if alpha is not None:
            chi = float(alpha)
        pressure = 0.0 if yield_pressure is None else float(yield_pressure)
        return cls(k=float(k), chi=chi, yield_pressure=pressure,
                   e_star=float(e_star), radius=float(radius),
                   linear=linear)

    @property
    def exponent(self) -> float:
        """n of F_e = k delta^n: 3/2 (sphere), 1 (cylinder)."""
        return 1.0 if self.linear else 1.5

    @property
    def plastic(self) -> bool:
        """Thornton's law (a yield pressure given)."""
        return self.yield_pressure > 0.0

    @property
    def yield_depth(self) -> float:
        """delta_y = (pi p_y / (2 E*))^2 R (in): where the largest Hertz
        pressure reaches p_y (inf for the elastic law)."""
        if not self.plastic:
            return math.inf
        return (math.pi * self.yield_pressure / (2.0 * self.e_star))**2 \
            * self.radius

    def envelope(self, depth: float) -> float:
        """The loading force (lb) at a new largest penetration (in)."""
        if depth <= 0.0:
            return 0.0
        if self.linear:
            return self.k * depth
        yield_depth = self.yield_depth
        if depth <= yield_depth:
            return self.k * depth**1.5
        return self.k * yield_depth**1.5 + math.pi * self.yield_pressure \
            * self.radius * (depth - yield_depth)

    def depth_at(self, force: float) -> float:
        """The penetration (in) at which the loading envelope carries
        ``force`` (lb): the preloaded contact's static depth."""
        if force <= 0.0:
            return 0.0
        if self.linear:
            return force / self.k
        yield_depth = self.yield_depth
        if force <= self.k * yield_depth**1.5:
            return (force / self.k) ** (2.0 / 3.0)
        return yield_depth + (force - self.k * yield_depth**1.5) / (
            math.pi * self.yield_pressure * self.radius)

    def force(self, gap, gap_rate):
        """Contact force (lb) for gaps (in) and their rates (in/s) of the
        elastic law (Thornton's needs its memory: ContactMemory)."""
        delta = np.maximum(-gap, 0.0)
        force = self.k * delta**self.exponent * (1.0 + self.chi
                                                 * (-gap_rate))
        return np.where(delta > 0.0, np.maximum(force, 0.0), 0.0)

    def energy(self, gap):
        """Elastic energy k delta^{n+1} / (n + 1) (in lb) of the elastic
        law ((2/5) k delta^{5/2} for a sphere)."""
        delta = np.maximum(-gap, 0.0)
        if self.linear:
            return 0.5 * self.k * delta**2
        return 0.4 * self.k * delta**2.5


class ContactMemory:
    """The state of k contacts under a :class:`HertzLaw`: each one's
    largest penetration, and Thornton's unloading curve from it (the
    elastic Hertz law with the enlarged radius R_p = 4 E* a_m^3 / (3 F_m),
    a_m^2 = R delta_m, from the plastic offset delta_p = delta_m -
    a_m^2 / R_p) and plastic work (the envelope's work to delta_m less
    the (2/5) F_m (delta_m - delta_p) unloading gives back).  Twin of
    fortran/chatter/contact_law.f90."""

    def __init__(self, law: HertzLaw, k: int):
        self.law = law
        self.depth_max = [0.0] * k
        self.unload_k = [0.0] * k
        self.offset = [0.0] * k
        self.work = [0.0] * k

    def remember(self, c: int, depth: float) -> None:
        """A penetration of contact c (in): a new largest one moves its
        unloading curve and plastic work."""
        law = self.law
        if not law.plastic or not depth > self.depth_max[c]:
            return
        self.depth_max[c] = depth
        yield_depth = law.yield_depth
        if depth <= yield_depth:
            return
        a2 = law.radius * depth
        force = law.envelope(depth)
        r_p = 4.0 * law.e_star * a2 * math.sqrt(a2) / (3.0 * force)
        self.unload_k[c] = 4.0 / 3.0 * law.e_star * math.sqrt(r_p)
        self.offset[c] = depth - a2 / r_p
        over = depth - yield_depth
        f_y = law.k * yield_depth**1.5
        loading = 0.4 * f_y * yield_depth + f_y * over + 0.5 * math.pi \
            * law.yield_pressure * law.radius * over**2
        self.work[c] = loading - 0.4 * force * (depth - self.offset[c])

    def elastic_force(self, c: int, depth: float) -> float:
        """F_e (lb) of contact c at penetration ``depth`` (in)."""
        law = self.law
        if not depth > 0.0:
            return 0.0
        if not law.plastic or depth >= self.depth_max[c] or \
                self.depth_max[c] <= law.yield_depth:
            return law.envelope(depth)
        over = depth - self.offset[c]
        return self.unload_k[c] * over**1.5 if over > 0.0 else 0.0

    def elastic_slope(self, c: int, depth: float) -> float:
        """dF_e/d delta (lb/in) of contact c at ``depth`` (in), on the
        branch :meth:`elastic_force` takes there."""
        law = self.law
        if not depth > 0.0:
            return 0.0
        if not law.plastic or depth >= self.depth_max[c] or \
                self.depth_max[c] <= law.yield_depth:
            if law.linear:
                return law.k
            if depth <= law.yield_depth:
                return 1.5 * law.k * math.sqrt(depth)
            return math.pi * law.yield_pressure * law.radius
        over = depth - self.offset[c]
        return 1.5 * self.unload_k[c] * math.sqrt(over) if over > 0.0 \
            else 0.0

    def force(self, c: int, depth: float, rate: float) -> float:
        """F = max(F_e (1 - chi rate), 0), rate the gap's (in/s)."""
        force = self.elastic_force(c, depth)
        if self.law.chi != 0.0 and force > 0.0:
            force = max(force * (1.0 - self.law.chi * rate), 0.0)
        return force

    def energy(self, c: int, depth: float) -> float:
        """The elastic energy contact c stores (in lb), (2/5) F_e (delta
        - delta_p); past the memory, of the unloading curve from delta."""
        if not depth > 0.0:
            return 0.0
        if not self.law.plastic:
            return float(self.law.energy(-depth))
        law = self.law
        offset = self.offset[c] if self.depth_max[c] > \
            law.yield_depth else 0.0
        if depth > self.depth_max[c] and depth > law.yield_depth:
            # ahead of the memory: the unloading curve from this depth
            a2 = law.radius * depth
            r_p = 4.0 * law.e_star * a2 * math.sqrt(a2) / (
                3.0 * law.envelope(depth))
            offset = depth - a2 / r_p
        return 0.4 * self.elastic_force(c, depth) * max(depth - offset,
                                                         0.0)

    def plastic_work(self) -> float:
        """The plastic work of every contact so far (in lb)."""
        return float(sum(self.work)) if self.law.plastic else 0.0


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


def series_forces(stiff, c_matrix, gap, linear=False) -> np.ndarray:
    """Forces (lb) of Hertz elements (stiffnesses ``stiff``, lb/in^1.5; 0:
    no force) in series with the flexibilities ``c_matrix`` (in/lb) at
    modal gaps ``gap`` (in): the minimiser over lambda >= 0 of
    sum (3/5) s^{-2/3} lambda^{5/3} + lambda^T C lambda / 2 + lambda^T g
    (docs/static-correction.md, "The static correction"), by exact coordinate
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
            if a > 0.0 and stiff[i] > 0.0 and linear:
                # a linear element (cylindrical button): a / (1 + c s)
                force[i] = stiff[i] * a / (1.0 + float(c_matrix[i][i])
                                           * stiff[i])
            elif a > 0.0 and stiff[i] > 0.0:
                depth = element_depth(a, float(c_matrix[i][i]) * stiff[i])
                force[i] = stiff[i] * depth * math.sqrt(depth)
            else:
                force[i] = 0.0
        if k == 1 or all(abs(f - o) <= eps4 * f for f, o in zip(force,
                                                                 old)):
            break
    return np.array(force)


def series_energy(stiffness: float, c_matrix, gap, linear=False) -> float:
    """The contacts' elastic energy (in lb) with the series springs:
    sum (2/5) k delta^{5/2} (linear: k delta^2 / 2) + lambda^T C lambda
    / 2, undamped forces."""
    force = series_forces([stiffness] * len(gap), c_matrix, gap, linear)
    total = 0.5 * float(force @ (np.asarray(c_matrix) @ force))
    if linear:
        return total + 0.5 * float(force @ force) / stiffness
    for f in force:
        if f > 0.0:
            total += 0.4 * f * (f / stiffness) ** (2.0 / 3.0)
    return total


def law_depth(memory: ContactMemory, c: int, a: float, b: float) -> float:
    """The root delta in [0, a] of delta + b F_e(delta) = a (a > 0, b >=
    0), F_e contact c's elastic force with its memory (continuous and
    increasing): Newton's method from a inside the root's bracket (a
    bisection where a step leaves it), until a step moves nothing or the
    bracket holds no float (twin of hertz_series.f90's law_depth)."""
    depth = a
    if b <= 0.0:
        return depth
    low, high = 0.0, a
    for _ in range(4 * MAX_NEWTON):
        f = depth + b * memory.elastic_force(c, depth) - a
        if f == 0.0:
            break
        if f > 0.0:
            high = depth
        else:
            low = depth
        step = depth - f / (1.0 + b * memory.elastic_slope(c, depth))
        if step == depth:
            break
        if not low < step < high:
            step = 0.5 * (low + high)
        if step in (low, high):
            break
        depth = step
    return depth


def series_law_forces(memory: ContactMemory, factor, c_matrix, gap):
    """:func:`series_forces` for Thornton's law: the forces factor_i
    F_e(delta_i) (factor Flores's max(1 - chi u, 0), 1 undamped) and the
    elements' depths delta_i (in), F_e of each contact's memory as it
    stands (remember the depths after; twin of series_law_forces)."""
    k = len(gap)
    force, depth = [0.0] * k, [0.0] * k
    if all(float(g) >= 0.0 for g in gap):
        return np.zeros(k), np.zeros(k)
    eps4 = 4.0 * EPS
    for _ in range(MAX_SWEEPS):
        old = list(force)
        for i in range(k):
            a = -float(gap[i])
            for j in range(k):
                if j != i:
                    a -= float(c_matrix[i][j]) * force[j]
            if a > 0.0 and factor[i] > 0.0:
                depth[i] = law_depth(memory, i, a, float(c_matrix[i][i])
                                     * factor[i])
                force[i] = factor[i] * memory.elastic_force(i, depth[i])
            else:
                force[i], depth[i] = 0.0, max(a, 0.0)
        if k == 1 or all(abs(f - o) <= eps4 * f for f, o in zip(force,
                                                                 old)):
            break
    return np.array(force), np.array(depth)


def series_law_energy(memory: ContactMemory, c_matrix, gap) -> float:
    """Thornton's elements' elastic energy (in lb) with the series
    springs: sum of each element's recoverable energy at its depth +
    lambda^T C lambda / 2, undamped forces, the memory as it stands."""
    force, depth = series_law_forces(memory, [1.0] * len(gap), c_matrix,
                                     gap)
    springs = 0.5 * float(force @ (np.asarray(c_matrix) @ force))
    return sum(memory.energy(c, float(d)) for c, d in enumerate(depth)) \
        + springs


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
