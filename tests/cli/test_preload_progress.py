"""`contactsep preload --progress always`: the bar has a total from the
start and an ETA, names the phase running, and ends full at the number of
simulations the command reports in its CSV (one row a run, written from
the search's own log, not from the bar)."""

from __future__ import annotations

import re
import sys

import pytest

from contactsep.cli import main
from contactsep.runs import stops
from contactsep.studies.preload.verify import expected_runs
from contactsep.runs.stops import SearchProgress

tqdm = pytest.importorskip("tqdm").tqdm


@pytest.fixture
def shown_at_once(monkeypatch):
    """The command's bar without its one-second delay and with every
    update drawn (the planted searches take well under a second)."""
    monkeypatch.setattr(stops, "progress_bar", lambda total, enabled: tqdm(
        total=total, file=sys.stderr, mininterval=0, miniters=1))


class FakeBar:
    """What SearchProgress asks of a tqdm bar, recorded."""

    def __init__(self):
        self.n, self.total, self.unit, self.phases = 0, None, "", []
        self.closed = False

    def update(self, n):
        self.n += n

    def set_description_str(self, text, refresh=True):
        self.phases.append(text)

    def close(self):
        self.closed = True


def test_the_total_starts_at_the_estimate_and_grows_past_it():
    bar = FakeBar()
    progress = SearchProgress(bar, expected=10)
    assert (bar.total, bar.unit) == (10, "run")
    progress.planned("nominal", 4)
    progress(4)
    assert (bar.n, bar.total) == (4, 10)
    progress.planned("robust", 9)         # 13 asked: past the estimate
    assert bar.total == 13 and bar.phases == ["nominal", "robust"]
    progress(9)
    progress.close()
    assert bar.closed and (bar.n, bar.total) == (13, 13)


def test_an_estimate_too_high_ends_full_and_an_interrupted_bar_does_not():
    bar = FakeBar()
    progress = SearchProgress(bar, expected=100)
    progress.planned("nominal", 3)
    progress(3)
    progress.close()
    assert (bar.n, bar.total) == (3, 3)
    bar = FakeBar()
    progress = SearchProgress(bar, expected=100)
    progress.planned("nominal", 3)
    progress(2)
    progress.close(finished=False)
    assert (bar.n, bar.total) == (2, 100)


def test_the_estimate_counts_the_search_s_phases():
    """Counted from the search's definition: 1 ceiling run, 3 octaves of
    4 scan values, bisection from a 2^(1/4) step to 1 % (ceil(log2(
    ln 2^(1/4) / ln 1.01)) = 5 steps), the fine band from 0.7 to 2 times
    the answer at 0.99 % steps (ln(2/0.7)/ln 1.0099 = 106.6: 107 values
    with the ends) and the 2N check within 2 % (5 values)."""
    assert expected_runs(verify=False) == 1 + 12 + 5 + 107
    assert expected_runs() == 1 + 12 + 5 + 107 + 5


def _bar_lines(err: str) -> list:
    return [line for line in re.split(r"[\r\n]", err) if "run" in line
            and "/" in line]


def _csv_runs(path) -> int:
    rows = [line for line in path.read_text().splitlines()
            if line and not line.startswith("#")]
    return len(rows) - 1                     # the header


def test_the_command_s_bar_ends_at_its_simulations(planted_preload,
                                                   shown_at_once, tmp_path,
                                                   capsys):
    out = tmp_path / "p.csv"
    assert main(["preload", "--n-modes", "4", "--workers", "1",
                 "--progress", "always", "--csv", str(out)]) == 0
    err = capsys.readouterr().err
    lines = _bar_lines(err)
    assert lines, err
    done, total = map(int, re.search(r"(\d+)/(\d+)", lines[-1]).groups())
    assert done == total == _csv_runs(out)
    # the phases are named; no line ran past its total
    assert "nominal" in err and "verify" in err
    for line in lines:
        shown, of = map(int, re.search(r"(\d+)/(\d+)", line).groups())
        assert shown <= of, line
    assert re.search(r"<\d\d:\d\d", lines[-1]), lines[-1]


def test_the_robust_search_s_batches_grow_the_total(planted_preload,
                                                    shown_at_once, tmp_path,
                                                    capsys):
    out = tmp_path / "p.csv"
    assert main(["preload", "--n-modes", "4", "--workers", "1",
                 "--progress", "always", "--csv", str(out), "--tolerance",
                 "h2=normal(0.04,0.0004)", "--samples", "400",
                 "--no-converge"]) == 0
    err = capsys.readouterr().err
    assert "robust" in err
    done, total = map(int, re.search(
        r"(\d+)/(\d+)", _bar_lines(err)[-1]).groups())
    assert done == total > expected_runs()
