"""The contact-force solves: the two unilateral contacts of the three
beams, the Hertz elements in series with the truncated modes' residual
flexibility, the one-step LCP (the laws themselves:
:mod:`contactsep.chatter.laws`).

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

import numpy as np

from contactsep.chatter.laws import ContactMemory

EPS = float(np.finfo(float).eps)


#: Most sweeps of the series solve's coordinate descent, and Newton
#: iterations of one element (as fortran/chatter/hertz_series.f90).
MAX_SWEEPS = 200
MAX_NEWTON = 100


def element_approach(i: int, c_matrix, gap, force) -> float:
    """The approach a_i = -g_i - sum_{j != i} C_ij lambda_j (in) that
    element ``i`` takes up with the other elements' forces as they stand:
    one step of the coordinate descent of every series solve, summed in
    j's order (twin of hertz_series.f90's element_approach)."""
    a = -float(gap[i])
    for j in range(len(gap)):
        if j != i:
            a -= float(c_matrix[i][j]) * force[j]
    return a


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
            a = element_approach(i, c_matrix, gap, force)
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
            a = element_approach(i, c_matrix, gap, force)
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
