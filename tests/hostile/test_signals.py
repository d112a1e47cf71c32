"""Deaf to signals (issue 18, class 3): Ctrl-C ends every command with
status 130 and SIGTERM with 143 within seconds, however long its work,
quietly (at most one line), leaving no process behind.

A compiled call cannot be interrupted from Python: the model's batches
are evaluated in pieces of about 0.5 s, a sweep's chunks are sized by
cost, and a long chatter run goes to a child process the parent kills."""

from __future__ import annotations

import importlib
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from kept_chunks import kept_designs

from contactsep import output
from contactsep.errors import InputError
from contactsep.model import evaluate, thesis_design

evaluate_module = importlib.import_module("contactsep.model.evaluate")
pieces_module = importlib.import_module("contactsep.output.pieces")

#: Seconds a command may take to stop after the signal: a few, on a
#: machine that other test runs share.
PROMPT = 5.0


def _stop(args, signum, after, tmp_path, group):
    """Start ``contactsep ARGS``, send ``signum`` ``after`` seconds later
    (to its process group, as a terminal does, or to it alone, as kill
    does); return (status, seconds to stop, stderr)."""
    process = subprocess.Popen(
        [sys.executable, "-m", "contactsep", *args], cwd=tmp_path,
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        start_new_session=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    time.sleep(after)
    assert process.poll() is None, "finished before the signal"
    sent = time.monotonic()
    if group:
        os.killpg(process.pid, signum)
    else:
        process.send_signal(signum)
    err = process.communicate(timeout=120)[1]
    took = time.monotonic() - sent
    # no child left behind (a killed one is reaped by init: a moment)
    deadline = time.monotonic() + PROMPT
    while True:
        try:
            os.killpg(process.pid, 0)
        except ProcessLookupError:
            break
        assert time.monotonic() < deadline, "a process outlived the command"
        time.sleep(0.1)
    return process.returncode, took, err


CTRL_C = (signal.SIGINT, 130, True)      # to the group, as a terminal
SIGTERM = (signal.SIGTERM, 143, False)    # to the command, as kill does
#: (command, seconds it runs before the signal, signal): each ran for
#: minutes, deaf, inside one compiled call (the chatter runs), or
#: between whole chunks and calls (study, sweep).  Each command with the
#: other signal: under -m slow.
LONG = [
    # (the thesis's step, a longer window: the designs' own at N = 1024 are
    # past the work budget, refused at once; 0.06 s now takes under 2 s)
    (["chatter", "--model", "hertz", "--n-modes", "1024", "--dt", "5e-8",
      "--t-end", "0.15"], 2.0, SIGTERM),
    (["chatter", "--model", "newton", "--n-modes", "1024", "--dt", "5e-8",
      "--t-end", "0.15"], 2.0, CTRL_C),
    (["chatter", "--model", "appE", "--n-modes", "128"], 2.0, CTRL_C),
    (["study", "fig5", "--n-modes", "100000"], 2.0, CTRL_C),
    # 1e5 designs: about 8 minutes on 2 cores (1000 took 4.6 s on a
    # loaded machine, 3 s was too close)
    (["sweep", "--vary", "h2=0.1:0.5:100000", "--n-modes", "300",
      "--workers", "2", "--csv", "s.csv"], 3.0, SIGTERM),
    # designs of seconds each (issue 17's search over a long window)
    # tau = 1e6 s: ~14 s (1e5 s took 1.9 s, too close to the signal)
    (["model", "--tau", "1e6"], 1.5, SIGTERM),
    (["sweep", "--vary", "h2=0.1:0.5:1000", "--tau", "1e4", "--workers",
      "2", "--csv", "s.csv"], 3.0, SIGTERM),
    # issue 16: the preload chart's batches on worker processes (killed
    # when stopped), a chatter sweep of pressed designs (~0.15 s each)
    (["study", "preload", "--n-modes", "64"], 3.0, CTRL_C),
    (["sweep", "--model", "hertz", "--vary", "h2=0.1:0.5:100", "--n-modes",
      "32", "--preload", "5", "--workers", "2", "--csv", "s.csv"], 3.0,
     SIGTERM),
]
OTHER = [pytest.param(args, after, CTRL_C if how is SIGTERM else SIGTERM,
                      marks=pytest.mark.slow) for args, after, how in LONG]


def _id(value):
    if isinstance(value, list):
        return " ".join(value)
    if isinstance(value, tuple):
        return "ctrl-c" if value == CTRL_C else "sigterm"
    return f"{value:g}s"


@pytest.mark.parametrize("args, after, how", LONG + OTHER, ids=_id)
def test_a_long_command_stops_at_once(tmp_path, args, after, how):
    signum, status, group = how
    code, took, err = _stop(args, signum, after, tmp_path, group)
    assert code == status, err
    assert took < PROMPT, took
    # one line at most beside the warnings given before the work (a
    # given dt coarser than the design's own)
    said = [line for line in err.splitlines()
            if not line.startswith("contactsep: warning: dt: ")]
    assert len(said) <= 1 and "Traceback" not in err
    if "--csv" in args:   # no file under the final name; the chunks kept
        assert not (tmp_path / "s.csv").exists()
        kept_designs(tmp_path / "s.csv")


def _sleep_then(seconds, value):
    time.sleep(seconds)
    return value


def _fail():
    raise ValueError("from the child")


class _Unpicklable(Exception):
    def __reduce__(self):
        raise TypeError("not picklable")


def _fail_unpicklably():
    raise _Unpicklable("a message")


def _children():
    """This process's children, zombies included (Linux /proc)."""
    found = set()
    for task in os.listdir(f"/proc/{os.getpid()}/task"):
        with open(f"/proc/{os.getpid()}/task/{task}/children") as f:
            found.update(f.read().split())
    return found


def test_a_run_in_a_child_answers_raises_and_is_killed_on_a_signal():
    """output.interruptible: the answer and the exceptions come back;
    a signal in the parent (here an alarm that raises) kills the child
    at once and propagates.  In a process where another test left
    threads running (a Dask client's executors), interruptible rightly
    runs the call in-process: the test then runs itself in a fresh
    interpreter, where the child path is the one taken."""
    import threading
    if threading.active_count() > 1:
        done = subprocess.run(
            [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
             f"{__file__}::test_a_run_in_a_child_answers_raises_and_is_"
             f"killed_on_a_signal"], capture_output=True, text=True,
            timeout=300, cwd=os.path.dirname(os.path.dirname(__file__)))
        assert done.returncode == 0, done.stdout[-2000:]
        assert "1 passed" in done.stdout
        return
    children_before = _children()
    assert output.interruptible(True, _sleep_then, 0.0, {"a": [1]}) == \
        {"a": [1]}
    with pytest.raises(ValueError, match="from the child"):
        output.interruptible(True, _fail)
    with pytest.raises(InputError, match="^a message$"):
        output.interruptible(True, _fail_unpicklably)
    # a large answer comes back whole
    big = np.arange(3_000_000.0)
    np.testing.assert_array_equal(
        output.interruptible(True, _sleep_then, 0.0, big), big)

    def alarm(signum, frame):
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGALRM, alarm)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        start = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            output.interruptible(True, _sleep_then, 60.0, None)
        assert time.monotonic() - start < PROMPT
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    # the child is gone, reaped: no child of this process but those
    # other tests may have left running before this one
    assert _children() <= children_before


