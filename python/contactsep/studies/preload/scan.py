"""The preload search's grid and its scan's steps: preload k is
2^(k / PER_OCTAVE) lb; what a row's scan asks for next, the bracket of
the answer it ends with, and, for runs made ahead for idle workers
(:mod:`~contactsep.studies.preload.runs_ahead`), what the scan's and the
bisection's next steps may ask for (:mod:`~contactsep.studies.preload.
search`, module docstring).
"""

from __future__ import annotations

import math


#: The scan's grid: preload k is 2^(k / PER_OCTAVE) lb; the scan starts
#: at FIRST_K (1/16 lb), goes down to LOWEST_K (2^-20 lb, ~1e-6 lb: a
#: preload that small is none) and up to HIGHEST_K (1024 lb), or a
#: row's ceiling below it: an event at the highest grid value tested
#: leaves the row without an answer (NaN).
PER_OCTAVE = 4
FIRST_K = -16
LOWEST_K = -80
HIGHEST_K = 40

def grid(k: int) -> float:
    """Preload k of the scan's grid (lb)."""
    return 2.0 ** (k / PER_OCTAVE)


def next_scan(scan: dict, zero, top_k: int) -> list:
    """The preloads a row's scan still needs (empty: done).  ``scan``
    maps grid index -> has an event; ``zero`` whether 0 lb has one
    (None: not tried); ``top_k`` the highest grid index the row may
    test."""
    events = [k for k, event in scan.items() if event]
    if events:
        top = max(events)
        return [grid(k) for k in range(top + 1, min(top + PER_OCTAVE,
                                                     top_k) + 1)
                if k not in scan]
    low = min(scan)
    if low > LOWEST_K:
        return [grid(k) for k in range(max(LOWEST_K, low - PER_OCTAVE),
                                       low)]
    return [0.0] if zero is None else []


def scan_bracket(scan: dict, zero) -> tuple:
    """(highest preload with an event, the next tested one above): the
    scan's bracket of the answer; (nan, nan) if it has no closed top."""
    events = [k for k, event in scan.items() if event]
    if events:
        top = max(events)
        if top + 1 not in scan:
            return math.nan, math.nan
        return grid(top), grid(top + 1)
    if zero:
        return 0.0, grid(min(scan))
    return -math.inf, 0.0               # closed even without a preload


def top_index(ceiling: float) -> int:
    """The highest grid index at or below ``ceiling`` lb (and the grid's
    top, HIGHEST_K)."""
    if ceiling >= grid(HIGHEST_K):
        return HIGHEST_K
    k = math.floor(PER_OCTAVE * math.log2(ceiling))
    return k - 1 if grid(k) > ceiling else k


def start_index(preload: float) -> int:
    """The grid index a scan starting near ``preload`` lb begins at: the
    octave whose top is the grid value at or just above it."""
    if not (preload > 0.0 and math.isfinite(preload)):
        return FIRST_K
    k = math.ceil(PER_OCTAVE * math.log2(preload) - 1e-9)
    return min(max(k - PER_OCTAVE + 1, LOWEST_K), HIGHEST_K)


def scan_ahead(scans, zeros, tops, tasks) -> list:
    """The scan's next octave after ``tasks`` if all closed, then if all
    events; the bisection's first midpoint in the bracket the scan holds
    now (where ``tasks``, all closed, end the scan); then its first
    midpoints between adjacent grid values of ``tasks`` and the scan
    (where a bracket may form there)."""
    rows = sorted({row for row, _ in tasks})
    held = [(row, math.sqrt(lo * hi)) for row in rows
            for lo, hi in [scan_bracket(scans[row], zeros[row])]
            if lo > 0.0 and math.isfinite(hi)]
    return octaves_ahead(scans, zeros, tops, tasks) + held + [
        (row, math.sqrt(grid(k) * grid(k + 1))) for row in rows
        for k in adjacent(scans[row], {
            round(PER_OCTAVE * math.log2(p)) for r, p in tasks
            if r == row and p > 0.0})]


def adjacent(scan: dict, asked: set) -> list:
    """The grid indices k with k and k + 1 both scanned or asked, one of
    them asked: where a bracket of the answer may form."""
    known = set(scan) | asked
    return [k for k in sorted(known)
            if k + 1 in known and (k in asked or k + 1 in asked)]


def octaves_ahead(scans, zeros, tops, tasks) -> list:
    """The scan's next octave after ``tasks`` if all closed, then if all
    events."""
    out = []
    for event in (False, True):
        for row in sorted({row for row, _ in tasks}):
            scan, zero = dict(scans[row]), zeros[row]
            for r, p in tasks:
                if r != row:
                    continue
                if p == 0.0:
                    zero = event
                else:
                    scan[round(PER_OCTAVE * math.log2(p))] = event
            out += [(row, p) for p in next_scan(scan, zero, tops[row])]
    return out


def midpoints_ahead(brackets, tolerance: float, levels: int = 5) -> list:
    """The bisection's next midpoints (``brackets``: (row, (lo, hi),
    this step's midpoint)), level by level to ``levels`` steps ahead,
    where a half is still wider than ``tolerance``."""
    out, halves = [], [(row, lo, m) for row, (lo, _), m in brackets] + [
        (row, m, hi) for row, (_, hi), m in brackets]
    for _ in range(levels):
        halves = [(row, lo, hi) for row, lo, hi in halves
                  if lo > 0.0 and hi > lo * (1.0 + tolerance)]
        mids = [(row, lo, math.sqrt(lo * hi), hi) for row, lo, hi in halves]
        out += [(row, m) for row, _, m, _ in mids]
        halves = [half for row, lo, m, hi in mids
                  for half in ((row, lo, m), (row, m, hi))]
    return out
