"""The sources keep the project's rules: the library never stops or prints,
modern Fortran style in the restored core, the transcription's card
layout, and every marked change recorded in RESTORATION.md."""

from __future__ import annotations

import re

import pytest

from conftest import ROOT

FORTRAN = ROOT / "fortran"
CORE = sorted([*(FORTRAN / "restored").glob("*.f90"),
               *(FORTRAN / "common").glob("*.f90")])
LEGACY = FORTRAN / "legacy" / "appg.f"


def code_lines(path):
    """(number, line) of the code, comments removed."""
    for number, line in enumerate(path.read_text().splitlines(), 1):
        code = line.split("!", 1)[0]
        if code.strip():
            yield number, code


@pytest.mark.parametrize("path", CORE, ids=lambda p: p.name)
def test_core_never_stops_prints_or_jumps(path):
    forbidden = re.compile(
        r"^\s*(stop|error\s+stop|print|pause)\b|write\s*\(\s*(\*|6)\b|"
        r"\bgo\s*to\b|\bcommon\s*/|\breal\s*\*\s*8|^\s*if\s*\(.*\)\s*\d+\s*,",
        re.IGNORECASE)
    bad = [(n, l) for n, l in code_lines(path) if forbidden.search(l)]
    assert not bad


@pytest.mark.parametrize("path", CORE, ids=lambda p: p.name)
def test_core_style(path):
    text = path.read_text()
    assert all(len(line) <= 80 for line in text.splitlines())
    modules = re.findall(r"^\s*module\s+(\w+)\s*$", text, re.I | re.M)
    assert len(modules) == 1
    assert re.search(r"^\s*implicit none", text, re.I | re.M)


def procedures(text):
    """(name, dummy arguments, body) of every subroutine and function."""
    joined = re.sub(r"&\s*\n\s*&?", " ", text)
    head = re.compile(
        r"^[ \t]*(?:(?:pure|elemental|recursive|module)\s+)*"
        r"(subroutine|function)\s+(\w+)\s*\(([^)]*)\)", re.I | re.M)
    for match in head.finditer(joined):
        kind, name = match.group(1), match.group(2)
        end = re.search(rf"^\s*end\s+{kind}\s+{name}\b", joined[match.end():],
                        re.I | re.M)
        body = joined[match.end():match.end() + end.start()]
        args = [a.strip() for a in match.group(3).split(",") if a.strip()]
        yield name, args, body


@pytest.mark.parametrize("path", CORE, ids=lambda p: p.name)
def test_every_dummy_argument_has_intent(path):
    missing = []
    for name, args, body in procedures(path.read_text()):
        declared = set()
        for line in body.splitlines():
            line = line.split("!", 1)[0]
            if re.search(r"intent\s*\(", line, re.I) and "::" in line:
                names = line.split("::", 1)[1]
                names = re.sub(r"\([^()]*\)", "", re.sub(r"\([^()]*\)", "",
                                                          names))
                declared |= {n.split("=")[0].strip().lower()
                             for n in names.split(",")}
        missing += [f"{name}({a})" for a in args if a.lower() not in declared]
    assert not missing


def test_transcription_card_layout():
    for number, line in enumerate(LEGACY.read_text().splitlines(), 1):
        assert len(line) <= 72, number
        if line[:1] not in ("C", "c", "*") and line.strip():
            label, statement = line[:5], line[6:]
            assert label.strip() == "" or label.strip().isdigit(), number
            assert line[5] == " " and statement.strip(), number


def test_every_marked_change_is_recorded():
    marks = set(re.findall(r"^C RESTORED: (\d+)", LEGACY.read_text(), re.M))
    notes = (FORTRAN / "RESTORATION.md").read_text()
    recorded = set(re.findall(r"^\| (\d+) \|", notes, re.M))
    assert marks and marks == recorded
