"""The shell examples of README.md and docs/*.md run as written (issue 19,
item 2): every ```sh block is valid bash; the quick commands run in a
scratch directory that looks like the checkout (its data/ and a .venv
whose activate script puts this interpreter's contactsep first); the
slow ones in the slow set.  Set-up commands (apt-get, pip) and the
benchmarks are checked for syntax only."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ROOT

PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
         *sorted((ROOT / "docs" / "howto").glob("*.md"))]
#: Commands checked for syntax only: installing, measuring, the
#: robust preload search at 381 samples, shown with its cost (hours),
#: and the commands that only regenerate a committed preload search
#: (docs/studies/preload.csv and preload_physical.csv, minutes of
#: thousands of simulations): tests/project/test_committed_searches.py
#: simulates again the runs that decide each row of them, checks their
#: '#' lines and columns, and that their page names these commands;
#: so do the tutorial's two slow steps, whose files are committed as
#: docs/studies/tutorial_preload.csv and tutorial_tolerance.csv
#: (tests/project/test_tutorial.py; here they read the my_relay.json
#: of the page's set-up, which the slow set alone never wrote).  So
#: do the other commands that only regenerate committed files of
#: docs/studies (docs/studies.md), whose files are checked fast:
#: `study all --out docs/studies` by tests/studies/
#: test_committed_outputs.py (test_committed_study_is_what_the_code_
#: computes, every study of eq. 23; tests/studies/thesis/test_studies.py
#: runs `study all --out DIR` into a scratch folder), `study chatter
#: --out docs/studies` by its test_committed_chatter_table_is_what_the_
#: code_computes (docs/chatter.md's `study chatter` runs the command
#: here), `study separator-fit --csv docs/studies/separator-fit.csv` by
#: tests/studies/thesis/test_separator_fit.py (one committed row fitted
#: again; its slow test runs the command and checks the findings).
NEVER_RUN = ("apt-get", "pip install", "pytest", "benchmarks/",
             "--samples 381",
             "study preload --converge --csv docs/studies/preload.csv",
             "study preload --separator physical --csv "
             "docs/studies/preload_physical.csv",
             "study preload --converge --out docs/studies",
             "--design my_relay.json --csv tutorial_preload.csv",
             "--samples 100 --seed 1 --csv tolerance.csv",
             "study all --out docs/studies",
             "study chatter --out docs/studies",
             "study separator-fit --csv docs/studies/separator-fit.csv")
#: Commands run only in the slow set (a minute or a large file).
SLOW = ("--samples 1000000", "study chatter", "study all", "study preload",
        "tolerance.csv", "study conclusion", "--preload 20",
        "contactsep preload", "study separator-fit", "contactsep report")
#: A command's limit: the slowest example (preload.md's robust preload
#: search, said there to take about 18 minutes on two cores) fits with
#: room for a loaded machine; below pytest's own per-test limit (1800 s).
COMMAND_TIMEOUT_S = 1700
#: Pages whose commands belong to a layer that changes them often (the
#: chatter layer's own page): run in the slow set.
SLOW_PAGES = {"chatter.md", "circuit-opening.md", "numerics.md",
              "convergence.md", "static-correction.md", "preload.md",
              "preload-family.md"}
ACTIVATE = ". .venv/bin/activate"


def blocks(page: Path) -> list[str]:
    return re.findall(r"^```sh\n(.*?)^```", page.read_text(),
                      flags=re.S | re.M)


def commands(block: str) -> list[str]:
    """The block's commands, continuation lines joined."""
    return [c.strip() for c in block.replace("\\\n", " ").splitlines()
            if c.strip() and not c.strip().startswith("#")]


def cases():
    for page in PAGES:
        for block in blocks(page):
            for command in commands(block):
                if command == ACTIVATE:
                    continue
                if any(word in command for word in NEVER_RUN):
                    continue
                slow = page.name in SLOW_PAGES or any(
                    word in command for word in SLOW)
                marks = [pytest.mark.slow] if slow else []
                where = page.relative_to(ROOT)
                yield pytest.param(command, marks=marks,
                                   id=f"{where}: {command[:60]}")


@pytest.mark.parametrize("page", PAGES,
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_every_shell_block_is_valid_bash(page):
    for block in blocks(page):
        done = subprocess.run(["bash", "-n"], input=block, text=True,
                              capture_output=True)
        assert done.returncode == 0, (block, done.stderr)


def test_readme_commands_say_the_venv_is_active():
    """Outside the set-up, a README block that runs a bare `contactsep`
    starts by activating the venv (or writes .venv/bin/contactsep)."""
    readme = (ROOT / "README.md").read_text()
    use = readme.split("## Set-up", 1)[1].split("\n## ", 1)[1]
    for block in re.findall(r"^```sh\n(.*?)^```", use, flags=re.S | re.M):
        if re.search(r"^contactsep ", block, flags=re.M):
            assert block.startswith(ACTIVATE + "\n"), block


@pytest.fixture(scope="module")
def checkout(tmp_path_factory) -> Path:
    """A scratch directory with the checkout's data/ and a .venv whose
    activate script and bin/contactsep are this interpreter's."""
    bin_dir = Path(sys.executable).parent
    if not (bin_dir / "contactsep").exists():
        pytest.skip("the contactsep command is not beside the interpreter")
    where = tmp_path_factory.mktemp("checkout")
    (where / "data").symlink_to(ROOT / "data")
    (where / "docs" / "studies").mkdir(parents=True)
    venv = where / ".venv" / "bin"
    venv.mkdir(parents=True)
    (venv / "activate").write_text(f'PATH="{bin_dir}:$PATH"\n')
    (venv / "contactsep").symlink_to(bin_dir / "contactsep")
    return where


@pytest.mark.parametrize("command", list(cases()))
def test_shell_command_runs(command, checkout):
    if "bench" in command or shutil.which("bash") is None:
        pytest.skip("not a command to run here")
    done = subprocess.run(["bash", "-e", "-o", "pipefail", "-c",
                           f"{ACTIVATE}\n{command}"], cwd=checkout,
                          capture_output=True, text=True,
                          timeout=COMMAND_TIMEOUT_S)
    assert done.returncode == 0, (command, done.stderr[-2000:])
    assert "Traceback" not in done.stderr
