"""An independent NumPy float64 model of the thesis, written from its equations.

This module is a second implementation of what Appendix G computes, written
from Chapter III and Appendices A-E of the thesis, *not* translated from the
listing, so that agreement between the two means something.  Everything is
float64 and vectorised over the modes (axis 0) and the time (axis 1).

Equation numbers are the thesis's: "III-(20)" is equation (20) of Chapter
III, "A-(7)" is equation (7) of Appendix A.  Units are the listing's (inches,
seconds, pounds; RHO in lb/ft^3, E in psi); signs are the listing's: the
upper contact starts at +y_s and falls toward the separator at DELY, so the
impact velocity and the impulse are negative and the separator and the lower
contact move in the negative direction.

What is computed (``run``)
--------------------------
* Masses M_i = gamma_i A_i L_i / g, gamma_i = RHO_i/1728 lb/in^3,
  g = 386.4 in/s^2 (Appendix B: g/(gamma A L) = 1/M); flexural constants
  a_i = sqrt(E I_i g / (A_i gamma_i)) (III-(1)); frequencies
  p_j = (k_jL)^2 a / L^2 (k = sqrt(p/a)) for the three members.
* Initial amplitudes A_j = (1/L) int_0^L f(x) X_j(x) dx, A-(7), with the
  static tip-load curve f(x) = (3 y_s/L^3)(L x^2/2 - x^3/6).  Closed form
  (derivation below) or Gauss-Legendre quadrature.
* First impact: the first t_1 > 0 at which y(L,t) = sum A_j X_j(L) cos p_j t
  (III-(3)) falls to DELY, bracketed on a grid of 1/32 of the shortest
  period (local minima between grid points are found from the velocity,
  III-(4), so a crossing that dips below DELY between two samples is not
  missed) and bisected to adjacent doubles.
* Impulse psi, III-(20):  psi = (1+e) v / (sum X_j1(L)^2/M1
  + sum X_j2(L/2)^2/M2 + sum X_j3(L)^2/M3).
* Upper contact after impact, E-(3), E-(4): A_j1 = A_j cos p_j t1,
  B_j1 = -A_j sin p_j t1; tip displacement and velocity at t = 0+ from
  E-(5) (III-(8), III-(9)): y = sum A_j1 X_j(L),
  ydot = sum p_j X_j(L) [B_j1 - psi X_j(L)/(M1 p_j)].
* Separator mid-span velocity, III-(12) at x = L/2, t = 0+:
  v0 = (psi/M2) sum X_j2(L/2)^2.
* Lower contact tip, III-(13) (equivalently IV-(21)):
  y3(L3,t) = sum (v0/L3) X_j3(L3)^2/p_j3 sin p_j3 t, on the listing's grid
  t_i = i DELT (i = 0, 1, ... while t_i < 0.060), and its extreme value:
  the largest abs(y3) over [t_0, t_last] of that grid, located by bisecting the
  velocity III-(14) between grid points (not the grid maximum).
* Closing ratios: GR = h2/L2, BETA = M1/(M2' + M3), MR1 = M2'/M1,
  MR3 = M2'/M3, M2' the separator mass as used at that point.

The closed form of A_j
----------------------
Every term of the mode function X(xi) = cosh v xi - cos v xi
- alpha (sinh v xi - sin v xi) (xi = x/L, v = k_jL) satisfies
X'''' = v^4 X for *any* alpha, so with f(xi) = (y_s/2)(3 xi^2 - xi^3),
f'''' = 0, four integrations by parts give, exactly,

    A_j = int_0^1 f X dxi = (1/v^4) [f X''' - f' X'' + f'' X' - f''' X]_0^1
        = y_s [ 3 X(1)/v^4 - (3/2) X~''(1)/v^2 + X~'''(1)/v ],

(X = v^n X~^(n); at xi = 0 the terms vanish because f(0) = f'(0) = 0 and
X(0) = X'(0) = 0 for any alpha; at xi = 1, f = y_s, f' = 3y_s/2, f'' = 0,
f''' = -3 y_s.)  For a mode that satisfies the free-end conditions
X''(L) = X'''(L) = 0 this is A_j = 3 y_s X_j(L)/(k_jL)^4, which needs
neither alpha nor any hyperbolic function (option ``"exact-mode"``).  The
two remaining boundary values are what the deck's rounded alpha leaves
over; they are kept, so ``"closed-form"`` is the exact integral of the
deck's own mode function, the integral the listing evaluates with its
D1..D8.  The cancellation is avoided by writing, with beta = 1 - alpha
(exact in floating point for 1/2 <= alpha <= 2),

    X(1)     =  e^{-v} + beta sinh v - cos v + alpha sin v,
    X~''(1)  =  e^{-v} + beta sinh v + cos v - alpha sin v,
    X~'''(1) = -e^{-v} + beta cosh v - sin v - alpha cos v,

in which no term is larger than max(1, abs(beta) cosh v): the absolute error is
a few ulps of 1/v, against A_j ~ 6 y_s/v^4, i.e. ~eps v^3 relative
(measured: <= 4e-13 for modes 1-10, against 0.38 for the D1..D8 form in
float64 at mode 10).

What the deck's alpha can carry.  The deck's mode function differs from the
exact one by delta alpha (sinh - sin); the integral weights the tip, so
A_j moves by about y_s delta_alpha e^v/(2v), relative
delta_alpha e^v v^3/12.  With alpha rounded to double (delta ~ 1e-16) that
is 7e-10 at mode 4, 8e-4 at mode 8 and 0.2 at mode 10; with alpha given to
9 decimals, as in the thesis decks, it is 4e-5 at mode 3 and 1.4e-3 at
mode 4.  The listing and ``"closed-form"``
integrate that function faithfully; ``"exact-mode"`` gives the A_j of the
exact mode from V and C alone.

Defaults: the listing's algorithm choices
-----------------------------------------
``run`` reproduces the listing's choices by default, so that it can be
compared with it number for number; where the listing departs from the
thesis, the thesis's version is a named option.

(a) ``impact_velocity="listing"``: the velocity in the impulse is the
    listing's ACT = sum_j -p_j A_j X_j(L), without sin p_j t1 (the sum of
    the modal velocity amplitudes).  ``"thesis"``: III-(19)/(20) and E-(9)
    use sum_j p_j B_j X_j(L) with B_j = B_j1 = -A_j sin p_j t1, the actual
    tip velocity at impact.  The two agree only if every sin p_j t1 = 1
    (e.g. N = 1 and DELY = 0).
(b) ``separator_mass="listing"``: the impulse uses the separator mass M2 of
    length L2, but the separator velocity and the closing ratios use
    M2 L2c/L2 (the listing's WM2 = WM2*(XL2C/XL2), the Table III equivalent
    length, applied between the two).  ``"equivalent"``: the Table III
    equivalent beam of length L2c everywhere (mass M2 L2c/L2 in the impulse,
    the velocity and the ratios; p2 with L2c), the correction of Chapter VI
    applied consistently.  ``"nominal"``: the beam of length L2 everywhere
    (Chapter III as derived, no correction).  Only the two consistent
    choices conserve energy for e = 1 (the energy balance of Chapter III-D
    uses one M2 throughout).
(c) p2 is computed with L2 (the listing's P2, printed but not used), except
    under ``separator_mass="equivalent"``.
(d) All sums run over the deck's N modes with the deck's constants: V
    (k_jL), C (X_j(L) or X_j(L/2)) and ALPHA; alpha enters only the A_j
    integral.  CT, CT2, CT3 = sum C^2, sum C2^2, sum C3^2.

Further differences from the listing, not options:

* t_impact is the crossing itself (to adjacent doubles); the listing's T is
  its last step-halving point above DELY, within about 1e-8 s of it, and its
  stepping can step over a crossing that dips below DELY between two DELT
  steps.
* The history grid is i*DELT (multiplication); the listing accumulates
  T = T + DELT, so the two grids drift apart by rounding and can differ by
  one point at the end.
* extreme_ty3/extreme_time are the true extremum (velocity root), not the
  largest printed sample.

Things in the thesis worth knowing (documented, not changed)
------------------------------------------------------------
* III-(13)/D-(5) come from ydot(x,0) = v0 delta(x - L), in which v0 has the
  units of velocity times length; the thesis then sets v0 to the separator
  velocity (in/s), so y3 = v0/L3 sum X^2/p sin pt is dimensionally a pure
  number read as inches and scales with the unit of L3.  The listing does
  the same; so does this model.
* sum_j X_j1(L)^2 = 4N grows without bound with N (a point impulse on a
  continuous beam), so psi -> 0 as N grows; v0 and y3, ratios of two such
  sums, converge.
"""

