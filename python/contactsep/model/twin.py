"""The general model (eq. 23) in NumPy, vectorised over designs.

Written from the thesis's equations (Chapter III, Chapter IV eqs. 21-24,
Appendices A-D); the compiled kernel (fortran/model/) is held against it.
Arrays are (M,) per design and (M, n) per design and mode; modes past a
member's N are masked out (X = 0) and reported as NaN.  No Python loop
runs per design: loops run over modes' end conditions, over refinement
iterations and over search levels, each on the whole batch.  The
extremes' branch and bound is in twin_extremes.py (one level's cells in
twin_extremes_cells.py, the exact phases in twin_extremes_phases.py).

Conventions (docs/model.md): displacements of the upper contact are
positive away from the separator, so it is released at +y_s and strikes
at y1(x1, t1) = gap; the lower contact's y3 is positive away from the
separator; V, psi and v0 are magnitudes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactsep import beams
from contactsep.constants import GRAVITY_IN_PER_S2
from contactsep.model import status
from contactsep.model.design import Packed
from contactsep.model.design_domain import REAL_COLUMNS, invalid_rows
from contactsep.model.twin_extremes import extremes

#: Acceleration of gravity (in/s^2): weight to mass (Appendix B).
GRAVITY = GRAVITY_IN_PER_S2


def member_constants(length, width, thickness, gamma, modulus):
    """Mass M = gamma A L / g and flexural constant a = sqrt(E I g/(A gamma))
    of a uniform beam (III-(1); Appendix B: g/(gamma A L) = 1/M)."""
    area = width * thickness
    inertia = width * thickness**3 / 12.0
    mass = gamma * area * length / GRAVITY
    a = np.sqrt(modulus * inertia * GRAVITY / (area * gamma))
    return mass, a


def mode_table(end_codes, xi, counts, n_max):
    """k_jL and X_j(xi) (M, n_max) per design's end condition; modes past
    the design's count masked (kL NaN, X 0)."""
    m = len(end_codes)
    kl = np.full((m, n_max), np.nan)
    values = np.zeros((m, n_max))
    for code, end in enumerate(beams.END_CONDITIONS, 1):
        rows = np.flatnonzero(end_codes == code)
        if rows.size == 0:
            continue
        table = beams.eigenvalues(end, n_max)
        kl[rows] = table
        xs = np.clip(xi[rows], 0.0, 1.0)
        unique, inverse = np.unique(xs, return_inverse=True)
        values[rows] = beams.mode_shapes(end, n_max, unique).T[inverse]
    live = np.arange(n_max)[None, :] < counts[:, None]
    return np.where(live, kl, np.nan), np.where(live, values, 0.0)


def frequencies(kl, a, length):
    """p_j = (k_jL)^2 a / L^2 (k = sqrt(p/a), III-(1))."""
    return kl**2 * (a / length**2)[:, None]


def release_amplitudes(ys, x_load_values, kl, flexibility):
    """A_j of the static shape under a point load with y(load) = y_s
    (Appendix A, eq. 7, exact modal coefficients of the untruncated shape):
    A_j = y_s X_j(a) / ((k_jL)^4 G(a)); tip-loaded cantilever: 3 y_s X_j(L)
    /(k_jL)^4."""
    with np.errstate(invalid="ignore"):
        amp = ys[:, None] * x_load_values / (kl**4 * flexibility[:, None])
    return np.where(np.isnan(kl), 0.0, amp)


def release_amplitudes_b(ys, x_load_values, b, flexibility):
    """release_amplitudes with the eigenvalues b_j = (k_jL)^2 given:
    A_j = y_s X_j(a) / (b_j^2 G(a)) (the modal coefficients of the static
    shape for any beam physics: docs/model.md)."""
    with np.errstate(invalid="ignore"):
        amp = ys[:, None] * x_load_values / (b**2 * flexibility[:, None])
    return np.where(np.isnan(b), 0.0, amp)


def _sum(c, p, t, func):
    """sum_j c_j func(p_j t) over live modes (p NaN -> term 0)."""
    with np.errstate(invalid="ignore"):
        terms = c * func(np.nan_to_num(p) * t[:, None])
    return terms.sum(axis=1)


