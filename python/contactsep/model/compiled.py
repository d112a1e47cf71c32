"""The compiled general model (fortran/model/, f2py module ``_model``):
one call evaluates a whole packed batch."""

from __future__ import annotations

import numpy as np

from contactsep.model import _model
from contactsep.model.design import Packed

_KERNEL = _model.model_api


def evaluate_packed(packed: Packed) -> dict:
    """Evaluate a packed batch; returns the contract's dict of arrays."""
    if packed.size == 0:
        # f2py cannot pass zero-length rows: the twin's empty answer
        from contactsep.model import twin
        return twin.evaluate_packed(packed)
    n_max = int(packed.ints[:, 3:].max())
    if packed.modes is None:
        (t1, v_impact, psi, v0, r, y3_max, t_max, y3_min, t_min, at_end,
         max_tied, min_tied, status, m1, m2, m3, p1, p2, p3,
         c3) = _KERNEL.evaluate_batch(max(n_max, 1), packed.real.T,
                                      packed.ints.T, packed.options)
    else:
        # the members' modes given (contactsep.model.given); a design
        # without them gets a count of 0, which the kernel refuses
        modes = packed.modes.rows(0, packed.size, max(n_max, 1))
        ints = np.where(modes.failed[:, None], 0, packed.ints).astype(
            np.int32)
        (t1, v_impact, psi, v0, r, y3_max, t_max, y3_min, t_min, at_end,
         max_tied, min_tied, status, m1, m2, m3, p1, p2, p3,
         c3) = _KERNEL.evaluate_batch_given(
             packed.real.T, ints.T, packed.options,
             np.nan_to_num(modes.b).T, modes.values.T,
             np.nan_to_num(modes.flex))
    return dict(t1=t1, v_impact=v_impact, psi=psi, v0=v0, R=r,
                y3_max=y3_max, t_max=t_max, y3_min=y3_min, t_min=t_min,
                at_window_end=at_end.astype(bool),
                t_max_tied=max_tied.astype(bool),
                t_min_tied=min_tied.astype(bool), status=status,
                M1=m1, M2=m2, M3=m3, p1=p1.T, p2=p2.T, p3=p3.T, c3=c3.T)


def mode_values(end_code: int, n: int, xi) -> tuple[np.ndarray, np.ndarray]:
    """k_jL (n,) and X_j(xi) (n, len(xi)) from the Fortran beam modes."""
    xi = np.atleast_1d(np.asarray(xi, dtype=np.float64))
    return _KERNEL.mode_values(end_code, n, xi)
