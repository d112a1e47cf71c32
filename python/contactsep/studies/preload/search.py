"""The preload search itself: the smallest preload with no discontinuity
event, from a function that says which preloads have one (the chart,
:mod:`contactsep.studies.preload.chart`, and ``contactsep preload``,
:mod:`contactsep.studies.preload.command`, run it on simulations).

For each design (the chart: the thesis rig for d = 0.125 ... 0.75 in and
y_s = 0.25, 0.5, 0.75 in) the search

0. with ``ceiling_first``, **tries the ceiling** first: the highest grid
   value at or below the row's ceiling (the largest preload the
   simulation takes), the one the scan would test last; an event there
   is the answer "none up to it" (NaN) at once, a closed one is kept
   for the scan;
1. **scans** the grid of preloads 2^(k/4) lb (19 % apart) upward from
   1/16 lb (or from a row's ``start``), an octave (four values) at a
   time, until the four values above the highest preload with an event
   are all closed (no event), or those of them up to the row's ceiling
   (it bends the lower contact by its length); if the first octave has
   no event it scans down instead, to 2^-20 lb, then tries 0;
2. **bisects** (geometric midpoints) between that highest event and the
   next grid value until they are within 1 %;
3. **checks finely** every preload of the fine grid FINE_RATIO^j lb
   (steps of 0.99 %: a window of events 1 % wide holds one of them)
   from the bracket's event (within 1 % below the answer) to 2 times
   the answer (BAND_HIGH), and from 0.7 times it (BAND_LOW) where the
   scan saw a closed grid value below its highest event (not monotone)
   or ``band_below`` asks: if one above the answer
   has an event, the highest such is the new lower end, the next tested
   preload above it the upper end, and 2-3 repeat (preloads above the
   ceiling are not tested; the fine grid is fixed, so a repeat tests
   only the preloads the last band did not).

The band below the bracket's event cannot move the answer (the answer
depends only on the highest event and the tested preloads above it);
it finds the closed windows below it, which a monotone scan gives no
sign of.

"Closed" is not monotone in preload (docs/preload-family.md, "The preload
chart"): below the highest preload with an event a smaller one may be
closed, and short open windows lie between the scan's values.  The
answer is therefore the smallest tested preload above which every
tested preload stays closed: closed at every fine step to 2 times it
and at the scan's steps to an octave above its last event (or to the
ceiling).  Each step keeps that true (a closed midpoint becomes the
upper end, an open one the lower end), and the answer is itself
closed.  A window of events narrower than 1 % may fall between two
fine steps, and one beyond 2 times the answer between two of the
scan's steps, unseen.  The ceiling tried first is a tested preload
like any other: an event there leaves no answer even where the scan
alone would have stopped below it, an octave short of it.

Every scan step, bisection step and band is one batch: ``has_event``
is called with all the rows' preloads at once (and runs the next steps
may need beside it on idle workers, ``speculate``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from contactsep.studies.preload.scan import (
    FIRST_K,
    PER_OCTAVE,
    grid,
    midpoints_ahead,
    next_scan,
    scan_ahead,
    scan_bracket,
    start_index,
    top_index,
)


#: The bisection stops when the bracket's ends are within this ratio - 1.
TOLERANCE = 0.01
#: The fine check around an answer: every preload FINE_RATIO^j lb
#: (j integer; steps of 0.99 %, so that any window 1 % wide holds one)
#: from BAND_LOW to BAND_HIGH times the answer (to 2: the whole octave
#: the scan checked closed above it; issue 25 saw a window 1.2 % wide at
#: 1.86 times an answer).
FINE_RATIO = 1.0099
BAND_LOW = 0.7
BAND_HIGH = 2.0


@dataclass(frozen=True)
class PreloadSearch:
    """One design's search: the answer and every preload it tested."""

    #: The smallest tested preload (lb) above which every tested preload
    #: has no discontinuity event (NaN: an event up to the grid's top).
    min_preload_lb: float
    #: (preload lb, has an event) of every simulation, by preload.
    tested: tuple
    #: The largest preload the search could test (lb; inf: the grid's
    #: top): the simulation's limit, :func:`largest_preload`.
    ceiling_lb: float = math.inf
    #: Where the fine band began, in times the answer: BAND_LOW, or 1
    #: where it began at the bracket's event, within 1 % below the
    #: answer (``band_below``).
    band_low: float = BAND_LOW

    @property
    def closed_below(self) -> tuple:
        """Tested preloads below the answer without an event: where
        "closed" is not monotone in preload."""
        return tuple(p for p, event in self.tested
                     if not event and p < self.min_preload_lb)


