"""The how-to "Run the preload search on a batch cluster (SLURM)"
(docs/howto/batch-cluster.md): its script builds the worker jobs' batch script with
dask-jobqueue, run here as far as that print and no further (nothing is
submitted: there is no queue here), and the command it gives the
scheduler file to takes every option it names."""

from __future__ import annotations

import contextlib
import io
import re
import shlex
import sys

import pytest

from conftest import ROOT

TITLE = "# Run the preload search on a batch cluster (SLURM)"


def section() -> str:
    text = (ROOT / "docs" / "howto" / "batch-cluster.md").read_text()
    start = text.index(TITLE)
    end = text.find("\n## ", start + len(TITLE))
    return text[start:end if end > 0 else None]


def script() -> str:
    (block,) = re.findall(r"^```python\n(.*?)^```", section(),
                          flags=re.S | re.M)
    return block


def test_the_script_builds_one_core_worker_jobs_of_this_environment():
    pytest.importorskip("dask_jobqueue")
    lines = script().splitlines()
    stop = next(i for i, line in enumerate(lines)
                if line.startswith("print(cluster.job_script())"))
    namespace: dict = {}
    out = io.StringIO()
    # the script up to its print: the cluster object (a scheduler here,
    # on loopback) and its job script, no job submitted
    code = "\n".join(lines[:stop + 1])
    code = code.replace("job_extra_directives=",
                        "scheduler_options={'host': '127.0.0.1'}, "
                        "job_extra_directives=", 1)
    try:
        with contextlib.redirect_stdout(out):
            exec(compile(code, "batch-cluster.md", "exec"), namespace)
    finally:
        if "cluster" in namespace:
            namespace["cluster"].close()
    job = out.getvalue()
    assert job.startswith("#!/usr/bin/env bash"), job
    assert "#SBATCH --cpus-per-task=1" in job
    assert "#SBATCH --partition=compute" in job
    assert "#SBATCH -t 02:00:00" in job
    (worker,) = [line for line in job.splitlines()
                 if "distributed.cli.dask_worker" in line]
    argv = shlex.split(worker)
    # the worker runs this interpreter, so it imports this contactsep
    assert argv[0] == sys.executable
    assert argv[argv.index("--nthreads") + 1] == "1"
    assert "cluster.scale(jobs=64)" in script()


def test_the_command_takes_every_option_it_names(capsys):
    from contactsep.cli import main
    (command,) = re.findall(r"^```text\n(contactsep preload .*?)^```",
                            section(), flags=re.S | re.M)
    words = shlex.split(command.replace("\\\n", " "))
    options = [w for w in words if w.startswith("--")]
    with pytest.raises(SystemExit):
        main(["preload", "--help"])
    helptext = capsys.readouterr().out
    for option in options:
        assert re.search(rf"(^|\s){re.escape(option)}\b", helptext), option
    assert "--scheduler-file" in options and "--resume" in options
