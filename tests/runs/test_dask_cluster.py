"""The preload search and the sweeps on a Dask cluster started as a user
starts one: ``dask scheduler --scheduler-file F`` and two ``dask worker
--scheduler-file F`` processes on 127.0.0.1, each its own process group,
killed at teardown.  The workers are separate processes, so nothing
planted in this one reaches them: the designs are real, small ones.

What the cluster must give: the answers and bytes of the local pool; a
lost scheduler one line naming it, the finished simulations kept so
that a new scheduler continues to the same answer; a lost worker
nothing lost."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time

import pytest
from dask_deployment import Deployment
from design_family import FAMILY

import contactsep
from contactsep.errors import InputError

distributed = pytest.importorskip("distributed")

#: A real design whose robust search is short (about 100 simulations of
#: a few ms of physics): the light beryllium-copper relay at N = 4, no
#: static correction, opens up to the largest preload it takes, so the
#: scan ends at that ceiling with no fine band.
DESIGN = FAMILY["becu_light"].replace(n_modes=4)
SETTINGS = {"dt": 1e-8, "t_end": 0.005, "static_correction": False}
#: p_target 0.6: met on the 95 % Wilson upper end of 0 of 3 (0.56), so
#: three samples can show it and the robust search runs.
ROBUST = {"tolerance": ["ys=uniform(0.029,0.031)"], "samples": 3,
          "p_target": 0.6, "converge": False}


def _robust(workers, journal=None):
    return contactsep.preload(DESIGN, workers=workers, journal=journal,
                              **ROBUST, **SETTINGS)


def test_a_robust_preload_on_the_cluster_is_the_local_pools(deployment):
    """The same JSON answer and CSV bytes on two Dask workers as on two
    local processes; the cluster's workers did the runs (a client
    ignored in favour of the local pool would also agree)."""
    local = _robust(2)
    with distributed.Client(scheduler_file=str(deployment.path)) as client, \
            distributed.get_task_stream(client) as stream:
        remote = _robust(client)
    assert remote.to_json_dict() == local.to_json_dict()
    assert remote.csv_text() == local.csv_text()
    assert remote.robust is not None and len(remote.robust.tested) > 2
    ran = {task["key"]: task["worker"] for task in stream.data
           if str(task["key"]).startswith("run_pack")}
    # the nominal search's runs, then K a preload the robust one tried,
    # and the runs made ahead for idle workers that were never asked for
    asked = remote.simulations + ROBUST["samples"] * len(
        remote.robust.tested)
    made, used = remote.timing["ahead"]
    # one task a pack of runs (runs/dask_packs.py: one run a pack until
    # a run is timed, then packs of MIN_PACK_S or more of runs of a few
    # ms): at most one task a run, and fewer once the runs are packed
    # (their exact count follows the runs' times); the packing's own
    # counts: tests/runs/test_dask_packs.py
    assert asked > 50 and 10 <= len(ran) <= asked + made - used
    assert len(set(ran.values())) == 2


def test_a_sweep_on_the_scheduler_file_writes_the_local_bytes(
        deployment, tmp_path):
    argv = [sys.executable, "-m", "contactsep", "sweep", "--model",
            "hertz", "--n-modes", "4", "--vary", "h2=0.1:0.8:8",
            "--progress", "never", "--csv"]
    local = subprocess.run([*argv, "local.csv", "--workers", "2"],
                           cwd=tmp_path, capture_output=True, text=True,
                           timeout=120)
    assert local.returncode == 0, local.stderr
    remote = subprocess.run([*argv, "remote.csv", "--scheduler-file",
                             str(deployment.path)], cwd=tmp_path,
                            capture_output=True, text=True, timeout=120)
    assert remote.returncode == 0, remote.stderr
    assert (tmp_path / "remote.csv").read_bytes() == \
        (tmp_path / "local.csv").read_bytes()


def test_a_study_on_the_scheduler_writes_the_local_bytes(deployment,
                                                       tmp_path):
    """A thesis study's simulations on the cluster (the materials study
    at N = 2: 13 s on two local workers) give the local pool's CSV."""
    argv = [sys.executable, "-m", "contactsep", "study", "materials",
            "--n-modes", "2", "--progress", "never", "--csv"]
    local = subprocess.run([*argv, "local.csv", "--workers", "2"],
                           cwd=tmp_path, capture_output=True, text=True,
                           timeout=300)
    assert local.returncode == 0, local.stderr
    before = _tasks_seen(deployment)
    remote = subprocess.run([*argv, "remote.csv", "--scheduler",
                             deployment.address], cwd=tmp_path,
                            capture_output=True, text=True, timeout=300)
    assert remote.returncode == 0, remote.stderr
    assert (tmp_path / "remote.csv").read_bytes() == \
        (tmp_path / "local.csv").read_bytes()
    # the simulations ran on the cluster: one task or more a row
    rows = [line for line in (tmp_path / "local.csv").read_text()
            .splitlines() if line and not line.startswith("#")]
    assert _tasks_seen(deployment) - before >= len(rows) - 1


