"""How a sweep is cut into chunks: by the measured cost of a design, so
that a chunk takes a fraction of a second whatever the model and N, and
every worker gets many of them."""

from __future__ import annotations

from contactsep.output.pieces import PIECE_S, PieceSizes, first_size

#: Chunks each worker gets of the work left, at least, while a chunk
#: stays above MIN_CHUNK_S (Chunks); otherwise a chunk is sized for
#: contactsep.output.pieces.PIECE_S, the one rule of timed pieces.
CHUNKS_PER_WORKER = 20
MIN_CHUNK_S = 0.2
#: The least seconds of a pack of simulations on Dask
#: (:mod:`contactsep.runs.dask_packs`): a batch's packs are all of
#: what is left, so MIN_CHUNK_S would leave workers idle; ten times the
#: parent's few milliseconds a task.
MIN_PACK_S = 0.05
#: Bytes a chunk's per-mode arrays may take.
CHUNK_MEMORY = 64 << 20


def chunk_seconds(left_s: float, workers: int,
                  least: float = MIN_CHUNK_S) -> float:
    """The one rule of a chunk's seconds: PIECE_S while much work is
    left (``left_s`` seconds of it), and each of ``workers`` a
    CHUNKS_PER_WORKER share of what is left towards the end, down to
    ``least`` seconds."""
    return min(PIECE_S, max(least, left_s / (CHUNKS_PER_WORKER
                                             * max(1, workers))))


class Chunks:
    """(first, last) of each chunk, sized by cost rather than count, so
    that a chunk takes about PIECE_S whatever N is (a signal is
    acted on between chunks, and a stopped pool finishes its running
    ones), each of ``workers`` gets at least CHUNKS_PER_WORKER of what
    is left (down to MIN_CHUNK_S a chunk: the last chunks keep every
    worker busy) and its per-mode arrays stay within CHUNK_MEMORY: at
    most ``chunk_size`` designs, the first few a guess from N, the
    others from the time per design measured so far (:meth:`record`).
    ``stored`` (first -> last) are chunks already computed (a resumed
    sweep): they are given as they are, and the new chunks fill the
    gaps.  The rows and counts do not depend on the chunking; merged
    means and standard deviations do to their last bits (the merge
    rounds differently for another partition)."""

    def __init__(self, size: int, chunk_size: int, modes: int,
                 costly: bool = False, workers: int = 1,
                 stored: dict | None = None) -> None:
        self.size = size
        self.workers = max(1, workers)
        self.stored = dict(stored or {})
        # the kernel's per-mode arrays: p1, p2, p3, c3 (8 bytes each)
        per_design = 8 * (4 * modes + 64)
        self.limit = max(1, min(chunk_size, CHUNK_MEMORY // per_design))
        # a design that may take seconds (model.evaluate.costly): one
        self._sizes = PieceSizes(1 if costly else first_size(modes),
                                 self.limit)
        self._position = 0

    @property
    def next(self) -> int:
        """Designs of the next new chunk."""
        return self._sizes.next

    @next.setter
    def next(self, designs: int) -> None:
        self._sizes.next = designs

    def record(self, designs: int, seconds: float) -> None:
        """A chunk of ``designs`` took ``seconds``: size the next ones,
        for PIECE_S each while much work is left, and for the workers'
        CHUNKS_PER_WORKER shares of what is left (down to MIN_CHUNK_S)
        towards the end."""
        self._sizes.observe(designs, seconds)
        left = (self.size - self._position) * self._sizes.seconds_per_item
        self._sizes.resize(chunk_seconds(left, self.workers))

    def __iter__(self):
        """(first, last) of each chunk, in order."""
        for first, last, _ in self.plan():
            yield first, last

    def plan(self):
        """(first, last, stored) of each chunk, in order."""
        starts = sorted(self.stored)
        first = 0
        while first < self.size:
            if first in self.stored:
                last = self.stored[first]
                self._position = last
                yield first, last, True
                first = last
                continue
            later = [s for s in starts if s > first]
            last = min(first + self.next, self.size,
                       later[0] if later else self.size)
            self._position = last
            yield first, last, False
            first = last
