"""Preload searches that survive being killed (``contactsep preload
--csv F --resume``, ``contactsep.preload(..., journal=DIR)``; issue 25's
multi-hour robust searches): a search killed (SIGKILL, in a forked
child: no clean-up of any kind) at several points and run again with
--resume ends with the CSV and JSON of an uninterrupted run and
simulates only what the killed run had not finished; a line cut by the
kill is dropped; a changed input is refused; the journal's digests tell
equal tasks from different ones.

The simulations are planted (tests/planted_preload.py: a known
threshold, a known tolerance study), as in test_design_preload: what is
tested is that a resumed search asks for and receives the same results,
not the physics."""

from __future__ import annotations

import json
import os
import signal
import sys

import numpy as np
import pytest
from design_family import FAMILY
from forked import killed_at, sigkill, terminated_then_resumed
from planted_preload import CALLS, fake_event, fake_sample

from contactsep.cli import main
from contactsep.errors import InputError
from contactsep.studies.preload import command as design_preload
from contactsep.studies.preload.chart import Simulations
from contactsep.runs.journal import ResumeError
from contactsep.runs.journal import RunJournal
from contactsep.runs.task_keys import task_key

COMMAND = ["preload", "--n-modes", "8", "--workers", "1", "--json",
           "--tolerance", "d=uniform(0.2,0.3)", "--samples", "20",
           "--p-target", "0.2", "--progress", "never"]


def _run(capsys, args) -> tuple[int, str, str]:
    status = main(list(args))
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def _cut_and_kill(self, args) -> None:
    """Half of the line of the run being kept, then SIGKILL."""
    key, _ = args
    self._file.write('{"key": "' + key[:20])
    self._file.flush()
    sigkill(self, args)


def _killed_at(args, count: int, cut: bool = False) -> None:
    """Run the command in a forked child that SIGKILLs itself at the
    ``count``-th simulation it would keep (``cut``: after writing half
    of that one's line)."""
    killed_at(args, RunJournal, "record", count,
              _cut_and_kill if cut else sigkill)


@pytest.fixture
def uninterrupted(planted_preload, tmp_path, capsys):
    """The command's CSV bytes, JSON and simulation count, run without
    --resume, and the count of simulations each search ran, in the
    order they run (the CSV's rows: one a simulation, a robust one a
    preload of up to 20 samples, its n and n_failed those that ran; the
    convergence check's runs lie between the repeat at 2N and the robust
    search)."""
    path = tmp_path / "reference.csv"
    CALLS.clear()
    status, out, err = _run(capsys, [*COMMAND, "--csv", str(path)])
    assert status == 0, err
    rows = [line.split(",") for line in path.read_text().splitlines()
            if not line.startswith("#")][1:]
    searches = {name: [r[0] for r in rows].count(name) for name in (
        "nominal", "verify", "converge", "robust", "robust_check")}
    for name in ("robust", "robust_check"):
        searches[f"{name}_runs"] = sum(int(r[2]) + int(r[4]) for r in rows
                                       if r[0] == name)
    return path.read_bytes(), json.loads(out), len(CALLS), searches


#: Where the child is killed: the simulation of that rank (1-based) it
#: was about to keep, from the searches' sizes.
WHERE = {"before the first": lambda s: 1,
         "in the nominal search": lambda s: s["nominal"] // 2,
         "in the repeat at 2N": lambda s: s["nominal"] + s["verify"] // 2,
         "in the robust search": lambda s: s["total"] - s[
             "robust_check_runs"] - s["robust_runs"] // 2,
         "in the robust answer's check": lambda s: s["total"] - s[
             "robust_check_runs"] // 2}


@pytest.mark.parametrize("where, cut", [
    ("before the first", False), ("in the nominal search", False),
    ("in the nominal search", True), ("in the repeat at 2N", False),
    ("in the robust search", False), ("in the robust search", True),
    ("in the robust answer's check", False)])
def test_a_killed_search_resumes_to_the_same_answer_and_csv(
        tmp_path, capsys, uninterrupted, where, cut):
    """Killed before it kept a simulation, in the nominal search, in its
    repeat at 2N, in the robust search (with half a line written, too),
    in the robust answer's check at 2N:
    the resumed run's CSV equals the uninterrupted run's byte for byte,
    its JSON the same, and it simulates exactly what the killed run had
    not kept."""
    reference, answer, total, searches = uninterrupted
    assert searches["nominal"] > 50 and searches["verify"] > 50
    # every simulation is in the CSV: the check at 4N's too (a few)
    assert 0 < searches["converge"] < 10
    assert searches["nominal"] + searches["verify"] + searches[
        "converge"] + searches["robust_runs"] + searches[
        "robust_check_runs"] == total
    assert searches["robust"] > 10 and searches["robust_check"] == 5
    count = WHERE[where]({**searches, "total": total})
    path = tmp_path / "p.csv"
    command = [*COMMAND, "--csv", str(path), "--resume"]
    _killed_at(command, count, cut)
    journal = tmp_path / ".p.csv.resume"
    lines = (journal / "runs.jsonl").read_text().splitlines()
    whole = [line for line in lines if line.endswith("}")]
    assert len(whole) == count - 1
    assert len(lines) == len(whole) + cut
    CALLS.clear()
    status, out, err = _run(capsys, command)
    assert status == 0, err
    assert path.read_bytes() == reference
    assert json.loads(out) == answer
    assert len(CALLS) == total - (count - 1)
    if count > 1:
        assert err.startswith(f"contactsep: --resume: {count - 1:,} "
                              f"finished simulations in .p.csv.resume, "
                              f"not run again\n")
    # nothing left beside the CSV: no journal, lock or temporary file
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.csv",
                                                           "reference.csv"]


