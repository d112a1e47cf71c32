"""The bytes a resumable sweep's chunks keep a design (docs/howto/resume.md),
printed as JSON.

Run from the repository root::

    python docs/studies/make_resume_bytes.py > docs/studies/resume_bytes.json

An eq23 sweep of one varied field (``contactsep sweep --vary
d=0.1:1:50000 --csv out.csv --resume``) in a temporary folder, its chunk
files kept (the store's removal at the end switched off): the slope of a
chunk file's bytes over its designs.  The slope, not the total over the
designs: a file's own header (~1.4 kB) adds to the total once a chunk,
and the chunks are sized by the measured time, so a loaded machine cuts
more of them.
"""

from __future__ import annotations

import contextlib
import io
import json
import tempfile
from pathlib import Path

import numpy as np

from contactsep.cli import main as cli_main
from contactsep.runs import journal

DESIGNS = 50_000


def chunks(folder: Path, designs: int = DESIGNS) -> tuple[list, list]:
    """(designs, bytes) of each chunk file the sweep leaves in folder."""
    remove = journal.ChunkStore.remove
    journal.ChunkStore.remove = lambda self: None
    try:
        out = folder / "out.csv"
        with contextlib.redirect_stdout(io.StringIO()):   # its summary
            code = cli_main(["sweep", "--vary", f"d=0.1:1:{designs}",
                             "--csv", str(out), "--resume",
                             "--progress", "never"])
        if code != 0:
            raise RuntimeError("the sweep failed")
    finally:
        journal.ChunkStore.remove = remove
    files = sorted((folder / ".out.csv.resume").glob("*.npz"))
    # a chunk's file is named by its first and last design
    sizes = [int(f.stem.split("-")[1]) - int(f.stem.split("-")[0])
             for f in files]
    return sizes, [f.stat().st_size for f in files]


def main() -> dict:
    with tempfile.TemporaryDirectory() as folder:
        sizes, sizes_bytes = chunks(Path(folder))
    per_design, header = np.polyfit(sizes, sizes_bytes, 1)
    return {"designs": DESIGNS, "bytes_per_design": float(per_design),
            "bytes_per_chunk": float(header)}


if __name__ == "__main__":
    print(json.dumps(main(), indent=2))
