"""One level of the extremes search
(:mod:`~contactsep.model.twin_extremes`): every live cell bounded, then
dropped, finished, polished or left to be halved; the NumPy twin of
fortran/model/extremes_cells.f90 and extremes_bounds.f90, vectorised over
the cells of every design searched.

On a cell of half-width r, with phi_j = p_j r:

* a mode with phi_j > PHI_LOW is bounded by its own exact maximum over the
  cell, |c_j| if the arc [p_j m - phi_j, p_j m + phi_j] reaches the crest,
  else a_j cos phi_j + |b_j| sin phi_j;
* the others by Taylor's theorem, y_L(m + x) <= A + B x + K x^2/2 with A,
  B the value and slope of their sum at m and K >= y_L'' on the cell
  (the sum of p_j^2 times each mode's own maximum of -c_j sin).

Where every mode is low, the lower parabola (K <= y_L'') gives a certified
value at a known point; a cell at an end of the window is also bounded by
Taylor about that end, where y3 and y3' are known.  A cell whose bound is
below the best value found by more than the tie is dropped; one whose
bound is within CONVERGED of a value it holds is finished; the others are
halved.  Cells with p_max r <= PHI_POLISH are first polished: Newton
steps to the vertex of y3's Taylor parabola, finished when the bound
about that point is within CONVERGED of its value (not tried on a side
whose curvature bound K has K r^2/2 > CONVERGED: the bound about any
point of the cell then stays about that much above its value).  The
bounds carry the rounding of the phases
(:mod:`~contactsep.model.twin_extremes_phases`) as a margin.
"""

from __future__ import annotations

import numpy as np

#: A cell is finished when its bound is within this of its value (times
#: sum |c_j|): the extremes are true to CONVERGED plus the rounding margin.
CONVERGED = 0.25e-12
#: Modes with p_j r <= PHI_LOW enter a cell's bound by Taylor's theorem.
PHI_LOW = 1.0
#: Cells with p_max r <= PHI_POLISH are polished by Newton steps.
PHI_POLISH = 1.0
#: Newton steps of a polish.
POLISH_STEPS = 3

_EPS = np.finfo(np.float64).eps


def _parabola_argmax(a, b, k, lo, hi):
    """(max, argmax) of a + b x + k x^2/2 over lo <= x <= hi (the
    smaller x of equal ends)."""
    f_lo = a + b * lo + 0.5 * k * lo * lo
    f_hi = a + b * hi + 0.5 * k * hi * hi
    x = np.where(f_hi > f_lo, hi, lo)
    top = np.maximum(f_lo, f_hi)
    with np.errstate(divide="ignore", invalid="ignore"):
        xv = -b / k
    inside = (k < 0.0) & (xv > lo) & (xv < hi)
    xv = np.where(inside, xv, 0.0)
    fv = a + b * xv + 0.5 * k * xv * xv
    better = inside & (fv > top)
    return np.where(better, fv, top), np.where(better, xv, x)


def _parabola_max(a, b, k, lo, hi):
    """max of a + b x + k x^2/2 over lo <= x <= hi."""
    ends = np.maximum(a + b * lo + 0.5 * k * lo * lo,
                      a + b * hi + 0.5 * k * hi * hi)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = -b / k
    inside = (k < 0.0) & (x > lo) & (x < hi)
    x = np.where(inside, x, 0.0)
    return np.where(inside, np.maximum(ends, a + b * x + 0.5 * k * x * x),
                    ends)


