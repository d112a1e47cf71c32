"""The tutorial's outputs (docs/tutorial.md), produced by running it.

Each command block of the page (```sh, one command; or ```python) that is
followed by a ```text block gets that block filled with what the command
prints on standard output: the first ``SHOWN`` lines, then
``... (K more lines)``.  The commands run in order in one scratch
directory, the Python blocks in this interpreter.  The set-up is the
command blocks before the first one with an output (the design file,
``my_relay.json``, that the others read); a command block with no output
after it further down (a command only shown, too long to run here) is
not run.

``python docs/_ext/tutorial_outputs.py`` rewrites the page's output
blocks and the two committed CSVs the slow steps write
(``docs/studies/tutorial_preload.csv``: ``contactsep preload --csv``'s
file, every simulation of the search; ``docs/studies/tutorial_tolerance.csv``:
the tolerance study's builds); ``tests/project/test_tutorial.py`` holds
the page to them and simulates again the runs that decide them.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import shutil
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "tutorial.md"
STUDIES = ROOT / "docs" / "studies"
PRELOAD_CSV = STUDIES / "tutorial_preload.csv"
TOLERANCE_CSV = STUDIES / "tutorial_tolerance.csv"
#: Lines of an output shown on the page; the rest are counted.
SHOWN = 24
#: Commands that take minutes (run by the slow tests only): the preload
#: search and the tolerance sweep, by the files they write.
SLOW_MARKERS = ("tutorial_preload.csv", "tolerance.csv")

_PAIR = re.compile(r"^```(sh|python)\n([^`]*)^```\n\n```text\n([^`]*)^```\n",
                   flags=re.S | re.M)


@dataclass(frozen=True)
class Step:
    """A command block of the page and the output block after it."""

    kind: str       # "sh" or "python"
    code: str
    shown: str      # the output block's text as on the page
    span: tuple     # where the output block's text lies in the page

    @property
    def slow(self) -> bool:
        return any(marker in self.code for marker in SLOW_MARKERS)

    @property
    def command(self) -> str:
        """The shell command, continuation lines joined."""
        return " ".join(self.code.replace("\\\n", " ").split())


def steps(text: str | None = None) -> list[Step]:
    text = PAGE.read_text() if text is None else text
    return [Step(m.group(1), m.group(2), m.group(3), m.span(3))
            for m in _PAIR.finditer(text)]


def shown(output: str) -> str:
    """What the page shows of an output."""
    lines = output.splitlines()
    if len(lines) > SHOWN:
        lines = lines[:SHOWN] + [f"... ({len(lines) - SHOWN} more lines)"]
    return "\n".join(lines) + "\n" if lines else ""


def run(step: Step, where: Path, namespace: dict) -> str:
    """Run a step in ``where``; its standard output."""
    if step.kind == "python":
        out = io.StringIO()
        before = os.getcwd()
        os.chdir(where)
        try:
            with contextlib.redirect_stdout(out):
                exec(compile(step.code, "tutorial.md", "exec"), namespace)
        finally:
            os.chdir(before)
        return out.getvalue()
    bin_dir = str(Path(sys.executable).parent)
    env = dict(os.environ, PATH=bin_dir + os.pathsep + os.environ["PATH"])
    done = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", step.code],
                          cwd=where, env=env, capture_output=True, text=True,
                          timeout=1800)
    if done.returncode != 0:
        raise RuntimeError(f"{step.command}: exit {done.returncode}: "
                           f"{done.stderr[-2000:]}")
    return done.stdout


def setup_steps(text: str | None = None) -> list[Step]:
    """The page's command blocks before the first one with an output
    block after it (the design file is written by one); those further
    down with no output are shown, not run."""
    text = PAGE.read_text() if text is None else text
    first = next(_PAIR.finditer(text)).start()
    blocks = re.finditer(r"^```sh\n([^`]*)^```\n", text, flags=re.M)
    return [Step("sh", b.group(1), "", (0, 0)) for b in blocks
            if b.start() < first]


def main() -> None:
    text = PAGE.read_text()
    namespace: dict = {}
    with tempfile.TemporaryDirectory() as scratch:
        where = Path(scratch)
        for step in setup_steps():
            run(step, where, namespace)
        pieces, last = [], 0
        for step in steps(text):
            output = run(step, where, namespace)
            start, end = step.span
            pieces += [text[last:start], shown(output)]
            last = end
        pieces.append(text[last:])
        PAGE.write_text("".join(pieces))
        shutil.copyfile(where / "tolerance.csv", TOLERANCE_CSV)
        shutil.copyfile(where / PRELOAD_CSV.name, PRELOAD_CSV)


if __name__ == "__main__":
    main()
