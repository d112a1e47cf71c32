"""``contactsep study NAME --resume`` for the studies of three-beam
simulations (the preload chart, the conclusions, the recommendations,
the buttons): a study killed (SIGKILL, in a forked child: no clean-up)
and run again with --resume writes the CSV of an uninterrupted run and
simulates only what the killed run had not kept; SIGTERM says where the
runs are; --resume is refused where it has nothing to keep.

The simulations are planted (tests/planted_preload.py), as in
test_run_journal: what is tested is the bookkeeping of a resumed study,
not the physics."""

from __future__ import annotations

import os

import pytest
from forked import killed_at, terminated_then_resumed
from planted_preload import CALLS, fake_zero_preload

from contactsep.cli import main
from contactsep.cli.studies import RESUMABLE
from contactsep.studies.thesis import conclusions
from contactsep.runs.journal import RunJournal

STUDIES = {
    "preload": ["study", "preload", "--n-modes", "8", "--workers", "1",
                "--progress", "never"],
    "preload converged": ["study", "preload", "--n-modes", "8",
                          "--converge", "--workers", "1",
                          "--progress", "never"],
    "conclusion5": ["study", "conclusion5", "--n-modes", "8",
                    "--workers", "1", "--progress", "never"],
}


@pytest.fixture
def planted(planted_preload, monkeypatch):
    monkeypatch.setattr(conclusions, "_zero_preload", fake_zero_preload)


def _run(capsys, args) -> tuple[int, str, str]:
    status = main(list(args))
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def _killed_at(args, count: int) -> None:
    """Run the command in a forked child that SIGKILLs itself at the
    ``count``-th simulation it would keep."""
    killed_at(args, RunJournal, "record", count)


@pytest.mark.parametrize("name", list(STUDIES))
@pytest.mark.parametrize("part", [0.0, 0.5, 0.97])
def test_a_killed_study_resumes_to_the_same_csv(planted, tmp_path, capsys,
                                                name, part):
    command = STUDIES[name]
    reference = tmp_path / "reference.csv"
    CALLS.clear()
    status, table, err = _run(capsys, [*command, "--csv", str(reference)])
    assert status == 0, err
    total = len(CALLS)
    assert total > 30
    count = 1 + int(part * (total - 1))
    path = tmp_path / "s.csv"
    resumed = [*command, "--csv", str(path), "--resume"]
    _killed_at(resumed, count)
    assert not path.exists()
    lines = (tmp_path / ".s.csv.resume" / "runs.jsonl").read_text()
    assert len(lines.splitlines()) == count - 1
    CALLS.clear()
    status, out, err = _run(capsys, resumed)
    assert status == 0, err
    assert path.read_bytes() == reference.read_bytes()
    assert out == table
    assert len(CALLS) == total - (count - 1)
    if count > 1:
        assert err.startswith(f"contactsep: --resume: {count - 1:,} "
                              f"finished simulations in .s.csv.resume, "
                              f"not run again\n")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["reference.csv",
                                                           "s.csv"]


def test_resume_with_out_keeps_the_journal_beside_name_csv(planted,
                                                           tmp_path,
                                                           capsys):
    out = tmp_path / "figs"
    command = [*STUDIES["preload"], "--csv", str(tmp_path / "r.csv")]
    assert _run(capsys, command)[0] == 0
    pytest.importorskip("matplotlib")
    resumed = [*STUDIES["preload"], "--out", str(out), "--resume"]
    _killed_at(resumed, 20)
    assert len((out / ".preload.csv.resume" / "runs.jsonl").read_text()
               .splitlines()) == 19
    CALLS.clear()
    status, _, err = _run(capsys, resumed)
    assert status == 0, err
    assert (out / "preload.csv").read_bytes() == (tmp_path /
                                                  "r.csv").read_bytes()
    assert sorted(p.name for p in out.iterdir()) == ["preload.csv",
                                                     "preload.png"]


