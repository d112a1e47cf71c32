"""Statistics the sweeps report: the Wilson score interval of a
proportion (the sweeps' p_exceed_ci95; the chatter sweeps' p_open_ci95)
and running moments of a stream of values (mean, sd, min, max).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: The standard normal's 97.5 % quantile: a two-sided 95 % interval.
Z95 = 1.959963984540054


def wilson_interval(successes: int, n: int, z: float = Z95
                    ) -> tuple[float, float]:
    """Wilson's score interval (Wilson 1927) for a proportion seen as
    ``successes`` out of ``n`` trials, at the two-sided level of the
    normal quantile ``z`` (default 95 %).

    Unlike the normal approximation p +- z sqrt(p(1-p)/n) it stays
    inside [0, 1] and is not empty at p = 0 or 1: with no design over
    the threshold in n, the interval is [0, z^2/(n + z^2)].
    """
    if n < 1 or not 0 <= successes <= n:
        raise ValueError(f"wilson_interval: need 0 <= successes <= n and "
                         f"n >= 1, found {successes} of {n}")
    z2 = z * z
    centre = (successes + z2 / 2) / (n + z2)
    half = z / (n + z2) * math.sqrt(successes * (n - successes) / n
                                    + z2 / 4)
    low = 0.0 if successes == 0 else max(0.0, centre - half)
    high = 1.0 if successes == n else min(1.0, centre + half)
    return low, high


@dataclass
class RunningMoments:
    """Count, mean, sample sd, min and max of values given chunk by chunk
    (:meth:`add`).  The sums are of the values less the first value seen,
    so that a mean far from zero with a small spread loses no digits to
    cancellation in the variance."""

    n: int = 0
    total: float = 0.0
    total_sq: float = 0.0
    low: float = math.inf
    high: float = -math.inf
    shift: float | None = None

    def add(self, values) -> None:
        values = np.asarray(values, dtype=float).ravel()
        if values.size == 0:
            return
        if self.shift is None:
            self.shift = float(values[0])
        d = values - self.shift
        self.n += values.size
        self.total += float(np.sum(d))
        self.total_sq += float(np.sum(d * d))
        self.low = min(self.low, float(values.min()))
        self.high = max(self.high, float(values.max()))

    @property
    def mean(self) -> float | None:
        """The mean (None without values)."""
        return self.shift + self.total / self.n if self.n else None

    @property
    def sd(self) -> float | None:
        """The sample standard deviation (None with fewer than 2)."""
        if self.n < 2:
            return None
        var = (self.total_sq - self.total**2 / self.n) / (self.n - 1)
        return math.sqrt(max(var, 0.0))