def _tasks_seen(deployment) -> int:
    """The tasks the cluster's scheduler has seen, in any state."""
    with distributed.Client(deployment.address, timeout=30) as client:
        return client.run_on_scheduler(lambda dask_scheduler: sum(
            sum(prefix.state_counts.values())
            for prefix in dask_scheduler.task_prefixes.values()))


def test_the_preload_command_runs_on_the_scheduler_the_file_names(
        deployment, monkeypatch, capsys):
    """The command hands the search a Client of the file's scheduler
    (the search itself: the test above)."""
    from contactsep.cli import main
    from contactsep.studies.preload import command as design_preload
    seen = []

    def reached(design, **kwargs):
        seen.append(kwargs["workers"].scheduler.address)
        raise InputError("reached")
    monkeypatch.setattr(design_preload, "preload", reached)
    assert main(["preload", "--n-modes", "4", "--scheduler-file",
                 str(deployment.path)]) == 2
    assert seen == [deployment.address]
    assert capsys.readouterr().err.strip().endswith("reached")


def test_the_study_command_runs_on_the_scheduler_it_is_given(
        deployment, monkeypatch, capsys):
    """study preload hands the chart a Client of --scheduler's."""
    from contactsep.cli import main
    from contactsep.studies.preload import chart as preload
    seen = []

    def reached(**kwargs):
        seen.append(kwargs["workers"].scheduler.address)
        raise InputError("reached")
    monkeypatch.setattr(preload, "preload_chart", reached)
    assert main(["study", "preload", "--n-modes", "4", "--scheduler",
                 deployment.address]) == 2
    assert seen == [deployment.address]
    assert capsys.readouterr().err.strip().endswith("reached")


@pytest.mark.parametrize("argv, message", [
    (["preload", "--scheduler-file", "missing.json"],
     "--scheduler-file missing.json: no such file (a Dask scheduler "
     "started with --scheduler-file FILE writes it)"),
    (["preload", "--scheduler", "tcp://127.0.0.1:1", "--scheduler-file",
      "f.json"], "--scheduler and --scheduler-file: give one"),
    (["preload", "--scheduler-file", "f.json", "--workers", "2"],
     "--workers: local processes; with --scheduler-file the Dask "
     "cluster's workers run the simulations (give one of them)"),
    (["study", "fig5", "--scheduler-file", "f.json"],
     "--scheduler and --scheduler-file are options of study preload"),
    (["sweep", "--vary", "h2=0.1:0.2:2", "--scheduler-file", "bad.json"],
     "--scheduler-file bad.json: not a Dask scheduler file"),
])
def test_bad_cluster_options_are_one_line(argv, message, capsys,
                                          tmp_path, monkeypatch):
    from contactsep.cli import main
    monkeypatch.chdir(tmp_path)
    (tmp_path / "bad.json").write_text("[1, 2]")
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err, err


