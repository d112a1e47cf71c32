"""Faults of a Dask cluster met by the command itself, on a cluster
started as a user starts one (tests/dask_deployment.py): ``contactsep
preload --csv F --resume --scheduler-file`` whose scheduler is SIGKILLed
mid-search, then resumed on a new one; a worker that cannot import
contactsep."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from dask_deployment import Deployment
from design_family import FAMILY

import contactsep
from contactsep.errors import InputError

distributed = pytest.importorskip("distributed")


#: ``contactsep preload`` small enough for a fault test: the thesis rig
#: at N = 4 over a 0.03 s window, no check at 4N (about 200 simulations
#: of a few tens of ms each).
PRELOAD_ARGV = [sys.executable, "-m", "contactsep", "preload", "--n-modes",
                "4", "--t-end", "0.03", "--no-converge", "--progress",
                "never", "--csv"]


def _journal_lines(csv: Path) -> int:
    try:
        return (csv.parent / f".{csv.name}.resume" / "runs.jsonl"
                ).read_bytes().count(b"\n")
    except FileNotFoundError:
        return 0


def test_the_preload_command_on_a_lost_scheduler_is_one_line_and_resumes(
        deployment, tmp_path):
    """The command's own path: ``preload --csv F --resume
    --scheduler-file`` with its scheduler SIGKILLed once 20 runs are in
    the journal exits 2 with one line naming that scheduler and what it
    kept; the same command with --resume on a new scheduler says it took
    them, finishes, and writes the local pool's CSV byte for byte (its
    text differs only in the time it says a rerun would take)."""
    local = subprocess.run([*PRELOAD_ARGV, "local.csv", "--workers", "2"],
                           cwd=tmp_path, capture_output=True, text=True,
                           timeout=300, check=False)
    assert local.returncode == 0, local.stderr
    csv = tmp_path / "remote.csv"
    lost = Deployment(tmp_path / "lost.json")
    address = lost.address
    try:
        command = subprocess.Popen(
            [*PRELOAD_ARGV, csv.name, "--resume", "--scheduler-file",
             str(lost.path)], cwd=tmp_path, stdout=subprocess.PIPE,
            stderr=subprocess.PIPE, text=True)
        deadline = time.monotonic() + 120
        while _journal_lines(csv) < 20 and command.poll() is None:
            assert time.monotonic() < deadline, "no runs journaled"
            time.sleep(0.01)
        os.killpg(lost.scheduler.pid, signal.SIGKILL)
        out, err = command.communicate(timeout=120)
    finally:
        lost.close()
    kept = _journal_lines(csv)
    assert command.returncode == 2, (out, err)
    assert err == (f"contactsep: error: the Dask scheduler {address} was "
                   f"lost (its connection closed); the {kept} simulations "
                   f"finished before it are kept (rerun with --resume to "
                   f"continue)\n"), err
    assert not out and not csv.exists()
    total = int(re.search(r"; (\d+) simulations", local.stdout)[1])
    assert 20 <= kept < total
    again = subprocess.run(
        [*PRELOAD_ARGV, csv.name, "--resume", "--scheduler-file",
         str(deployment.path)], cwd=tmp_path, capture_output=True,
        text=True, timeout=300, check=False)
    assert again.returncode == 0, again.stderr
    assert again.stderr.startswith(
        f"contactsep: --resume: {kept:,} finished simulations in "
        f".{csv.name}.resume, not run again\n"), again.stderr
    assert csv.read_bytes() == (tmp_path / "local.csv").read_bytes()


#: A worker preload that hides contactsep from the worker, as another
#: environment (dask alone) would: its import fails there.
HIDE_CONTACTSEP = """
import sys

class Hidden:
    def find_spec(self, name, path=None, target=None):
        if name.partition(".")[0] == "contactsep":
            raise ModuleNotFoundError(f"No module named {name!r}",
                                      name=name)
        return None

sys.meta_path.insert(0, Hidden())
"""


def test_a_worker_that_cannot_import_contactsep_is_refused(tmp_path):
    """One of two workers cannot import contactsep: the search is refused
    in one line naming that worker, before any run (no task on the
    cluster, no journal left); the command says the same line, exit 2."""
    hide = tmp_path / "hide_contactsep.py"
    hide.write_text(HIDE_CONTACTSEP)
    cluster = Deployment(tmp_path / "hidden.json",
                         worker_args=("--preload", str(hide)))
    try:
        with distributed.Client(scheduler_file=str(cluster.path)) as client:
            imports = client.run(exec, "import contactsep",
                                 on_error="return")
            hidden = [address for address, error in imports.items()
                      if isinstance(error, ModuleNotFoundError)]
            assert len(hidden) == 1 and len(imports) == 2, imports
            with distributed.get_task_stream(client) as stream, \
                    pytest.raises(InputError) as error:
                contactsep.preload(FAMILY["becu_light"].replace(n_modes=4),
                                   workers=client)
        command = subprocess.run(
            [sys.executable, "-m", "contactsep", "preload", "--n-modes",
             "4", "--progress", "never", "--csv", "out.csv", "--resume",
             "--scheduler-file", str(cluster.path)], cwd=tmp_path,
            capture_output=True, text=True, timeout=120, check=False)
    finally:
        cluster.close()
    line = (f"the Dask worker {hidden[0]} cannot run contactsep "
            f"(ModuleNotFoundError(\"No module named 'contactsep'\")); 1 "
            f"of 2 workers fail: start them from this environment")
    assert str(error.value) == line
    assert not stream.data
    assert command.returncode == 2, command.stderr
    assert command.stderr == f"contactsep: error: {line}\n"
    assert not command.stdout
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "hidden.json", "hide_contactsep.py"]
