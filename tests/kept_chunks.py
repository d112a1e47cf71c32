"""What an unfinished sweep leaves beside its output: the finished chunks
(``.NAME.resume/``), read with NumPy alone (not the store's own code)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

_CHUNK = re.compile(r"^(\d{12})-(\d{12})\.npz$")


def kept_designs(output: Path) -> int:
    """The designs kept beside ``output``: the chunk files, none
    overlapping another, each holding as many rows as its name says (an
    AssertionError otherwise).  The workers save the chunks they finish,
    so after a stop a later chunk may be kept while an earlier one, in
    flight, is not: a resume computes only the gaps."""
    store = output.parent / f".{output.name}.resume"
    assert (store / "manifest.json").is_file(), sorted(
        p.name for p in output.parent.iterdir())
    spans = sorted((int(m.group(1)), int(m.group(2)), path)
                   for path in store.iterdir()
                   if (m := _CHUNK.match(path.name)))
    end, total = 0, 0
    for first, last, path in spans:
        assert first >= end and last > first, (first, last, end)
        with np.load(path) as chunk:
            lengths = {len(chunk[key]) for key in chunk.files}
        assert lengths == {last - first}, (path.name, lengths)
        end, total = last, total + last - first
    return total