def upper_displacement(a_coef, p, t):
    """y1(x1, t) = sum A_j X_j(x1) cos p_j t (III-(3)); a_coef = A_j X_j."""
    return _sum(a_coef, p, t, np.cos)


def upper_velocity(a_coef, p, t):
    """dy1/dt(x1, t) = -sum p_j A_j X_j(x1) sin p_j t (III-(4))."""
    return -_sum(a_coef * np.nan_to_num(p), p, t, np.sin)


def first_impact(a_coef, p, gap, horizon):
    """First t > 0 with y1(x1, t) = gap, and a NO_IMPACT mask.

    Safe steps: with B = sum |A_j X_j| p_j^2 >= |y1''|, the lower bound
    f + f' s - B s^2/2 of f = y1 - gap has no root before its first
    positive one, so stepping to it never passes the first crossing; near
    a simple root the steps converge quadratically.  A last Newton step
    from the left polishes t1.
    """
    pn = np.nan_to_num(p)
    bound = np.sum(np.abs(a_coef) * pn**2, axis=1)
    t = np.zeros(len(gap))
    f = upper_displacement(a_coef, p, t) - gap
    missed = ~(f > 0.0) | ~(bound > 0.0)
    active = ~missed
    for _ in range(100000):
        if not np.any(active):
            break
        rows = np.flatnonzero(active)
        fr = upper_displacement(a_coef[rows], p[rows], t[rows]) - gap[rows]
        dr = upper_velocity(a_coef[rows], p[rows], t[rows])
        b = bound[rows]
        root = np.sqrt(dr * dr + 2.0 * b * np.maximum(fr, 0.0))
        with np.errstate(divide="ignore", invalid="ignore"):
            step = np.where(dr >= 0.0, (dr + root) / b,
                            2.0 * np.maximum(fr, 0.0) / (root - dr))
        done = (fr <= 0.0) | (step <= 1e-13 * np.maximum(t[rows], 1e-3))
        t[rows] = np.where(done, t[rows], t[rows] + step)
        late = t[rows] > horizon[rows]
        missed[rows[late]] = True
        active[rows[done | late]] = False
    fr = upper_displacement(a_coef, p, t) - gap
    dr = upper_velocity(a_coef, p, t)
    with np.errstate(divide="ignore", invalid="ignore"):
        newton = np.where(dr < 0.0, -fr / dr, 0.0)
    t = np.where(missed, np.nan, t + newton)
    return t, missed


def impact_velocity(a_coef, p, t1, listing=False):
    """V = |dy1/dt(x1, t1)|; listing: |sum p_j A_j X_j(x1)| (ACT, no sin)."""
    if listing:
        return np.abs(np.sum(a_coef * np.nan_to_num(p), axis=1))
    return np.abs(upper_velocity(a_coef, p, np.nan_to_num(t1)))


def impulse(e, v, s1, m1, s2, m2, s3, m3):
    """psi = (1+e) V / sum_j [X1j^2/M1 + X2j^2/M2 + X3j^2/M3] (eqs. 20, 23);
    s_i = sum_j X_ij(x_i)^2."""
    return (1.0 + e) * v / (s1 / m1 + s2 / m2 + s3 / m3)


def separator_velocity(psi, s2, m2):
    """v0 = (psi/M2) sum_j X2j(x2)^2 (eq. 12 at the contact point)."""
    return psi * s2 / m2


def lower_coefficients(gain, x3_values, p3):
    """c_j of y3(x3, t) = sum c_j sin p3j t, c_j = gain X3j(x3)^2 / p3j:
    gain v0/L3 as printed (eqs. 13, 23) or psi/M3 (the impulse form)."""
    with np.errstate(invalid="ignore"):
        c = gain[:, None] * x3_values**2 / p3
    return np.where(np.isnan(p3), 0.0, c)


def mass_ratio(m2, s2, m3, s3):
    """R = (M2 / sum X2j(x2)^2) / (M3 / sum X3j(x3)^2) (eq. 24)."""
    return (m2 / s2) / (m3 / s3)


