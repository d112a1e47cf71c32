"""Output files clobbered or half-written (issue 18, class 2): every file a
command writes replaces its target only when finished and only after
every option was checked; a failed write leaves the old file; two sweeps
never mix one file; two outputs are never one file; a device is written
in place and a directory refused."""

from __future__ import annotations

import json
import os
import re
import resource
import signal
import stat
import subprocess
import sys
import time

import pytest
from hostile_cli import debris, device, main, refusal, run
from kept_chunks import kept_designs

OLD = "old contents\n"


def _old_file(tmp_path, name="out.csv"):
    path = tmp_path / name
    path.write_text(OLD)
    return path


@pytest.mark.parametrize("args", [
    ["--n-modes", "0"], ["--chunk-size", "-5"], ["--workers", "0"],
    ["--vary", "h2=0.1:nan:3"], ["--threshold", "nan"],
    ["--parquet", "{tmp}/out.parquet"], ["--scheduler", "not an address"]])
def test_a_refused_sweep_leaves_the_old_csv(tmp_path, capsys, monkeypatch,
                                            args):
    """A sweep refused for a bad option had already truncated the CSV to
    its header (--parquet: pyarrow made unimportable here)."""
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    path = _old_file(tmp_path)
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    status, _, err = main(capsys, "sweep", "--vary", "h2=0.1:0.5:5",
                          "--csv", str(path), "--workers", "1", *args)
    refusal(status, err)
    assert path.read_text() == OLD
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.csv"]


def _file_size_limit(limit):
    def apply():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return apply


@pytest.mark.parametrize("args", [
    ["sweep", "--vary", "h2=0.1:0.5:5000", "--workers", "1", "--csv"],
    ["study", "fig7", "--csv"],
    ["chatter", "--n-modes", "2", "--csv"],
    ["replay", "data/decks/thesis_all.dat", "-o"]])
def test_a_write_that_fails_partway_leaves_the_old_file(tmp_path, args):
    """A file-size limit (as a full disk): the write fails mid-row; the
    old file stays whole and no temporary file is left."""
    from conftest import ROOT
    path = _old_file(tmp_path)
    done = run(*args, str(path), cwd=ROOT,
               preexec_fn=_file_size_limit(8192))
    assert "File too large" in refusal(done.returncode, done.stderr)
    assert path.read_text() == OLD
    assert debris(tmp_path) == []


