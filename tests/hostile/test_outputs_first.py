"""Outputs checked before work (issue 31, item 5): a --csv, --png,
--parquet or --out in a folder that does not exist or cannot be written
is refused before any computation, in every command that writes; a full
disk names the file it could not write."""

from __future__ import annotations

import os
import time

import pytest
from hostile_cli import device, main, refusal

#: Commands that compute for seconds to minutes before they write.
LONG = {
    "chatter": ["chatter", "--model", "newton", "--n-modes", "1024"],
    "preload": ["study", "preload"],
    "conclusion3": ["study", "conclusion3"],
    "fig6": ["study", "fig6", "--n-modes", "100"],
    "sweep": ["sweep", "--vary", "h2=0.1:0.5:100000"],
    "chatter sweep": ["sweep", "--model", "hertz", "--vary",
                      "h2=0.1:0.5:1000"],
}
OPTIONS = {"chatter": ["--csv", "--png"], "preload": ["--csv", "--png"],
           "conclusion3": ["--csv", "--png"], "fig6": ["--csv", "--png"],
           "sweep": ["--csv", "--parquet"],
           "chatter sweep": ["--csv", "--parquet"]}
CASES = [(name, option) for name in LONG for option in OPTIONS[name]]


@pytest.mark.parametrize("name, option", CASES)
def test_an_output_in_a_missing_folder_is_refused_first(
        capsys, tmp_path, monkeypatch, name, option):
    monkeypatch.chdir(tmp_path)
    start = time.monotonic()
    code, out, err = main(capsys, *LONG[name], option, "NODIR/x.out")
    assert time.monotonic() - start < 5.0
    message = refusal(code, err)
    assert message.startswith(f"{option} NODIR/x.out: no such directory")
    assert out == ""


@pytest.mark.parametrize("name, option", CASES[::2])
def test_an_output_in_a_folder_that_cannot_be_written_is_refused_first(
        capsys, tmp_path, monkeypatch, name, option):
    """As an unprivileged user in a read-only folder (root writes
    anywhere: the folder's check is made to answer as it would)."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "RODIR").mkdir()
    real = os.access
    target = str(tmp_path / "RODIR")
    monkeypatch.setattr(os, "access", lambda path, mode, **kw: False if
                        os.fspath(path) == target else real(path, mode,
                                                            **kw))
    code, _, err = main(capsys, *LONG[name], option, "RODIR/x.out")
    assert refusal(code, err).startswith(f"{option} RODIR/x.out: "
                                         f"directory ")
    assert "is not writable" in err


def test_study_out_folder_may_be_made(capsys, tmp_path, monkeypatch):
    """--out DIR is made at the end: a DIR not there yet is fine when
    its nearest folder can be written."""
    monkeypatch.chdir(tmp_path)
    code, _, err = main(capsys, "study", "fig5", "--out", "new/sub")
    assert code == 0, err
    assert (tmp_path / "new" / "sub" / "fig5.csv").exists()


@pytest.mark.parametrize("option", ["--csv", "--parquet"])
def test_a_full_disk_names_the_file(capsys, tmp_path, option):
    if option == "--parquet":
        pytest.importorskip("pyarrow")
    full = device(tmp_path, "full", 7)
    other = str(tmp_path / ("x.parquet" if option == "--csv" else "x.csv"))
    second = "--parquet" if option == "--csv" else "--csv"
    if second == "--parquet":
        pytest.importorskip("pyarrow")
    code, _, err = main(capsys, "sweep", "--vary", "h2=0.1:0.5:2000",
                        option, full, second, other, "--workers", "1")
    message = refusal(code, err)
    assert message == f"{option}: No space left on device: {full}"