from __future__ import annotations

import math
import types
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from contactsep.constants import (
    CUBIC_INCHES_PER_CUBIC_FOOT,
    GRAVITY_IN_PER_S2,
    LISTING_TAU_S,
)
from contactsep.restored.dataset import DataSet
# the amplitudes and the first-impact search are the twin's own
# procedures, public here (__all__) as the reference's API
from contactsep.restored.reference_amplitudes import (
    AMPLITUDE_METHODS,
    _choice,
    initial_amplitudes,
    mode_values,
)
from contactsep.restored.reference_search import (
    _SAMPLES_PER_PERIOD,
    _as_output,
    _bisect,
    _cos_sum,
    _sin_sum,
    first_impact,
)

__all__ = [
    "G", "IN3_PER_FT3", "TAU", "AMPLITUDE_METHODS", "IMPACT_VELOCITIES",
    "SEPARATOR_MASSES", "ReferenceResult", "masses", "flexural_constants",
    "frequencies", "mode_values", "initial_amplitudes", "first_impact",
    "tip_displacement", "tip_velocity", "lower_tip_displacement",
    "lower_tip_velocity", "history_grid", "run",
]

#: Acceleration due to gravity used by the listing, in/s^2.
G = GRAVITY_IN_PER_S2
#: Cubic inches per cubic foot (RHO lb/ft^3 -> gamma lb/in^3).
IN3_PER_FT3 = CUBIC_INCHES_PER_CUBIC_FOOT
#: End of the lower-contact history (the listing's TAU), s.
TAU = LISTING_TAU_S