def test_a_changed_option_refuses_to_resume(planted, tmp_path, capsys):
    path = tmp_path / "s.csv"
    command = [*STUDIES["preload"], "--csv", str(path), "--resume"]
    _killed_at(command, 20)
    status, _, err = _run(capsys, [*command, "--damping", "flores"])
    assert status == 2
    assert err == (f"contactsep: error: --resume: the unfinished search in "
                   f"{path} (.s.csv.resume) was made with other inputs "
                   f"(inputs.damping differs); rerun without --resume, or "
                   f"remove it, to start afresh\n")
    assert _run(capsys, command)[0] == 0


def test_without_resume_a_leftover_journal_goes(planted, tmp_path, capsys):
    path = tmp_path / "s.csv"
    command = [*STUDIES["preload"], "--csv", str(path)]
    _killed_at([*command, "--resume"], 20)
    CALLS.clear()
    status, _, err = _run(capsys, command)
    assert status == 0, err
    assert len(CALLS) > 30            # nothing taken from the journal
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.csv"]


def test_sigterm_says_where_the_finished_simulations_are(planted,
                                                         tmp_path):
    """SIGTERM mid-study: no CSV, one line naming the journal, and the
    same command finishes it."""
    path = tmp_path / "s.csv"
    terminated_then_resumed(
        [*STUDIES["conclusion5"], "--csv", str(path), "--resume"], path, 12)


@pytest.mark.parametrize("argv, message", [
    (["study", "fig5", "--csv", "f.csv", "--resume"],
     "--resume: study fig5 runs no three-beam simulations to keep (it is "
     "for preload, conclusion3, conclusion5, conclusion6, conclusion7, "
     "contact-points, materials, buttons)"),
    (["study", "preload", "--resume"],
     "--resume keeps the finished simulations beside the output: give "
     "--csv or --out"),
    (["study", "preload", "--resume", "--png", "p.png"],
     "--resume keeps the finished simulations beside the output: give "
     "--csv or --out"),
    (["study", "preload", "--resume", "--csv", os.devnull],
     f"--resume keeps the finished simulations beside the output: "
     f"{os.devnull} is not a regular file")])
def test_resume_is_refused_where_it_keeps_nothing(planted, tmp_path,
                                                  capsys, monkeypatch,
                                                  argv, message):
    monkeypatch.chdir(tmp_path)
    status, _, err = _run(capsys, argv)
    assert status == 2
    assert err == f"contactsep: error: {message}\n"
    assert CALLS == [] and list(tmp_path.iterdir()) == []


def test_the_resumable_studies_are_those_of_simulations():
    """Every study that runs its simulations on a pool takes --resume:
    the list equals the registries it is written from."""
    from contactsep.studies.thesis.conclusions import STUDIES as CONCLUSIONS
    from contactsep.studies.thesis.recommendations import STUDIES as ADVICE
    assert set(RESUMABLE) == {"preload", "buttons", *CONCLUSIONS, *ADVICE}


def test_a_study_journal_kept_before_its_runs_were_typed_still_answers():
    """The thesis studies' runs became typed tasks; a journal names a run
    by the tuple it was handed before (key_tuple), so a journal kept by
    an earlier version is still answered from."""
    from contactsep.model.thesis_rig import thesis_design
    from contactsep.runs.task_keys import task_key
    from contactsep.studies.thesis import (
        buttons,
        conclusions,
        contact_points,
        materials,
    )
    design, settings = thesis_design(), {"t_end": 0.01}
    law = {"nu": 0.3}
    pairs = [
        (contact_points._opening, contact_points.OpeningRun(
            design, 6.0, settings), (design, 6.0, settings)),
        (materials._run, materials.MaterialsRun(design, 6.0, law, settings),
         (design, 6.0, law, settings)),
        (conclusions._zero_preload, conclusions.FreeRun(
            design, "hertz", settings), (design, "hertz", settings)),
        (buttons._zero_preload, buttons.ButtonRun(design, settings),
         (design, settings)),
    ]
    for function, typed, plain in pairs:
        assert task_key(function, typed) == task_key(function, plain)
    # and a different run is a different key
    assert task_key(contact_points._opening, contact_points.OpeningRun(
        design, 0.0, settings)) != task_key(contact_points._opening,
                                            (design, 6.0, settings))
