"""A finite-element Timoshenko beam for the tests: a different method from
the package's (element matrices and a generalised eigenproblem, not
frequency equations or transfer matrices).

Elements: the two-node Timoshenko element of Friedman and Kosmatka
(1993), cubic deflection and quadratic rotation interpolated
interdependently (exact for a static load at the nodes, no shear
locking), stiffness
int EI psi'^2 + kGA (w' - psi)^2 and consistent mass int rhoA w^2 +
rhoI psi^2, both integrated by Gauss quadrature of the shape functions
(so no hand-expanded matrix can carry a typo).  Dimensionless: EI = 1,
rho A = 1, L = 1, rho I = r2, kGA = 1/s2; the eigenvalues are b^2.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

ENDS = {"clamped-free": ("clamped", "free"),
        "clamped-clamped": ("clamped", "clamped"),
        "clamped-pinned": ("clamped", "pinned"),
        "pinned-pinned": ("pinned", "pinned")}


def shape_functions(x, length, s2):
    """N_w, N_w', N_psi, N_psi' (4, len(x)) at x in [0, length]; DOFs
    [w1, psi1, w2, psi2].  The element's fields are the homogeneous
    static solution, w cubic and psi = w' - Q/kGA with Q = -6 EI a3
    (EI = 1, 1/kGA = s2): built from the nodal values by inverting the
    4x4 map, no hand-written shape function to mistype."""
    g = 6.0 * s2
    nodal = np.array([[1.0, 0.0, 0.0, 0.0],
                      [0.0, 1.0, 0.0, g],
                      [1.0, length, length**2, length**3],
                      [0.0, 1.0, 2.0 * length, 3.0 * length**2 + g]])
    inverse = np.linalg.inv(nodal)
    one, zero = np.ones_like(x), np.zeros_like(x)
    w = np.array([one, x, x**2, x**3])
    dw = np.array([zero, one, 2 * x, 3 * x**2])
    psi = np.array([zero, one, 2 * x, 3 * x**2 + g])
    dpsi = np.array([zero, zero, 2 * one, 6 * x])
    return tuple(inverse.T @ f for f in (w, dw, psi, dpsi))


def element(length, r2, s2):
    x, w = np.polynomial.legendre.leggauss(8)
    t, w = 0.5 * (x + 1.0) * length, 0.5 * w * length
    nw, dnw, npsi, dnpsi = shape_functions(t, length, s2)
    stiff = np.einsum("q,iq,jq->ij", w, dnpsi, dnpsi)
    if s2 > 0.0:
        gamma = dnw - npsi
        stiff += np.einsum("q,iq,jq->ij", w, gamma, gamma) / s2
    mass = np.einsum("q,iq,jq->ij", w, nw, nw) + \
        r2 * np.einsum("q,iq,jq->ij", w, npsi, npsi)
    return stiff, mass


def assemble(end, elements, r2=0.0, s2=0.0, kr=None, kt=None,
             masses=(), points=(), level=0):
    """K, M and the free DOFs of a mesh with nodes at the masses and
    ``points``, about ``elements`` elements, each halved ``level``
    times (so that Romberg's meshes are exact halvings); returns (K, M,
    free, nodes)."""
    cuts = sorted({0.0, 1.0, *(xi for xi, _ in masses), *points})
    nodes = [0.0]
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        count = max(1, int(round(elements * (hi - lo)))) * 2**level
        nodes.extend(lo + (hi - lo) * np.arange(1, count + 1) / count)
    nodes = np.array(nodes)
    dofs = 2 * len(nodes)
    k = np.zeros((dofs, dofs))
    m = np.zeros((dofs, dofs))
    for e in range(len(nodes) - 1):
        ke, me = element(nodes[e + 1] - nodes[e], r2, s2)
        sl = slice(2 * e, 2 * e + 4)
        k[sl, sl] += ke
        m[sl, sl] += me
    for xi, mu in masses:
        node = int(np.argmin(np.abs(nodes - xi)))
        m[2 * node, 2 * node] += mu
    fixed = []
    for side, node in zip(ENDS[end], (0, len(nodes) - 1)):
        if side == "free":
            continue
        if kt is None:
            fixed.append(2 * node)
        else:
            k[2 * node, 2 * node] += kt
        if side == "clamped":
            if kr is None:
                fixed.append(2 * node + 1)
            else:
                k[2 * node + 1, 2 * node + 1] += kr
    free = np.setdiff1d(np.arange(dofs), fixed)
    return k, m, free, nodes


def eigenvalues(end, elements, count, level=0, **options):
    """b_j (count,) of the FE model.  Solved as M u = (1/b^2) K u for the
    largest 1/b^2: a backward-stable solver then gives the lowest b^2
    to their own relative precision (K u = b^2 M u would give them only
    to eps times the mesh's highest b^2)."""
    k, m, free, _ = assemble(end, elements, level=level, **options)
    size = len(free)
    values = scipy.linalg.eigh(m[np.ix_(free, free)], k[np.ix_(free, free)],
                               eigvals_only=True,
                               subset_by_index=[size - count, size - 1])
    return 1.0 / np.sqrt(values[::-1])


def converged(end, count, elements=16, **options):
    """b_j extrapolated from meshes of n, 2n and 4n elements (Romberg:
    the eigenvalue error is c2 h^2 + c4 h^4 + ..., h^2 from the
    element's constant shear strain, h^4 from its cubic deflection), and
    the finest mesh's values."""
    values = [eigenvalues(end, elements, count, level=k, **options)
              for k in range(3)]
    first = [(4.0 * fine - coarse) / 3.0
             for coarse, fine in zip(values[:-1], values[1:])]
    return (16.0 * first[1] - first[0]) / 15.0, values[-1]


def static_deflection(end, xi, elements=64, **options):
    """w(xi) under a unit load at xi (the FE model is exact at nodes)."""
    k, _, free, nodes = assemble(end, elements, points=(xi,), **options)
    node = int(np.argmin(np.abs(nodes - xi)))
    load = np.zeros(k.shape[0])
    load[2 * node] = 1.0
    u = np.zeros(k.shape[0])
    u[free] = np.linalg.solve(k[np.ix_(free, free)], load[free])
    return u[2 * node]
