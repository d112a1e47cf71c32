"""The ``datum`` role of the docs (docs/_ext/data_values.py): its
resolver on CSVs written here (selection, aggregates, formats, and each
failure as one printable line), and every use of the role on the pages
resolved against the committed files, so a broken one fails here before
the site is built.  Runs without Sphinx."""

from __future__ import annotations

import csv
import io
import re
import subprocess
import sys

import pytest

from conftest import ROOT

EXT = ROOT / "docs" / "_ext"
sys.path.insert(0, str(EXT))
import data_values
from data_values import DatumError, resolve

DOCS = ROOT / "docs"
#: A use of the role in a Markdown page: {datum}`...`.
USE = re.compile(r"\{datum\}`([^`]*)`")

TABLE = """\
# a comment line, as every CSV the package writes starts
# d_in,ys_in,answer_lb (not the header: a comment)
model,d_in,ys_in,answer_lb,n_modes,converged
hertz,0.25,0.5,15.5725953406,32,1
hertz,0.25,0.75,25.0626915636,64,1
hertz,0.5,0.5,4.01097985005,32,0
hertz,0.5,0.75,nan,32,0
newton,0.250,0.50,9.5,16,1
# a trailing comment, as an interrupted sweep ends
"""


@pytest.fixture
def base(tmp_path):
    (tmp_path / "t.csv").write_text(TABLE)
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "big.csv").write_text(
        "n,label\n1234567,a\n2.5,b\n7,\n")
    return tmp_path


@pytest.mark.parametrize("spec, shown", [
    # one row, selected numerically (0.25 == 0.250) and as text
    ("t.csv:answer_lb@model=hertz,d_in=0.25,ys_in=0.5:.4g", "15.57"),
    ("t.csv:answer_lb@d_in=0.25,ys_in=0.5,model=newton:.2f", "9.50"),
    ("t.csv:answer_lb@model=newton", "9.5"),          # as written
    ("t.csv:n_modes@d_in=0.25,ys_in=0.75", "64"),
    ("t.csv:model@n_modes=16", "newton"),              # text, no format
    ("t.csv:d_in@model=newton", "0.250"),
    (" t.csv : answer_lb @ model = newton : .1f ", "9.5"),   # spaces
    # aggregates (NaN skipped by max, min and sum)
    ("t.csv:max(answer_lb)@model=hertz:.4g", "25.06"),
    ("t.csv:max(answer_lb)@model=hertz", "25.0626915636"),
    ("t.csv:min(answer_lb)", "4.01097985005"),
    ("t.csv:min(answer_lb):.3g", "4.01"),
    ("t.csv:sum(n_modes)", "176"),
    ("t.csv:sum(n_modes)@converged=1:,d", "112"),
    ("t.csv:sum(answer_lb)@d_in=0.5:.3f", "4.011"),
    ("t.csv:rows", "5"),
    ("t.csv:rows@converged=1", "3"),
    ("t.csv:rows@model=hertz,converged=0", "2"),
    ("t.csv:rows@model=hertz,d_in=9", "0"),
    # formats
    ("sub/big.csv:n@label=a:,d", "1,234,567"),
    ("sub/big.csv:n@label=a:.3g", "1.23e+06"),
    ("sub/big.csv:n@label=b:.0%", "250%"),
    ("sub/big.csv:n@label=b:n", "2.5"),           # n takes a float too
    ("t.csv:max(n_modes)@converged=0:d", "32"),
    ("sub/big.csv:sum(n):,.1f", "1,234,576.5"),
    ("t.csv:n_modes@d_in=0.25,ys_in=0.75:03d", "064"),
    ("t.csv:answer_lb@model=newton:d", None),   # 9.5 is no integer
    # the pages' exponent: no plus, no leading zeros
    ("sub/big.csv:n@label=a:.1sci", "1.2e6"),
    ("t.csv:answer_lb@model=newton:.0sci", "1e1"),
    ("t.csv:min(answer_lb):.2sci", "4.01e0"),
])
def test_resolves(base, spec, shown):
    if shown is None:
        with pytest.raises(DatumError, match="not an integer"):
            resolve(spec, base)
    else:
        assert resolve(spec, base) == shown


