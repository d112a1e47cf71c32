"""A plane-stress finite-element model of a rectangular strip, the tests'
own (it imports nothing from contactsep): nine-node Lagrange quadrilaterals
(biquadratic), consistent mass, 3 x 3 Gauss points, on a uniform mesh;
the first natural frequencies with both end faces fully fixed (u = v = 0:
a perfect clamp of the 2-D continuum).

Units are the caller's (in, lb, s: E in psi, rho in lb s^2/in^4).
"""

from __future__ import annotations

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as sparse_linalg


def _lagrange(s):
    """1-D quadratic shape functions at nodes -1, 0, 1 and their
    derivatives, (3, len(s)) each."""
    s = np.asarray(s, dtype=float)
    n = np.array([s * (s - 1) / 2, 1 - s**2, s * (s + 1) / 2])
    dn = np.array([s - 0.5, -2 * s, s + 0.5])
    return n, dn


def element_matrices(a, b, modulus, nu, rho):
    """Stiffness and mass (18 x 18) of a 2a x 2b element (plane stress,
    unit thickness); dof order: node (i, j) with i along x, j along y,
    node index 3 j + i, then (u, v)."""
    g, w = np.polynomial.legendre.leggauss(3)
    d = modulus / (1 - nu**2) * np.array([[1, nu, 0], [nu, 1, 0],
                                          [0, 0, (1 - nu) / 2]])
    k = np.zeros((18, 18))
    m = np.zeros((18, 18))
    nx, dnx = _lagrange(g)
    for q, (wq, sx) in enumerate(zip(w, g)):
        for r, (wr, sy) in enumerate(zip(w, g)):
            shape = np.outer(nx[:, r], nx[:, q]).ravel()      # [j, i]
            dshape_x = np.outer(nx[:, r], dnx[:, q]).ravel() / a
            dshape_y = np.outer(dnx[:, r], nx[:, q]).ravel() / b
            strain = np.zeros((3, 18))
            strain[0, 0::2] = dshape_x
            strain[1, 1::2] = dshape_y
            strain[2, 0::2] = dshape_y
            strain[2, 1::2] = dshape_x
            weight = wq * wr * a * b
            k += weight * strain.T @ d @ strain
            n = np.zeros((2, 18))
            n[0, 0::2] = shape
            n[1, 1::2] = shape
            m += weight * rho * n.T @ n
    return k, m


def clamped_strip_frequencies(length, depth, modulus, nu, rho, nx, ny,
                              count=1):
    """The first ``count`` circular frequencies (rad/s) of a strip
    length x depth, both ends' faces fixed, on nx x ny elements."""
    k_e, m_e = element_matrices(length / nx / 2, depth / ny / 2, modulus,
                                nu, rho)
    cols = 2 * nx + 1
    node = np.arange(cols * (2 * ny + 1)).reshape(2 * ny + 1, cols)
    rows, columns, k_values, m_values = [], [], [], []
    for ey in range(ny):
        for ex in range(nx):
            nodes = node[2 * ey:2 * ey + 3, 2 * ex:2 * ex + 3].ravel()
            dofs = np.stack([2 * nodes, 2 * nodes + 1], axis=1).ravel()
            rows.append(np.repeat(dofs, 18))
            columns.append(np.tile(dofs, 18))
            k_values.append(k_e.ravel())
            m_values.append(m_e.ravel())
    size = 2 * node.size
    shape = (size, size)
    rows, columns = np.concatenate(rows), np.concatenate(columns)
    stiffness = sparse.coo_matrix((np.concatenate(k_values),
                                   (rows, columns)), shape=shape).tocsc()
    mass = sparse.coo_matrix((np.concatenate(m_values), (rows, columns)),
                             shape=shape).tocsc()
    fixed = np.concatenate([node[:, 0], node[:, -1]])
    fixed = np.concatenate([2 * fixed, 2 * fixed + 1])
    free = np.setdiff1d(np.arange(size), fixed)
    stiffness = stiffness[free][:, free]
    mass = mass[free][:, free]
    values = sparse_linalg.eigsh(stiffness, k=count, M=mass, sigma=0.0,
                                 which="LM", return_eigenvectors=False)
    return np.sqrt(np.sort(values))