KEYS = ("t1", "psi", "y3_max", "t_max", "status", "p1", "p3", "c3",
        "at_window_end")


def test_a_batch_in_pieces_equals_one_call(monkeypatch):
    """The batch's pieces (sized by their time) give the bits one call
    gives, per-mode arrays padded to the batch's N as one call pads."""
    design = thesis_design(d=np.linspace(0.1, 1.0, 57),
                           n_modes=np.array([4, 150, 50] * 19))
    calls = []
    from contactsep.model import compiled
    original = compiled.evaluate_packed

    def counted(packed):
        calls.append(packed.size)
        return original(packed)

    monkeypatch.setattr(compiled, "evaluate_packed", counted)
    pieces = evaluate(design)
    assert len(calls) > 1 and sum(calls) == 57
    monkeypatch.setattr(pieces_module, "FIRST_PIECE_COST", 10**9)
    whole = evaluate(design)
    assert calls[-1] == 57
    for key in KEYS:
        np.testing.assert_array_equal(getattr(pieces, key),
                                      getattr(whole, key), err_msg=key)


def test_a_costly_batch_in_child_processes_equals_one_call(monkeypatch):
    """N >= 200 or tau >= 1 s: pieces from one design up, each in a child
    process (the answers come back through a pipe, bit for bit)."""
    design = thesis_design(d=np.linspace(0.1, 1.0, 9),
                           n_modes=np.array([4, 300, 50] * 3),
                           tau=np.array([0.06, 0.06, 2.0] * 3))
    assert evaluate_module.costly(300, 2.0)
    pieces = evaluate(design)
    monkeypatch.setattr(evaluate_module, "COSTLY_MODES", 10**9)
    monkeypatch.setattr(evaluate_module, "COSTLY_TAU_S", np.inf)
    monkeypatch.setattr(pieces_module, "FIRST_PIECE_COST", 10**9)
    whole = evaluate(design)
    for key in KEYS:
        np.testing.assert_array_equal(getattr(pieces, key),
                                      getattr(whole, key), err_msg=key)


@pytest.mark.parametrize("how", [SIGTERM, CTRL_C], ids=["sigterm", "ctrl-c"])
def test_a_stopped_preload_without_a_journal_says_nothing_was_kept(
        tmp_path, how):
    """SIGTERM (or Ctrl-C) stopped a preload search without a word; with
    no --resume its finished runs are lost, and one line says so and
    how to keep them next time."""
    signum, status, group = how
    # the thick separator: an answer (about 5 lb) and minutes of search
    # (the rig at d = 0.25 has an event at its ceiling: one run says so)
    code, took, err = _stop(["preload", "--n-modes", "16", "--d", "0.75",
                             "--workers", "1", "--progress", "never"],
                            signum, 3.0, tmp_path, group)
    assert code == status and took < PROMPT, (code, took, err)
    assert err == ("contactsep: stopped; nothing was kept: with --csv FILE "
                   "--resume every finished simulation is kept beside FILE "
                   "and the same command continues from them\n")
