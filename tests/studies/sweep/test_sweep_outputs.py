"""Sweeps that say what happened (issue 19, item 4): rows with status,
n_failed and its warning, exit 2 when every design fails, the Wilson
interval, the inputs in the summary and the Parquet metadata, 12-digit
CSV numbers, end conditions and n_modes varied, --set and --design."""

from __future__ import annotations

import csv
import io
import json
import math
import sys
import warnings

import numpy as np
import pytest
from sweep_collect import Collect

from contactsep.cli import main
from contactsep.errors import ContactsepWarning
from contactsep.model import evaluate, thesis_design
from contactsep.model.design_domain import SIZE_RANGE
from contactsep.runs import stops
from contactsep.studies.sweep import run as runner
from contactsep.studies.sweep import spec as sweep
from contactsep.studies.sweep.writers import CsvWriter, ParquetWriter
from contactsep.studies.stats import wilson_interval


def _no_constant(name):
    raise AssertionError(f"not strict JSON: {name}")


def read_csv(path) -> tuple[list[str], list[dict]]:
    lines = path.read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    assert lines[:len(comments)] == comments
    rows = list(csv.DictReader(io.StringIO("\n".join(
        lines[len(comments):]))))
    return comments, rows


# Wilson's interval against published values and scipy

@pytest.mark.parametrize("k, n, low, high", [
    # Newcombe (1998), Stat. Med. 17:857, Table I, method 3 (score)
    (81, 263, 0.2553, 0.3662), (15, 148, 0.0624, 0.1605),
    (0, 20, 0.0, 0.1611), (1, 29, 0.0061, 0.1718), (29, 29, 0.8830, 1.0)])
def test_wilson_interval_published_values(k, n, low, high):
    lo, hi = wilson_interval(k, n)
    assert round(lo, 4) == low and round(hi, 4) == high


