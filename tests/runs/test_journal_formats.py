"""A journal on disk outlives the code that wrote it: the journals in
tests/golden/journals/ were written by the package before its two resume
systems became one (``tests/golden/journals/make.py``, run on that
code): the golden sweep (``--chunk-size 4 --resume``) SIGKILLed at its
third chunk, the golden preload search (``--resume``) at its 40th run.

Today's code continues each to the golden outputs, computing only what
the journal lacks; killed at the same moment, it writes the same files
(the manifest and the runs' lines byte for byte, the same chunks); one
made by other code is refused in the one line the old code printed.

The code digest in a manifest is the digest of the code that wrote it,
which a reorganisation changes: to reuse them here the digest is
planted as the one the journal records, as it is for a journal of
today's code (the refusal of another digest is tested below and in
test_resume and test_run_journal)."""

from __future__ import annotations

import json
import shutil
import sys

import numpy as np
import pytest

from conftest import ROOT
from forked import killed_at
from kept_chunks import kept_designs

sys.path.insert(0, str(ROOT / "tests" / "golden"))
import outputs as golden  # noqa: E402

from contactsep.cli import main  # noqa: E402
from contactsep.runs import code_digest  # noqa: E402
from contactsep.runs.journal import ChunkStore, RunJournal  # noqa: E402
from contactsep.studies.sweep import chunk_runs  # noqa: E402

JOURNALS = ROOT / "tests" / "golden" / "journals"
#: The golden command, what it was run with, and where it was killed.
KILLED = {"sweep": (("--chunk-size", "4", "--resume"), ChunkStore, "save",
                    3),
          "preload": (("--resume",), RunJournal, "record", 40)}


def _command(name: str) -> golden.Golden:
    command = golden.BY_NAME[name]
    return golden.Golden(command.name, (*command.argv, *KILLED[name][0]),
                         command.files)


def _journal(name: str, tmp_path):
    """The old code's journal of ``name``, beside its CSV in tmp_path."""
    kept = tmp_path / f".{name}.csv.resume"
    shutil.copytree(JOURNALS / name, kept)
    return kept


def _recorded_digest(name: str, monkeypatch) -> None:
    """The code digest planted as the one the old journal records."""
    recorded = json.loads((JOURNALS / name / "manifest.json").read_text())[
        "code_sha256"]
    monkeypatch.setattr(code_digest, "code_digest", lambda *a: recorded)


def test_the_old_codes_journals_are_whole():
    """What the tests below start from: two chunks of four designs, and
    39 whole lines of runs (the 40th was being kept when it was
    killed)."""
    assert sorted(p.name for p in (JOURNALS / "sweep").iterdir()) == [
        "000000000000-000000000004.npz", "000000000004-000000000008.npz",
        "manifest.json"]
    lines = (JOURNALS / "preload" / "runs.jsonl").read_bytes().split(b"\n")
    assert lines[-1] == b"" and len(lines) == 40
    assert all(len(json.loads(line)["key"]) == 64 for line in lines[:-1])


def test_a_sweep_journal_of_the_old_code_is_continued(tmp_path,
                                                      monkeypatch):
    _journal("sweep", tmp_path)
    assert kept_designs(tmp_path / "sweep.csv") == 8
    _recorded_digest("sweep", monkeypatch)
    computed = []
    original = chunk_runs.evaluate_chunk_timed

    def counted(spec, first, last):
        computed.append((first, last))
        return original(spec, first, last)
    monkeypatch.setattr(chunk_runs, "evaluate_chunk_timed", counted)
    command = _command("sweep")
    assert golden.run(command, tmp_path) == golden.stored(command)
    # designs 0..7 taken from the old chunks, 8..23 computed
    assert min(first for first, _ in computed) == 8
    assert sum(last - first for first, last in computed) == 24 - 8
    assert not (tmp_path / ".sweep.csv.resume").exists()


def test_a_preload_journal_of_the_old_code_is_continued(tmp_path,
                                                        monkeypatch):
    _journal("preload", tmp_path)
    _recorded_digest("preload", monkeypatch)
    found, recorded = [], []
    lookup, record = RunJournal.lookup, RunJournal.record

    def counted_lookup(self, key):
        out = lookup(self, key)
        found.append(out[0])
        return out

    def counted_record(self, key, result):
        recorded.append(key)
        return record(self, key, result)
    monkeypatch.setattr(RunJournal, "lookup", counted_lookup)
    monkeypatch.setattr(RunJournal, "record", counted_record)
    command = _command("preload")
    assert golden.run(command, tmp_path) == golden.stored(command)
    # each of the 39 kept runs answered from the journal, none run again
    kept = [json.loads(line)["key"] for line in
            (JOURNALS / "preload" / "runs.jsonl").read_text().splitlines()]
    assert sum(found) == 39 and recorded
    assert not set(kept) & set(recorded)
    assert not (tmp_path / ".preload.csv.resume").exists()


@pytest.mark.parametrize("name", ["sweep", "preload"])
def test_killed_at_the_same_moment_todays_code_writes_the_same_journal(
        name, tmp_path, monkeypatch):
    _recorded_digest(name, monkeypatch)
    _, owner, method, count = KILLED[name]
    killed_at(golden.argv(_command(name), tmp_path), owner, method, count)
    written = tmp_path / f".{name}.csv.resume"
    old = JOURNALS / name
    assert sorted(p.name for p in written.iterdir()) == sorted(
        p.name for p in old.iterdir())
    for path in old.iterdir():
        if path.suffix == ".npz":
            with np.load(path) as a, np.load(written / path.name) as b:
                assert a.files == b.files
                for key in a.files:
                    assert a[key].dtype == b[key].dtype, key
                    np.testing.assert_array_equal(a[key], b[key])
        else:
            assert (written / path.name).read_bytes() == \
                path.read_bytes(), path.name


@pytest.mark.parametrize("name, what, advice", [
    ("sweep", "sweep beside {csv} (.sweep.csv.resume)",
     "rerun without --resume"),
    ("preload", "search in {csv} (.preload.csv.resume)",
     "rerun without --resume, or remove it,")])
def test_an_old_journal_of_other_code_is_refused_in_the_old_line(
        name, what, advice, tmp_path, capsys):
    """The line the old code printed for this journal with another code
    digest (run on that code), exit 2, and the journal left as it was."""
    kept = _journal(name, tmp_path)
    manifest = json.loads((kept / "manifest.json").read_text())
    manifest["code_sha256"] = "0" * 64
    (kept / "manifest.json").write_text(json.dumps(manifest))
    before = {p.name: p.read_bytes() for p in kept.iterdir()}
    assert main(golden.argv(_command(name), tmp_path)) == 2
    csv = tmp_path / f"{name}.csv"
    assert capsys.readouterr().err == (
        f"contactsep: error: --resume: the unfinished "
        f"{what.format(csv=csv)} was made with other inputs (code_sha256 "
        f"differs); {advice} to start afresh\n")
    assert {p.name: p.read_bytes() for p in kept.iterdir()} == before
    assert sorted(p.name for p in tmp_path.iterdir()) == [kept.name]