def search_level(s, d, level, centre, a, b, alive, cos_phi, sin_phi):
    """Bound, prune and polish the cells of one level (cells of designs
    d, at their levels) in place; returns the mask of cells that need no
    children.  ``s``: the designs' search (twin_extremes), whose best
    values the cells' candidates are offered to."""
    r = s.tau[d] * 0.5**(level + 1)
    turns = s.quadrants[d] >> np.minimum(level, 63)[:, None]
    full = turns >= 2                                   # phi_j >= pi
    cph = np.where(full, -1.0, cos_phi)
    sph = np.where(full, 0.0, np.maximum(sin_phi, 0.0))
    ac = s.absc[d]
    pr = s.p[d]
    low = ~full & (pr * r[:, None] <= PHI_LOW)
    abs_b = np.abs(b)
    up_mode = np.where(a >= ac * cph, ac, a * cph + abs_b * sph)
    down_mode = np.where(-a >= ac * cph, ac, -a * cph + abs_b * sph)
    value = a.sum(axis=1)
    signed = np.stack([value, -value], axis=1)
    sides = np.broadcast_to(np.arange(2), alive.shape)
    s.best.offer(np.repeat(d, 2), sides.ravel(), np.repeat(centre, 2),
                 signed.ravel())
    coarse = (s.min_quadrant[d] >> np.minimum(level, 63)) >= 2
    a_low = np.where(low, a, 0.0).sum(axis=1)
    slope_low = np.where(low, pr * b, 0.0).sum(axis=1)
    curve_up = np.where(low, pr * pr * down_mode, 0.0).sum(axis=1)
    curve_down = np.where(low, pr * pr * up_mode, 0.0).sum(axis=1)
    high_up = np.where(low, 0.0, up_mode).sum(axis=1)
    high_down = np.where(low, 0.0, down_mode).sum(axis=1)
    margin = (9.0 * (level + 1) + 2.0 * s.n[d] + 8.0) * _EPS * s.scale[d]
    bound = np.stack([
        _parabola_max(a_low, slope_low, curve_up, -r, r) + high_up,
        _parabola_max(-a_low, -slope_low, curve_down, -r, r) + high_down],
        axis=1)
    # certified lower bounds of each cell's maxima, at a point: the lower
    # Taylor parabola's top, the other modes at their least
    # (where every mode is low: with high modes at their least they would
    # not help)
    low_max, x_max = _parabola_argmax(a_low, slope_low, -curve_down, -r, r)
    low_min, x_min = _parabola_argmax(-a_low, -slope_low, -curve_up, -r, r)
    all_low = (s.p_max[d] * r <= PHI_LOW)[:, None]
    sure = np.where(all_low, np.stack([low_max, low_min], axis=1),
                    -np.inf)
    s.best.offer(np.repeat(d, 2), sides.ravel(),
                 (centre[:, None] + np.stack([x_max, x_min], axis=1)).ravel(),
                 sure.ravel())
    # a cell at an end of the window whose modes are all low: Taylor about
    # that end, where y3 and its slope are known, bounds it too
    all_low = all_low[:, 0]
    for at_start, (y_col, slope_col) in ((True, (0, 1)), (False, (2, 3))):
        edge = all_low & ((centre - r <= 0.0) if at_start else
                          (centre + r >= s.tau[d]))
        if not np.any(edge):
            continue
        lo, hi = (0.0 * r, 2.0 * r) if at_start else (-2.0 * r, 0.0 * r)
        for side, sign in ((0, 1.0), (1, -1.0)):
            y_end = sign * s.ends[d, y_col]
            curve_side = curve_up if side == 0 else curve_down
            end_bound = _parabola_max(y_end, sign * s.ends[d, slope_col],
                                      curve_side, lo, hi)
            bound[:, side] = np.where(edge, np.minimum(bound[:, side],
                                                       end_bound),
                                      bound[:, side])
            sure[:, side] = np.where(edge, np.maximum(sure[:, side], y_end),
                                     sure[:, side])
    conv = (CONVERGED * s.scale[d])[:, None]
    drop = (bound + margin[:, None] < s.best.value[d] - s.best.tie[d][:, None]
            ) | (bound - np.maximum(signed, sure) <= conv)
    alive &= ~(drop & ~coarse[:, None])
    # no polish where the side's curvature bound K has K r^2/2 > conv:
    # the bound about any point of the cell stays above its value by about
    # that much (the compiled kernel's test, the same expression)
    curve = np.stack([curve_up, curve_down], axis=1)
    polish = (alive & (s.p_max[d] * r <= PHI_POLISH)[:, None]
              & ~(curve * (r * r * 0.5)[:, None] > conv))
    if np.any(polish):
        alive &= ~_polish(s, polish, d, centre, a, b, r, curve, conv)
    return ~alive.any(axis=1)


def _polish(s, polish, d, centre, a, b, r, curve, conv):
    """Newton steps (at most POLISH_STEPS) from each cell's centre to the
    vertex of y3's Taylor parabola, for the side asking; the point is
    offered as a candidate.  Returns the cells (and sides) whose bound
    around that point (the cell's curvature bound) is within conv."""
    done = np.zeros(polish.shape, dtype=bool)
    cells = np.flatnonzero(polish.any(axis=1))
    pc = s.p[d[cells]]
    ac, bc = a[cells], b[cells]
    for side, sign in ((0, 1.0), (1, -1.0)):
        k = np.flatnonzero(polish[cells, side])
        shift = np.zeros(k.size)
        a2, b2 = ac[k], bc[k]
        ok = np.ones(k.size, dtype=bool)
        for _ in range(POLISH_STEPS):
            slope = np.sum(pc[k] * b2, axis=1)
            second = -np.sum(pc[k] * pc[k] * a2, axis=1)
            ok &= sign * second < 0.0
            with np.errstate(divide="ignore", invalid="ignore"):
                shift = np.where(ok, shift - slope / second, shift)
            ok &= np.abs(shift) <= r[cells[k]]
            x = pc[k] * np.where(ok, shift, 0.0)[:, None]
            cx, sx = np.cos(x), np.sin(x)
            a2 = ac[k] * cx + bc[k] * sx
            b2 = bc[k] * cx - ac[k] * sx
        k, shift, a2, b2 = k[ok], shift[ok], a2[ok], b2[ok]
        if k.size == 0:
            continue
        value = sign * a2.sum(axis=1)
        slope = sign * np.sum(pc[k] * b2, axis=1)
        cell = cells[k]
        s.best.offer(d[cell], np.full(k.size, side), centre[cell] + shift,
                     value)
        lo, hi = -r[cell] - shift, r[cell] - shift
        bound = _parabola_max(value, slope, curve[cell, side], lo, hi)
        done[cell, side] = bound - value <= conv[cell, 0]
    return done
