"""Extremes of y3(t) = sum_j c_j sin(p_j t) over 0 <= t <= tau: the NumPy
twin of fortran/model/extremes.f90, vectorised over designs and cells.

Branch and bound over a list of cells (docs/model.md, "The extremes of y3").  The
window is halved level by level; every live cell carries each mode's
a_j = c_j sin(p_j m) and b_j = c_j cos(p_j m) at its centre m, rotated
from its parent's by the exact half-angle of the level (no trigonometric
call after the first; the phases are exact,
:mod:`~contactsep.model.twin_extremes_phases`).  Each level's cells are
bounded, and dropped, finished, polished or halved
(:mod:`~contactsep.model.twin_extremes_cells`).  The maximum and the
minimum share the cells.  The search never stops on a
level count with an unrefined answer: it ends when no cell is left, or
gives up (UNRESOLVED) when its work budget runs out.  A design needing
more than BLOCK_CELL_BUDGET live cell-modes is searched again (deferred),
its window in time-ordered segments (a segment needing more than CELL_BUDGET
halved again; the deferred designs' pending segments are Python lists,
one per design, popped a round at a time for all of them).  Every
choice, constant and budget is the compiled kernel's, so that both give
the same statuses.
"""

from __future__ import annotations

import numpy as np

from contactsep.model.twin_extremes_cells import search_level
from contactsep.model.twin_extremes_phases import (half_angle_quadrants,
                                                   halve, root_phases)

#: Two values of y3 closer than this (times sum |c_j|) are a tie: the
#: earlier time is reported.
TIE = 1e-12
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
        finished = search_level(s, d, level[rows], centre, a, b, alive,
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
