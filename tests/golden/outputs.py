"""The golden command set: commands whose outputs must stay byte for byte
what they were while the package is reorganised (its modules moved, its
run machinery merged), kept as files beside this one.

Each command runs in-process (``contactsep.cli.main``) in a scratch
directory; what it prints on stdout and each file it writes is one
golden file.  What a run cannot reproduce is taken out first and only
that: a sweep's ``elapsed_s``; a Parquet file is kept as its table and
its ``contactsep`` metadata (the file's bytes name the pyarrow that
wrote it).  Resumed runs are killed part-way (SIGKILL, in a forked
child) and run again: their outputs must be the uninterrupted run's
golden files.

``python tests/golden/outputs.py`` rewrites the golden files from the
installed package; do that only for a change meant to move an output,
and say so in the commit and the CHANGELOG.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import sys
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
DECK = ROOT / "data" / "decks" / "thesis_d0125.dat"

#: The preload search of the golden set: the thesis rig at d = 0.75 in,
#: N = 4, a 0.03 s window (seconds, not minutes), no check at 4N.
PRELOAD = ["preload", "--n-modes", "4", "--d", "0.75", "--t-end", "0.03",
           "--no-converge", "--workers", "1", "--progress", "never",
           "--json"]


@dataclass(frozen=True)
class Golden:
    """A command of the golden set: its name (the golden files' stem),
    its arguments (``{out}``: the scratch directory), and the files it
    writes there besides stdout."""

    name: str
    argv: tuple
    files: tuple = ()
    #: stdout is the machine's (a text with timings): not kept
    quiet: bool = False


COMMANDS = (
    Golden("replay", ("replay", str(DECK))),
    Golden("model", ("model", "--d", "0.5", "--json")),
    Golden("sweep", ("sweep", "--vary", "h2=0.1:0.8:8", "--vary",
                     "ys=0.4:0.6:3", "--workers", "1", "--csv",
                     "{out}/sweep.csv", "--parquet", "{out}/sweep.parquet",
                     "--json"), ("sweep.csv", "sweep.parquet")),
    Golden("chatter", ("chatter", "--model", "hertz", "--n-modes", "8",
                       "--t-end", "0.003", "--json")),
    Golden("preload", (*PRELOAD, "--csv", "{out}/preload.csv"),
           ("preload.csv",)),
    Golden("preload_robust", (*PRELOAD, "--tolerance",
                              "d=normal(0.75,0.005)", "--samples", "5",
                              "--p-target", "0.5", "--seed", "3", "--csv",
                              "{out}/robust.csv"), ("robust.csv",)),
    Golden("fig5", ("study", "fig5", "--csv", "{out}/fig5.csv"),
           ("fig5.csv",)),
    Golden("table1", ("study", "table1", "--csv", "{out}/table1.csv"),
           ("table1.csv",)),
    Golden("conclusion8", ("study", "conclusion8", "--csv",
                           "{out}/conclusion8.csv"), ("conclusion8.csv",)),
)
BY_NAME = {golden.name: golden for golden in COMMANDS}


def argv(golden: Golden, out: Path) -> list:
    """The command's arguments with its scratch directory filled in."""
    return [a.replace("{out}", str(out)) for a in golden.argv]


def kept(name: str, data: bytes) -> bytes:
    """What the golden file keeps of an output: all of it, but a sweep
    summary's elapsed_s and a Parquet file's writer (see the module)."""
    if name.endswith(".parquet"):
        return _parquet_kept(data)
    if name == "sweep.stdout":
        summary = json.loads(data)
        summary.pop("elapsed_s", None)
        return (json.dumps(summary, indent=2, sort_keys=True) + "\n"
                ).encode()
    return data


def _parquet_kept(data: bytes) -> bytes:
    import pyarrow.parquet as pq
    table = pq.read_table(io.BytesIO(data))
    meta = table.schema.metadata or {}
    kept = {"columns": table.column_names,
            "types": [str(t) for t in table.schema.types],
            "rows": {name: [repr(v) for v in table.column(name).to_pylist()]
                     for name in table.column_names},
            "contactsep": json.loads(meta.get(b"contactsep", b"null"))}
    return (json.dumps(kept, indent=1, sort_keys=True) + "\n").encode()


def run(golden: Golden, out: Path) -> dict:
    """Run the command in ``out``; {golden file name: bytes kept}."""
    from contactsep.cli import main
    out.mkdir(parents=True, exist_ok=True)
    stdout, stderr = io.StringIO(), io.StringIO()
    cwd = os.getcwd()
    os.chdir(out)
    try:
        with contextlib.redirect_stdout(stdout), \
                contextlib.redirect_stderr(stderr):
            status = main(argv(golden, out))
    finally:
        os.chdir(cwd)
    if status != 0:
        raise AssertionError(f"{golden.name}: exit {status}: "
                             f"{stderr.getvalue()}")
    produced = {} if golden.quiet else {
        f"{golden.name}.stdout": kept(f"{golden.name}.stdout",
                                      stdout.getvalue().encode())}
    for name in golden.files:
        produced[file_name(golden, name)] = kept(name,
                                                 (out / name).read_bytes())
    return produced


def file_name(golden: Golden, name: str) -> str:
    """The golden file of an output (a Parquet file's is JSON)."""
    return f"{golden.name}.{name}" + (".json" if name.endswith(".parquet")
                                      else "")


def stored(golden: Golden) -> dict:
    """The golden files of a command: {name: bytes}."""
    names = ([] if golden.quiet else [f"{golden.name}.stdout"]) + \
        [file_name(golden, name) for name in golden.files]
    return {name: (HERE / name).read_bytes() for name in names}


def write_all() -> None:
    """Rewrite every golden file from the installed package."""
    import tempfile
    with tempfile.TemporaryDirectory() as scratch:
        for golden in COMMANDS:
            for name, data in run(golden, Path(scratch) / golden.name
                                  ).items():
                (HERE / name).write_bytes(data)
                print(f"wrote tests/golden/{name} ({len(data):,} bytes)")


if __name__ == "__main__":
    sys.exit(write_all())