def search(n_rows: int, has_event, tolerance: float = TOLERANCE,
           ceilings=None, starts=None, band=True, band_batch=None,
           band_below=False, ceiling_first=False, speculate=None
           ) -> list[PreloadSearch]:
    """Run the scan, the bisection and the fine check around the answer
    for ``n_rows`` designs at once (module docstring).

    ``has_event(tasks)`` takes a list of (row, preload lb) and returns,
    in order, whether each has a discontinuity event (one batch).
    ``ceilings``: each row's largest preload to test (lb; default the
    grid's top, 1024 lb): the scan above the last event stops there,
    even short of an octave, and an event at the highest grid value
    below it leaves the row without an answer (NaN).  ``starts``: each
    row's guess of its answer (lb; None: scan from 1/16 lb): the scan
    begins at the octave that ends there.  ``band`` True: the fine
    check (:func:`fine_band`); a callable: ``band(row, answer)`` lists
    the preloads to check instead (the robust answer's, above the
    answer only: each preload there is a whole tolerance study); False:
    none, the answer is then closed at the scan's steps to an octave
    above its last event.  ``band_batch`` None: a band is one batch; an
    integer k: a row's band runs from its top down, k preloads a batch,
    and stops after the first batch with an event (where each preload is
    a whole tolerance study): the highest event in the band is the same
    as the whole band's, so the answer is too (every step depends only
    on the highest event and the tested preloads above it), with fewer
    preloads tried below it.  ``band_below`` (the fine check, ``band``
    True): True, the band from BAND_LOW times the answer; False, from
    the bracket's event (within 1 % below the answer), and from
    BAND_LOW only where the scan saw a closed grid value below its
    highest event (the same answer: module docstring).
    ``ceiling_first``: each row with a finite ceiling first tries the
    highest grid value at or below it (module docstring, step 0).
    ``speculate(asked, tasks)`` before a scan or bisection batch of
    ``asked`` runs: the (row, preload) the next steps may ask for, most
    likely first (:mod:`~contactsep.studies.preload.runs_ahead`); the same runs
    are asked for with it as without.
    """
    if band_batch is not None and not (isinstance(band_batch, int)
                                       and band_batch >= 1):
        raise ValueError(f"band_batch: found {band_batch!r}, expected None "
                         f"or a positive integer")
    state = _Search(n_rows, has_event, ceilings, starts, band, band_below,
                    speculate)
    state.scan(ceiling_first)
    while True:
        state.bisect(tolerance)
        if not band:
            break
        # (not below the grid's floor, 2^-20 lb: a preload that small
        # is none, and a band there would creep down a band at a time)
        rows = [row for row, (lo, hi) in enumerate(state.brackets)
                if lo > 0.0 and math.isfinite(hi)
                and state.checked[row] != hi]
        if not rows:
            break
        state.check_bands(rows, band_batch)
    return state.results()


