"""Extremes of y3(t) = sum_j c_j sin(p_j t) over 0 <= t <= tau: the NumPy
twin of fortran/model/extremes.f90, vectorised over designs and cells.

Branch and bound over a list of cells (docs/model.md, "The extremes of y3").  The
window is halved level by level; every live cell carries each mode's
a_j = c_j sin(p_j m) and b_j = c_j cos(p_j m) at its centre m, rotated
from its parent's by the exact half-angle of the level (no trigonometric
call after the first).  On a cell of half-width r, with phi_j = p_j r:

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
maximum and the minimum share the cells.  The search never stops on a
level count with an unrefined answer: it ends when no cell is left, or
gives up (UNRESOLVED) when its work budget runs out.  A design needing
more than BLOCK_CELL_BUDGET live cell-modes is searched again (deferred),
its window in time-ordered segments (a segment needing more than CELL_BUDGET
halved again; the deferred designs' pending segments are Python lists,
one per design, popped a round at a time for all of them).  Every
choice, constant and budget is the compiled kernel's, so that both give
the same statuses.

Phases are exact: p_j tau/2 is split into hi + lo (Dekker's product), the
root centre's sin and cos are sin(hi) + lo cos(hi) and cos(hi) - lo
sin(hi), and every finer level's half-angle comes from the coarser one by
the half-angle formulas, its quadrant read from the bits of
floor(p_j tau/pi) (computed with a three-double pi).  So the accuracy does
not fall with the window's length: rounding adds ~9 eps per level and
~n eps per sum, which the bounds carry as a margin.
"""

from __future__ import annotations

import numpy as np

#: Two values of y3 closer than this (times sum |c_j|) are a tie: the
#: earlier time is reported.
TIE = 1e-12
#: A cell is finished when its bound is within this of its value (times
#: sum |c_j|): the extremes are true to CONVERGED plus the rounding margin.
CONVERGED = 0.25e-12
#: Modes with p_j r <= PHI_LOW enter a cell's bound by Taylor's theorem.
PHI_LOW = 1.0
#: Cells with p_max r <= PHI_POLISH are polished by Newton steps.
PHI_POLISH = 1.0
#: Newton steps of a polish.
POLISH_STEPS = 3
#: Most cell-mode evaluations per design before the search gives up.
WORK_BUDGET = 2**31
#: Most live cell-modes of a design searched with others, and of a
#: segment of a design searched alone (memory: 48 bytes each).
BLOCK_CELL_BUDGET = 2**14
CELL_BUDGET = 2**18
#: Deepest level (the cells are then tau / 2^61 wide), and deepest segment
#: of a design searched alone.
MAX_DEPTH = 60
MAX_SEGMENT_LEVELS = 24
#: Designs searched together (bounds the twin's memory).
CHUNK = 4096

_EPS = np.finfo(np.float64).eps
_SPLIT = 134217729.0                    # 2^27 + 1 (Dekker)
_PI = (3.141592653589793, 1.2246467991473532e-16, -2.9947698097183397e-33)


def _two_product(x, y):
    """(hi, lo) with hi + lo = x y exactly (Dekker, no fused multiply-add)."""
    hi = x * y
    tx = _SPLIT * x
    xh = tx - (tx - x)
    xl = x - xh
    ty = _SPLIT * y
    yh = ty - (ty - y)
    yl = y - yh
    lo = ((xh * yh - hi) + xh * yl + xl * yh) + xl * yl
    return hi, lo


def half_angle_quadrants(p, tau):
    """floor(p tau / pi) as int64: bit l of it and the next are the
    quadrant of p tau / 2^(l+1) (exact while below 2^52)."""
    hi, lo = _two_product(p, tau)
    k = np.floor(hi / _PI[0])
    rest = hi
    for part in _PI:
        u, e = _two_product(k, part)
        rest = (rest - u) - e
    rest = rest + lo
    k = k + np.floor(rest / _PI[0])
    return np.where(np.isfinite(k), k, 0.0).astype(np.int64)


def root_phases(p, tau):
    """cos and sin of p tau / 2, from the exact product."""
    hi, lo = _two_product(p, 0.5 * tau)
    c, s = np.cos(hi), np.sin(hi)
    return c - lo * s, s + lo * c


