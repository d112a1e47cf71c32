"""`contactsep chatter` lists the summary and at most the first ten
circuit openings (issue 30 item 6); --events all lists every one, and
the JSON and CSV always hold them all."""

from __future__ import annotations

import json
import re

import pytest

from contactsep.cli import main

#: A run with more than ten openings (the thesis rig at N = 8, 15 of
#: them; counted from the JSON, the other output), every setting given.
ARGV = ["chatter", "--model", "hertz", "--n-modes", "8", "--dt", "5e-8",
        "--t-end", "0.06", "--preload", "0"]


def listed(out: str) -> list[str]:
    return re.findall(r"^  [* ] +\S+ to +\S+", out, flags=re.M)


@pytest.fixture(scope="module")
def openings():
    import contextlib
    import io
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main([*ARGV, "--json"]) == 0
    count = len(json.loads(buffer.getvalue())["circuit_open_intervals"])
    assert count > 10, "the case must have more than ten openings"
    return count


def test_the_text_lists_at_most_ten_openings(openings, capsys):
    assert main(ARGV) == 0
    out = capsys.readouterr().out
    assert len(listed(out)) == 10
    assert f"... {openings - 10} more (--events all" in out


@pytest.mark.parametrize("events, expected", [("all", None), ("3", 3),
                                              ("0", 0)])
def test_events_sets_how_many(events, expected, openings, capsys):
    assert main([*ARGV, "--events", events]) == 0
    out = capsys.readouterr().out
    assert len(listed(out)) == (openings if expected is None else expected)
    assert ("more (--events all" in out) == (expected is not None)


def test_a_bad_events_value_is_one_line(capsys):
    assert main([*ARGV, "--events", "many"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--events: found 'many'" in err
