"""contactsep.sweep and SweepResult.to_pandas (issue 30, item 5): the
rows and summary a Python sweep returns are what ``contactsep sweep``
writes for the same sweep — its CSV read back by ``contactsep.read``
(the CSV's 12 digits), its comment lines and its ``--json`` summary."""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json

import numpy as np
import pytest

import contactsep
from contactsep.cli import main
from contactsep.studies.sweep.spec import SweepError
from contactsep.studies.sweep.result import SweepResult

pandas = pytest.importorskip("pandas")


def command(argv) -> dict:
    """``contactsep sweep ARGV --json``'s summary."""
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main(["sweep", *argv, "--json", "--workers", "1"]) == 0
    return json.loads(buffer.getvalue())


def same_as_csv(frame, path) -> None:
    written = contactsep.read(path)
    assert frame.columns.tolist() == written.columns.tolist()
    assert len(frame) == len(written)
    for name in frame.columns:
        ours, theirs = frame[name].to_numpy(), written[name].to_numpy()
        if ours.dtype.kind == "f":
            # the CSV keeps 12 significant digits
            np.testing.assert_allclose(ours, theirs, rtol=5e-12, atol=0)
        else:
            assert ours.tolist() == theirs.tolist(), name
    assert frame.attrs["comments"] == written.attrs["comments"]


def without_time(summary: dict) -> dict:
    return {k: v for k, v in summary.items() if k != "elapsed_s"}


def test_an_eq23_sweep_is_the_commands_csv_and_summary(tmp_path):
    path = tmp_path / "tolerance.csv"
    argv = ["--vary", "ys=0.25,0.5", "--sample", "d=normal(0.25,0.01)",
            "--samples", "40", "--seed", "3", "--threshold", "0.015",
            "--n-modes", "6"]
    summary = command([*argv, "--csv", str(path)])
    result = contactsep.sweep(vary=["ys=0.25,0.5"],
                              sample=["d=normal(0.25,0.01)"], samples=40,
                              seed=3, threshold=0.015, fixed={"n_modes": 6},
                              workers=1)
    assert isinstance(result, SweepResult)
    frame = result.to_pandas()
    same_as_csv(frame, path)
    assert frame.columns.tolist() == ["ys_in", "d_in", "y3_max_in",
                                      "t_max_s", "psi_lb_s", "v0_in_s",
                                      "status"]
    assert without_time(frame.attrs["summary"]) == without_time(summary)
    assert without_time(result.summary) == without_time(summary)
    # the summary's numbers are the rows' own (an independent count)
    y3 = frame["y3_max_in"].to_numpy()
    assert summary["n"] == 80
    assert 0 < summary["p_exceed"] < 1
    assert summary["p_exceed"] == pytest.approx((y3 > 0.015).mean(),
                                                rel=1e-15)
    assert summary["y3_max_mean_in"] == pytest.approx(y3.mean(), rel=1e-12)
    one = result.to_pandas("summary")
    assert len(one) == 1 and one["p_exceed"][0] == summary["p_exceed"]
    assert "inputs" not in one.columns
    # frozen, as every result
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.summary = {}


def test_a_chatter_sweep_is_the_commands_csv_and_summary(tmp_path):
    path = tmp_path / "hertz.csv"
    summary = command(["--model", "hertz", "--vary", "h2=0.2,0.4",
                       "--n-modes", "4", "--preload", "0.05", "--csv",
                       str(path)])
    result = contactsep.sweep(vary=["h2=0.2,0.4"], model="hertz",
                              fixed={"n_modes": 4},
                              settings={"preload": 0.05}, workers=1)
    frame = result.to_pandas()
    same_as_csv(frame, path)
    assert "max_lower_gap_in" in frame.columns and len(frame) == 2
    assert without_time(result.summary) == without_time(summary)


def test_summary_only_keeps_no_rows():
    result = contactsep.sweep(vary=["d=0.1:0.5:5"], rows=False, workers=1)
    kept = contactsep.sweep(vary=["d=0.1:0.5:5"], workers=1)
    assert result.columns is None
    assert result.summary["n"] == kept.summary["n"] == 5
    assert result.summary["y3_max_mean_in"] == pytest.approx(
        kept.to_pandas()["y3_max_in"].mean(), rel=1e-12)
    with pytest.raises(ValueError, match="rows=False"):
        result.to_pandas()
    with pytest.raises(ValueError, match="expected 'rows' or 'summary'"):
        kept.to_pandas("events")


def test_a_bad_axis_is_the_commands_error():
    with pytest.raises(SweepError, match="varied twice"):
        contactsep.sweep(vary=["d=0.1,0.2", "d=0.3,0.4"])