def halve(cos_phi, sin_phi, quadrant):
    """cos and sin of phi/2 from those of phi; quadrant (0-3) of phi/2."""
    up = cos_phi >= 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        hc = np.where(up, np.sqrt(0.5 * (1.0 + cos_phi)), 0.0)
        hs = np.where(up, 0.0, np.sqrt(0.5 * (1.0 - cos_phi)))
        hs = np.where(up, np.abs(sin_phi) / (2.0 * hc), hs)
        hc = np.where(up, hc, np.abs(sin_phi) / (2.0 * hs))
    hc = np.where(np.isfinite(hc), hc, 0.0)
    hs = np.where(np.isfinite(hs), hs, 0.0)
    cos_sign = np.where((quadrant == 1) | (quadrant == 2), -1.0, 1.0)
    sin_sign = np.where(quadrant >= 2, -1.0, 1.0)
    return cos_sign * hc, sin_sign * hs


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


class _Best:
    """Per design and side (0: max of y3, 1: max of -y3): the best value
    and the points that may tie with it."""

    def __init__(self, m, tie):
        self.value = np.full((m, 2), -np.inf)
        self.tie = tie
        self.points = []          # (design, side, t, value) arrays

    def offer(self, design, side, t, value):
        best = np.full_like(self.value, -np.inf)
        np.maximum.at(best, (design, side), value)
        self.value = np.maximum(self.value, best)
        near = value >= self.value[design, side] - self.tie[design]
        self.points.append((design[near], side[near], t[near], value[near]))

    def earliest(self, p_max):
        """(time of the earliest point within the tie, whether another lies
        more than half the shortest period away) per design and side."""
        d, s, t, v = (np.concatenate(x) for x in zip(*self.points))
        near = v >= self.value[d, s] - self.tie[d]
        d, s, t = d[near], s[near], t[near]
        first = np.full(self.value.shape, np.inf)
        last = np.full(self.value.shape, -np.inf)
        np.minimum.at(first, (d, s), t)
        np.maximum.at(last, (d, s), t)
        with np.errstate(divide="ignore", invalid="ignore"):
            tied = (last - first) > (np.pi / p_max)[:, None]
        return first, tied


def extremes(c, p, tau):
    """(y3_max, t_max, y3_min, t_min, at_window_end, max_tied, min_tied,
    unresolved) over 0 <= t <= tau; c, p (M, n), NaN p past a design's
    modes.  Unresolved designs (work budget) have NaN extremes."""
    parts = [_extremes(c[k:k + CHUNK], p[k:k + CHUNK], tau[k:k + CHUNK])
             for k in range(0, max(len(tau), 1), CHUNK)]
    return tuple(np.concatenate(x) for x in zip(*parts))


class _Search:
    """The designs' modes and what their searches know so far."""

    def __init__(self, c, p, tau):
        live = ~np.isnan(p)
        self.c = np.where(live, c, 0.0)
        self.p = np.where(live, p, 0.0)
        self.tau = tau
        self.n = live.sum(axis=1)
        self.absc = np.abs(self.c)
        self.scale = self.absc.sum(axis=1)
        self.p_max = self.p.max(axis=1, initial=0.0)
        self.quadrants = half_angle_quadrants(self.p, tau[:, None])
        self.min_quadrant = np.where(live, self.quadrants,
                                     np.iinfo(np.int64).max).min(axis=1)
        self.cos0, self.sin0 = root_phases(self.p, tau[:, None])
        # y3 and its slope at the window's two ends (exact phases)
        self.ends = np.stack([
            np.zeros(len(tau)), np.sum(self.c * self.p, axis=1),
            np.sum(self.c * 2.0 * self.sin0 * self.cos0, axis=1),
            np.sum(self.c * self.p * (self.cos0**2 - self.sin0**2),
                   axis=1)], axis=1)
        self.best = _Best(len(tau), TIE * self.scale)
        self.work = np.zeros(len(tau))
        self.gave_up = ~(self.p_max * tau < 2.0**52)

    def chain(self, designs, cos_phi, sin_phi, levels):
        """cos and sin of p_j tau / 2^(levels+1) of the designs from those
        of the level above (levels >= 1)."""
        shift = np.minimum(levels, 63)[:, None]
        return halve(cos_phi, sin_phi,
                     (self.quadrants[designs] >> shift) & 3)