#: ``impact_velocity=`` choices of :func:`run`.
IMPACT_VELOCITIES = ("listing", "thesis")
#: ``separator_mass=`` choices of :func:`run`.
SEPARATOR_MASSES = ("listing", "equivalent", "nominal")


def _frozen(values) -> np.ndarray:
    arr = np.array(values, dtype=np.float64, copy=True)
    arr.setflags(write=False)
    return arr


# ---------------------------------------------------------------------------
# Members: masses, flexural constants, frequencies
# ---------------------------------------------------------------------------

def _member(ds: DataSet, i: int) -> tuple[float, float, float, float]:
    """(L, b, h, RHO) of member i = 1 (upper), 2 (separator), 3 (lower)."""
    if i == 1:
        return ds.xl, ds.b, ds.h, ds.rho
    if i == 2:
        return ds.xl2, ds.b2, ds.h2, ds.rho2
    return ds.xl3, ds.b3, ds.h3, ds.rho3


def masses(ds: DataSet) -> tuple[float, float, float]:
    """M_i = gamma_i A_i L_i / g of the three members (nominal lengths),
    lb s^2/in (Appendix B: g/(gamma A L) = 1/M)."""
    out = []
    for i in (1, 2, 3):
        length, b, h, rho = _member(ds, i)
        out.append((rho / IN3_PER_FT3) * (b * h) * length / G)
    return tuple(out)


def flexural_constants(ds: DataSet) -> tuple[float, float, float]:
    """a_i = sqrt(E I_i g / (A_i gamma_i)) (III-(1)), in^2/s; the listing's
    W, W2, W3.  With I = b h^3/12 and A = b h this is h sqrt(E g/(12 gamma))."""
    out = []
    for i in (1, 2, 3):
        _, b, h, rho = _member(ds, i)
        gamma = rho / IN3_PER_FT3
        area, inertia = b * h, b * h**3 / 12.0
        out.append(math.sqrt(ds.e * inertia * G / (area * gamma)))
    return tuple(out)


