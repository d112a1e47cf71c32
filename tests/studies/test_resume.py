"""Sweeps that survive being killed (issue 29 item 3): a sweep run with
--resume and killed (SIGKILL, in a forked child: no clean-up of any
kind) at several points, then run again with --resume, ends with a CSV
and a Parquet file byte-identical to an uninterrupted run's and the same
summary; a changed input refuses to resume; statistics merged from
chunks equal a single pass."""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest
from forked import killed_at

from contactsep.cli import main as cli_main
from contactsep.runs import journal as resume
from contactsep.studies.sweep import chunk_runs
from contactsep.studies.sweep import run as runner
from contactsep.studies.sweep import spec as sweep
from contactsep.studies.sweep import writers
from contactsep.studies.sweep.chatter import ChatterSummary
from contactsep.studies.stats import BLOCK, RunningMoments

EQ23 = ["sweep", "--vary", "h2=0.1:0.8:7", "--sample",
        "ys=uniform(0.45,0.55)", "--samples", "40", "--chunk-size", "23",
        "--workers", "1", "--threshold", "0.11", "--progress", "never",
        "--json"]
HERTZ = ["sweep", "--model", "hertz", "--n-modes", "4", "--vary",
         "h2=0.1:0.8:10", "--chunk-size", "3", "--workers", "1",
         "--progress", "never", "--json"]


def _outputs(directory, args):
    return [*args, "--csv", str(directory / "out.csv"), "--parquet",
            str(directory / "out.parquet")]


def _run(capsys, args) -> tuple[int, dict | None, str]:
    status = cli_main(list(args))
    captured = capsys.readouterr()
    summary = json.loads(captured.out) if status == 0 else None
    if summary is not None:
        summary.pop("elapsed_s")
    return status, summary, captured.err


def _killed_at(args, where: str, count: int) -> None:
    """Run the command in a forked child that SIGKILLs itself at the
    ``count``-th call of ``where`` (the CSV writer's write or close, the
    store's save or remove): the state on disk of a command killed
    there."""
    owner, name = {
        "write": (writers.CsvWriter, "write"),
        "close": (writers.CsvWriter, "close"),
        "save": (resume.ChunkStore, "save"),
        "remove": (resume.ChunkStore, "remove")}[where]
    killed_at(args, owner, name, count)


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    """Each sweep's outputs and summary, run once without --resume."""
    out = {}
    for name, args in (("eq23", EQ23), ("hertz", HERTZ)):
        directory = tmp_path_factory.mktemp(name)
        assert cli_main(_outputs(directory, args)) == 0
        out[name] = directory
    return out


def _summary_of(directory, args, capsys) -> dict:
    status, summary, _ = _run(capsys, [*args, "--csv", str(
        directory / "again.csv")])
    assert status == 0
    return summary


@pytest.mark.parametrize("name, args", [("eq23", EQ23), ("hertz", HERTZ)])
@pytest.mark.parametrize("where, count", [("save", 1), ("write", 1),
                                          ("write", 4), ("close", 1),
                                          ("remove", 1)])
def test_a_killed_sweep_resumes_to_identical_bytes(
        tmp_path, capsys, uninterrupted, name, args, where, count):
    """Killed before its first chunk was kept, after 1 or 4 chunks,
    while its files were being put in place, after they were (its
    chunks not yet removed): the resumed run's files equal the
    uninterrupted run's byte for byte, its summary the same numbers."""
    command = _outputs(tmp_path, [*args, "--resume"])
    _killed_at(command, where, count)
    store = tmp_path / ".out.csv.resume"
    assert store.is_dir()
    kept = sorted(p.name for p in store.glob("*.npz"))
    status, summary, err = _run(capsys, command)
    assert status == 0, err
    reference = uninterrupted[name]
    for file in ("out.csv", "out.parquet"):
        assert (tmp_path / file).read_bytes() == \
            (reference / file).read_bytes(), file
    # the same summary as a run that kept nothing
    assert summary == _summary_of(reference, args, capsys)
    # nothing left beside the outputs: no chunks, lock or temporary file
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "out.csv", "out.parquet"]
    if where == "write" and count == 4:
        assert len(kept) >= 4


def test_the_resumed_run_computes_only_what_is_missing(tmp_path, capsys,
                                                       monkeypatch):
    command = _outputs(tmp_path, [*EQ23, "--resume"])
    _killed_at(command, "write", 5)
    store = runner.ChunkStore(str(tmp_path / "out.csv"),
                              sweep.make_spec(
                                  vary=["h2=0.1:0.8:7"],
                                  sample=["ys=uniform(0.45,0.55)"],
                                  samples=40))
    kept = store.designs
    assert kept >= 4 * 23
    computed = []
    original = chunk_runs.evaluate_chunk_timed

    def counted(spec, first, last):
        computed.append(last - first)
        return original(spec, first, last)
    monkeypatch.setattr(chunk_runs, "evaluate_chunk_timed", counted)
    status, _, err = _run(capsys, command)
    assert status == 0, err
    assert sum(computed) == 7 * 40 - kept


def test_a_changed_input_refuses_to_resume(tmp_path, capsys):
    command = _outputs(tmp_path, [*EQ23, "--resume"])
    _killed_at(command, "write", 2)
    changed = [a.replace("h2=0.1:0.8:7", "h2=0.1:0.9:7") for a in command]
    status, _, err = _run(capsys, changed)
    assert status == 2
    assert err.count("\n") == 1 and "Traceback" not in err
    assert err.startswith("contactsep: error: --resume: the unfinished "
                          "sweep beside ")
    assert "(inputs.vary.d_in.stop differs)" in err
    # the kept chunks are still there for the command that made them
    assert list((tmp_path / ".out.csv.resume").glob("*.npz"))
    status, _, err = _run(capsys, command)
    assert status == 0, err


