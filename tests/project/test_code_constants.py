"""The ``constant`` role of the docs (docs/_ext/code_constants.py): its
resolver on the package's constants (items, formats, words, and each
failure as one printable line), and every use of the role on the pages
resolved, so a renamed constant fails here before the site is built.
Runs without Sphinx."""

from __future__ import annotations

import re
import sys

import pytest

from conftest import ROOT

sys.path.insert(0, str(ROOT / "docs" / "_ext"))
import code_constants
from code_constants import ConstantError, resolve

from contactsep.model import design_domain
from contactsep.runs import chunks

DOCS = ROOT / "docs"
#: A use of the role in a Markdown page: {constant}`...`.
USE = re.compile(r"\{constant\}`([^`]*)`")


@pytest.mark.parametrize("spec, shown", [
    ("contactsep.runs.chunks.CHUNKS_PER_WORKER", str(chunks.CHUNKS_PER_WORKER)),
    ("contactsep.runs.chunks.MIN_CHUNK_S", str(chunks.MIN_CHUNK_S)),
    ("contactsep.runs.chunks.MIN_CHUNK_S:.2f", f"{chunks.MIN_CHUNK_S:.2f}"),
    ("contactsep.model.design_domain.SIZE_RANGE[1]:g",
     f"{design_domain.SIZE_RANGE[1]:g}"),
    ("contactsep.model.design_domain.SIZE_RANGE[0]:g",
     f"{design_domain.SIZE_RANGE[0]:g}"),
    (" contactsep.runs.chunks.CHUNKS_PER_WORKER : words ",
     ["zero", "one", "two", "three", "four", "five", "six", "seven",
      "eight", "nine", "ten", "eleven", "twelve", "thirteen", "fourteen",
      "fifteen", "sixteen", "seventeen", "eighteen", "nineteen",
      "twenty"][chunks.CHUNKS_PER_WORKER]),
])
def test_a_constant_is_shown_as_asked(spec, shown):
    assert resolve(spec) == shown


@pytest.mark.parametrize("number, shown", [
    (1e5, "1e5"), (1024, "1024"), (1e-5, "1e-5"), (3e8, "3e8"),
    (10**12, "1e12"), (10.0, "10"), (0.5, "0.5"), (2.5e-7, "2.5e-7"),
    (123456789.0, "123456789")])
def test_the_sci_format_is_the_shorter_form(number, shown):
    assert code_constants._format(number, "sci", "x") == shown
    assert float(shown) == number          # the same number


def test_the_words_are_the_numbers():
    """The words format's table, against the numbers spelled out."""
    assert code_constants.WORDS[:5] == ["zero", "one", "two", "three",
                                        "four"]
    assert code_constants.WORDS[12] == "twelve"
    assert code_constants.WORDS[20] == "twenty"
    assert len(code_constants.WORDS) == 21


@pytest.mark.parametrize("spec, message", [
    ("numpy.pi", "not a name of the contactsep package"),
    ("contactsep.runs.chunks.chunk_seconds", "is not a constant"),
    ("contactsep.runs.chunks.NO_SUCH", "has no NO_SUCH"),
    ("contactsep.model.design_domain.SIZE_RANGE", "not one value"),
    ("contactsep.model.design_domain.SIZE_RANGE[5]", "has no item [5]"),
    ("contactsep.model.design_domain.SIZE_RANGE[x]",
     "is not an integer or a quoted key"),
    ("contactsep.runs.chunks.MIN_CHUNK_S:words", "has no word"),
    ("contactsep.runs.chunks.MIN_CHUNK_S:d", "does not take"),
    ("contactsep.runs.backend.Backend", "a class, not a value"),
    ("contactsep.no_module.X", "no_module is not a constant of contactsep"),
    ("", "expected MODULE.NAME"),
])
def test_every_failure_is_one_line(spec, message):
    with pytest.raises(ConstantError) as caught:
        resolve(spec)
    text = str(caught.value)
    assert message in text
    assert "\n" not in text and text.isprintable()


def _uses():
    found = []
    for path in sorted(DOCS.rglob("*.md")):
        if "_build" in path.parts or "generated" in path.parts:
            continue
        for spec in USE.findall(path.read_text(encoding="utf-8")):
            found.append((path.relative_to(DOCS).as_posix(), spec))
    return found


def test_the_pages_use_the_role():
    assert len(_uses()) >= 10


@pytest.mark.parametrize("page, spec", _uses())
def test_every_use_on_the_pages_resolves(page, spec):
    assert resolve(spec)