def evaluate_packed(packed: Packed) -> dict:
    """Evaluate a packed batch; returns the contract's dict of arrays.

    The thesis's steps in its order, each on every row at once: the
    members' constants and mode tables, the frequencies, the release
    from the static deflection, the first impact and its impulse
    (eq. 23), the lower contact's response and its extremes.  A row's
    status is the first of these steps that failed it.
    """
    rows = _checked_rows(packed)
    safe, code = rows.safe, rows.code
    impact_option, lower_option, lc_option, release_option = (
        int(v) for v in packed.options)
    masses, consts, xi = _members(safe)
    modes = _modes(packed, rows, xi)
    p1, p2, p3 = _frequencies(safe, modes, consts, lc_option)
    m1, m2, m3 = masses
    m2_psi, m2_v0 = _separator_masses(safe, m2, lc_option)
    amplitudes = _release(rows, modes, xi, release_option)
    x1v, x2v, x3v = modes.values

    a_coef = amplitudes * x1v
    horizon = 2.0 * np.pi / p1[:, 0]
    t1, missed = first_impact(a_coef, p1, safe["gap"], horizon)
    code[missed & (code == status.OK)] = status.NO_IMPACT
    v = impact_velocity(a_coef, p1, t1, listing=impact_option == 1)
    s1, s2, s3 = (np.sum(x**2, axis=1) for x in (x1v, x2v, x3v))
    psi = impulse(safe["e"], v, s1, m1, s2, m2_psi, s3, m3)
    v0 = separator_velocity(psi, s2, m2_v0)
    gain = psi / m3 if lower_option == 1 else v0 / safe["L3"]
    c3 = lower_coefficients(gain, x3v, p3)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = mass_ratio(m2_v0, s2, m3, s3)
    (y_max, t_max, y_min, t_min, at_end, max_tied, min_tied,
     unresolved) = extremes(c3, p3, safe["tau"])
    code[unresolved & (code == status.OK)] = status.UNRESOLVED

    out = dict(t1=t1, v_impact=v, psi=psi, v0=v0, R=r, y3_max=y_max,
               t_max=t_max, y3_min=y_min, t_min=t_min, M1=m1, M2=m2_psi,
               M3=m3)
    return _results(out, code, (at_end, max_tied, min_tied),
                    (("p1", p1), ("p2", p2), ("p3", p3), ("c3", c3)))


@dataclass
class _Rows:
    """A batch's inputs with the invalid rows replaced by ones (their
    results NaN at the end), and every row's status so far."""
    safe: dict
    ends: list
    counts: list
    n_max: int
    code: np.ndarray


def _checked_rows(packed: Packed) -> _Rows:
    real, ints = packed.real, packed.ints
    col = {name: real[:, k] for k, name in enumerate(REAL_COLUMNS)}
    m = packed.size
    counts = [ints[:, 3 + i].astype(np.int64) for i in range(3)]
    n_max = int(max((c.max() for c in counts), default=1)) if m else 1
    code = np.full(m, status.OK, dtype=np.int32)
    bad = invalid_rows(real, ints)
    code[bad] = status.INVALID_INPUT
    safe = {k: np.where(bad, 1.0, v) for k, v in col.items()}
    ends = [np.where(bad, 1, ints[:, i]) for i in range(3)]
    counts = [np.where(bad, 1, c) for c in counts]
    return _Rows(safe, ends, counts, n_max, code)


def _members(safe: dict) -> tuple[list, list, list]:
    """Each member's mass, frequency constant and contact point x/L."""
    masses, consts, xi = [], [], []
    for i in "123":
        mass, a = member_constants(safe["L" + i], safe["b" + i],
                                   safe["h" + i], safe["gamma" + i],
                                   safe["E" + i])
        masses.append(mass)
        consts.append(a)
        xi.append(safe["x" + i] / safe["L" + i])
    return masses, consts, xi


@dataclass
class _Modes:
    """The three members' k_jL and mode values at the contact points;
    ``given``: the batch's given modes (model/given.py) or None, with
    ``b`` their (k_jL)^2 and ``table`` their values, the failed rows'
    replaced by ones."""
    kl: tuple
    values: tuple
    given: object = None
    b: np.ndarray | None = None
    table: np.ndarray | None = None


