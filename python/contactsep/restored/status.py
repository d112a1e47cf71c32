"""Status codes of the restored core, mirrored from their one home,
fortran/restored/status.f90 (pinned by tests/shared/test_constants.py).
"""

#: Success.
OK = 0
#: Card reader: no data set is left (only blank lines remain).
END_OF_DECK = 1
#: An argument is outside its documented range (a caller's mistake).
BAD_ARGUMENT = 2
#: A field holds text that its FORMAT cannot read as a number.
CARD_NOT_NUMERIC = 10
#: A field reads as NaN or Infinity (or overflows the working precision).
CARD_NOT_FINITE = 11
#: A line is longer than the 80 columns of a card.
CARD_TOO_LONG = 12
#: A line holds a TAB character, which has no column on a card.
CARD_HAS_TAB = 13
#: The deck ends inside a data set (fewer than 6 + 3N cards).
DECK_TRUNCATED = 14
#: Card 5 gives a number of modes N below 1.
NO_MODES = 15
#: N is larger than the caller's max_modes.
TOO_MANY_MODES = 16
#: A line holds a character other than printable ASCII (a stray CR,
#: a NUL, a form feed, a non-ASCII byte).
CARD_NOT_PRINTABLE = 17
#: A value lies outside the range the listing needs (a length that is
#: not positive, ER outside [0, 1], ...; see contactsep_validation).
OUT_OF_RANGE = 18
#: The tip sum at T = 0 is not above DELY: the search has no start.
RELEASE_NOT_ABOVE = 20
#: T + DELT == T: the impact search cannot advance in this precision.
SEARCH_STALLED = 21
#: The tip sum or DELY is NaN or infinite: no crossing can be found.
SEARCH_NOT_FINITE = 22
#: No impact within max_trace trace lines (the tip may never reach
#: DELY), or no room for the trace lines of one.
TRACE_FULL = 23
#: T + DELT does not advance T in the history loop (DELT <= 0 or tiny).
HISTORY_STALLED = 24
#: The history up to TAU needs more than max_history lines.
HISTORY_FULL = 25
#: The listing needs more than max_listing bytes.
LISTING_FULL = 26
#: A work array could not be allocated.
OUT_OF_MEMORY = 27
#: An internal WRITE of a listing record failed.
FORMAT_FAILED = 28
