"""Reading the documentation pages from the tests: a page's text with
its white space joined, the ``datum`` role a page uses for a value of a
committed CSV, and the rows of docs/studies's CSVs."""

from __future__ import annotations

import csv
import importlib.util
import re
from pathlib import Path

import numpy as np

from conftest import ROOT

STUDIES = ROOT / "docs" / "studies"


def page(name: str) -> str:
    """The page's text, every run of white space one blank."""
    return " ".join((ROOT / "docs" / name).read_text().split())


def quoted(name: str, pattern: str) -> tuple[str, ...]:
    """The groups of ``pattern`` (a regular expression, white space
    already one blank) in page ``name``; fails when it is not there."""
    found = re.search(pattern, page(name))
    assert found, f"{name}: no longer says {pattern!r}"
    return found.groups()


NUMBER = r"([-+]?[\d.]+(?:e-?\d+)?)"


def printed(value: float, claim: str) -> bool:
    """``value`` written as the page writes ``claim`` is ``claim``: to its
    decimals (0.137, +5.4), or to its significant digits (3.6e-6)."""
    claim = claim.replace(",", "")
    if "e" in claim:
        digits = len(claim.split("e")[0].replace(".", "").lstrip("+-0")) - 1
        return f"{value:.{digits}e}" == f"{float(claim):.{digits}e}"
    decimals = len(claim.split(".")[1]) if "." in claim else 0
    text = f"{value:+.{decimals}f}" if claim[0] in "+-" else \
        f"{value:.{decimals}f}"
    return text == claim


def rows(name: str) -> list[dict]:
    """The rows of the committed docs/studies/NAME.csv."""
    lines = [line for line in (STUDIES / f"{name}.csv").read_text()
             .splitlines() if not line.startswith("#")]
    return list(csv.DictReader(lines))


def column(name: str, key: str, **where) -> np.ndarray:
    return np.array([float(r[key]) for r in rows(name)
                     if all(np.isclose(float(r[k]), v) if not
                            isinstance(v, str) else r[k] == v
                            for k, v in where.items())])


def check(claims, values) -> None:
    claims, values = list(claims), list(values)
    assert len(claims) == len(values)
    for claim, value in zip(claims, values):
        assert printed(value, claim), (claim, value)


# -- docs/studies.md, the figures ---------------------------------------------

def role(name: str, key: str, fmt: str | None, **where) -> str:
    """The datum role that shows ``key`` of docs/studies/NAME.csv in
    the row ``where`` selects (white space as on a joined page)."""
    filters = ",".join(f"{k}={v:g}" if not isinstance(v, str) else
                       f"{k}={v}" for k, v in where.items())
    filters = f"@{filters}" if filters else ""
    fmt = f":{fmt}" if fmt else ""
    return f"{{datum}}`studies/{name}.csv:{key}{filters}{fmt}`"


def says(name: str, text: str) -> None:
    assert text in page(name), f"{name}: no longer says {text!r}"




def script_module(path: Path):
    """The Python file ``path`` (a docs/studies/make_*.py script, or a
    test module whose constants a page quotes) loaded as a module."""
    spec = importlib.util.spec_from_file_location(f"_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
