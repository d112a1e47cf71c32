"""How the journals beside this file were made: on the package before
its resume systems became one (commit d582bb5, contactsep 0.1.0), the
golden sweep with ``--chunk-size 4 --resume`` SIGKILLed at its third
chunk and the golden preload search with ``--resume`` at its 40th run
(tests/runs/test_journal_formats.py continues them with today's code).

``python tests/golden/journals/make.py OUT`` writes them again into OUT
from the installed package; they are kept as the old code wrote them,
so a rewrite with the code of today tests nothing: leave them."""

from __future__ import annotations

import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path[:0] = [str(HERE.parents[1]), str(HERE.parent)]

import outputs as golden  # noqa: E402
from forked import killed_at  # noqa: E402

try:                                    # the code of today
    from contactsep.runs.journal import ChunkStore, RunJournal
except ImportError:                     # the code that wrote them
    from contactsep.studies.resume import ChunkStore
    from contactsep.studies.run_journal import RunJournal


def write_all(out: Path) -> None:
    for name, owner, method, count, extra in (
            ("sweep", ChunkStore, "save", 3, ("--chunk-size", "4")),
            ("preload", RunJournal, "record", 40, ())):
        command = golden.BY_NAME[name]
        resumed = golden.Golden(command.name,
                                (*command.argv, *extra, "--resume"),
                                command.files)
        scratch = out / "scratch" / name
        scratch.mkdir(parents=True)
        killed_at(golden.argv(resumed, scratch), owner, method, count)
        shutil.copytree(scratch / f".{name}.csv.resume", out / name)
        print(f"wrote {out / name}")
    shutil.rmtree(out / "scratch")


if __name__ == "__main__":
    write_all(Path(sys.argv[1]))