class _Search:
    """The state of one search of ``n_rows`` designs (:func:`search`'s
    arguments): what each row's scan saw, every preload tested, the
    brackets, and the steps that move them, one batch a call."""

    def __init__(self, n_rows, has_event, ceilings, starts, band,
                 band_below, speculate):
        self.n_rows, self.has_event = n_rows, has_event
        self.band, self.speculate = band, speculate
        self.band_below = band_below
        self.limits = list(ceilings) if ceilings else [math.inf] * n_rows
        self.tops = [top_index(c) for c in self.limits]
        # a row's first octave lies below its top (at least one preload)
        self.firsts = [min(start_index(s) if s is not None else FIRST_K,
                           top - PER_OCTAVE + 1)
                       for s, top in zip(starts or [None] * n_rows,
                                         self.tops)]
        self.scans = [{} for _ in range(n_rows)]
        self.zeros = [None] * n_rows
        self.tested = [{} for _ in range(n_rows)]
        self.brackets = self.below = None
        self.checked = [None] * n_rows

    def run(self, tasks, on_grid=False, ahead=()):
        """One batch: ``has_event`` on ``tasks`` ((row, preload) each),
        the runs ``ahead`` named to ``speculate`` first; on the scan's
        grid (``on_grid``) the scan records each too."""
        if not tasks:
            return
        if self.speculate is not None and ahead:
            self.speculate(len(tasks), ahead)
        for (row, preload), event in zip(tasks, self.has_event(tasks)):
            self.tested[row][preload] = bool(event)
            if on_grid and preload == 0.0:
                self.zeros[row] = bool(event)
            elif on_grid:
                k = round(PER_OCTAVE * math.log2(preload))
                self.scans[row][k] = bool(event)

    def _first_octave(self):
        return [(row, grid(k)) for row in range(self.n_rows)
                if not self.scans[row].get(self.tops[row])
                for k in range(self.firsts[row],
                               self.firsts[row] + PER_OCTAVE)
                if k <= self.tops[row] and k not in self.scans[row]]

    def _scan_ahead(self, tasks):
        return scan_ahead(self.scans, self.zeros, self.tops, tasks)

    def scan(self, ceiling_first):
        """Steps 0 and 1 (module docstring): the ceiling if asked, then
        the scan; then each row's bracket and whether its band looks
        below the answer."""
        if ceiling_first:
            # the scan's last preload, tried first: an event there is
            # the row's answer (none), whatever lies below it
            first = self._first_octave()
            self.run([(row, grid(self.tops[row]))
                      for row in range(self.n_rows)
                      if math.isfinite(self.limits[row])], on_grid=True,
                     ahead=first + self._scan_ahead(first))
        tasks = self._first_octave()
        while True:
            self.run(tasks, on_grid=True, ahead=self._scan_ahead(tasks))
            tasks = [(row, p) for row in range(self.n_rows)
                     for p in next_scan(self.scans[row], self.zeros[row],
                                        self.tops[row])]
            if not tasks:
                break
        self.brackets = [list(scan_bracket(self.scans[row], self.zeros[row]))
                         for row in range(self.n_rows)]
        # where the scan saw a closed grid value below its highest
        # event, closed windows may lie below the answer: the band
        # looks there too
        self.below = [self.band_below or _not_monotone(self.scans[row])
                      for row in range(self.n_rows)]

    def _band_ahead(self, row, lo, hi):
        # the fine band's preloads for any answer in (lo, hi]
        if self.band is not True:
            return []
        low = BAND_LOW * hi if self.below[row] else hi
        return [(row, p) for p in fine_grid(low, BAND_HIGH * lo)
                if p <= self.limits[row] and p not in self.tested[row]]

    def bisect(self, tolerance):
        """Step 2: every bracket bisected to ``tolerance``."""
        _bisect(self.brackets, self.tested, self.has_event, tolerance,
                None if self.speculate is None else
                lambda asked, mids: self.speculate(asked, [
                    task for row, (lo, hi), _ in mids
                    for task in self._band_ahead(row, lo, hi)] +
                    midpoints_ahead(mids, tolerance)))

    def check_bands(self, rows, band_batch):
        """Step 3 for ``rows``: the band around each new answer; an event
        above it moves the bracket up to it (every tested preload above
        stays closed)."""
        brackets, tested = self.brackets, self.tested
        # (from the bracket's event, not from the answer: a fine step
        # between them, closed, is the answer the whole band gives)
        checks = self.band if callable(self.band) else (
            lambda row, answer: fine_band(answer) if self.below[row] else
            fine_grid(brackets[row][0], BAND_HIGH * answer))
        bands = {row: [p for p in checks(row, brackets[row][1])
                       if p not in tested[row] and p <= self.limits[row]]
                 for row in rows}
        if band_batch is None:
            self.run([(row, p) for row in rows for p in bands[row]])
        else:
            _run_from_the_top(bands, tested, self.run, band_batch)
        # an event the band found near its top: the scan's grid values
        # to an octave above it are tested too (as the scan did above
        # its last event), until they are all closed
        while True:
            tasks = [(row, p) for row in rows
                     for p in _octave_above(tested[row], self.tops[row])]
            if not tasks:
                break
            self.run(tasks)
        for row in rows:
            self.checked[row] = brackets[row][1]
            # the highest event now (above the answer if the band found
            # one), and the smallest tested preload above it (the band
            # may have put one between the bisection's ends)
            top = max(p for p, event in tested[row].items() if event)
            above = [p for p in tested[row] if p > top]
            brackets[row] = [top, min(above) if above else math.nan]

    def results(self) -> list:
        """Each row's :class:`PreloadSearch`."""
        return [PreloadSearch(min_preload_lb=hi,
                              tested=tuple(sorted(self.tested[row].items())),
                              ceiling_lb=self.limits[row],
                              band_low=BAND_LOW if self.below[row] else 1.0)
                for row, (_, hi) in enumerate(self.brackets)]


