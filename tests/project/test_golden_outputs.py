"""The golden command set (tests/golden/outputs.py): a deck replay, the
general model, a sweep with Parquet, a Hertz chatter run, the preload
search nominal and robust at small N, three studies, and a sweep and a
preload search killed part-way and resumed, give today's outputs byte
for byte.  The golden files were written by the package before its
upper floors were reorganised: a reorganisation that changes no
behaviour leaves every one of them as it is.  (What the numbers are
worth is the business of the other tests: the restoration against the
listing, the model against its independent reference, the chatter runs
against an independent simulator.)"""

from __future__ import annotations

import difflib
import sys

import pytest

from conftest import ROOT
from forked import killed_at

sys.path.insert(0, str(ROOT / "tests" / "golden"))
import outputs as golden  # noqa: E402


def assert_same(produced: dict, stored: dict) -> None:
    assert sorted(produced) == sorted(stored)
    for name, data in produced.items():
        if data != stored[name]:
            diff = "\n".join(list(difflib.unified_diff(
                stored[name].decode(errors="replace").splitlines(),
                data.decode(errors="replace").splitlines(),
                "golden", "now", lineterm="", n=1))[:30])
            pytest.fail(f"tests/golden/{name} differs (if the change is "
                        f"meant, python tests/golden/outputs.py rewrites "
                        f"it):\n{diff}")


@pytest.mark.parametrize("command", golden.COMMANDS,
                         ids=lambda g: g.name)
def test_a_command_gives_its_golden_outputs(command, tmp_path):
    assert_same(golden.run(command, tmp_path), golden.stored(command))


def _resumed(name: str, owner, method: str, count: int, tmp_path,
             chunked=()) -> None:
    """The golden command ``name`` with --resume, SIGKILLed at the
    ``count``-th call of ``owner.method`` and run again: the golden
    outputs, and the journal kept between the two runs."""
    command = golden.BY_NAME[name]
    resumed = golden.Golden(command.name, (*command.argv, *chunked,
                                           "--resume"), command.files)
    tmp_path.mkdir(parents=True, exist_ok=True)
    killed_at(golden.argv(resumed, tmp_path), owner, method, count)
    journals = [p for p in tmp_path.iterdir() if p.name.endswith(".resume")]
    assert journals, sorted(p.name for p in tmp_path.iterdir())
    assert not any((tmp_path / f).exists() for f in command.files)
    assert_same(golden.run(resumed, tmp_path), golden.stored(command))
    assert not any(p.name.endswith(".resume") for p in tmp_path.iterdir())


def test_a_killed_sweep_resumes_to_its_golden_outputs(tmp_path):
    from contactsep.runs.journal import ChunkStore
    _resumed("sweep", ChunkStore, "save", 3, tmp_path,
             ("--chunk-size", "4"))


def test_a_killed_preload_search_resumes_to_its_golden_outputs(tmp_path):
    from contactsep.runs.journal import RunJournal
    _resumed("preload", RunJournal, "record", 40, tmp_path)


def test_the_golden_set_spans_the_commands_it_promises():
    """Replay, model, sweep (CSV and Parquet), chatter, preload nominal
    and robust, three studies: each golden file holds an output, none
    an absolute path of the machine that wrote it."""
    argv0 = [g.argv[0] for g in golden.COMMANDS]
    for command in ("replay", "model", "sweep", "chatter", "preload"):
        assert command in argv0
    assert argv0.count("study") >= 3
    assert any("--tolerance" in g.argv for g in golden.COMMANDS)
    assert any(f.endswith(".parquet") for g in golden.COMMANDS
               for f in g.files)
    for command in golden.COMMANDS:
        for name, data in golden.stored(command).items():
            assert len(data) > 100, name
            assert b"/tmp/" not in data and str(ROOT).encode() not in data
