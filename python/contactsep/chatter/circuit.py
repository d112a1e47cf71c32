"""Circuit discontinuity: when each contact is open, when both are, and
which openings count as discontinuity events.

The circuit runs through either contact (Chapter I): it opens only while
BOTH gaps exceed the open threshold (default 1e-6 in).  Each contact's
open intervals come from the instants its gap crosses the threshold:
found on the exact modal flow by the adaptive Hertz stepper, or by
root-finding the gap between samples (linear interpolation: the
Moreau-Jean positions are linear within a step).  An opening of the
circuit counts as a *discontinuity event* when it lasts at least
``min_open`` (default 1e-5 s, the detection time of MIL-STD-202 Method
310's contact-chatter monitoring; 0 counts every opening).  The totals
(``circuit_open_s``, ``first_circuit_open_s``, ``longest_open_s``) count
every opening: they are the physics, continuous in the design, and do
not depend on the instrument's detection time (docs/chatter.md).
"""

from __future__ import annotations

import numpy as np

#: Gap (in) above which a contact counts as open.
OPEN_THRESHOLD = 1e-6
#: Shortest opening (s) that counts as a discontinuity event.
MIN_OPEN = 1e-5
#: Fewest samples in the lower contact's first swing for its first lift
#: (else NaN): at 100 the largest sampled gap is within ~(pi/100)^2 / 2
#: = 5e-4 of the swing's own peak.
FIRST_LIFT_SAMPLES = 100


def first_lift(t, gap_lower, first_impact: float, half_period: float
               ) -> float:
    """The lower contact's largest gap (in) in its first swing: from the
    upper contact's first impact to half a period of the lower contact's
    first mode after it, at the samples.  The chatter model's
    counterpart of eq. 23's y3_max, and, unlike the largest gap over the
    window, it converges in N and dt (the rattle after the first swing is
    chaotic; docs/chatter.md).  NaN without an impact, or with fewer
    than FIRST_LIFT_SAMPLES samples in the swing."""
    if not (np.isfinite(first_impact) and half_period > 0.0):
        return float("nan")
    t = np.asarray(t)
    inside = (t >= first_impact) & (t <= first_impact + half_period)
    if np.count_nonzero(inside) < FIRST_LIFT_SAMPLES:
        return float("nan")
    return float(np.max(np.asarray(gap_lower)[inside]))


def crossings_from_samples(t, gap, threshold=OPEN_THRESHOLD):
    """Instants where the sampled gap crosses the threshold, by linear
    interpolation between the samples either side, and whether each is an
    opening (the gap rising above it).  Returns (times, opening)."""
    t = np.asarray(t, dtype=float)
    above = np.asarray(gap, dtype=float) - threshold
    is_open = above > 0.0
    k = np.flatnonzero(is_open[1:] != is_open[:-1])
    a, b = above[k], above[k + 1]
    times = t[k] + (t[k + 1] - t[k]) * a / (a - b)
    return times, is_open[k + 1]


def open_intervals(open_at_start, times, opening, t_end) -> np.ndarray:
    """(k, 2) intervals of [0, t_end] during which a contact is open, from
    its state at t = 0 and its crossings (times ascending, each flagged
    opening or closing): nothing past t_end, no zero-length interval."""
    times = np.clip(np.asarray(times, dtype=float), 0.0, t_end)
    starts, ends = [], []
    start = 0.0 if open_at_start else None
    for when, up in zip(times, opening):
        if up and start is None:
            start = when
        elif not up and start is not None:
            starts.append(start)
            ends.append(when)
            start = None
    if start is not None:
        starts.append(start)
        ends.append(float(t_end))
    spans = np.array([starts, ends], dtype=float).T.reshape(-1, 2)
    return spans[spans[:, 1] > spans[:, 0]]


def intersect(a, b) -> np.ndarray:
    """Intersection of two sorted lists of disjoint intervals ((k, 2))."""
    out = []
    i = j = 0
    while i < len(a) and j < len(b):
        start = max(a[i, 0], b[j, 0])
        end = min(a[i, 1], b[j, 1])
        if end > start:
            out.append((start, end))
        if a[i, 1] < b[j, 1]:
            i += 1
        else:
            j += 1
    return np.array(out, dtype=float).reshape(-1, 2)


def total(spans) -> float:
    """Total length (s) of (k, 2) intervals."""
    return float(np.sum(spans[:, 1] - spans[:, 0])) if len(spans) else 0.0


def discontinuity(upper_open, lower_open, min_open=MIN_OPEN) -> dict:
    """The circuit's open intervals (both contacts open), their total, the
    first opening and the longest, and the discontinuity events: the
    openings of at least ``min_open`` s.  An opening cut by the window's
    end counts by its length inside the window."""
    circuit = intersect(upper_open, lower_open)
    lengths = circuit[:, 1] - circuit[:, 0]
    events = circuit[lengths >= min_open]
    return dict(
        upper_open_intervals=upper_open,
        lower_open_intervals=lower_open,
        circuit_open_intervals=circuit,
        circuit_open_s=total(circuit),
        first_circuit_open_s=float(circuit[0, 0]) if len(circuit)
        else float("nan"),
        longest_open_s=float(lengths.max()) if len(circuit) else 0.0,
        events=events, n_events=len(events), chatters=len(events) > 0)


def open_from_samples(t, gap, t_end, threshold=OPEN_THRESHOLD
                      ) -> np.ndarray:
    """:func:`open_intervals` of a sampled gap (crossings interpolated)."""
    times, opening = crossings_from_samples(t, gap, threshold)
    return open_intervals(gap[0] > threshold, times, opening, t_end)