def frequencies(ds: DataSet, separator_length: float | None = None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """p_j = (k_jL)^2 a / L^2, rad/s, of the upper contact, the separator
    and the lower contact, from the deck's V, V2, V3.

    ``separator_length`` replaces L2 in p2 (e.g. the equivalent length L2c).
    """
    a1, a2, a3 = flexural_constants(ds)
    l2 = ds.xl2 if separator_length is None else separator_length
    v, v2, v3 = (np.asarray(x, dtype=np.float64) for x in (ds.v, ds.v2, ds.v3))
    return v**2 * a1 / ds.xl**2, v2**2 * a2 / l2**2, v3**2 * a3 / ds.xl3**2


# ---------------------------------------------------------------------------
# The result
# ---------------------------------------------------------------------------

@dataclass(frozen=True, eq=False)
class ReferenceResult:
    """What :func:`run` computes for one data set.

    Names shared with :class:`contactsep.restored.result.Result` mean the same
    quantity as the listing prints it (under the default options).
    """

    #: The data set.
    inputs: DataSet
    #: The options used: amplitudes, impact_velocity, separator_mass.
    options: Mapping[str, str]
    #: Flexural constants a_i (the listing's W, W2, W3), in^2/s.
    w: float
    w2: float
    w3: float
    #: Frequencies p_j of the upper contact, separator, lower contact, rad/s.
    p: np.ndarray
    p2: np.ndarray
    p3: np.ndarray
    #: Initial amplitudes A_j (APE), in.
    ape: np.ndarray
    #: Time of the first impact t_1, s.
    t_impact: float
    #: Actual tip velocity just before impact, sum p_j B_j1 X_j(L), in/s
    #: (the listing's ACT printed after the impact, statement 315).
    impact_velocity: float
    #: The velocity used in the impulse (listing: sum -p_j A_j X_j(L)).
    impulse_velocity: float
    #: Impulse psi, III-(20), lb s.
    ey: float
    #: sum X_j1(L)^2, sum X_j2(L/2)^2, sum X_j3(L3)^2 over the deck's modes.
    ct: float
    ct2: float
    ct3: float
    #: A_j1, B_j1 after the first impact, E-(3), E-(4), in.
    a1: np.ndarray
    b1: np.ndarray
    #: Upper tip displacement and velocity at t = 0+ after the impact.
    tip_ty: float
    tip_tydtl: float
    #: Separator mid-span velocity v0, III-(12), in/s (TY2DT).
    ty2dt: float
    #: Lower-contact tip history y3(L3, t), III-(13): times and values.
    history_t: np.ndarray
    history_ty3: np.ndarray
    #: Largest-|y3| value over [history_t[0], history_t[-1]] and its time.
    extreme_ty3: float
    extreme_time: float
    #: Masses, lb s^2/in: upper, separator as in the closing ratios, lower.
    wm: float
    wm2: float
    wm3: float
    #: Separator mass in the impulse denominator and in v0.
    wm2_impulse: float
    wm2_velocity: float
    #: Closing ratios GR = h2/L2, BETA = M1/(M2'+M3), MR1 = M2'/M1,
    #: MR3 = M2'/M3.
    gr: float
    beta: float
    mr1: float
    mr3: float


def history_grid(delt: float, tau: float = TAU) -> np.ndarray:
    """The listing's lower-contact grid: t_i = i*DELT for i = 0, 1, ...
    while t_i < tau (built by multiplication, not accumulation)."""
    if not delt > 0.0:
        raise ValueError(f"DELT must be positive, got {delt!r}")
    count = int(math.ceil(tau / delt)) + 1 if tau > 0.0 else 0
    t = np.arange(count, dtype=np.float64) * delt
    return t[t < tau]


def _lower_coefficients(res: ReferenceResult) -> tuple[np.ndarray, np.ndarray]:
    """III-(13): y3 = sum coef_j sin p3_j t; returns (coef, p3)."""
    ds = res.inputs
    c3 = np.asarray(ds.c3, dtype=np.float64)
    return res.ty2dt * c3**2 / (ds.xl3 * res.p3), res.p3


def lower_tip_displacement(res: ReferenceResult, t):
    """y3(L3, t) = sum (v0/L3) X_j3(L3)^2 / p_j3 sin p_j3 t, III-(13)."""
    coef, p3 = _lower_coefficients(res)
    return _as_output(_sin_sum(coef, p3, t), t)


def lower_tip_velocity(res: ReferenceResult, t):
    """dy3/dt (L3, t) = sum (v0/L3) X_j3(L3)^2 cos p_j3 t, III-(14)."""
    coef, p3 = _lower_coefficients(res)
    return _as_output(_cos_sum(coef * p3, p3, t), t)


def _upper_modes(obj, amplitudes: str) -> tuple[np.ndarray, np.ndarray,
                                                  np.ndarray]:
    if isinstance(obj, ReferenceResult):
        return obj.ape, obj.p, np.asarray(obj.inputs.c, dtype=np.float64)
    if isinstance(obj, DataSet):
        p = frequencies(obj)[0]
        return (initial_amplitudes(obj, amplitudes), p,
                np.asarray(obj.c, dtype=np.float64))
    raise TypeError(f"expected a DataSet or ReferenceResult, got {type(obj)}")


def tip_displacement(obj, t, *, amplitudes: str = "closed-form"):
    """Upper tip before impact, y(L,t) = sum A_j X_j(L) cos p_j t, III-(3).

    ``obj`` is a DataSet (A_j by ``amplitudes``) or a ReferenceResult (its
    own A_j).  X_j(L) is the deck's C.  Scalar t gives a float.
    """
    ape, p, c = _upper_modes(obj, amplitudes)
    return _as_output(_cos_sum(ape * c, p, t), t)


def tip_velocity(obj, t, *, amplitudes: str = "closed-form"):
    """Upper tip velocity before impact, sum -p_j A_j X_j(L) sin p_j t,
    III-(4)."""
    ape, p, c = _upper_modes(obj, amplitudes)
    return _as_output(_sin_sum(-p * ape * c, p, t), t)


def _extreme(res: ReferenceResult) -> tuple[float, float]:
    """Largest |y3| over the history's span: velocity roots and the ends."""
    t_grid = res.history_t
    if t_grid.size == 0:
        return float("nan"), float("nan")
    t0, t1 = float(t_grid[0]), float(t_grid[-1])
    candidates = [np.array([t0, t1])]
    p3 = res.p3
    if t1 > t0 and p3.size and np.all(p3 > 0.0):
        step = 2.0 * math.pi / float(np.max(p3)) / _SAMPLES_PER_PERIOD
        count = int(math.ceil((t1 - t0) / step))
        t = t0 + (t1 - t0) * np.arange(count + 1) / count
        vel = lambda s: lower_tip_velocity(res, s)   # noqa: E731
        v = vel(t)
        k = np.nonzero((v[:-1] > 0.0) != (v[1:] > 0.0))[0]
        candidates.append(_bisect(vel, t[k], t[k + 1]))
    t_all = np.concatenate(candidates)
    y_all = lower_tip_displacement(res, t_all)
    i = int(np.argmax(np.abs(y_all)))
    return float(y_all[i]), float(t_all[i])


# ---------------------------------------------------------------------------
# The run
# ---------------------------------------------------------------------------

def run(data_set: DataSet, *, amplitudes: str = "closed-form",
        impact_velocity: str = "listing", separator_mass: str = "listing",
        tau: float = TAU, history_times=None,
        search_horizon: float | None = None,
        quadrature_panels: int | None = None) -> ReferenceResult:
    """Run the Chapter III model on one data set.

    Options (module docstring for the full story):

    ``amplitudes``
        ``"closed-form"`` (default), ``"quadrature"``, ``"exact-mode"``: how
        A_j of A-(7) is evaluated (:func:`initial_amplitudes`).
    ``impact_velocity``
        ``"listing"`` (default): the impulse uses ACT = sum -p_j A_j X_j(L),
        the listing's quirk (no sin p_j t1).  ``"thesis"``: III-(20) with
        the actual tip velocity at impact, sum p_j B_j1 X_j(L).
    ``separator_mass``
        ``"listing"`` (default): M2 (length L2) in the impulse, M2 L2c/L2 in
        the separator velocity and the closing ratios, p2 with L2.
        ``"equivalent"``: the Table III equivalent beam (length L2c) for all
        of them.  ``"nominal"``: length L2 for all of them.
    ``tau``, ``history_times``
        The lower-contact history is evaluated at ``history_times`` if given,
        else on :func:`history_grid` (DELT, tau).
    ``search_horizon``
        Longest time searched for the first impact (default four periods of
        the upper contact's first mode).
    ``quadrature_panels``
        Panels of the Gauss-Legendre rule for ``amplitudes="quadrature"``.
    """
    ds = data_set
    _choice("amplitudes", amplitudes, AMPLITUDE_METHODS)
    _choice("impact_velocity", impact_velocity, IMPACT_VELOCITIES)
    _choice("separator_mass", separator_mass, SEPARATOR_MASSES)
    if separator_mass != "nominal" and not ds.xl2c > 0.0:
        raise ValueError(
            f"separator_mass={separator_mass!r} needs XL2C > 0, got {ds.xl2c!r}")

    m1, m2, m3 = masses(ds)
    a1c, a2c, a3c = flexural_constants(ds)
    m2_equiv = m2 * (ds.xl2c / ds.xl2) if separator_mass != "nominal" else m2
    m2_impulse = m2_equiv if separator_mass == "equivalent" else m2
    m2_velocity = m2_equiv          # listing and equivalent: corrected
    m2_ratios = m2_equiv
    p, p2, p3 = frequencies(
        ds, ds.xl2c if separator_mass == "equivalent" else None)

    c, c2, c3 = (np.asarray(x, dtype=np.float64) for x in (ds.c, ds.c2, ds.c3))
    ape = initial_amplitudes(ds, amplitudes, panels=quadrature_panels)

    # first impact, III-(3) = DELY
    t1 = first_impact(ape, p, c, ds.dely, horizon=search_horizon)

    # upper contact at the impact, E-(3) and E-(4)
    a1 = ape * np.cos(p * t1)
    b1 = -ape * np.sin(p * t1)
    v_actual = float(np.sum(p * b1 * c))
    v_impulse = (float(np.sum(-p * ape * c)) if impact_velocity == "listing"
                 else v_actual)

    # impulse, III-(20)
    ct, ct2, ct3 = float(np.sum(c**2)), float(np.sum(c2**2)), \
        float(np.sum(c3**2))
    psi = (1.0 + ds.er) * v_impulse / (ct / m1 + ct2 / m2_impulse + ct3 / m3)

    # upper tip at t = 0+ after impact, E-(5) (III-(8), III-(9)) at t = 0
    tip_ty = float(np.sum(a1 * c))
    tip_tydtl = float(np.sum(p * c * (b1 - psi * c / (m1 * p))))

    # separator mid-span velocity, III-(12) at x = L/2, t = 0+
    v0 = psi / m2_velocity * ct2

    t_hist = (history_grid(ds.delt, tau) if history_times is None
              else np.asarray(history_times, dtype=np.float64).reshape(-1))

    res = ReferenceResult(
        inputs=ds,
        options=types.MappingProxyType(dict(
            amplitudes=amplitudes, impact_velocity=impact_velocity,
            separator_mass=separator_mass)),
        w=a1c, w2=a2c, w3=a3c,
        p=_frozen(p), p2=_frozen(p2), p3=_frozen(p3),
        ape=_frozen(ape), t_impact=t1,
        impact_velocity=v_actual, impulse_velocity=v_impulse, ey=psi,
        ct=ct, ct2=ct2, ct3=ct3, a1=_frozen(a1), b1=_frozen(b1),
        tip_ty=tip_ty, tip_tydtl=tip_tydtl, ty2dt=v0,
        history_t=_frozen(t_hist), history_ty3=_frozen(np.zeros(t_hist.shape)),
        extreme_ty3=float("nan"), extreme_time=float("nan"),
        wm=m1, wm2=m2_ratios, wm3=m3,
        wm2_impulse=m2_impulse, wm2_velocity=m2_velocity,
        gr=ds.h2 / ds.xl2, beta=m1 / (m2_ratios + m3),
        mr1=m2_ratios / m1, mr3=m2_ratios / m3)

    # lower contact, III-(13), and its extreme value (velocity III-(14))
    y3 = np.asarray(lower_tip_displacement(res, t_hist), dtype=np.float64)
    object.__setattr__(res, "history_ty3", _frozen(y3.reshape(t_hist.shape)))
    extreme, t_extreme = _extreme(res)
    object.__setattr__(res, "extreme_ty3", extreme)
    object.__setattr__(res, "extreme_time", t_extreme)
    return res
