"""Constants have one home each (issue 20): the Fortran module that defines
them, mirrored in Python and pinned here; nothing else writes them."""

from __future__ import annotations

import re

import pytest

from conftest import ROOT
from contactsep import constants
from contactsep.chatter import status as chatter_status
from contactsep.model import status as model_status
from contactsep.restored import status as restored_status

FORTRAN = ROOT / "fortran"
PYTHON = ROOT / "python" / "contactsep"


def fortran_parameters(path, prefix=r"\w+"):
    """name -> value of every public named constant in a Fortran module."""
    text = path.read_text()
    return {name: value for name, value in re.findall(
        rf"parameter, public ::\s*({prefix})\s*=\s*([-+.\w]+)", text)}


def test_shared_constants_are_the_fortran_ones():
    found = fortran_parameters(FORTRAN / "common" / "constants.f90")
    values = {name: float(value.removesuffix("_wp"))
              for name, value in found.items()}
    assert values == {
        "gravity": constants.GRAVITY_IN_PER_S2,
        "cubic_inches_per_cubic_foot": constants.CUBIC_INCHES_PER_CUBIC_FOOT,
        "listing_tau": constants.LISTING_TAU_S}
    # the listing's own literals (Appendix G): 386.4, 1728.0, TAU = 0.060
    assert (constants.GRAVITY_IN_PER_S2, constants.CUBIC_INCHES_PER_CUBIC_FOOT,
            constants.LISTING_TAU_S) == (386.4, 1728.0, 0.060)
    listing = (FORTRAN / "legacy" / "appendix_g_as_printed.txt").read_text()
    assert "386.4" in listing and "1728.0" in listing
    assert "TAU = 0.060" in listing


@pytest.mark.parametrize("home, module", [
    ("restored/status.f90", restored_status),
    ("model/model_status.f90", model_status),
    ("chatter/chatter_status.f90", chatter_status)],
    ids=["restored", "model", "chatter"])
def test_status_codes_are_mirrored(home, module):
    fortran = {name.upper(): int(value) for name, value in
               fortran_parameters(FORTRAN / home, r"status_\w+").items()}
    python = {f"STATUS_{name}": value for name, value in vars(module).items()
              if name.isupper() and isinstance(value, int)}
    assert fortran and fortran == python
    assert len(set(fortran.values())) == len(fortran)   # one meaning each


def code_text(path):
    """The code of a source file, comments and docstrings left out."""
    text = path.read_text()
    if path.suffix == ".py":
        text = re.sub(r'"""(.|\n)*?"""', "", text)
        return "\n".join(line.split("#", 1)[0] for line in text.splitlines())
    return "\n".join(line.split("!", 1)[0] for line in text.splitlines())


HOMES = {FORTRAN / "common" / "constants.f90", PYTHON / "constants.py"}
SOURCES = sorted(p for p in [*FORTRAN.glob("*/*.f90"), *PYTHON.rglob("*.py")]
                 if p not in HOMES)


@pytest.mark.parametrize("path", SOURCES,
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_nothing_else_writes_a_shared_constant(path):
    """386.4 and 1728 appear as numbers only in their homes (and in the
    transcription, fortran/legacy/, which is the listing as printed)."""
    assert not re.search(r"(?<![\w.])(386\.4|1728\.?0*)(?![\w.])",
                         code_text(path))