def test_a_second_sweep_on_the_same_csv_is_refused(tmp_path):
    """Two sweeps writing one CSV both exited 0 and the file mixed their
    rows.  The second is refused while the first runs; the first,
    stopped, keeps whole chunks and says so in its last line."""
    path = _old_file(tmp_path)
    first = subprocess.Popen(
        [sys.executable, "-m", "contactsep", "sweep", "--vary",
         "h2=0.1:0.5:100000000", "--workers", "1", "--csv", str(path)],
        stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        while ".out.csv.lock" not in debris(tmp_path):
            assert time.monotonic() < deadline and first.poll() is None
            time.sleep(0.05)
        second = run("sweep", "--vary", "h2=0.1:0.5:5", "--workers", "1",
                     "--csv", str(path))
        assert refusal(second.returncode, second.stderr) == (
            f"{path}: in use: another contactsep command (process "
            f"{first.pid}) is writing it (it holds .out.csv.lock); wait for "
            f"it or write elsewhere")
        assert path.read_text() == OLD
    finally:
        first.send_signal(signal.SIGINT)
        err = first.communicate(timeout=60)[1]
    assert first.returncode == 130, err
    # the old file stays under its name; the finished chunks beside it
    assert path.read_text() == OLD
    done = int(re.search(r"interrupted: (\d+) of 100000000 designs", err
                         ).group(1))
    assert done > 0 and kept_designs(path) == done
    assert debris(tmp_path) == [".out.csv.resume"]


@pytest.mark.parametrize("args, message", [
    (["study", "fig5", "--csv", "{tmp}/x.png", "--png", "{tmp}/x.png"],
     "--png {tmp}/x.png: the same file as --csv {tmp}/x.png"),
    (["sweep", "--vary", "h2=0.1:0.5:5", "--csv", "{tmp}/x.png",
      "--parquet", "{tmp}/./x.png"],
     "--parquet {tmp}/./x.png: the same file as --csv {tmp}/x.png"),
    (["chatter", "--n-modes", "2", "--csv", "{tmp}/x.png", "--png",
      "{tmp}/link.png"],
     "--png {tmp}/link.png: the same file as --csv {tmp}/x.png"),
    (["study", "fig5", "--design", "{tmp}/x.png", "--csv", "{tmp}/x.png"],
     "--csv {tmp}/x.png: the --design file the command reads"),
    (["study", "all", "--out", "{tmp}/x.png"],
     "--out {tmp}/x.png: not a directory"),
])
def test_two_outputs_are_never_one_file(tmp_path, capsys, args, message):
    """study fig5 --csv X.png --png X.png silently overwrote the CSV."""
    target = tmp_path / "x.png"
    target.write_text(json.dumps({"d_in": 0.3}))
    (tmp_path / "link.png").symlink_to(target)
    before = target.read_text()
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    status, out, err = main(capsys, *args)
    assert refusal(status, err).startswith(
        message.replace("{tmp}", str(tmp_path)))
    assert out == ""                         # refused before any work
    assert target.read_text() == before


@pytest.mark.parametrize("command", [["study", "fig5"],
                                     ["chatter", "--n-modes", "2"]])
def test_a_png_to_a_device_is_written_in_place(tmp_path, command):
    """--png /dev/full wrote /dev/full.png beside it; a device is written
    in place (the null device takes it, the full one is an error)."""
    pytest.importorskip("matplotlib")
    null = device(tmp_path, "null", 3)
    done = run(*command, "--png", null)
    assert done.returncode == 0, done.stderr
    full = device(tmp_path, "full", 7)
    done = run(*command, "--png", full)
    assert "No space left on device" in refusal(done.returncode,
                                                done.stderr)
    for path in (null, full):
        assert stat.S_ISCHR(os.stat(path).st_mode)
        assert not os.path.exists(path + ".png")
    if os.geteuid() == 0:
        assert sorted(p.name for p in tmp_path.iterdir()) == ["full", "null"]


@pytest.mark.parametrize("command", [["study", "fig5"],
                                     ["chatter", "--n-modes", "2"]])
def test_a_png_onto_a_directory_is_refused_before_any_work(tmp_path,
                                                          capsys, command):
    pytest.importorskip("matplotlib")
    target = tmp_path / "figs"
    target.mkdir()
    status, out, err = main(capsys, *command, "--png", str(target))
    assert refusal(status, err) == f"Is a directory, not a file: {target}"
    assert out == ""
    assert list(target.iterdir()) == [] and \
        sorted(p.name for p in tmp_path.iterdir()) == ["figs"]


def test_a_png_named_otherwise_is_still_a_png(tmp_path, capsys):
    """--png fig.txt was a traceback after the table was printed."""
    pytest.importorskip("matplotlib")
    path = tmp_path / "fig.txt"
    status, _, err = main(capsys, "study", "fig5", "--png", str(path))
    assert status == 0, err
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_finished_sweep_leaves_no_lock_or_temporary_file(tmp_path,
                                                           capsys):
    path = _old_file(tmp_path)
    for _ in range(2):
        status, _, err = main(capsys, "sweep", "--vary", "h2=0.1:0.5:5",
                              "--csv", str(path), "--workers", "1")
        assert status == 0, err
        assert debris(tmp_path) == []
    rows = [r for r in path.read_text().splitlines() if not r.startswith("#")]
    assert len(rows) == 6
