"""``evaluate(design)``: the general model on one design or a batch."""

from __future__ import annotations

import dataclasses
import importlib
from dataclasses import dataclass

import numpy as np

from contactsep.errors import InputError
from contactsep.model import status as status_codes
from contactsep.model.design import Design, outside_domain, pack

BACKENDS = ("compiled", "numpy")

_SCALARS = ("t1", "v_impact", "psi", "v0", "R", "y3_max", "t_max",
            "y3_min", "t_min", "at_window_end", "status", "M1", "M2", "M3")
_PER_MODE = ("p1", "p2", "p3", "c3")


@dataclass(frozen=True, repr=False)
class Evaluation:
    """Results of the general model, NumPy arrays of the batch's shape
    (0-d for one design); per-mode arrays add a trailing mode axis.

    Times: ``t1`` from the release; ``t_max``, ``t_min`` and the argument
    of :meth:`y3` from the impact.  Designs whose ``status`` is not 0 have
    NaN results (:data:`contactsep.model.status.MESSAGES` says why).
    """

    t1: np.ndarray
    """First impact time after release (s)."""
    v_impact: np.ndarray
    """Impact speed of the upper contact at x1 (in/s, >= 0)."""
    psi: np.ndarray
    """Impulse of the impact (lb s, >= 0), eqs. 20 and 23."""
    v0: np.ndarray
    """Separator velocity at x2 just after the impact (in/s), eq. 12."""
    R: np.ndarray
    """Mass ratio of eq. 24, (M2/sum X2j^2)/(M3/sum X3j^2)."""
    y3_max: np.ndarray
    """Largest lower-contact displacement away from the separator over
    0 <= t <= tau (in)."""
    t_max: np.ndarray
    """Time of y3_max after the impact (s)."""
    y3_min: np.ndarray
    """Smallest lower-contact displacement (in; negative: through the
    separator's original position)."""
    t_min: np.ndarray
    """Time of y3_min after the impact (s)."""
    at_window_end: np.ndarray
    """True where y3_max sits at t = tau: the window cuts the maximum."""
    status: np.ndarray
    """Per-design status code (0 = ok; see contactsep.model.status)."""
    M1: np.ndarray
    """Upper contact mass (lb s^2/in)."""
    M2: np.ndarray
    """Separator mass used in the impulse (lb s^2/in)."""
    M3: np.ndarray
    """Lower contact mass (lb s^2/in)."""
    p1: np.ndarray
    """Upper contact frequencies (rad/s), trailing mode axis."""
    p2: np.ndarray
    """Separator frequencies (rad/s), trailing mode axis."""
    p3: np.ndarray
    """Lower contact frequencies (rad/s), trailing mode axis."""
    c3: np.ndarray
    """Modal coefficients of y3(x3, t) = sum c3_j sin(p3_j t) (in)."""

    def y3(self, t) -> np.ndarray:
        """Lower-contact displacement at x3 (in) at times ``t`` after the
        impact (s); the result has the batch shape followed by t's shape."""
        t = np.asarray(t, dtype=np.float64)
        c = np.nan_to_num(self.c3)
        p = np.nan_to_num(self.p3)
        phase = p[(..., ) + (None,) * t.ndim] * t
        return np.sum(c[(..., ) + (None,) * t.ndim] * np.sin(phase),
                      axis=-1 - t.ndim)

    def messages(self) -> np.ndarray:
        """The meaning of each design's status, as strings."""
        lookup = np.vectorize(lambda code: status_codes.MESSAGES[int(code)],
                              otypes=[object])
        return lookup(self.status)

    def to_dict(self) -> dict:
        """Plain Python values (lists for batches): JSON-ready."""
        return {f.name: getattr(self, f.name).tolist()
                for f in dataclasses.fields(self)}

    def __repr__(self) -> str:
        shape = self.status.shape
        if shape == ():
            return (f"Evaluation(status={int(self.status)}, "
                    f"psi={float(self.psi):.6g} lb s, "
                    f"v0={float(self.v0):.6g} in/s, "
                    f"y3_max={float(self.y3_max):.6g} in)")
        ok = int(np.sum(self.status == 0))
        return f"Evaluation(shape={shape}, ok={ok}/{self.status.size})"


def _backend(name: str):
    if name not in BACKENDS:
        raise InputError(f"backend: found {name!r}, expected one of "
                         f"{', '.join(BACKENDS)}")
    if name == "numpy":
        return importlib.import_module("contactsep.model.twin")
    try:
        return importlib.import_module("contactsep.model.compiled")
    except ImportError as error:
        raise InputError(f"backend 'compiled': the compiled model is not "
                         f"available ({error}); use backend='numpy'") from None


def evaluate(design: Design, *, backend: str = "compiled") -> Evaluation:
    """Evaluate the general model (eq. 23) on a design or a batch.

    ``backend="compiled"`` runs the Fortran kernel (one call for the whole
    batch); ``"numpy"`` the NumPy twin.  Per-design failures are statuses.
    """
    if not isinstance(design, Design):
        raise InputError(f"design: expected a contactsep.Design, found "
                         f"{type(design).__name__}")
    packed = pack(design)
    out = _refuse_outside_domain(packed,
                                 _backend(backend).evaluate_packed(packed))
    shape = packed.shape
    fields = {}
    for key in _SCALARS:
        fields[key] = np.asarray(out[key]).reshape(shape)
    for key in _PER_MODE:
        value = np.asarray(out[key])
        fields[key] = value.reshape(shape + value.shape[1:])
    return Evaluation(**fields)


def _refuse_outside_domain(packed, out: dict) -> dict:
    """Designs outside the model's domain (the kernel computes them, but
    not to true digits) get status 2 and NaN results, as the kernel gives
    any other invalid design."""
    bad = outside_domain(packed.real, packed.ints) & (
        np.asarray(out["status"]) == status_codes.OK)
    if not np.any(bad):
        return out
    out = dict(out)
    for key, value in out.items():
        value = np.array(value)
        if key == "status":
            value[bad] = status_codes.INVALID_INPUT
        elif value.dtype.kind == "f":
            value[bad] = np.nan
        elif value.dtype.kind == "b":
            value[bad] = False
        out[key] = value
    return out
