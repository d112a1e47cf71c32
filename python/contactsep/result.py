"""What the restored core returns for one data set: every printed quantity."""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass

import numpy as np

from contactsep.dataset import DataSet


@dataclass(frozen=True, eq=False, repr=False)
class Result:
    """Every quantity the Appendix G listing prints for one data set.

    Names follow the listing (lower-cased); arrays are NumPy arrays of the
    build's precision (float32 for ``"single"``, float64 for ``"double"``).
    ``to_dict()`` and ``to_json()`` give every field as plain values.

    Attributes
    ----------
    inputs
        The data set that was run.
    precision
        ``"single"`` (the listing's REAL) or ``"double"``.
    p
        Upper-contact natural frequencies P(I), rad/s.
    ape
        Initial modal amplitudes APE(I) (the D1-D8 closed-form integrals),
        in.
    trace_t
        Impact-search trace, one entry per printed line: T, s.
    trace_ty
        Impact-search trace: tip displacement TY, in.
    trace_tydtl
        Impact-search trace: tip velocity TYDTL, in/s.
    t_impact
        Time of the first impact T (the last point of the search above
        DELY), s.
    ey
        Impulse EY (the listing's psi, eq. 20 with its ACT), lb s.
    ct
        CT: sum of squared upper-tip mode values used in the impulse.
    ct2
        CT2: sum of squared separator mid-span mode values.
    ct3
        CT3: sum of squared lower-tip mode values.
    a1
        Post-impact coefficients A1(I), B1(I,1) of the upper contact.
    b1
        Post-impact coefficients B1(I,1) of the upper contact.
    tip_ty
        Upper-contact tip state printed at line 315 (T = 0 after impact):
        displacement TY, velocity TYDTL, and ACT = sum P*B1*C (the tip
        velocity just before impact).
    tip_tydtl
        Its tip velocity TYDTL at T = 0 after impact, in/s.
    tip_act
        ACT = sum P*B1*C: the tip velocity just before impact, in/s.
    ty2dt
        Separator mid-span velocity TY2DT after impact, in/s.
    history_t
        Lower-contact tip history: times T and displacements TY3, up to TAU.
    history_ty3
        Lower-contact tip displacements TY3 at history_t, in.
    p2
        Separator and lower-contact frequencies P2(I), P3(I), rad/s.
    p3
        Lower-contact frequencies P3(I), rad/s.
    wm
        Masses WM, WM2 (after the XL2C correction, as printed), WM3, lb
        s^2/in.
    wm2
        Separator mass WM2 after the XL2C correction (as printed).
    wm3
        Lower-contact mass WM3, lb s^2/in.
    gr
        Closing ratios: GR = H2/XL2, BETA = WM/(WM2+WM3), MR1 = WM2/WM, MR3
        = WM2/WM3.
    beta
        BETA = WM/(WM2+WM3).
    mr1
        MR1 = WM2/WM.
    mr3
        MR3 = WM2/WM3.
    listing
        This data set's part of the listing, exactly as the program prints
        it.
    """

    #: The data set that was run.
    inputs: DataSet
    #: ``"single"`` (the listing's REAL) or ``"double"``.
    precision: str
    #: Upper-contact natural frequencies P(I), rad/s.
    p: np.ndarray
    #: Initial modal amplitudes APE(I) (the D1-D8 closed-form integrals), in.
    ape: np.ndarray
    #: Impact-search trace, one entry per printed line: T, s.
    trace_t: np.ndarray
    #: Impact-search trace: tip displacement TY, in.
    trace_ty: np.ndarray
    #: Impact-search trace: tip velocity TYDTL, in/s.
    trace_tydtl: np.ndarray
    #: Time of the first impact T (the last point of the search above DELY), s.
    t_impact: float
    #: Impulse EY (the listing's psi, eq. 20 with its ACT), lb s.
    ey: float
    #: Sums of squared mode values CT (upper tip), CT2 (separator mid-span),
    #: CT3 (lower tip) used in the impulse.
    ct: float
    ct2: float
    ct3: float
    #: Post-impact coefficients A1(I), B1(I,1) of the upper contact.
    a1: np.ndarray
    b1: np.ndarray
    #: Upper-contact tip state printed at line 315 (T = 0 after impact):
    #: displacement TY, velocity TYDTL, and ACT = sum P*B1*C (the tip
    #: velocity just before impact).
    tip_ty: float
    tip_tydtl: float
    tip_act: float
    #: Separator mid-span velocity TY2DT after impact, in/s.
    ty2dt: float
    #: Lower-contact tip history: times T and displacements TY3, up to TAU.
    history_t: np.ndarray
    history_ty3: np.ndarray
    #: Separator and lower-contact frequencies P2(I), P3(I), rad/s.
    p2: np.ndarray
    p3: np.ndarray
    #: Masses WM, WM2 (after the XL2C correction, as printed), WM3, lb s^2/in.
    wm: float
    wm2: float
    wm3: float
    #: Closing ratios: GR = H2/XL2, BETA = WM/(WM2+WM3), MR1 = WM2/WM,
    #: MR3 = WM2/WM3.
    gr: float
    beta: float
    mr1: float
    mr3: float
    #: This data set's part of the listing, exactly as the program prints it.
    listing: str

    @property
    def tip_velocity_before(self) -> float:
        """Tip velocity at the impact time (the last trace line's TYDTL)."""
        return float(self.trace_tydtl[-1]) if self.trace_tydtl.size else float("nan")

    @property
    def extreme_ty3(self) -> float:
        """Largest-magnitude lower-contact displacement in the history."""
        if not self.history_ty3.size:
            return float("nan")
        return float(self.history_ty3[np.argmax(np.abs(self.history_ty3))])

    @property
    def extreme_time(self) -> float:
        """Time of :attr:`extreme_ty3` on the listing's time grid."""
        if not self.history_ty3.size:
            return float("nan")
        return float(self.history_t[np.argmax(np.abs(self.history_ty3))])

    def __repr__(self) -> str:
        return (f"Result(precision={self.precision!r}, N={self.inputs.n}, "
                f"h2={self.inputs.h2!r}, t_impact={self.t_impact:.6g} s, "
                f"ey={self.ey:.6g} lb s, ty2dt={self.ty2dt:.6g} in/s, "
                f"extreme_ty3={self.extreme_ty3:.6g} in, "
                f"history={self.history_t.size} lines)")

    def to_dict(self, *, listing: bool = False) -> dict:
        """Every field as plain Python values (arrays as lists, the data
        set as a dict of its cards' values); the listing text only when
        ``listing`` is true."""
        out = {}
        for field in dataclasses.fields(self):
            if field.name == "listing" and not listing:
                continue
            value = getattr(self, field.name)
            if field.name == "inputs":
                value = {f.name: _plain(getattr(value, f.name))
                         for f in dataclasses.fields(value)}
            out[field.name] = _plain(value)
        out["extreme_ty3"] = self.extreme_ty3
        out["extreme_time"] = self.extreme_time
        return out

    def to_json(self, *, listing: bool = False, **options) -> str:
        """:meth:`to_dict` as JSON text (``options`` go to json.dumps)."""
        return json.dumps(self.to_dict(listing=listing), **options)


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value
