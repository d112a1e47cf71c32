"""The preload command's error estimate (``min_preload_change``): the
answer at N checked at twice the modes and half the step around it, and
searched again there only where that check fails (docs/chatter.md,
"The preload command").

The check is the convergence check's (:func:`contactsep.studies.
preload_converge.window_answer`): at 2N, dt/2, every preload of the
fine grid (FINE_RATIO^j lb) within MARGIN (2 %) either side of the
answer, in one batch, four or five runs.  Where none from the answer to
2 % above it has an event and one within 2 % below has one, the
threshold at 2N, dt/2 lies in that window, and the answer at 2N
restricted to it (the smallest of those preloads above their highest
event) is ``verify_min_preload_lb``: ``min_preload_change`` is then
within 2 % by construction, resolved to the fine grid's 0.99 %.  A
window of events further above the answer at 2N is not seen by it, as
the convergence check does not see one (the whole search at 2N looked
to 2 times its answer).  Where the check fails (the threshold moved
more than about 2 %, or the answer is none or 0), the whole search at
2N, dt/2, as before: its answer and change are the whole search's.
"""

from __future__ import annotations

import math

from contactsep.studies.preload_converge import MARGIN, window_answer
from contactsep.studies.preload_search import PreloadSearch, fine_grid


def window_preloads(answer: float) -> list:
    """The fine grid's preloads within MARGIN either side of ``answer``
    lb."""
    return fine_grid(answer * (1.0 - MARGIN), answer * (1.0 + MARGIN))


def verify_search(has_event, answer: float, ceiling: float,
                  search_whole) -> tuple[PreloadSearch, bool]:
    """(the search at 2N, dt/2, whether it is the local check) for the
    answer ``answer`` lb at N.  ``has_event(preloads)``: whether each
    preload has an event at 2N, dt/2 (one batch); ``ceiling``: the
    largest preload that design takes; ``search_whole(known)``: the whole
    search there, given the runs already made (preload lb -> has an
    event), which it takes instead of running them again."""
    preloads = window_preloads(answer) if (
        math.isfinite(answer) and answer > 0.0) else []
    # a window cut by the ceiling cannot show that 2 % above is closed
    if not preloads or answer * (1.0 + MARGIN) > ceiling:
        return search_whole({}), False
    tested = tuple(zip(preloads, (bool(e) for e in has_event(preloads))))
    local = window_answer(answer, tested)
    if local is None:
        return search_whole(dict(tested)), False
    return PreloadSearch(min_preload_lb=local, tested=tested,
                         ceiling_lb=ceiling), True
