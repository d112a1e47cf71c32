"""Arithmetic in the ``datum`` role (docs/_ext/data_expressions.py):
``=EXPR[:FORMAT]`` over values of CSVs written here; only arithmetic is
evaluated, and each failure is one printable line."""

from __future__ import annotations

import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "docs" / "_ext"))
import data_expressions
from data_values import DatumError, files, resolve

TABLE = """\
# a comment
label,seconds,count
no,4.08,0
"CSV, streamed",5.67,3
zero,0,0
"""


@pytest.fixture
def base(tmp_path):
    (tmp_path / "t.csv").write_text(TABLE)
    return tmp_path


@pytest.mark.parametrize("spec, shown", [
    ("=[t.csv:seconds@label=no] * 2:.2f", "8.16"),
    (r"=100 * ([t.csv:seconds@label=CSV\, streamed] / "
     r"[t.csv:seconds@label=no] - 1):+.1f", "+39.0"),
    ("=abs([t.csv:seconds@label=no] - 5):.2f", "0.92"),
    ("=max([t.csv:count@label=no], 2) ** 2", "4"),
    ("=round([t.csv:seconds@label=no])", "4"),
    ("=-[t.csv:sum(count)]", "-3"),
    ("=[t.csv:rows] / 2:.1f", "1.5"),
])
def test_an_expression_is_its_arithmetic(base, spec, shown):
    assert resolve(spec, base) == shown


@pytest.mark.parametrize("spec, says", [
    ("=2 * 3", "needs at least one"),
    ("=[t.csv:seconds@label=no] / [t.csv:seconds@label=zero]",
     "division by zero"),
    ("=__import__('os').getcwd() + [t.csv:rows]", "only numbers"),
    ("=[t.csv:seconds@label=no].real", "only numbers"),
    ("=[t.csv:label@label=no] + 1", "is not a number"),
    ("=[t.csv:seconds@label=no] +", "not an expression"),
    ("=[t.csv:nothing] + 1", "no column 'nothing'"),
])
def test_a_bad_expression_is_one_line(base, spec, says):
    with pytest.raises(DatumError) as caught:
        resolve(spec, base)
    message = str(caught.value)
    assert says in message and "\n" not in message and message.isprintable()


def test_the_expression_names_its_files():
    spec = "=[a.csv:x] / [../benchmarks/results/r.md#2:y@k=v]:.1f"
    assert files(spec) == ["a.csv", "../benchmarks/results/r.md"]
    assert data_expressions.split(spec) == (
        "v0 / v1", ["a.csv:x", "../benchmarks/results/r.md#2:y@k=v"], ".1f")