@pytest.mark.parametrize("spec, says", [
    ("none.csv:answer_lb", "none.csv: answer_lb: no such file"),
    ("t.csv:speed@model=newton", "no column 'speed'"),
    ("t.csv:answer_lb@speed=1", "no column 'speed'"),
    ("t.csv:max(speed)", "no column 'speed'"),
    ("t.csv:answer_lb@d_in=7", "no row matches"),
    ("t.csv:max(answer_lb)@d_in=7", "no row matches"),
    ("t.csv:answer_lb@d_in=0.25", "3 rows match, one is needed"),
    ("t.csv:answer_lb", "5 rows match"),
    ("t.csv:answer_lb@model=newton:.2q", "bad format '.2q'"),
    ("t.csv:answer_lb@model=newton:.2qsci", "bad format '.2qsci'"),
    ("t.csv:model@n_modes=16:.2f", "'newton' is not a number"),
    ("t.csv:max(model)", "'hertz' is not a number"),
    ("t.csv:answer_lb@d_in=0.5,ys_in=0.75:.4g", "the value is nan"),
    ("sub/big.csv:label@n=7", "the cell is empty"),
    ("t.csv:max(answer_lb)@ys_in=0.75,d_in=0.5",
     "every matching value is NaN"),
    ("t.csv:answer_lb@d_in", "filter 'd_in' is not KEY=VALUE"),
    ("t.csv:answer_lb@=3", "is not KEY=VALUE"),
    ("t.csv", "expected FILE:COLUMN"),
    ("t.csv:", "expected FILE:COLUMN"),
    (":answer_lb", "expected FILE:COLUMN"),
    ("t.csv:@d_in=0.5", "no column in datum"),
    ("/abs/t.csv:answer_lb", "must be relative to docs/"),
    ("sub:n", "sub: n: cannot read it"),                 # a directory
    ("bad.csv:n", "data row 2 has 3 cells, the header 2"),
    ("latin.csv:n", "cannot read it"),
    ("empty.csv:n", "no header line"),
    # white space of any kind is one space; a control character escaped
    ("t.csv:answer_lb@d_in=0.25\n,ys_in=\t0.5\x00",
     "where d_in=0.25, ys_in=0.5\\x00: no row matches"),
])
def test_each_failure_is_one_printable_line(base, spec, says):
    (base / "bad.csv").write_text("n,label\n1,a\n2,b,c\n")
    (base / "latin.csv").write_bytes(b"n,label\n1,\xe9\n")
    (base / "empty.csv").write_text("# only a comment\n\n")
    with pytest.raises(DatumError) as caught:
        resolve(spec, base)
    message = str(caught.value)
    assert says in message
    assert message.isprintable() and "\n" not in message


def test_a_failure_names_the_file_column_and_filters(base):
    for spec in ("t.csv:answer_lb@d_in=7,model=hertz:.2f",
                 "t.csv:missing@d_in=7,model=hertz:.2f"):
        with pytest.raises(DatumError) as caught:
            resolve(spec, base)
        assert str(caught.value).startswith(
            "t.csv: " + spec.split(":")[1].split("@")[0]
            + " where d_in=7, model=hertz: ")


def test_the_resolver_imports_without_sphinx():
    code = ("import sys; sys.path.insert(0, sys.argv[1]); "
            "import data_values; "
            "bad = [m for m in sys.modules "
            "if m.split('.')[0] in ('sphinx', 'docutils')]; "
            "assert not bad, bad")
    done = subprocess.run([sys.executable, "-c", code, str(EXT)],
                          capture_output=True, text=True, timeout=60,
                          check=False)
    assert done.returncode == 0, done.stderr


def uses(docs):
    """(page, line, spec) of every {datum} in the Markdown pages."""
    found = []
    for page in sorted(docs.rglob("*.md")):
        if "_build" in page.parts:
            continue
        text = page.read_text(encoding="utf-8")
        for match in USE.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            found.append((page.relative_to(docs), line, match.group(1)))
    return found


def broken(docs):
    """The uses that do not resolve, with their error."""
    failures = []
    for page, line, spec in uses(docs):
        try:
            resolve(spec, docs)
        except DatumError as error:
            failures.append(f"{page}:{line}: {error}")
    return failures


