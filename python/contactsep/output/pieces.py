"""Long work cut into pieces by their measured time: the one sizing rule
of a sweep's chunks (:class:`contactsep.runs.chunks.Chunks`) and of a
large batch's pieces (:func:`contactsep.model.evaluate.evaluate`).

Python sees Ctrl-C and SIGTERM only between compiled calls, and a pool
stopped mid-sweep finishes the chunks it is running: so no piece should
take much more than :data:`PIECE_S`, whatever the model and N.  The
first piece is a guess from the modes (:func:`first_size`); each next
one follows the time per item measured so far, at most :data:`GROWTH`
times the one before (a slow start -- imports, page faults -- is
forgotten half way at each faster piece).  Results never depend on the
pieces.
"""

from __future__ import annotations

#: Seconds of work a piece is sized for.
PIECE_S = 0.5
#: Modes x items of the first piece, before any is timed.
FIRST_PIECE_COST = 4096
#: A piece is at most this many times the one before it.
GROWTH = 8


def first_size(modes: int, limit: int | None = None) -> int:
    """Items of the first piece of work at ``modes`` modes a design: a
    piece of about FIRST_PIECE_COST modes x designs, at least one, at
    most ``limit``."""
    size = max(1, FIRST_PIECE_COST // max(int(modes), 1))
    return size if limit is None else max(1, min(limit, size))


class PieceSizes:
    """The size of the next piece (``next``, items) from the pieces
    timed so far.

    Parameters
    ----------
    first : int
        The first piece's size (:func:`first_size`, or 1 for work whose
        items may each take seconds).
    limit : int, optional
        The most items a piece may hold (memory, a user's chunk size).

    Examples
    --------
    >>> sizes = PieceSizes(first=100)
    >>> sizes.record(100, 0.01)       # 0.1 ms an item: 0.5 s is 5,000
    >>> sizes.next                    # but at most 8 times the last
    800
    """

    def __init__(self, first: int, limit: int | None = None) -> None:
        self.limit = limit
        self.next = max(1, first if limit is None else min(limit, first))
        self._seconds_per_item = None

    @property
    def seconds_per_item(self) -> float:
        """The measured time an item (s; 1e-9 at least, so that a piece
        timed at 0 s does not ask for an unbounded next one); 0 before
        any piece is timed."""
        if self._seconds_per_item is None:
            return 0.0
        return max(self._seconds_per_item, 1e-9)

    def observe(self, items: int, seconds: float) -> None:
        """A piece of ``items`` took ``seconds``: the estimate follows a
        slower piece at once, a faster one half way."""
        rate = seconds / max(items, 1)
        if self._seconds_per_item is None or rate > self._seconds_per_item:
            self._seconds_per_item = rate
        else:
            self._seconds_per_item = 0.5 * (self._seconds_per_item + rate)

    def resize(self, target_s: float = PIECE_S) -> None:
        """Size the next piece for ``target_s`` seconds of work."""
        rate = self.seconds_per_item or 1e-9
        size = min(GROWTH * self.next, target_s / rate)
        if self.limit is not None:
            size = min(self.limit, size)
        self.next = int(max(1, size))

    def record(self, items: int, seconds: float,
               target_s: float = PIECE_S) -> None:
        """:meth:`observe`, then :meth:`resize` for ``target_s``."""
        self.observe(items, seconds)
        self.resize(target_s)
