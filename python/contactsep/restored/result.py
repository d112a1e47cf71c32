"""What the restored core returns for one data set: every printed quantity."""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass

import numpy as np

from contactsep.constants import LISTING_TAU_S
from contactsep.restored.dataset import DataSet


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


@dataclass(frozen=True, eq=False)
class Result:
    """Every quantity the Appendix G listing prints for one data set.

    Names follow the listing (lower-cased); arrays are NumPy arrays of the
    build's precision (float32 for ``"single"``, float64 for ``"double"``).
    Units: inch, pound (force), second.

    Attributes
    ----------
    inputs : DataSet
        The data set that was run.
    precision : str
        ``"single"`` (the listing's REAL) or ``"double"``.
    p : ndarray
        Upper-contact natural frequencies P(I), rad/s.
    ape : ndarray
        Initial modal amplitudes APE(I) (the D1-D8 integrals), in.
    trace_t, trace_ty, trace_tydtl : ndarray
        Impact-search trace, one entry per printed line: time T (s), tip
        displacement TY (in), tip velocity TYDTL (in/s).
    t_impact : float
        Time of the first impact T (last point of the search above DELY), s.
    ey : float
        Impulse EY (the listing's psi, eq. 20 with its ACT), lb s.
    ct, ct2, ct3 : float
        Sums of squared mode values: upper tip, separator mid-span, lower
        tip (dimensionless), used in the impulse.
    a1, b1 : ndarray
        Post-impact coefficients A1(I), B1(I,1) of the upper contact, in.
    tip_ty, tip_tydtl, tip_act : float
        Upper-contact tip state at line 315 (T = 0 after impact):
        displacement (in), velocity (in/s), ACT = sum P*B1*C (in/s).
    ty2dt : float
        Separator mid-span velocity TY2DT after impact, in/s.
    history_t, history_ty3 : ndarray
        Lower-contact tip history for T < ``tau`` (the listing's TAU =
        0.060 s): times (s) and displacements TY3 (in, signed as the
        listing signs them: the kick's direction is the sign of TY2DT).
    p2, p3 : ndarray
        Separator and lower-contact frequencies P2(I), P3(I), rad/s.
    wm, wm2, wm3 : float
        Masses WM, WM2 (after the XL2C correction), WM3, lb s^2/in.
    gr, beta, mr1, mr3 : float
        Closing ratios GR = H2/XL2, BETA = WM/(WM2+WM3), MR1 = WM2/WM,
        MR3 = WM2/WM3 (dimensionless).
    listing : str
        This data set's part of the listing, exactly as the program prints.
    tau : float
        End of the history window, s (0.060 unless ``solve(tau=...)``).

    Derived (properties): ``extreme_ty3``/``extreme_time``, the largest
    |TY3| whichever its sign; ``separation_ty3``/``separation_time``, the
    farthest TY3 in the kick's direction (the lower contact's largest
    separation from the separator; eq. 13 lets the contact swing back
    through the separator, and ``extreme_ty3`` then may be that swing).
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
    #: End of the history window (the listing's TAU = 0.060 s), s.
    tau: float = LISTING_TAU_S

    def __repr__(self) -> str:
        return (f"Result(precision={self.precision!r}, n={self.inputs.n}, "
                f"t_impact={self.t_impact:.6g} s, ey={self.ey:.6g} lb s, "
                f"extreme_ty3={self.extreme_ty3:.6g} in at "
                f"{self.extreme_time:.6g} s, "
                f"{self.history_ty3.size} history lines)")

    def to_dict(self) -> dict:
        """Plain Python values (lists, floats, str): ``json.dumps``-able.
        ``inputs`` becomes a dict of the data set's fields."""
        out = {}
        for field in dataclasses.fields(self):
            value = getattr(self, field.name)
            if isinstance(value, DataSet):
                value = {f.name: _plain(getattr(value, f.name))
                         for f in dataclasses.fields(value)}
            out[field.name] = _plain(value)
        return out

    def to_json(self, **kwargs) -> str:
        """:meth:`to_dict` as JSON text (keyword arguments go to
        :func:`json.dumps`)."""
        return json.dumps(self.to_dict(), **kwargs)

    @property
    def tip_velocity_before(self) -> float:
        """Tip velocity at the impact time (the last trace line's TYDTL)."""
        return float(self.trace_tydtl[-1]) if self.trace_tydtl.size else float("nan")

    @property
    def extreme_ty3(self) -> float:
        """Largest-magnitude lower-contact displacement in the history,
        whichever its sign: after the contact has swung back through the
        separator (eq. 13 has nothing there to stop it) this may be that
        swing; :attr:`separation_ty3` is the separation itself."""
        if not self.history_ty3.size:
            return float("nan")
        return float(self.history_ty3[np.argmax(np.abs(self.history_ty3))])

    @property
    def separation_ty3(self) -> float:
        """Signed TY3 (in) farthest in the kick's direction (the sign of
        TY2DT): the lower contact's largest separation from the separator,
        which it leaves in that direction.  Unlike :attr:`extreme_ty3` it
        never reports a swing back through the separator (which eq. 13,
        with no separator in the way, allows).  NaN without a kick."""
        index = self._separation_index()
        return float("nan") if index is None \
            else float(self.history_ty3[index])

    @property
    def separation_time(self) -> float:
        """Time of :attr:`separation_ty3` on the listing's grid, s."""
        index = self._separation_index()
        return float("nan") if index is None else float(self.history_t[index])

    def _separation_index(self):
        if not self.history_ty3.size or not self.ty2dt:
            return None
        return int(np.argmax(np.sign(self.ty2dt) * self.history_ty3))

    @property
    def extreme_time(self) -> float:
        """Time of :attr:`extreme_ty3` on the listing's time grid."""
        if not self.history_ty3.size:
            return float("nan")
        return float(self.history_t[np.argmax(np.abs(self.history_ty3))])
