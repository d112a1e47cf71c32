"""The robust search's band from the top down (preload_search.search's
``band_batch``, preload_robust.ROBUST_BAND_BATCH): on any planted set of
events (a threshold and windows above it, at random) it gives the
answer of the whole band in one batch, the search the robust answers
before it used, trying a subset of that search's preloads; and where
the band finds a window high above the answer it tries fewer."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from contactsep.studies.preload import search as preload_search
from contactsep.studies.preload.robust import ROBUST_BAND_HIGH
from contactsep.studies.preload.search import fine_band, search


def _robust_band(row, answer):
    """The robust search's band: the fine grid above the answer to 1.5
    times it (preload_robust.robust_preload's, without nominal events)."""
    return [p for p in fine_band(answer)
            if answer < p <= ROBUST_BAND_HIGH * answer]


def _planted(rows):
    """has_event for rows of (threshold, [(lo, hi) windows]): an event
    below the threshold or inside a window; every call's preloads are
    recorded per row."""
    asked = [[] for _ in rows]

    def has_event(tasks):
        out = []
        for row, p in tasks:
            asked[row].append(p)
            threshold, windows = rows[row]
            out.append(p < threshold or any(lo <= p <= hi
                                            for lo, hi in windows))
        return out
    return has_event, asked


window = st.tuples(st.floats(1.0, 2.2), st.floats(0.0, 0.03))
row = st.tuples(st.floats(-6.0, 3.0),
                st.lists(window, min_size=0, max_size=4))


def _rows(drawn):
    """(threshold lb, windows lb) from (log2 threshold, [(ratio to the
    threshold, relative width)])."""
    out = []
    for log_threshold, windows in drawn:
        t = 2.0 ** log_threshold
        out.append((t, [(t * r, t * r * (1.0 + w)) for r, w in windows]))
    return out


@settings(max_examples=150, deadline=None)
@given(st.lists(row, min_size=1, max_size=3), st.integers(1, 6))
def test_from_the_top_gives_the_whole_bands_answer(drawn, batch):
    rows = _rows(drawn)
    whole_event, whole_asked = _planted(rows)
    whole = search(len(rows), whole_event, band=_robust_band)
    top_event, top_asked = _planted(rows)
    top = search(len(rows), top_event, band=_robust_band, band_batch=batch)
    for a, b, asked_a, asked_b in zip(whole, top, whole_asked, top_asked):
        assert b.min_preload_lb == a.min_preload_lb or (
            math.isnan(a.min_preload_lb) and math.isnan(b.min_preload_lb))
        # a subset of the preloads, each with the same outcome
        assert set(b.tested) <= set(a.tested)
        assert len(asked_b) == len(set(asked_b))      # none asked twice


def test_a_window_high_in_the_band_spares_the_preloads_below_it():
    """A threshold at 1 lb and a window at 1.4 lb, 1 % wide: both
    searches answer just above the window; the whole band tries every
    fine preload from the first answer up, the top-down band only those
    above the window (and its batch)."""
    rows = [(1.0, [(1.4, 1.414)])]
    whole_event, whole_asked = _planted(rows)
    whole, = search(1, whole_event, band=_robust_band)
    top_event, top_asked = _planted(rows)
    top, = search(1, top_event, band=_robust_band, band_batch=4)
    assert 1.414 < top.min_preload_lb == whole.min_preload_lb < 1.414 * 1.01
    below = [p for p in top_asked[0] if 1.01 < p < 1.4]
    assert len(below) <= 3          # the window's own batch at most
    assert len([p for p in whole_asked[0] if 1.01 < p < 1.4]) > 25
    assert len(top_asked[0]) < len(whole_asked[0]) - 25


def test_the_nominal_search_keeps_its_whole_band():
    """band_batch is the robust search's: the nominal search (band True)
    runs its band in one batch, below the answer too (its closed windows
    below are part of its answer)."""
    rows = [(1.0, [])]
    has_event, asked = _planted(rows)
    found, = search(1, has_event)
    assert min(asked[0]) < 0.71 * found.min_preload_lb
    assert preload_search.BAND_LOW == 0.7


@pytest.mark.parametrize("batch", [0, -1])
def test_a_batch_below_one_is_refused(batch):
    with pytest.raises(ValueError, match="band_batch"):
        search(1, _planted([(1.0, [])])[0], band=_robust_band,
               band_batch=batch)