def _not_monotone(scan: dict) -> bool:
    """Whether a row's scan (grid index -> has an event) has a closed
    grid value below its highest event."""
    events = [k for k, event in scan.items() if event]
    return bool(events) and any(not event and k < max(events)
                                for k, event in scan.items())


def _run_from_the_top(bands: dict, tested: list, run, batch: int) -> None:
    """Each row's band (``bands``: row -> preloads), highest first,
    ``batch`` preloads a row a batch, until a batch has an event or the
    band is done."""
    pending = {row: sorted(preloads, reverse=True)
               for row, preloads in bands.items() if preloads}
    while pending:
        run([(row, p) for row, preloads in pending.items()
             for p in preloads[:batch]])
        for row in list(pending):
            done, pending[row] = pending[row][:batch], pending[row][batch:]
            if not pending[row] or any(tested[row][p] for p in done):
                del pending[row]


def _octave_above(tested: dict, top_k: int) -> list:
    """The scan's grid values above a row's highest event, to an octave
    above it (and the row's top, ``top_k``), not yet tested."""
    top = max(p for p, event in tested.items() if event)
    if top <= 0.0:
        return []
    first = math.floor(PER_OCTAVE * math.log2(top) + 1e-9) + 1
    return [grid(k) for k in range(first, min(first + PER_OCTAVE - 1,
                                              top_k) + 1)
            if grid(k) not in tested]


def fine_band(answer: float, low: float = BAND_LOW) -> list:
    """The preloads of the fine grid, FINE_RATIO^j lb, from ``low``
    (default BAND_LOW) to BAND_HIGH times ``answer`` (the fine check,
    module docstring)."""
    return fine_grid(low * answer, BAND_HIGH * answer)


def fine_grid(lo: float, hi: float) -> list:
    """The preloads of the fine grid, FINE_RATIO^j lb, from ``lo`` to
    ``hi`` lb (either end included to round-off)."""
    step = math.log(FINE_RATIO)
    first = math.ceil(math.log(lo) / step - 1e-9)
    last = math.floor(math.log(hi) / step + 1e-9)
    return [FINE_RATIO ** j for j in range(first, last + 1)]


def _bisect(brackets, tested, has_event, tolerance, speculate=None
            ) -> None:
    """Geometric bisection of every bracket (event, closed) until its
    ends are within ``tolerance``, one batch per step for all rows;
    ``speculate(asked, [(row, (lo, hi), midpoint), ...])`` before each."""
    while True:
        tasks = [(row, math.sqrt(lo * hi))
                 for row, (lo, hi) in enumerate(brackets)
                 if lo > 0.0 and hi > lo * (1.0 + tolerance)]
        if not tasks:
            return
        if speculate is not None:
            speculate(len(tasks), [(row, tuple(brackets[row]), m)
                                   for row, m in tasks])
        for (row, preload), event in zip(tasks, has_event(tasks)):
            tested[row][preload] = bool(event)
            brackets[row][0 if event else 1] = preload