def test_a_changed_input_refuses_to_resume(planted_preload, tmp_path,
                                           capsys):
    path = tmp_path / "p.csv"
    command = [*COMMAND, "--csv", str(path), "--resume"]
    _killed_at(command, 30)
    status, _, err = _run(capsys, [*command, "--seed", "1"])
    assert status == 2
    assert err == (f"contactsep: error: --resume: the unfinished search in "
                   f"{path} (.p.csv.resume) was made with other inputs "
                   f"(inputs.seed differs); rerun without --resume, or "
                   f"remove it, to start afresh\n")
    assert len((tmp_path / ".p.csv.resume" / "runs.jsonl").read_text()
               .splitlines()) == 29
    status, _, err = _run(capsys, command)
    assert status == 0, err


def test_without_resume_a_leftover_journal_goes_once_the_csv_is_written(
        planted_preload, tmp_path, capsys):
    path = tmp_path / "p.csv"
    command = [*COMMAND, "--csv", str(path)]
    _killed_at([*command, "--resume"], 30)
    CALLS.clear()
    status, _, err = _run(capsys, command)
    assert status == 0, err
    assert len(CALLS) > 200         # nothing taken from the journal
    assert sorted(p.name for p in tmp_path.iterdir()) == ["p.csv"]


@pytest.mark.parametrize("argv, message", [
    ([], "--resume keeps the finished simulations beside the output: give "
         "--csv"),
    (["--csv", os.devnull], "--resume keeps the finished simulations "
                            f"beside the output: {os.devnull} is not a "
                            f"regular file")])
def test_resume_needs_a_csv_file(planted_preload, capsys, argv,
                                 message):
    status, _, err = _run(capsys, [*COMMAND, "--resume", *argv])
    assert status == 2
    assert err == f"contactsep: error: {message}\n"
    assert CALLS == []


def test_a_refused_command_leaves_no_journal(planted_preload, tmp_path,
                                             capsys):
    path = tmp_path / "p.csv"
    status, _, err = _run(capsys, [*COMMAND, "--csv", str(path), "--resume",
                                   "--perturbation", "0.5"])
    assert status == 2 and err.startswith("contactsep: error: "
                                          "--perturbation: found")
    assert list(tmp_path.iterdir()) == []


def test_a_second_command_on_the_same_journal_is_refused(tmp_path):
    with RunJournal(tmp_path / "j", {"a": 1}, label="p.csv"):
        with pytest.raises(InputError, match=r"^p\.csv: in use: another "
                                             r"contactsep command"):
            RunJournal(tmp_path / "j", {"a": 1}, label="p.csv")
    with RunJournal(tmp_path / "j", {"a": 1}) as again:
        assert len(again) == 0


def test_the_api_leaves_the_journal_for_the_caller(planted_preload,
                                                   tmp_path):
    design = FAMILY["steel_relay"].replace(n_modes=8)
    first = design_preload.preload(design, workers=1, verify=False,
                                   journal=tmp_path / "j")
    simulated = len(CALLS)
    assert len((tmp_path / "j" / "runs.jsonl").read_text().splitlines()) \
        == simulated == first.simulations
    again = design_preload.preload(design, workers=1, verify=False,
                                   journal=str(tmp_path / "j"))
    assert len(CALLS) == simulated            # every run from the journal
    assert again == first
    with pytest.raises(ResumeError, match="inputs.verify differs"):
        design_preload.preload(design, workers=1, journal=tmp_path / "j")


def double(task):
    CALLS.append(("double", task))
    return (task, 2 * task, np.int64(task) * 3)


def refuse(task):
    raise AssertionError(f"ran {task} again")