def _extremes(c, p, tau):
    m = len(tau)
    s = _Search(c, p, tau)
    designs = np.arange(m)
    for side, sign in ((0, 1.0), (1, -1.0)):
        s.best.offer(designs, np.full(m, side), np.zeros(m), np.zeros(m))
        s.best.offer(designs, np.full(m, side), tau.copy(),
                     sign * s.ends[:, 2])
    # every design at once, each with at most BLOCK_CELL_BUDGET live
    # cell-modes; a design that needs more is searched again (deferred), a
    # segment of its window at a time in time order, a segment needing more
    # than CELL_BUDGET searched again as its two halves
    designs = np.flatnonzero((s.scale > 0.0) & ~s.gave_up)
    deferred = _search_segment(s, designs, np.zeros(designs.size, int),
                               np.zeros(designs.size, int),
                               BLOCK_CELL_BUDGET)
    # pending segments (level, index) per deferred design, the next last
    stacks = {int(d): [(0, 0)] for d in designs[deferred]}
    while True:
        active = [d for d, stack in stacks.items()
                  if stack and not s.gave_up[d]]
        if not active:
            break
        designs = np.array(active)
        top = [stacks[d].pop() for d in active]
        levels = np.array([t[0] for t in top])
        indices = np.array([t[1] for t in top])
        overflow = _search_segment(s, designs, levels, indices,
                                   CELL_BUDGET)
        for d, level, index, over in zip(active, levels, indices,
                                         overflow):
            if not over:
                continue
            if level == MAX_SEGMENT_LEVELS:
                s.gave_up[d] = True
            else:
                stacks[d] += [(level + 1, 2 * index + 1),
                              (level + 1, 2 * index)]
    first, tied = s.best.earliest(s.p_max)
    y_max, y_min = s.best.value[:, 0], -s.best.value[:, 1]
    for value in (y_max, y_min, first[:, 0], first[:, 1]):
        value[s.gave_up] = np.nan
    tied[s.gave_up] = False
    at_end = first[:, 0] == tau
    return (y_max, first[:, 0], y_min, first[:, 1], at_end, tied[:, 0],
            tied[:, 1], s.gave_up)


def _search_segment(s, designs, k_seg, segment, budget):
    """Branch and bound on segment `segment` of 2^k_seg of each design;
    returns the designs that needed more than `budget` live cell-modes
    (their cells dropped at that level)."""
    cos_phi, sin_phi = s.cos0[designs], s.sin0[designs]
    a = s.c[designs] * sin_phi
    b = s.c[designs] * cos_phi
    centre = 0.5 * s.tau[designs]
    for level in range(1, int(k_seg.max(initial=0)) + 1):
        walk = level <= k_seg
        cx, sx = s.chain(designs, cos_phi, sin_phi,
                         np.full(designs.size, level))
        right = ((segment >> np.maximum(k_seg - level, 0)) & 1) == 1
        turn = np.where(right, 1.0, -1.0)[:, None]
        a2 = a * cx + turn * b * sx
        b2 = b * cx - turn * a * sx
        step = s.tau[designs] * 0.5**(level + 1)
        a = np.where(walk[:, None], a2, a)
        b = np.where(walk[:, None], b2, b)
        centre = np.where(walk, centre + turn[:, 0] * step, centre)
        cos_phi = np.where(walk[:, None], cx, cos_phi)
        sin_phi = np.where(walk[:, None], sx, sin_phi)
    # the cells: their design (index into `designs`), centre, phases,
    # and whether they are alive for the max and for the min
    rows = np.arange(designs.size)
    alive = np.ones((designs.size, 2), dtype=bool)
    overflow = np.zeros(designs.size, dtype=bool)
    level = k_seg.copy()
    while rows.size:
        d = designs[rows]
        count = np.bincount(rows, minlength=designs.size)
        s.work[designs] += count * s.n[designs]
        out = s.work[designs] > WORK_BUDGET
        s.gave_up[designs[out]] = True
        deep = level > MAX_DEPTH
        s.gave_up[designs[deep & (count > 0)]] = True
        over = (count * s.n[designs] > budget) & ~out & ~deep
        overflow |= over
        keep = ~(out | over | deep)[rows]
        rows, centre, a, b, alive = (rows[keep], centre[keep], a[keep],
                                     b[keep], alive[keep])
        d = designs[rows]
        finished = _level(s, d, level[rows], centre, a, b, alive,
                          cos_phi[rows], sin_phi[rows])
        cos_phi, sin_phi = s.chain(designs, cos_phi, sin_phi, level + 1)
        level = level + 1
        split = ~finished
        rows, centre, a, b, alive = (rows[split], centre[split], a[split],
                                     b[split], alive[split])
        cx, sx = cos_phi[rows], sin_phi[rows]
        step = 0.5 * s.tau[designs[rows]] * 0.5**level[rows]
        rows = np.concatenate([rows, rows])
        centre = np.concatenate([centre - step, centre + step])
        a, b = (np.concatenate([a * cx - b * sx, a * cx + b * sx]),
                np.concatenate([b * cx + a * sx, b * cx - a * sx]))
        alive = np.concatenate([alive, alive])
    return overflow


def _level(s, d, level, centre, a, b, alive, cos_phi, sin_phi):
    """Bound, prune and polish the cells of one level (cells of designs
    d, at their levels) in place; returns the mask of cells that need no
    children."""
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