def test_wilson_interval_equals_scipy():
    stats = pytest.importorskip("scipy.stats")
    for n in (1, 2, 7, 50, 1000, 10**6):
        for k in sorted({0, 1, n // 3, n // 2, n - 1, n}):
            ci = stats.binomtest(k, n).proportion_ci(method="wilson")
            lo, hi = wilson_interval(k, n)
            assert lo == pytest.approx(ci.low, abs=1e-12)
            assert hi == pytest.approx(ci.high, abs=1e-12)
    with pytest.raises(ValueError):
        wilson_interval(3, 2)


# failures

def test_failed_designs_are_counted_warned_and_left_out(tmp_path, capsys):
    path = tmp_path / "s.csv"
    status = main(["sweep", "--sample", "d=normal(0.05,0.05)", "--samples",
                   "2000", "--threshold", "0.12", "--json", "--csv",
                   str(path), "--workers", "1"])
    assert status == 0
    captured = capsys.readouterr()
    summary = json.loads(captured.out, parse_constant=_no_constant)
    _, rows = read_csv(path)
    d = np.array([float(r["d_in"]) for r in rows])
    codes = np.array([int(r["status"]) for r in rows])
    # a separator thinner than the model's domain (<= 0 included) is
    # the one way these designs fail
    thin = d < SIZE_RANGE[0]
    assert np.array_equal(codes != 0, thin) and np.all(codes[thin] == 2)
    bad = int(np.sum(thin))
    assert 0 < bad < 2000
    assert summary["n_failed"] == bad and summary["n"] == 2000 - bad
    assert summary["n_failed_by_status"] == {"2": bad}
    y = np.array([float(r["y3_max_in"]) for r in rows])
    assert np.all(np.isnan(y[thin]))
    exceed = int(np.sum(y[~thin] > 0.12))
    assert summary["p_exceed"] == exceed / (2000 - bad)
    assert summary["p_exceed_ci95"] == list(wilson_interval(exceed,
                                                           2000 - bad))
    assert captured.err == (f"contactsep: warning: {bad:,} of 2,000 designs "
                            f"failed ({bad:,} invalid input); the "
                            f"statistics are over the other "
                            f"{2000 - bad:,}\n")


def test_every_design_failing_is_exit_2_after_the_summary(tmp_path, capsys):
    path = tmp_path / "s.csv"
    assert main(["sweep", "--vary", "d=-0.1,0", "--json", "--threshold",
                 "0.1", "--csv", str(path), "--workers", "1"]) == 2
    captured = capsys.readouterr()
    summary = json.loads(captured.out, parse_constant=_no_constant)
    assert summary["n"] == 0 and summary["n_failed"] == 2
    assert summary["y3_max_mean_in"] is None and summary["p_exceed"] is None
    assert captured.err.count("\n") == 1
    assert captured.err.startswith("contactsep: error: 2 of 2 designs "
                                   "failed (2 invalid input)")
    assert len(read_csv(path)[1]) == 2      # the rows are kept


# inputs and outputs

def test_the_summary_records_its_inputs(capsys, tmp_path):
    assert main(["sweep", "--vary", "d=0.1:0.3:3", "--vary",
                 "end2=clamped-clamped,pinned-pinned", "--sample",
                 "ys=uniform(0.45,0.55)", "--samples", "4", "--seed", "11",
                 "--restitution", "0.3", "--set", "n_modes=6", "--json",
                 "--threshold", "0.1", "--workers", "1"]) == 0
    inputs = json.loads(capsys.readouterr().out)["inputs"]
    assert inputs == {
        "seed": 11, "samples": 4, "designs": 24, "backend": "compiled",
        "vary": {"d_in": {"start": 0.1, "stop": 0.3, "count": 3},
                 "end2": {"values": ["clamped-clamped", "pinned-pinned"]}},
        "sample": {"ys_in": {"distribution": "uniform", "low": 0.45,
                             "high": 0.55}},
        "fixed": {"e": 0.3, "n_modes": 6}}


def test_rows_are_the_designs_evaluated_one_by_one(tmp_path):
    path = tmp_path / "s.csv"
    assert main(["sweep", "--vary", "end2=clamped-clamped,pinned-pinned",
                 "--vary", "n_modes=2,8", "--set", "x3=15", "--d", "0.3",
                 "--csv", str(path), "--workers", "1"]) == 0
    _, rows = read_csv(path)
    assert list(rows[0]) == ["end2", "n_modes", "y3_max_in", "t_max_s",
                             "psi_lb_s", "v0_in_s", "status"]
    assert [(r["end2"], r["n_modes"]) for r in rows] == [
        ("clamped-clamped", "2"), ("clamped-clamped", "8"),
        ("pinned-pinned", "2"), ("pinned-pinned", "8")]
    for row in rows:
        one = evaluate(thesis_design(d=0.3, x3=15.0, end2=row["end2"],
                                     n_modes=int(row["n_modes"])))
        for key, name in (("y3_max_in", "y3_max"), ("psi_lb_s", "psi"),
                          ("v0_in_s", "v0"), ("t_max_s", "t_max")):
            # 12 significant digits: the kernel and its twin agree to
            # 1e-12, so the CSV keeps what means something
            assert float(row[key]) == pytest.approx(float(getattr(one, name)),
                                                    rel=6e-12, abs=0)
        assert int(row["status"]) == 0


def test_csv_numbers_have_twelve_digits_parquet_every_bit(tmp_path):
    pq = pytest.importorskip("pyarrow.parquet")
    spec = sweep.make_spec(sample=["d=normal(0.25,0.01)"], samples=300,
                           seed=3, base={"n_modes": 6})
    memory, csv_path = Collect(), tmp_path / "s.csv"
    parquet_path = tmp_path / "s.parquet"
    runner.run_sweep(spec, writers=[memory, CsvWriter(str(csv_path), spec),
                                    ParquetWriter(str(parquet_path), spec)],
                     chunk_size=128, workers=1)
    exact = memory.table()
    comments, rows = read_csv(csv_path)
    for key in ("d_in", "y3_max_in", "t_max_s", "psi_lb_s", "v0_in_s"):
        text = [r[key] for r in rows]
        digits = [len(t.lstrip("-").split("e")[0].replace(".", "")
                      .lstrip("0")) for t in text]
        assert max(digits) <= 12
        values = np.array([float(t) for t in text])
        assert np.all(np.abs(values - exact[key]) <= 5e-12 * np.abs(
            exact[key]))
    table = pq.read_table(parquet_path)
    for key in exact:
        assert np.array_equal(table.column(key).to_numpy(), exact[key])
    meta = json.loads(table.schema.metadata[b"contactsep"])
    assert meta["inputs"] == json.loads(json.dumps(spec.inputs()))
    assert meta["title"] == comments[0][2:]


def test_names_of_a_field_are_one_column():
    tables = []
    for name in ("d", "h2", "d_in"):
        out = Collect()
        runner.run_sweep(sweep.make_spec(vary=[f"{name}=0.2,0.4"]),
                         writers=[out], workers=1)
        tables.append(out.table())
    for table in tables:
        assert list(table)[0] == "d_in"
        assert np.array_equal(table["y3_max_in"], tables[0]["y3_max_in"])
    assert np.array_equal(tables[0]["y3_max_in"], evaluate(
        thesis_design(d=np.array([0.2, 0.4]))).y3_max)


def test_new_axes_are_independent_of_chunking_and_workers():
    spec = sweep.make_spec(vary=["end2=clamped-clamped,clamped-pinned",
                                 "n_modes=3,5", "d=0.2:0.6:3"],
                           sample=["e=uniform(0.3,0.45)"], samples=5, seed=2)
    a, b = Collect(), Collect()
    runner.run_sweep(spec, writers=[a], chunk_size=1000, workers=1)
    runner.run_sweep(spec, writers=[b], chunk_size=7, workers=2)
    ta, tb = a.table(), b.table()
    assert len(ta["status"]) == 60
    assert all(np.array_equal(ta[k], tb[k]) for k in ta)


@pytest.mark.parametrize("argv, message", [
    (["--vary", "end2=clamped-clamped:pinned-pinned:2"], "expected one of"),
    (["--sample", "end2=normal(1,2)"], "end2 cannot be sampled"),
    (["--vary", "n_modes=2.5"], "expected an integer >= 1"),
    (["--d", "0.3", "--vary", "h2=0.1,0.2"], "h2: fixed by a design option"),
    (["--vary", "restitution=0.1", "--vary", "e=0.2"], "varied twice"),
])
def test_bad_sweeps_are_one_line_errors(argv, message, capsys):
    assert main(["sweep", *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err


def test_progress_always_without_tqdm_says_so(monkeypatch):
    monkeypatch.setitem(sys.modules, "tqdm", None)
    with pytest.warns(ContactsepWarning, match="needs tqdm"):
        assert stops.progress_bar(10, True) is None
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert stops.progress_bar(10, None) is None    # auto: silent
        assert stops.progress_bar(10, False) is None


def test_comments_say_what_the_sweep_was(tmp_path):
    path = tmp_path / "s.csv"
    assert main(["sweep", "--sample", "d=normal(0.25,0.01)", "--samples",
                 "3", "--seed", "5", "--vary", "end3=clamped-free,"
                 "clamped-pinned", "--n-modes", "5", "--csv", str(path)]) == 0
    comments, rows = read_csv(path)
    assert "# designs: 6" in comments
    assert "# vary end3: clamped-free, clamped-pinned" in comments
    assert "# samples: 3 per grid point, seed 5" in comments
    assert "# sample d_in ~ normal(mean 0.25, sd 0.01)" in comments
    assert "# fixed n_modes = 5" in comments
    assert len(rows) == 6 and math.isfinite(float(rows[0]["y3_max_in"]))


def test_a_design_file_is_where_the_sweep_starts(tmp_path, capsys):
    saved = tmp_path / "saved.json"
    assert main(["model", "--d", "0.3", "--restitution", "0.25",
                 "--json"]) == 0
    saved.write_text(capsys.readouterr().out)
    path = tmp_path / "s.csv"
    # the file's d gives way to the sweep's; the rest of it stays
    assert main(["sweep", "--design", str(saved), "--vary", "d=0.2,0.4",
                 "--vary", "end2=clamped-clamped,pinned-pinned", "--csv",
                 str(path), "--json", "--workers", "1"]) == 0
    inputs = json.loads(capsys.readouterr().out)["inputs"]
    assert inputs["fixed"]["e"] == 0.25 and "d_in" not in inputs["fixed"]
    _, rows = read_csv(path)
    assert len(rows) == 4
    for row in rows:
        one = evaluate(thesis_design(d=float(row["d_in"]), e=0.25,
                                     end2=row["end2"]))
        assert float(row["v0_in_s"]) == pytest.approx(float(one.v0),
                                                      rel=6e-12, abs=0)
    # typed on the command line, a field cannot also be swept
    assert main(["sweep", "--design", str(saved), "--d", "0.3", "--vary",
                 "d=0.2,0.4"]) == 2
    assert "fixed by a design option and varied" in capsys.readouterr().err


def test_a_design_file_sweep_is_titled_by_its_file(tmp_path, capsys):
    """A sweep of a --design file says so in its CSV's first line and
    its Parquet title, not "on the thesis design" (issue 30)."""
    pytest.importorskip("pyarrow")
    import pyarrow.parquet as pq
    saved = tmp_path / "relay.json"
    saved.write_text(json.dumps({"L1": 10.0, "L3": 10.0, "x1": 10.0,
                                 "x3": 10.0}))
    plain, typed = tmp_path / "plain.csv", tmp_path / "typed.csv"
    parquet = tmp_path / "typed.parquet"
    assert main(["sweep", "--vary", "d=0.2,0.4", "--csv", str(plain),
                 "--json", "--workers", "1"]) == 0
    assert main(["sweep", "--design", str(saved), "--vary", "d=0.2,0.4",
                 "--csv", str(typed), "--parquet", str(parquet), "--json",
                 "--workers", "1"]) == 0
    capsys.readouterr()
    first = read_csv(plain)[0][0]
    assert first.endswith("on the thesis design")
    named = read_csv(typed)[0][0]
    assert named == first.replace("the thesis design",
                                  f"the design of {saved}")
    about = json.loads(pq.read_schema(parquet).metadata[b"contactsep"])
    assert about["title"] == named[2:]
    # the rows are the file's design, not the thesis rig's
    _, rows = read_csv(typed)
    one = evaluate(thesis_design(d=0.4, L1=10.0, L3=10.0, x1=10.0,
                                 x3=10.0))
    assert float(rows[1]["v0_in_s"]) == pytest.approx(float(one.v0),
                                                      rel=6e-12, abs=0)


def test_a_progress_bar_leaves_no_thread_behind():
    """tqdm's monitor thread, once started, made every later long call
    of the process run in it rather than in a child a signal can stop
    (output.interruptible with other threads running)."""
    import threading
    pytest.importorskip("tqdm")
    before = {t.ident for t in threading.enumerate()}
    bar = stops.progress_bar(10, True)
    bar.update(1)
    bar.close()
    after = {t.ident for t in threading.enumerate() if t.is_alive()}
    assert after <= before
