"""The thesis's conclusion 8 (``contactsep study conclusion8``): where
the lower contact touches the separator decides how complex its response
is; "if contact is made at the nodal point of a contact's second mode,
the displacement response at that point will resemble that of a single
degree of freedom system".

The lower contact's displacement at its contact point x3 after the
impact is, by eq. 23, y3(t) = sum_j c3_j sin(p3_j t) with
c3_j proportional to X_j(x3)^2 / p_j (the velocity start at x3, seen
at x3).  For each x3 = r L3 (r = 0.50 ... 1.00) the study reports

* ``first_mode_share``: c3_1^2 / sum_j c3_j^2, the first mode's share of
  the mean-square displacement (1: a one-degree-of-freedom response);
* ``n_maxima``: the local maxima of y3(t) over the first mode's period
  after the impact whose prominence is at least ``PROMINENCE`` of the
  largest |y3| there (1: one swing a period, as a single degree of
  freedom swings).

Both converge in N (docs/studies.md, "Conclusion 8").  The count of all
local maxima does not: the velocity start at a point excites every mode
with c3_j p3_j ~ X_j(x3)^2, which does not decay, so each mode added
adds wiggles of its own; a prominence threshold counts the swings a
sensor would see.
"""

from __future__ import annotations

import numpy as np

from contactsep import beams
from contactsep.model.fields import design_lines
from contactsep.studies.study import (
    Study,
    evaluate_all,
    refuse_fixed,
    thesis_study_design,
)

#: The contact points x3/L3.
RATIOS = np.round(np.arange(0.50, 1.0001, 0.01), 10)
#: Modes per member (the share and n_maxima at N = 32 equal those at
#: N = 64: tests/studies/thesis/test_conclusion8.py, slow).
MODES = 32
#: A maximum counts when it rises this fraction of max |y3| above the
#: higher of the minima that separate it from higher maxima.
PROMINENCE = 0.2
#: Samples per period of the highest mode.
SAMPLES_PER_PERIOD = 16
FIXED = {"x3": "its x axis, x3/L3 = 0.50-1.00"}


def second_mode_node(end: str = "clamped-free") -> float:
    """The node of the second mode inside the member, as x/L: the root
    of X_2 between the supports, by bisection on the mode shape."""
    low, high = 0.05, 0.999
    value = beams.mode_shapes(end, 2, [low, high])[1]
    if np.sign(value[0]) == np.sign(value[1]):
        raise ValueError(f"{end}: no node of mode 2 found")
    sign_low = np.sign(value[0])
    for _ in range(60):
        mid = 0.5 * (low + high)
        if np.sign(beams.mode_shapes(end, 2, [mid])[1, 0]) == sign_low:
            low = mid
        else:
            high = mid
    return 0.5 * (low + high)


def count_maxima(y: np.ndarray, prominence: float) -> int:
    """Local maxima of the sampled curve ``y`` whose prominence (the
    height above the higher of the lowest points between it and a higher
    sample on either side, or the curve's end) is at least
    ``prominence``.  Only the curve's turning points (and ends) matter:
    the peaks are among them and so are the lowest points between."""
    rising = np.diff(y) > 0
    turns = np.flatnonzero(rising[1:] != rising[:-1]) + 1
    y = y[np.concatenate([[0], turns, [y.size - 1]])]
    peaks = np.flatnonzero((y[1:-1] > y[:-2]) & (y[1:-1] >= y[2:])) + 1
    count = 0
    for k in peaks:
        left = y[k::-1]
        higher = np.flatnonzero(left > y[k])
        low_left = left[:higher[0]].min() if higher.size else left.min()
        right = y[k:]
        higher = np.flatnonzero(right > y[k])
        low_right = right[:higher[0]].min() if higher.size else right.min()
        if y[k] - max(low_left, low_right) >= prominence:
            count += 1
    return count


def _history(c: np.ndarray, p: np.ndarray, t: np.ndarray) -> np.ndarray:
    """y3(t) = sum_j c_j sin(p_j t), a mode at a time (a design's whole
    (samples x modes) table would take gigabytes at N = 64)."""
    y = np.zeros_like(t)
    for cj, pj in zip(c, p):
        y += cj * np.sin(pj * t)
    return y


def conclusion8(*, backend="compiled", **overrides) -> Study:
    """Conclusion 8: the first mode's share and the swings of the lower
    contact's response against its contact point x3/L3 (module doc);
    ``n_modes`` defaults to MODES."""
    refuse_fixed("conclusion8", overrides, FIXED)
    overrides.setdefault("n_modes", MODES)
    base = thesis_study_design(**overrides)
    ratios = RATIOS
    ev = evaluate_all(base.replace(x3=ratios * float(base.L3)), backend)
    c3 = np.nan_to_num(ev.c3)
    share = c3[:, 0]**2 / np.sum(c3**2, axis=1)
    p3 = np.asarray(ev.p3)[0]
    period = 2.0 * np.pi / p3[0]
    count = int(np.ceil(period * p3.max() / (2.0 * np.pi)
                        * SAMPLES_PER_PERIOD)) + 1
    t = np.linspace(0.0, period, count)
    maxima = np.array([count_maxima(y, PROMINENCE * np.abs(y).max())
                       for y in (_history(c, p3, t) for c in c3)])
    node = second_mode_node(str(base.end3))
    return Study(
        "conclusion8", "Conclusion 8: the lower contact's response against "
        "its contact point x3/L3", {
            "r": ratios, "x3_in": ratios * float(base.L3),
            "first_mode_share": share, "n_maxima": maxima,
            "y3_max_in": ev.y3_max},
        (f"second mode's node of the lower contact: x3/L3 = {node:.6f}",
         "first_mode_share: c3_1^2 / sum c3_j^2 of y3(x3, t) = sum c3_j "
         "sin(p3_j t) (eq. 23); 1 is a one-degree-of-freedom response",
         f"n_maxima: local maxima of y3 over the first mode's period "
         f"after the impact, prominence >= {PROMINENCE:g} of max |y3| "
         f"there",
         "model: eq. 23 (contactsep.model); units in each column's name",
         *design_lines(base, ("x3",)),
         "y3 > 0: the lower contact moves away from the separator; "
         "times from the impact"))
