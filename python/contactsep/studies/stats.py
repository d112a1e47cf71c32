"""Statistics the sweeps report: the Wilson score interval of a
proportion (the sweeps' p_exceed_ci95; the chatter sweeps' p_open_ci95)
and running moments of a stream of values (mean, sd, min, max).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

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


#: Values summed at a time by RunningMoments: its sums do not depend on
#: how the values were chunked (a resumed sweep's summary is the same bits
#: as an uninterrupted one's).
BLOCK = 65536


@dataclass
class RunningMoments:
    """Count, mean, sample sd, min and max of values given chunk by chunk
    (:meth:`add`), or of partial moments computed elsewhere
    (:meth:`merge`, a worker's chunk).  The sums are of the values less
    the first value seen, so that a mean far from zero with a small
    spread loses no digits to cancellation in the variance; values are
    summed BLOCK at a time whatever the chunks, so the same values in
    the same order give the same bits."""

    n: int = 0
    total: float = 0.0
    total_sq: float = 0.0
    low: float = math.inf
    high: float = -math.inf
    shift: float | None = None
    #: Values given and not yet summed (fewer than BLOCK).
    pending: list = field(default_factory=list, repr=False)
    _pending_n: int = field(default=0, repr=False)

    def add(self, values) -> None:
        values = np.asarray(values, dtype=float).ravel()
        if values.size == 0:
            return
        if self.shift is None:
            self.shift = float(values[0])
        self.pending.append(values)
        self._pending_n += values.size
        if self._pending_n >= BLOCK:
            joined = np.concatenate(self.pending)
            whole = joined.size - joined.size % BLOCK
            for start in range(0, whole, BLOCK):
                self._fold(joined[start:start + BLOCK])
            rest = joined[whole:].copy()
            self.pending = [rest] if rest.size else []
            self._pending_n = rest.size

    def _fold(self, values: np.ndarray) -> None:
        d = np.array(values) - self.shift     # a fresh, aligned array
        self.n += values.size
        self.total += float(np.sum(d))
        self.total_sq += float(np.sum(d * d))
        self.low = min(self.low, float(values.min()))
        self.high = max(self.high, float(values.max()))

    def _folded(self) -> "RunningMoments":
        """A copy with the pending values summed (the properties')."""
        copy = RunningMoments(self.n, self.total, self.total_sq, self.low,
                              self.high, self.shift)
        if self.pending:
            copy._fold(np.concatenate(self.pending))
        return copy

    def merge(self, other: "RunningMoments") -> None:
        """Add the values ``other`` has seen (Chan et al. 1979: its sums
        moved to this shift), as if given to :meth:`add` after these."""
        other = other._folded()
        if other.n == 0:
            return
        if self.shift is None:
            self.shift = other.shift
        delta = other.shift - self.shift
        self.n += other.n
        self.total += other.total + other.n * delta
        self.total_sq += (other.total_sq + 2.0 * delta * other.total
                          + other.n * delta * delta)
        self.low = min(self.low, other.low)
        self.high = max(self.high, other.high)

    def __getstate__(self) -> dict:
        """Pickled (a worker's partial moments) with its values summed."""
        return dict(self._folded().__dict__)

    @property
    def count(self) -> int:
        """Values seen (summed or pending)."""
        return self.n + self._pending_n

    @property
    def mean(self) -> float | None:
        """The mean (None without values)."""
        m = self._folded()
        return m.shift + m.total / m.n if m.n else None

    @property
    def sd(self) -> float | None:
        """The sample standard deviation (None with fewer than 2)."""
        m = self._folded()
        if m.n < 2:
            return None
        var = (m.total_sq - m.total**2 / m.n) / (m.n - 1)
        return math.sqrt(max(var, 0.0))

    @property
    def minimum(self) -> float:
        return self._folded().low

    @property
    def maximum(self) -> float:
        return self._folded().high
