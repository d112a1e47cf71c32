"""The committed benchmark runs on the pages (docs/_ext/benchmark_runs.py):
a saved run read back into its provenance and parts, the parts a
directive selects, a table cell read by the ``datum`` role, and each
failure as one printable line; the directive rendered by Sphinx on a
page written here.  Runs on files written here (the committed runs are
checked by tests/project/test_performance_page.py)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "docs" / "_ext"))
import benchmark_runs
from data_values import DatumError, resolve

RUN = """\
<!-- python benchmarks/bench_x.py --save -->
run 2026-12-04 02:00 UTC, commit abc1234, load 1.0 (1-min avg), 2 cores

clock: process CPU time
numpy.sin: 17.47 ns an element
| run (thesis rig, 0-0.06 s) | ms | x numpy.sin |
|---|---:|---:|
| hertz N=16 (default) | 40.1 | 4.84 |
| hertz N=16, summary only | 30.3 | 3.66 |

  k seconds
  1    0.49

| workers | output | seconds |
|---|---|---:|
| 1 | no | 4.08 |
| 1 | CSV | 5.67 |
"""


@pytest.fixture
def base(tmp_path):
    """docs/ of a site whose ../benchmarks/results holds one run."""
    results = tmp_path / "benchmarks" / "results"
    results.mkdir(parents=True)
    (results / "bench_x.md").write_text(RUN)
    (tmp_path / "docs").mkdir()
    return tmp_path / "docs"


def test_a_run_reads_back_as_its_parts(base):
    run = benchmark_runs.read_run(base / benchmark_runs.RESULTS /
                                  "bench_x.md")
    assert run.command == "python benchmarks/bench_x.py --save"
    assert run.provenance == ("2026-12-04 02:00 UTC, commit abc1234, load "
                              "1.0 (1-min avg), 2 cores")
    assert [part.kind for part in run.parts] == ["text", "table", "text",
                                                 "table"]
    # a text line right above a table is its own part; spaces kept
    assert run.parts[0].lines == ("clock: process CPU time",
                                  "numpy.sin: 17.47 ns an element")
    assert run.parts[2].lines == ("  k seconds", "  1    0.49")
    assert len(run.parts[3].lines) == 4


@pytest.mark.parametrize("spec, parts", [
    (None, [1, 2, 3, 4]), ("2", [2]), ("1-3", [1, 2, 3]),
    ("1, 3-4", [1, 3, 4])])
def test_the_parts_a_directive_selects(spec, parts):
    assert benchmark_runs.selected(spec, 4, "x.md") == parts


@pytest.mark.parametrize("spec, says", [
    ("5", "the run has parts 1 to 4"), ("0", "the run has parts 1 to 4"),
    ("3-2", "the run has parts 1 to 4"), ("two", "expected numbers")])
def test_a_bad_selection_is_one_line(spec, says):
    with pytest.raises(DatumError) as caught:
        benchmark_runs.selected(spec, 4, "x.md")
    assert says in str(caught.value) and "\n" not in str(caught.value)


@pytest.mark.parametrize("spec, shown", [
    ("../benchmarks/results/bench_x.md:ms@$1=hertz N=16 (default)", "40.1"),
    (r"../benchmarks/results/bench_x.md#1:$3@$1=hertz N=16\, summary only",
     "3.66"),
    ("../benchmarks/results/bench_x.md#2:seconds@output=CSV", "5.67"),
    ("../benchmarks/results/bench_x.md#2:max(seconds):.1f", "5.7"),
    ("../benchmarks/results/bench_x.md#2:rows", "2"),
])
def test_the_datum_role_reads_a_runs_table(base, spec, shown):
    assert resolve(spec, base) == shown


@pytest.mark.parametrize("spec, says", [
    ("../benchmarks/results/bench_x.md#3:seconds", "the run has 2 tables"),
    ("../benchmarks/results/bench_x.md#b:seconds", "#b is not a table"),
    ("../benchmarks/results/nothing.md:seconds", "no such benchmark run"),
    ("../benchmarks/results/bench_x.md#2:$9", "no column '$9'"),
    ("../benchmarks/results/bench_x.md:ms@$1=hertz N=16", "no row matches"),
])
def test_a_bad_table_datum_is_one_line(base, spec, says):
    with pytest.raises(DatumError) as caught:
        resolve(spec, base)
    assert says in str(caught.value) and "\n" not in str(caught.value)


def test_a_file_that_is_not_a_saved_run_is_refused(tmp_path):
    (tmp_path / "plain.md").write_text("# a page\n\n| a |\n|---|\n| 1 |\n")
    with pytest.raises(DatumError, match="not a saved benchmark run"):
        benchmark_runs.read_run(tmp_path / "plain.md")


def test_the_directive_and_role_render_with_sphinx(base, tmp_path):
    """A page built by Sphinx shows the selected parts from the file:
    the table's cells and the text lines, not the parts left out, and
    the provenance in the sentence."""
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    (base / "conf.py").write_text(
        "import sys\n"
        f"sys.path.insert(0, {str(ROOT / 'docs' / '_ext')!r})\n"
        "extensions = ['myst_parser', 'benchmark_runs', 'data_values']\n")
    (base / "index.md").write_text(
        "# Runs\n\nThe run ({benchmark-provenance}`bench_x`):\n\n"
        "```{benchmark-run} bench_x\n:parts: 1-2\n```\n\n"
        "CSV: {datum}`../benchmarks/results/bench_x.md#2:seconds@"
        "output=CSV` s.\n")
    out = tmp_path / "html"
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "-q", "-b",
                           "html", str(base), str(out)],
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    page = (out / "index.html").read_text()
    assert "commit abc1234, load 1.0" in page
    assert "numpy.sin: 17.47 ns an element" in page
    assert "<td>" in page and "hertz N=16, summary only" in page
    assert "CSV: 5.67 s." in page
    assert "0.49" not in page                   # part 3 not selected
