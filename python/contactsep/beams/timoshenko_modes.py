"""The normal modes of the general beam
(:class:`~contactsep.beams.timoshenko.Beam`): each mode's state along the
beam from the null vector of the multiple-shooting system at its
eigenvalue (:mod:`~contactsep.beams.timoshenko`), normalised by
quadrature.

Normalisation (the package's convention, int X^2 dx = L, with the whole
mass): int_0^1 (X_i X_j + r2 Psi_i Psi_j) dxi + sum_m mu_m X_i X_j(xi_m)
= delta_ij, X = w/L and Psi = L psi per unit modal coordinate (so that
the generalised mass of every mode is the bare beam's mass rho A L, and
Psi = dX/dxi for Bernoulli-Euler).  Sign: the left end's moment (clamped
end) or rotation (pinned end) is positive, as the closed-form modes'.
"""

from __future__ import annotations

import numpy as np

from contactsep.beams.timoshenko import (ENDS, Beam, assemble, eigenvalues,
                                         expm, mesh, state_scale,
                                         system_matrix)


def _gauss(points: int):
    x, w = np.polynomial.legendre.leggauss(points)
    return 0.5 * (x + 1.0), 0.5 * w


def _states(beam: Beam, nodes, b, node_states, xi):
    """Unscaled states (n_modes, len(xi), 4) at the points xi."""
    scale = state_scale(b)
    a = system_matrix(beam, b, scale)
    seg = np.clip(np.searchsorted(nodes, xi, side="right") - 1, 0,
                  len(nodes) - 2)
    offset = xi - nodes[seg]
    t = expm(a[:, None] * offset[None, :, None, None])
    z = np.einsum("mpij,mpj->mpi", t, node_states[:, seg, :])
    return z * (scale[:, None, None] ** np.arange(4))


def _null_vectors(matrix):
    """The null vector of each matrix at a root (its last right singular
    vector: K is not symmetric, and inverse iteration may start on a
    vector its left null vector is orthogonal to)."""
    return np.linalg.svd(matrix)[2][:, -1, :]


def modes(beam: Beam, n: int, xi=(), b=None):
    """b_j (n,), with X_j(xi) and Psi_j(xi) (n, len(xi)) normalised as
    the module docstring says; ``b``: the eigenvalues when already known
    (``eigenvalues(beam, n)``, the costly part)."""
    xi = np.atleast_1d(np.asarray(xi, dtype=np.float64))
    if np.any(~np.isfinite(xi)) or np.any((xi < 0.0) | (xi > 1.0)):
        raise ValueError("xi must lie in [0, 1]")
    b = eigenvalues(beam, n) if b is None else np.array(b, dtype=float)
    nodes = mesh(beam, float(b[-1]))
    matrix = assemble(beam, nodes, b)
    node_states = _null_vectors(matrix).reshape(n, len(nodes), 4)
    # quadrature: Gauss panels short enough for the fastest wave
    wave = np.sqrt(b[-1] + b[-1]**2 * (beam.r2 + beam.s2))
    panels = []
    for lo, hi in zip(nodes[:-1], nodes[1:]):
        count = max(1, int(np.ceil(wave * (hi - lo) / 2.0)))
        panels.extend(zip(lo + (hi - lo) * np.arange(count) / count,
                          lo + (hi - lo) * np.arange(1, count + 1) / count))
    gx, gw = _gauss(20)
    lo = np.array([p[0] for p in panels])
    width = np.array([p[1] - p[0] for p in panels])
    qx = (lo[:, None] + width[:, None] * gx[None, :]).ravel()
    qw = (width[:, None] * gw[None, :]).ravel()
    z = _states(beam, nodes, b, node_states, qx)
    norm = np.einsum("p,mp->m", qw, z[..., 0]**2 + beam.r2 * z[..., 1]**2)
    if beam.masses:
        where = np.array([m[0] for m in beam.masses])
        mu = np.array([m[1] for m in beam.masses])
        at = _states(beam, nodes, b, node_states, where)[..., 0]
        norm += np.einsum("m,jm->j", mu, at**2)
    edge = _states(beam, nodes, b, node_states, np.array([0.0]))[:, 0, :]
    lead = edge[:, 2] if ENDS[beam.end][0] == "clamped" else edge[:, 1]
    factor = np.where(lead < 0.0, -1.0, 1.0) / np.sqrt(norm)
    z = _states(beam, nodes, b, node_states, xi) * factor[:, None, None]
    return b, z[..., 0], z[..., 1]
