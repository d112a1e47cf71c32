"""`study chatter|preload|conclusionN --progress` (issue 30 item 6): a
bar of the simulations on stderr when asked, none when not, closed
after the study."""

from __future__ import annotations

import argparse

import pytest

from contactsep.cli import build_parser
from contactsep.cli.study_runs import study_bar

pytest.importorskip("tqdm")


def test_always_draws_a_bar_that_counts_and_closes(monkeypatch):
    # (the bar shows itself once the study has taken a second); no
    # monitor thread, which would outlive the test and keep later tests'
    # long calls from forking (output.interruptible)
    import tqdm
    monkeypatch.setattr(tqdm.tqdm, "monitor_interval", 0)
    with study_bar(argparse.Namespace(progress="always"), 3) as update:
        bar = update.__self__
        for _ in range(3):
            update(1)
        assert (bar.n, bar.total, bar.unit) == (3, 3, " simulations")
        assert not bar.disable
    assert bar.disable                 # closed


@pytest.mark.parametrize("choice", ["never", "auto"])
def test_never_and_auto_off_a_terminal_draw_nothing(choice, capsys):
    with study_bar(argparse.Namespace(progress=choice), 3) as update:
        assert update is None
    assert capsys.readouterr().err == ""


def test_study_takes_the_option():
    study = build_parser()._subparsers._group_actions[0].choices["study"]
    args = study.parse_args(["chatter", "--progress", "never"])
    assert args.progress == "never"
    with pytest.raises(Exception):
        study.parse_args(["chatter", "--progress", "sometimes"])
