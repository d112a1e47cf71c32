"""Every CSV the project writes parses, and the committed docs/studies
outputs are what the code computes now (issue 19, items 1 and 7).

A CSV here is '#' comment lines (each one line), a header, and rows as
wide as the header: read with the csv module, never by splitting on
commas.  The committed studies are compared with a fresh computation:
comments, header and text columns exactly, numbers to 1e-10 of their
column's largest magnitude (the files hold 12 significant digits; the
compiled kernel's results may differ in the last bits between machines
and libm versions, far below that).
"""

from __future__ import annotations

import csv
import io
import subprocess
import sys

import numpy as np
import pytest

from conftest import DECK_DIR, ROOT
from contactsep import studies
from contactsep.studies.sweep import run as runner
from contactsep.studies.sweep import spec as sweep
from contactsep.studies.sweep.writers import CsvWriter
COMMITTED = ROOT / "docs" / "studies"


def parse(text: str) -> tuple[list[str], list[str], list[list[str]]]:
    """(comments, header, rows) of a CSV's text, checking its shape."""
    lines = text.splitlines()
    comments = []
    while lines and lines[0].startswith("#"):
        comments.append(lines.pop(0))
    assert lines, "no header"
    assert not any(line.startswith("#") for line in lines), \
        "a comment after the header"
    header, *rows = list(csv.reader(io.StringIO("\n".join(lines) + "\n")))
    assert len(set(header)) == len(header), header
    for number, row in enumerate(rows, 1):
        assert len(row) == len(header), (number, row)
    return comments, header, rows


def sweep_csv(tmp_path) -> str:
    spec = sweep.make_spec(vary=["end2=clamped-clamped,pinned-pinned",
                                 "d=-0.1:0.5:3"],
                           sample=["ys=normal(0.5,0.02)"], samples=4)
    path = tmp_path / "sweep.csv"
    runner.run_sweep(spec, writers=[CsvWriter(str(path), spec)],
                     workers=1)
    return path.read_text()


def replay_csv() -> str:
    return subprocess.run(
        [sys.executable, "-m", "contactsep", "replay",
         str(DECK_DIR / "thesis_all.dat"), "--format", "csv"],
        capture_output=True, check=True, text=True).stdout


def test_every_csv_the_project_writes_parses(tmp_path):
    texts = {name: f(**({"ys": 0.4} if name == "fig5" else {})).csv_text()
             for name, f in studies.STUDIES.items()}
    texts["sweep"] = sweep_csv(tmp_path)
    texts["replay"] = replay_csv()
    for path in sorted(COMMITTED.glob("*.csv")):
        texts[f"committed {path.name}"] = path.read_text()
    assert "committed chatter.csv" in texts
    for name, text in texts.items():
        comments, header, rows = parse(text)
        assert rows, name
    # the sweep's failed designs are rows too, with their status
    _, header, rows = parse(texts["sweep"])
    status = [row[header.index("status")] for row in rows]
    assert status.count("2") == 8 and len(rows) == 24


def test_the_chatter_commands_csv_parses(tmp_path):
    """`contactsep chatter --csv` (the chatter layer's gap histories)."""
    from contactsep.cli import build_parser
    chatter = build_parser()._subparsers._group_actions[0].choices[
        "chatter"]
    if not any("--csv" in a.option_strings for a in chatter._actions):
        pytest.skip("contactsep chatter has no --csv yet (issue 16)")
    path = tmp_path / "gaps.csv"
    subprocess.run([sys.executable, "-m", "contactsep", "chatter",
                    "--model", "appE", "--n-modes", "4", "--csv",
                    str(path)], check=True, capture_output=True)
    _, header, rows = parse(path.read_text())
    assert header[0] == "t_s" and len(rows) > 100


def test_pandas_reads_them_with_comment_hash(tmp_path):
    pandas = pytest.importorskip("pandas")
    for path in sorted(COMMITTED.glob("*.csv")):
        _, header, rows = parse(path.read_text())
        frame = pandas.read_csv(path, comment="#")
        assert frame.shape == (len(rows), len(header)), path.name


def compare(committed: str, fresh: str, name: str) -> None:
    old_comments, old_header, old_rows = parse(committed)
    new_comments, new_header, new_rows = parse(fresh)
    assert old_comments == new_comments, name
    assert old_header == new_header, name
    assert len(old_rows) == len(new_rows), name
    for k, column in enumerate(old_header):
        old = [row[k] for row in old_rows]
        new = [row[k] for row in new_rows]
        try:
            a = np.array(old, dtype=float)
            b = np.array(new, dtype=float)
        except ValueError:
            assert old == new, (name, column)
            continue
        assert np.array_equal(np.isnan(a), np.isnan(b)), (name, column)
        ok = ~np.isnan(a)
        scale = np.max(np.abs(b[ok]), initial=0.0)
        assert np.all(np.abs(a[ok] - b[ok]) <= 1e-10 * scale), \
            (name, column)


@pytest.mark.parametrize("name", list(studies.STUDIES))
def test_committed_study_is_what_the_code_computes(name):
    committed = (COMMITTED / f"{name}.csv").read_text()
    compare(committed, studies.STUDIES[name]().csv_text(), name)
    assert (COMMITTED / f"{name}.png").read_bytes()[:8] == \
        b"\x89PNG\r\n\x1a\n"


def test_committed_chatter_table_is_what_the_code_computes():
    """45 three-beam simulations at N <= 32 (2 to 6 s on two cores, so
    run by default: the whole table, not one row).  The chatter layer's
    own changes move these numbers: regenerate with `contactsep study
    chatter --out docs/studies`."""
    from contactsep.studies.thesis.chatter_table import chatter_table
    committed = (COMMITTED / "chatter.csv").read_text()
    compare(committed, chatter_table().csv_text(), "chatter")
    assert (COMMITTED / "chatter.png").read_bytes()[:8] == \
        b"\x89PNG\r\n\x1a\n"