@pytest.mark.parametrize("workers", [1, 2])
def test_simulations_keep_each_result_and_run_only_the_new_ones(
        tmp_path, workers):
    tasks = [3, 1, 4, 1, 9]
    with RunJournal(tmp_path / "j", {}) as journal, \
            Simulations(workers, journal=journal) as sims:
        assert sims.map(double, tasks) == [(t, 2 * t, 3 * t) for t in tasks]
        assert journal.recorded == 5 and journal.reused == 0
    with RunJournal(tmp_path / "j", {}) as journal:
        assert len(journal) == 4      # 1 twice: one simulation
        # the function named in the key: another one's results are not
        # these
        assert not journal.lookup(task_key(refuse, 3))[0]
        with Simulations(workers, journal=journal) as sims:
            out = sims.map(double, [9, 3, 2])
        assert out[0] == (9, 18, 27) and out[1] == (3, 6, 9)
        assert journal.reused == 2 and journal.recorded == 1
        assert sims.runs == 3


def test_the_digest_tells_equal_tasks_from_different_ones():
    design = FAMILY["becu_light"]
    base = (design, "hertz", {"dt": 1e-8, "t_end": 0.01}, 0.05)
    key = task_key(fake_event, base)
    # equal values, other objects and types: the same simulation
    assert key == task_key(fake_event, (
        design.replace(n_modes=design.n_modes), "hertz",
        {"t_end": np.float64(0.01), "dt": 1e-8}, np.float64(0.05)))
    # one bit of the preload, a setting, a field, the model, the function
    for other in ((design, "hertz", {"dt": 1e-8, "t_end": 0.01},
                   np.nextafter(0.05, 1.0)),
                  (design, "hertz", {"dt": 1e-8, "t_end": 0.011}, 0.05),
                  (design.replace(ys=design.ys * (1 + 1e-15)), "hertz",
                   {"dt": 1e-8, "t_end": 0.01}, 0.05),
                  (design, "newton", {"dt": 1e-8, "t_end": 0.01}, 0.05)):
        assert task_key(fake_event, other) != key
    assert task_key(fake_sample, base) != key


def test_sigterm_says_where_the_finished_simulations_are(planted_preload,
                                                         tmp_path):
    """SIGTERM mid-search (the command's own handler: exit 143): no CSV,
    one line on stderr naming the journal and what it holds, and the
    same command with --resume finishes it."""
    path = tmp_path / "p.csv"
    terminated_then_resumed([*COMMAND, "--csv", str(path), "--resume"],
                            path, 25)


def test_a_real_search_killed_on_two_workers_resumes_to_the_same_bytes(
        tmp_path):
    """The real simulation on two worker processes (the thesis rig,
    d = 0.75 in, N = 2, a 30 ms window: its first impact at 22 ms, so
    the search, its repeat at 2N, the convergence check, the robust
    search of 3 samples and its check all run): the command SIGKILLed
    once its journal holds 150 runs, then run again with --resume, ends
    with the CSV and JSON bytes of an uninterrupted run."""
    import subprocess
    import time
    command = [sys.executable, "-m", "contactsep", "preload", "--n-modes",
               "2", "--d", "0.75", "--t-end", "0.03", "--workers", "2",
               "--tolerance", "d=normal(0.75,0.005)", "--samples", "3",
               "--p-target", "0.6", "--json", "--progress", "never"]
    reference = subprocess.run([*command, "--csv", str(tmp_path / "r.csv")],
                               capture_output=True, timeout=600)
    assert reference.returncode == 0, reference.stderr
    path, runs = tmp_path / "p.csv", tmp_path / ".p.csv.resume/runs.jsonl"
    child = subprocess.Popen([*command, "--csv", str(path), "--resume"],
                             stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 300
        while child.poll() is None and time.monotonic() < deadline and (
                not runs.exists() or runs.read_text().count("\n") < 150):
            time.sleep(0.05)
    finally:
        child.kill()
        child.wait()
    assert child.returncode == -signal.SIGKILL
    kept = runs.read_text().count("\n")
    assert kept >= 150
    again = subprocess.run([*command, "--csv", str(path), "--resume"],
                           capture_output=True, timeout=600)
    assert again.returncode == 0, again.stderr
    assert again.stderr.decode().startswith(
        f"contactsep: --resume: {kept} finished simulations")
    assert path.read_bytes() == (tmp_path / "r.csv").read_bytes()
    assert again.stdout == reference.stdout
    data = json.loads(again.stdout)
    assert data["robust"]["checked"] and data["simulations"] > kept


def test_a_journal_made_by_other_code_is_refused(planted_preload, tmp_path,
                                                 capsys, monkeypatch):
    path = tmp_path / "p.csv"
    command = [*COMMAND, "--csv", str(path), "--resume"]
    _killed_at(command, 30)
    from contactsep.runs import code_digest
    original = code_digest.code_digest
    monkeypatch.setattr(code_digest, "code_digest", lambda *a: "0" * 64)
    status, _, err = _run(capsys, command)
    assert status == 2
    assert err == (f"contactsep: error: --resume: the unfinished search in "
                   f"{path} (.p.csv.resume) was made with other inputs "
                   f"(code_sha256 differs); rerun without --resume, or "
                   f"remove it, to start afresh\n")
    monkeypatch.setattr(code_digest, "code_digest", original)
    status, _, err = _run(capsys, command)
    assert status == 0, err