def test_chunks_made_by_other_code_are_refused(tmp_path, capsys,
                                               monkeypatch):
    command = _outputs(tmp_path, [*EQ23, "--resume"])
    _killed_at(command, "write", 2)
    from contactsep.runs import code_digest
    original = code_digest.code_digest
    monkeypatch.setattr(code_digest, "code_digest", lambda *a: "0" * 64)
    status, _, err = _run(capsys, command)
    assert status == 2
    assert err.count("\n") == 1
    assert "(code_sha256 differs); rerun without --resume" in err
    monkeypatch.setattr(code_digest, "code_digest", original)
    status, _, err = _run(capsys, command)
    assert status == 0, err


def test_without_resume_an_earlier_runs_chunks_are_dropped(tmp_path,
                                                           capsys):
    command = _outputs(tmp_path, [*EQ23, "--resume"])
    _killed_at(command, "write", 2)
    status, _, err = _run(capsys, [a for a in command if a != "--resume"])
    assert status == 0, err
    assert not (tmp_path / ".out.csv.resume").exists()


def test_resume_needs_an_output(capsys):
    status, _, err = _run(capsys, [*EQ23, "--resume"])
    assert status == 2
    assert err == ("contactsep: error: --resume keeps the finished chunks "
                   "beside the output: give --csv or --parquet\n")
    status, _, err = _run(capsys, [*EQ23, "--resume", "--csv", os.devnull])
    assert status == 2
    assert err == ("contactsep: error: --resume keeps the finished chunks "
                   f"beside the output: {os.devnull} is not a regular "
                   f"file\n")


def test_workers_summaries_merged_equal_the_rows_summary():
    """Nothing written: each worker sends its chunk's summary and the
    parent merges them; the same numbers as the summary of the rows
    (counts exact, means and sds to 1e-12)."""
    spec = sweep.make_spec(vary=["h2=0.1:0.8:5"],
                           sample=["ys=uniform(0.45,0.55)"], samples=3000)
    merged = runner.run_sweep(spec, threshold=0.11, workers=2,
                              chunk_size=997)

    class Rows:
        def write(self, columns):
            pass

        def close(self, interrupted=None):
            pass
    rows = runner.run_sweep(spec, writers=[Rows()], threshold=0.11,
                            workers=1, chunk_size=997)
    for key in ("n", "n_failed", "n_failed_by_status", "p_exceed",
                "y3_max_min_in", "y3_max_max_in"):
        assert merged[key] == rows[key], key
    for key in ("y3_max_mean_in", "y3_max_sd_in"):
        assert merged[key] == pytest.approx(rows[key], rel=1e-12), key


# --- statistics merged from chunks ---------------------------------------

def _moments_by_hand(values):
    """Mean and sample sd by math.fsum (exactly rounded sums)."""
    n = len(values)
    mean = math.fsum(values) / n
    var = math.fsum((v - mean) ** 2 for v in values) / (n - 1)
    return mean, math.sqrt(var)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_moments_merged_from_chunks_equal_a_single_pass(seed):
    rng = np.random.default_rng(seed)
    values = 0.11 + 1e-3 * rng.standard_normal(3 * BLOCK + 1234)
    cuts = np.sort(rng.choice(values.size, 40, replace=False))
    pieces = np.split(values, cuts)
    single = RunningMoments()
    single.add(values)
    chunked = RunningMoments()
    merged = RunningMoments()
    for piece in pieces:
        chunked.add(piece)
        partial = RunningMoments()
        partial.add(piece)
        merged.merge(partial)
    mean, sd = _moments_by_hand(values.tolist())
    # added in any chunks: the same bits (the sums go BLOCK at a time)
    assert (chunked.count, chunked.mean, chunked.sd) == \
        (single.count, single.mean, single.sd)
    for m in (single, merged):
        assert m.count == values.size
        assert m.mean == pytest.approx(mean, rel=1e-12, abs=0)
        assert m.sd == pytest.approx(sd, rel=1e-9, abs=0)
        assert (m.minimum, m.maximum) == (values.min(), values.max())


def test_summaries_merged_from_chunks_count_exactly():
    rng = np.random.default_rng(7)
    n = 5000
    y3 = 0.1 + 0.02 * rng.random(n)
    status = rng.choice([0, 0, 0, 1, 2, 3], n)
    columns = {"y3_max_in": y3, "status": status}
    single = sweep.Summary(threshold=0.115)
    single.add(columns)
    merged = sweep.Summary(threshold=0.115)
    for start in range(0, n, 777):
        part = sweep.Summary(threshold=0.115)
        part.add({k: v[start:start + 777] for k, v in columns.items()})
        merged.merge(part)
    ok = status == 0
    assert merged.n == single.n == int(ok.sum())
    assert merged.exceed == single.exceed == int((y3[ok] > 0.115).sum())
    assert merged.failed == single.failed == {
        code: int((status == code).sum()) for code in (1, 2, 3)}
    assert merged.as_dict()["y3_max_mean_in"] == pytest.approx(
        math.fsum(y3[ok]) / ok.sum(), rel=1e-12, abs=0)
    chatter = {"n_events": rng.integers(0, 3, n), "status": status,
               "max_lower_gap_in": rng.random(n),
               "circuit_open_s": rng.random(n)}
    one, many = ChatterSummary(), ChatterSummary()
    one.add(chatter)
    for start in range(0, n, 999):
        part = ChatterSummary()
        part.add({k: v[start:start + 999] for k, v in chatter.items()})
        many.merge(part)
    assert (many.opened, many.n, many.failed) == (
        int((chatter["n_events"][ok] > 0).sum()), int(ok.sum()),
        single.failed)