def _modes(packed: Packed, rows: _Rows, xi: list) -> _Modes:
    if packed.modes is None:
        tables = [mode_table(rows.ends[k], xi[k], rows.counts[k],
                             rows.n_max) for k in range(3)]
        return _Modes(tuple(t[0] for t in tables),
                      tuple(t[1] for t in tables))
    code = rows.code
    given = packed.modes.rows(0, code.size, rows.n_max)
    code[given.failed & (code == status.OK)] = status.INVALID_INPUT
    # b_j = (k_jL)^2 given (model/given.py): kl = sqrt(b_j) only
    # where a closed form needs k_jL; the release uses b_j^2 itself
    # rows without modes computed on ones, their results NaN below
    b_given = np.where(given.failed[:, None, None], 1.0, given.b)
    x_given = np.where(given.failed[:, None, None], 1.0, given.values)
    return _Modes(tuple(np.sqrt(b_given[:, k]) for k in range(3)),
                  tuple(x_given[:, k] for k in range(3)),
                  given, b_given, x_given)


def _frequencies(safe: dict, modes: _Modes, consts: list,
                 lc_option: int) -> tuple:
    """p1, p2, p3; the separator's on its contact length Lc where the
    option says so."""
    kl1, kl2, kl3 = modes.kl
    p1 = frequencies(kl1, consts[0], safe["L1"])
    p3 = frequencies(kl3, consts[2], safe["L3"])
    lc = safe["Lc"]
    has_lc = lc > 0.0
    l2_freq = np.where(has_lc & (lc_option in (1, 2)), lc, safe["L2"])
    p2 = frequencies(kl2, consts[1], l2_freq)
    if modes.given is not None:
        p1, p2, p3 = (modes.b[:, k] * (c / length**2)[:, None]
                      for k, (c, length) in enumerate(zip(
                          consts, (safe["L1"], l2_freq, safe["L3"]))))
    return p1, p2, p3


def _separator_masses(safe: dict, m2, lc_option: int) -> tuple:
    """The separator's mass in the impulse and in its velocity (on its
    contact length Lc where the option says so)."""
    lc = safe["Lc"]
    has_lc = lc > 0.0
    m2_psi = np.where(has_lc & (lc_option == 2), m2 * lc / safe["L2"], m2)
    m2_v0 = np.where(has_lc & (lc_option in (0, 2)), m2 * lc / safe["L2"],
                     m2)
    return m2_psi, m2_v0


def _release(rows: _Rows, modes: _Modes, xi: list,
             release_option: int):
    """The upper contact's modal amplitudes released from the static
    deflection ys (at its tip, or at the contact point); a zero static
    flexibility is invalid input."""
    safe, ends, code = rows.safe, rows.ends, rows.code
    m = code.size
    tip_release = (release_option == 0) & (ends[0] == 1)
    xi_load = np.where(tip_release, 1.0, xi[0])
    if modes.given is None:
        flex = np.zeros(m)
        for c, end in enumerate(beams.END_CONDITIONS, 1):
            where = ends[0] == c
            flex[where] = beams.static_flexibility(end, xi_load[where])
        _, load_values = mode_table(ends[0], xi_load, rows.counts[0],
                                    rows.n_max)
    else:
        flex, load_values = modes.given.flex, modes.table[:, 3]
    zero_flex = ~(flex > 0.0)
    code[zero_flex & (code == status.OK)] = status.INVALID_INPUT
    flex = np.where(zero_flex, 1.0, flex)
    if modes.given is None:
        return release_amplitudes(safe["ys"], load_values, modes.kl[0],
                                  flex)
    return release_amplitudes_b(safe["ys"], load_values, modes.b[:, 0],
                                flex)


def _results(out: dict, code: np.ndarray, flags: tuple,
             per_mode: tuple) -> dict:
    """The contract's dict: a row whose results are not finite is
    NOT_FINITE; a failed row's results NaN (its flags False)."""
    at_end, max_tied, min_tied = flags
    finite = np.ones(code.size, dtype=bool)
    for value in out.values():
        finite &= np.isfinite(value) | (code != status.OK)
    code[~finite] = status.NOT_FINITE
    failed = code != status.OK
    for key in out:
        out[key] = np.where(failed, np.nan, out[key])
    out["at_window_end"] = np.where(failed, False, at_end)
    out["t_max_tied"] = np.where(failed, False, max_tied)
    out["t_min_tied"] = np.where(failed, False, min_tied)
    out["status"] = code
    for key, value in per_mode:
        out[key] = np.where(failed[:, None], np.nan, value)
    out["c3"] = np.where(np.isnan(out["p3"]), np.nan, out["c3"])
    return out
