"""What the release's energy allows the lower contact (docs/model.md,
"The energy bound on y3").

The released upper contact holds the strain energy of its static shape,
U = y_s^2 / (2 G1(a)), G1(a) = G(xi) L1^3 / (E1 I1) its static flexibility
at the load point a (the tip for a tip-released cantilever, else x1).
No later motion of any member can hold more: the impact only moves
energy between the members (restitution e <= 1 removes some).  A
displacement y of the lower contact at its contact point x3 stores at
least y^2 / (2 G3(x3)) (the static shape under a point load is the
displacement of least strain energy), so every physically consistent
model obeys

    |y3| <= y_s sqrt(G3(x3) / G1(a)).

Eq. 23 in its impulse form (``lower_response="impulse"``) obeys it: the
lower contact receives the energy psi^2 S3 / 2, psi = (1+e) V /
(S1 + S2 + S3), S_i = sum_j X_ij^2 / M_i, which is at most
(1+e)^2 S1 S3 / (S1 + S2 + S3)^2 <= (1+e)^2/4 <= 1 times the upper
contact's least kinetic energy V^2 / (2 S1) at the impact speed V, itself
at most U; and the N-mode response stores at least y^2 / (2 G3N),
G3N = sum_j X3j^2 / (M3 p3j^2) <= G3.  The form as printed (v0/L3) need
not (the thesis's small steel relay: 0.026 in from a 0.02 in release of
an identical spring).
"""

from __future__ import annotations

import warnings

import numpy as np

from contactsep import beams
from contactsep.errors import ContactsepWarning


class EnergyBoundWarning(ContactsepWarning):
    """An eq. 23 y3_max beyond what the release's energy allows."""


def _flexibility(end, length, width, thick, modulus, xi):
    """Static flexibility (in/lb) of a member at xi = a / L."""
    inertia = np.asarray(width) * np.asarray(thick) ** 3 / 12.0
    shape = np.vectorize(lambda e, x: float(beams.static_flexibility(
        str(e), x)))(end, xi)
    return shape * np.asarray(length) ** 3 / (np.asarray(modulus) * inertia)


def y3_energy_bound(design, shapes=None) -> np.ndarray:
    """The largest |y3| (in) at x3 that the release's strain energy
    allows (module doc): y_s sqrt(G3(x3) / G1(a)), for a design or a
    batch (an array of the design's shape).  ``shapes``: the members'
    dimensionless flexibilities (G1(a), G3(x3)), arrays of the batch's
    shape, where the beam physics is not the thesis's (shear, springs:
    contactsep.model.given); None: the thesis's closed forms."""
    d = design
    if shapes is not None:
        g1, g3 = (np.asarray(g, dtype=float) * np.asarray(length) ** 3 / (
            np.asarray(modulus) * np.asarray(width)
            * np.asarray(thick) ** 3 / 12.0)
            for g, length, width, thick, modulus in (
                (shapes[0], d.L1, d.b1, d.h1, d.E1),
                (shapes[1], d.L3, d.b3, d.h3, d.E3)))
        return np.abs(np.asarray(d.ys, dtype=float)) * np.sqrt(g3 / g1)
    length1 = np.asarray(d.L1, dtype=float)
    x1 = length1 if d.x1 is None else np.asarray(d.x1, dtype=float)
    tip = (np.asarray(d.end1) == "clamped-free") & (d.release == "tip")
    xi1 = np.where(tip, 1.0, x1 / length1)
    length3 = np.asarray(d.L3, dtype=float)
    x3 = length3 if d.x3 is None else np.asarray(d.x3, dtype=float)
    g1 = _flexibility(d.end1, d.L1, d.b1, d.h1, d.E1, xi1)
    g3 = _flexibility(d.end3, d.L3, d.b3, d.h3, d.E3, x3 / length3)
    return np.abs(np.asarray(d.ys, dtype=float)) * np.sqrt(g3 / g1)


def exceeds_energy_bound(design, y3_max, shapes=None) -> np.ndarray:
    """Where ``y3_max`` (in) exceeds :func:`y3_energy_bound` (by more
    than round-off, 1e-9 relative); ``shapes`` as there."""
    with np.errstate(invalid="ignore"):
        return np.asarray(y3_max) > y3_energy_bound(design, shapes) * (
            1.0 + 1e-9)


def warn_if_beyond(design, y3_max, status, stacklevel=3,
                   shapes=None) -> None:
    """One :class:`EnergyBoundWarning` when a design with status 0 has a
    y3_max beyond :func:`y3_energy_bound` (a batch: how many); ``shapes``
    as there."""
    ok = np.asarray(status) == 0
    beyond = exceeds_energy_bound(design, y3_max, shapes) & ok
    if not np.any(beyond):
        return
    form = np.asarray(design.lower_response).item() \
        if np.ndim(design.lower_response) == 0 else "mixed"
    why = (f"what the release's strain energy allows (y_s sqrt(G3(x3)/"
           f"G1), docs/model.md); lower_response {form!r}"
           + (" (v0/L3, the listing's) is not energy-consistent: "
              "'impulse' is" if form == "as-printed" else ""))
    if np.ndim(beyond) == 0:
        message = (f"y3_max {float(y3_max):.4g} in exceeds "
                   f"{float(y3_energy_bound(design, shapes)):.4g} in, "
                   f"{why}")
    else:
        message = (f"y3_max of {int(np.sum(beyond)):,} of {beyond.size:,} "
                   f"designs exceeds {why}")
    warnings.warn(message, EnergyBoundWarning, stacklevel=stacklevel)