def test_every_use_on_the_pages_resolves_against_the_committed_files():
    assert uses(DOCS), "no {datum} on the pages: the scan finds none"
    assert broken(DOCS) == []


def test_the_scan_finds_a_broken_use(base):
    (base / "page.md").write_text(
        "At least {datum}`t.csv:answer_lb@model=newton:.1f` lb,\n"
        "and **{datum}`t.csv:answer_lb@model=nobody:.1f` lb**.\n")
    assert [(str(p), n) for p, n, _ in uses(base)] == [("page.md", 1),
                                                        ("page.md", 2)]
    [failure] = broken(base)
    assert failure.startswith("page.md:2: t.csv: answer_lb where "
                              "model=nobody: no row matches")


def test_the_role_renders_with_docutils():
    """The role itself, without Sphinx: the value as text; a broken
    one an error system message at its line."""
    docutils = pytest.importorskip("docutils.core")
    from docutils import nodes
    from docutils.parsers.rst import roles

    roles.register_local_role("datum", data_values.datum_role)
    lines = (DOCS / "studies" / "preload.csv").read_text().splitlines()
    held = sum(r["converged"] == "1" for r in
               csv.DictReader(x for x in lines if x[:1] != "#"))
    tree = docutils.publish_doctree(
        "Held: :datum:`studies/preload.csv:rows@converged=1`.\n\n"
        "Next, :datum:`studies/preload.csv:nothing`.\n",
        settings_overrides={"report_level": 3, "halt_level": 5,
                            "warning_stream": io.StringIO()})
    first = next(iter(tree.findall(nodes.paragraph)))
    assert first.astext() == f"Held: {held}."
    [message] = tree.findall(nodes.system_message)
    assert (message["level"], message["line"]) == (3, 3)
    assert "datum: studies/preload.csv: nothing: no column 'nothing'" \
        in message.astext()


def test_an_error_points_at_the_roles_own_line(tmp_path):
    """MyST gives a role its paragraph's first line; the error's line is
    the role's own, the first use at or after it."""
    page = tmp_path / "page.md"
    use = "t.csv:rows@x=1"
    page.write_text(f"Intro {{datum}}`{use}`.\n\nA paragraph\nof three\n"
                    f"lines, {{datum}}`{use}` here.\n")
    assert data_values.source_line(str(page), use, 1) == 1
    assert data_values.source_line(str(page), use, 3) == 5
    assert data_values.source_line(str(page), "t.csv:other", 3) == 3
    assert data_values.source_line("<string>", use, 7) == 7


SUMMARY = """{"n": 1000, "p": 0.0845, "ci": [0.08, 0.09], "ok": true,
 "none": null, "inputs": {"seed": 0, "sample": {"d_in": {"sd": 0.01}}},
 "label": "hertz"}"""


@pytest.mark.parametrize("spec, shown", [
    ("s.json:n:,d", "1,000"),
    ("s.json:p", "0.0845"),
    ("s.json:p:.2f", "0.08"),
    ("s.json:ci[1]:.2f", "0.09"),
    ("s.json:inputs.seed", "0"),
    ("s.json:inputs.sample.d_in.sd:g", "0.01"),
    ("s.json:ok", "1"),
    ("s.json:label", "hertz"),
    ("s.json:rows", "1"),
])
def test_a_committed_json_object_is_one_row_of_its_leaves(tmp_path, spec,
                                                           shown):
    (tmp_path / "s.json").write_text(SUMMARY)
    assert resolve(spec, tmp_path) == shown


@pytest.mark.parametrize("text, spec, says", [
    (SUMMARY, "s.json:none", "the cell is empty"),
    (SUMMARY, "s.json:nope", "no column 'nope'"),
    (SUMMARY, "s.json:ci", "no column 'ci'"),
    ("[1, 2]", "s.json:x", "not a JSON object"),
    ("{nan", "s.json:x", "not a JSON file"),
    (None, "s.json:x", "no such file"),
])
def test_a_json_file_that_cannot_be_read_is_one_line(tmp_path, text, spec,
                                                      says):
    if text is not None:
        (tmp_path / "s.json").write_text(text)
    with pytest.raises(DatumError) as caught:
        resolve(spec, tmp_path)
    assert says in str(caught.value)
    assert "\n" not in str(caught.value)
