"""Where the two contacts touch the separator (issue 28, item 4): the
upper contact at ``Design.x2``, the lower one at ``Design.x2_lower``
(None: at x2, the thesis's single point).  Functions take a Design
(duck-typed: design.py imports this module)."""

from __future__ import annotations

import numpy as np

from contactsep import beams


def lower_point_problem(design, clearance: float) -> str | None:
    """x2_lower: None, or one finite number inside the separator's span,
    at least ``clearance`` L2 from a clamped end (the rule of x2,
    design.SUPPORT_CLEARANCE; checked where L2 and end2 are single
    values); the message, or None."""
    value = design.x2_lower
    if value is None:
        return None
    if isinstance(value, (bool, np.bool_, str)) or np.ndim(value) != 0 \
            or np.asarray(value).dtype.kind not in "iuf":
        return (f"x2_lower: found {value!r}, expected one number (in; "
                f"None: x2) shared by a batch")
    x = float(value)
    length, end = np.asarray(design.L2), np.asarray(design.end2)
    if length.ndim or end.ndim or not np.isfinite(float(length)):
        return None if np.isfinite(x) else \
            f"x2_lower: found {x!r}, expected a finite number (in)"
    length = float(length)
    end = beams.ALIASES.get(str(end), str(end))
    low = 0.0 if end == "pinned-pinned" else clearance * length
    high = length - clearance * length if end == "clamped-clamped" \
        else length
    free = end == "clamped-free"
    if np.isfinite(x) and low < x and (x < high or (free and x <= high)):
        return None
    return (f"x2_lower: found {x!r}, expected {low:.6g} < x2_lower "
            f"{'<=' if free else '<'} {high:.6g} in: inside the span of "
            f"the {end} separator (end2), at least "
            f"{clearance:g} L2 from a clamped end")


def separator_points(design) -> tuple[float, float]:
    """(x2, x2_lower) of a single design, in: where the upper and the
    lower contact touch the separator, defaults resolved (mid-span;
    x2_lower = x2)."""
    x2 = float(design.L2) / 2.0 if design.x2 is None else float(design.x2)
    lower = x2 if design.x2_lower is None else float(design.x2_lower)
    return x2, lower


def lower_point_differs(design) -> bool:
    """True where the lower contact touches the separator elsewhere than
    the upper one (x2_lower given and not x2, in any design of a
    batch)."""
    if design.x2_lower is None:
        return False
    x2 = np.asarray(design.L2, dtype=np.float64) / 2.0 \
        if design.x2 is None else np.asarray(design.x2, dtype=np.float64)
    return bool(np.any(x2 != float(design.x2_lower)))
