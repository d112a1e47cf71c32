"""Circuit discontinuity: when each contact is open, and when both are.

The circuit runs through either contact (Chapter I): it opens only while
BOTH gaps exceed the open threshold (default 1e-6 in).  Intervals are
found on the sampled gaps; an interval's ends are the first and last
samples that are open, so a total is good to one sample step.
"""

from __future__ import annotations

import numpy as np

#: Gap (in) above which a contact counts as open.
OPEN_THRESHOLD = 1e-6


def intervals(t, is_open) -> np.ndarray:
    """(k, 2) start and end times of the runs where is_open holds."""
    is_open = np.asarray(is_open, dtype=bool)
    if not is_open.any():
        return np.zeros((0, 2))
    edges = np.diff(np.concatenate([[0], is_open.astype(np.int8), [0]]))
    starts = np.flatnonzero(edges == 1)
    ends = np.flatnonzero(edges == -1) - 1
    return np.stack([t[starts], t[ends]], axis=1)


def total(spans) -> float:
    """Total length (s) of (k, 2) intervals."""
    return float(np.sum(spans[:, 1] - spans[:, 0])) if len(spans) else 0.0


def discontinuity(t, gap_upper, gap_lower, threshold=OPEN_THRESHOLD
                  ) -> dict:
    """Open intervals of each contact and of the circuit, their totals, the
    first opening of the circuit and the largest lower gap."""
    up = np.asarray(gap_upper) > threshold
    low = np.asarray(gap_lower) > threshold
    circuit = intervals(t, up & low)
    return dict(
        upper_open_intervals=intervals(t, up),
        lower_open_intervals=intervals(t, low),
        circuit_open_intervals=circuit,
        circuit_open_s=total(circuit),
        first_circuit_open_s=float(circuit[0, 0]) if len(circuit)
        else float("nan"),
        max_lower_gap_in=float(np.max(gap_lower)) if len(gap_lower)
        else float("nan"))
