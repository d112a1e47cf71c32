"""DataFrames (issue 30 item 5): contactsep.read() reads every CSV and
Parquet file the package writes, its comment lines kept; to_pandas() on
Evaluation and ChatterResult.  Values are checked against an independent
reader (the csv module, pyarrow) and against the result's own arrays."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

import contactsep
from contactsep.chatter import simulate
from contactsep.cli import main
from contactsep.errors import InputError

pandas = pytest.importorskip("pandas")

ROOT = Path(__file__).resolve().parents[3]
COMMITTED = sorted((ROOT / "docs" / "studies").glob("*.csv"))


def by_csv_module(path: Path):
    """(comments, header, rows) read with the csv module."""
    comments, rows = [], []
    with open(path, newline="") as handle:
        for line in handle:
            if line.startswith("#"):
                comments.append(line[1:].strip())
            else:
                rows.append(line)
    table = list(csv.reader(rows))
    return comments, table[0], table[1:]


@pytest.mark.parametrize("path", COMMITTED, ids=lambda p: p.name)
def test_read_gives_every_committed_csv_with_its_comments(path):
    frame = contactsep.read(path)
    comments, header, rows = by_csv_module(path)
    assert frame.attrs["comments"] == comments and comments
    assert frame.columns.tolist() == header
    assert len(frame) == len(rows)
    for k, name in enumerate(header):
        column = frame[name].tolist()
        for got, text in zip(column, (row[k] for row in rows)):
            if text == "":  # an empty field (the preload CSV's dt_s:
                # the design's own step) is a missing value to pandas
                assert isinstance(got, float) and np.isnan(got)
                continue
            try:
                expected = float(text)
            except ValueError:
                assert str(got) == text
                continue
            assert got == expected or (np.isnan(got) and np.isnan(expected))


def test_read_equals_pandas_with_comment_lines(tmp_path, capsys):
    """A sweep's CSV (comments first and, interrupted, last): read()
    equals pandas.read_csv(comment='#'), the documented workaround."""
    path = tmp_path / "sweep.csv"
    assert main(["sweep", "--vary", "h2=0.1:0.8:8", "--workers", "1",
                 "--csv", str(path)]) == 0
    capsys.readouterr()
    frame = contactsep.read(path)
    pandas.testing.assert_frame_equal(frame,
                                      pandas.read_csv(path, comment="#"))
    assert frame.attrs["comments"][0].startswith("contactsep sweep")


def test_read_gives_parquet_with_its_metadata(tmp_path, capsys):
    pq = pytest.importorskip("pyarrow.parquet")
    path = tmp_path / "sweep.parquet"
    assert main(["sweep", "--vary", "h2=0.1:0.8:8", "--workers", "1",
                 "--parquet", str(path)]) == 0
    capsys.readouterr()
    frame = contactsep.read(path)
    table = pq.read_table(path)
    assert frame.columns.tolist() == table.column_names
    for name in table.column_names:
        assert frame[name].tolist() == table.column(name).to_pylist()
    meta = json.loads(table.schema.metadata[b"contactsep"])
    assert frame.attrs["contactsep"] == meta
    assert frame.attrs["comments"][0] == meta["title"]


def test_read_refuses_what_is_not_a_table(tmp_path):
    missing = tmp_path / "nothing.csv"
    with pytest.raises(InputError, match="nothing.csv"):
        contactsep.read(missing)
    binary = tmp_path / "noise.csv"
    binary.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(InputError, match="noise.csv"):
        contactsep.read(binary)


def test_chatter_csv_reads_back_as_its_gaps_frame(tmp_path, capsys):
    path = tmp_path / "gaps.csv"
    assert main(["chatter", "--model", "hertz", "--n-modes", "4", "--dt",
                 "5e-8", "--t-end", "0.03", "--csv", str(path)]) == 0
    capsys.readouterr()
    r = simulate(contactsep.thesis_design(n_modes=4), model="hertz",
                 dt=5e-8, t_end=0.03)
    read, made = contactsep.read(path), r.to_pandas("gaps")
    assert read.columns.tolist() == made.columns.tolist()
    # the CSV holds 9 significant digits
    for name in ("t_s", "gap_upper_in", "gap_lower_in"):
        np.testing.assert_allclose(read[name], made[name], rtol=5e-9,
                                   atol=1e-15)
    assert (read["circuit_open"] == made["circuit_open"]).all()


def test_evaluation_frames_hold_the_arrays():
    d = np.linspace(0.1, 1.0, 5)
    batch = contactsep.evaluate(contactsep.thesis_design(d=d, n_modes=6))
    frame = batch.to_pandas()
    assert len(frame) == 5 and frame.index.name == "design"
    np.testing.assert_array_equal(frame["psi_lb_s"], batch.psi)
    np.testing.assert_array_equal(frame["y3_max_in"], batch.y3_max)
    modes = batch.to_pandas(modes=True)
    assert modes.index.names == ["design", "mode"] and len(modes) == 30
    np.testing.assert_array_equal(modes.loc[3]["p2_rad_s"], batch.p2[3])
    assert set(batch.to_dict()) == set(frame.columns) | set(modes.columns)


def test_chatter_frames_hold_the_summary_and_events():
    r = simulate(contactsep.thesis_design(n_modes=8), model="hertz",
                 dt=5e-8, t_end=0.06)
    summary = r.to_pandas()
    data = r.to_json_dict()
    assert len(summary) == 1
    for key in ("first_impact_s", "max_lower_gap_in", "circuit_open_s",
                "n_events", "energy_ratio", "status"):
        assert summary[key][0] == data[key]
    assert summary["d_in"][0] == 0.25 and summary["model"][0] == "hertz"
    events = r.to_pandas("events")
    np.testing.assert_array_equal(events[["start_s", "end_s"]].to_numpy(),
                                  np.asarray(r.events).reshape(-1, 2))
    assert (events["duration_s"] >= r.min_open_s).all()
    openings = r.to_pandas("openings")
    assert len(openings) == len(r.circuit_open_intervals)
    assert openings["event"].sum() == r.n_events
    with pytest.raises(ValueError, match="expected summary"):
        r.to_pandas("everything")
