"""`study chatter|preload|conclusionN --progress` (issue 30 item 6): a
bar of the simulations on stderr when asked, none when not, closed
after the study."""

from __future__ import annotations

import argparse

import pytest

from contactsep.cli import build_parser
from contactsep.cli.studies import _bar

pytest.importorskip("tqdm")


def test_always_draws_a_bar_that_counts_and_closes(capsys):
    with _bar(argparse.Namespace(progress="always"), 3) as update:
        for _ in range(3):
            update(1)
    err = capsys.readouterr().err
    assert "3/3" in err and "simulations" in err


@pytest.mark.parametrize("choice", ["never", "auto"])
def test_never_and_auto_off_a_terminal_draw_nothing(choice, capsys):
    with _bar(argparse.Namespace(progress=choice), 3) as update:
        assert update is None
    assert capsys.readouterr().err == ""


def test_study_takes_the_option():
    study = build_parser()._subparsers._group_actions[0].choices["study"]
    args = study.parse_args(["chatter", "--progress", "never"])
    assert args.progress == "never"
    with pytest.raises(Exception):
        study.parse_args(["chatter", "--progress", "sometimes"])
