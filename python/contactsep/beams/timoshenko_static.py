"""The static flexibility of the general beam
(:class:`~contactsep.beams.timoshenko.Beam`): its deflection under a point
load, from the multiple-shooting system of
:mod:`~contactsep.beams.timoshenko` at zero frequency with the load's
jump of the shear force on its right-hand side (shear and supports
included; masses carry no static load).
"""

from __future__ import annotations

import numpy as np

from contactsep.beams.timoshenko import Beam, assemble, mesh


def static_flexibility(beam: Beam, xi) -> np.ndarray:
    """G(xi) = y(a) EI/(F L^3): deflection under a point load F at a =
    xi L (shear and supports included; masses carry no static load)."""
    xi = np.asarray(xi, dtype=np.float64)
    if np.any(~np.isfinite(xi)) or np.any((xi < 0.0) | (xi > 1.0)):
        raise ValueError("xi must lie in [0, 1]")
    plain = Beam(beam.end, 0.0, beam.s2, beam.kr, beam.kt)
    out = np.empty(xi.shape)
    for index, point in np.ndenumerate(xi):
        nodes = mesh(plain, 1.0, extra=(float(point),))
        matrix = assemble(plain, nodes, 0.0)[0]
        rhs = np.zeros(matrix.shape[0])
        at = int(np.flatnonzero(nodes == point)[0])
        if at == 0:
            # on the left support itself: its rows read on the state
            # before the load, Q(0-) = kt w, so Q(0+) - kt w = -F (the
            # row as timoshenko's end rows scaled it); a rigid support
            # does not move
            if plain.kt is None:
                out[index] = 0.0
                continue
            rhs[0] = -1.0 / max(plain.kt, 1.0)
        else:
            rhs[2 + 4 * (at - 1) + 3] = -1.0    # Q(a+) - Q(a-) = -F
        try:
            state = np.linalg.solve(matrix, rhs)
        except np.linalg.LinAlgError:
            raise ValueError(f"{beam}: a mechanism (no static "
                             f"equilibrium)") from None
        out[index] = state[4 * at]
    return out


def static_influence(beam: Beam, xi: float, eta: float) -> float:
    """G(xi, eta) = y(xi) EI/(F L^3): deflection at x = xi L under a point
    load F at a = eta L (shear and supports included; masses carry no
    static load), both points inside (0, 1]; on the diagonal
    :func:`static_flexibility`."""
    xi, eta = float(xi), float(eta)
    if not (0.0 < xi <= 1.0 and 0.0 < eta <= 1.0):
        raise ValueError("xi and eta must lie in (0, 1]")
    plain = Beam(beam.end, 0.0, beam.s2, beam.kr, beam.kt)
    nodes = mesh(plain, 1.0, extra=(xi, eta))
    matrix = assemble(plain, nodes, 0.0)[0]
    rhs = np.zeros(matrix.shape[0])
    load = int(np.flatnonzero(nodes == eta)[0])
    read = int(np.flatnonzero(nodes == xi)[0])
    rhs[2 + 4 * (load - 1) + 3] = -1.0      # Q(a+) - Q(a-) = -F
    try:
        state = np.linalg.solve(matrix, rhs)
    except np.linalg.LinAlgError:
        raise ValueError(f"{beam}: a mechanism (no static "
                         f"equilibrium)") from None
    return float(state[4 * read])