def test_a_lost_scheduler_is_one_line_and_a_new_one_continues(
        deployment, tmp_path):
    """The scheduler SIGKILLed mid-search: one line naming it (the
    command's exit 2: an InputError), the finished simulations in the
    journal; the same search on a new deployment takes them and ends
    with the uninterrupted answer, simulating only the rest."""
    from contactsep.runs import dask_run
    from contactsep.runs.dask_run import SchedulerLost
    from contactsep.runs.journal import RunJournal
    uninterrupted = _robust(1)
    # the runs a search on two workers makes ahead and never asks for
    made, used = _robust(2).timing["ahead"]
    never_asked = made - used
    inputs = {"test": "lost scheduler"}
    lost = Deployment(tmp_path / "lost.json")
    address = lost.address
    try:
        # the lost client's own reconnection log lines kept off the log
        with dask_run.quiet_dask(), distributed.Client(address) as client, \
                RunJournal(tmp_path / "journal", inputs) as journal:
            killer = _kill_after(journal, 20, lost.scheduler)
            with pytest.raises(SchedulerLost) as error:
                _robust(client, journal)
            kept = len(journal)
            killer.join()
    finally:
        lost.close()
    message = str(error.value)
    assert message.startswith(f"the Dask scheduler {address} was lost")
    assert message.endswith("(rerun with --resume to continue)")
    assert "\n" not in message and 20 <= kept < uninterrupted.simulations
    with distributed.Client(scheduler_file=str(deployment.path)) as client, \
            RunJournal(tmp_path / "journal", inputs) as journal:
        again = _robust(client, journal)
        # every kept run is taken again, but those made ahead that the
        # search never asks for
        assert kept - never_asked <= journal.reused <= kept
        asked = again.simulations + ROBUST["samples"] * len(
            again.robust.tested)
        made, used = again.timing["ahead"]
        assert journal.recorded == asked - journal.reused - used + made
    assert again.to_json_dict() == uninterrupted.to_json_dict()
    assert again.csv_text() == uninterrupted.csv_text()


def _kill_after(journal, count, process):
    import threading

    def watch():
        deadline = time.monotonic() + 120
        while len(journal) < count and time.monotonic() < deadline:
            time.sleep(0.01)
        os.killpg(process.pid, signal.SIGKILL)
    thread = threading.Thread(target=watch, daemon=True)
    thread.start()
    return thread


def test_workers_running_other_code_are_refused(deployment, monkeypatch):
    """This process made to report another code digest: the workers'
    real one then differs, and the search is refused before any run."""
    from contactsep.runs import code_digest
    # the workers import their own, unpatched
    monkeypatch.setattr(code_digest, "code_digest", lambda: "0" * 64)
    with distributed.Client(scheduler_file=str(deployment.path)) as client, \
            distributed.get_task_stream(client) as stream:
        with pytest.raises(InputError) as error:
            _robust(client)
    message = str(error.value)
    assert "runs other simulation code" in message, message
    assert "2 of 2 workers differ" in message and "\n" not in message
    assert not stream.data


@pytest.mark.slow
def test_a_worker_lost_mid_search_loses_nothing(tmp_path):
    """One of two workers SIGKILLed after 20 runs: Dask runs its tasks
    again on the other, and the answer is the local pool's.  (Slow: 180 s
    on a loaded machine, a deployment of its own and one worker left.)"""
    local = _robust(1)
    cluster = Deployment(tmp_path / "workers.json")
    done = []

    def progress(count):
        done.append(count)
        if len(done) == 20:
            os.killpg(cluster.workers[0].pid, signal.SIGKILL)
    try:
        with distributed.Client(scheduler_file=str(cluster.path)) as client:
            remote = contactsep.preload(DESIGN, workers=client,
                                        progress=progress, **ROBUST,
                                        **SETTINGS)
            left = len(client.nthreads())
    finally:
        cluster.close()
    assert len(done) > 20 and left == 1
    assert remote.to_json_dict() == local.to_json_dict()
    assert remote.csv_text() == local.csv_text()


#: The tasks _recorded ran, in the order they ran (an in-process worker).
_RAN = []


def _recorded(task):
    _RAN.append(task)
    return task.upper()


def test_a_batch_runs_costliest_first_and_returns_in_the_tasks_order():
    """One single-threaded worker, in this process, runs the batch in
    the ``order`` given (the costliest first), whatever the tasks' own
    order; the results come back in the tasks' order, each handed to
    ``finished`` once."""
    from contactsep.runs.dask_map import run_tasks
    tasks = [f"task {i}" for i in range(12)]
    order = [5, 11, 0, 7, 3, 9, 1, 10, 2, 8, 4, 6]
    seen, counted = {}, []
    _RAN.clear()
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1,
                                  processes=False,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        out = run_tasks(client, _recorded, tasks, order=order,
                        finished=seen.__setitem__, progress=counted.append)
    assert _RAN == [tasks[i] for i in order]
    assert out == [task.upper() for task in tasks]
    assert seen == dict(enumerate(out)) and counted == [1] * len(tasks)
