"""Shared fixtures: the thesis decks, and decks the tests generate."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from contactsep.restored import cards, thesis_decks
from contactsep.restored.dataset import DataSet

# the preload command's planted physics, a fixture for every test module
from planted_preload import planted_preload  # noqa: E402, F401
# a Dask deployment of a scheduler and two workers, one a test module
from dask_deployment import deployment  # noqa: F401

ROOT = Path(__file__).resolve().parent.parent
DECK_DIR = ROOT / "data" / "decks"
THESIS_DECKS = sorted(DECK_DIR.glob("*.dat"))
PRECISIONS = ("single", "double")


def deck_id(path: Path) -> str:
    return path.stem


def with_modes(data_set: DataSet, n: int) -> DataSet:
    """The data set with N modes, constants from the project's beam code."""
    return data_set.replace(**thesis_decks.mode_constants(n))


def variant_data_sets() -> dict[str, list[DataSet]]:
    """Decks beyond the thesis's: other materials, sizes, N, DELY."""
    base = thesis_decks.thesis_data_set(0.250)
    steel = base.replace(e=30.0e6, rho=490.0, rho2=490.0, rho3=490.0)
    brass_thin = base.replace(
        e=15.0e6, rho=532.0, rho2=532.0, rho3=532.0, h=0.0625, h3=0.0625,
        xl=10.0, xl3=10.0, b=0.75, b3=0.75, ystat=0.2)
    variants = {
        "steel": [steel],
        "brass_thin": [brass_thin],
        "wide_separator": [base.replace(xl2=4.0, b2=1.0, h2=0.4,
                                        xl2c=4.5, er=0.8)],
        "dely_positive": [base.replace(dely=0.05)],
        "dely_negative": [base.replace(dely=-0.02, ystat=0.3)],
        "delt_coarse": [base.replace(delt=0.002)],
        "several_sets": [base, steel, base.replace(er=1.0)],
    }
    for n in (1, 2, 3):
        variants[f"n{n}"] = [with_modes(base, n)]
    return variants


def write_deck(tmp_path: Path, name: str, data_sets: list[DataSet],
               newline: str = "\n") -> Path:
    text = cards.format_deck(data_sets)
    if newline != "\n":
        text = text.replace("\n", newline)
    path = tmp_path / f"{name}.dat"
    path.write_bytes(text.encode("ascii"))
    return path


@pytest.fixture(params=THESIS_DECKS, ids=deck_id)
def thesis_deck(request) -> Path:
    return request.param


@pytest.fixture(params=PRECISIONS)
def precision(request) -> str:
    return request.param


def as_precision(values, precision: str) -> np.ndarray:
    """Values rounded to the working precision, as the program reads them."""
    dtype = np.float32 if precision == "single" else np.float64
    return np.asarray(values, dtype=dtype).astype(np.float64)


#: Seconds past pytest-timeout's limit at which the watchdog below ends
#: the run.
WATCHDOG_MARGIN_S = 60.0


@pytest.fixture(autouse=True)
def _hang_watchdog(request):
    """End the run if a test outlives the per-test limit inside a
    compiled call (issue 26).  f2py calls hold the GIL, so neither of
    pytest-timeout's methods can act while a Fortran loop runs (a
    Flores sign error made one run forever); faulthandler's timer is a
    C thread that needs no GIL: it dumps every thread's stack and exits
    (status 1)."""
    import faulthandler
    import sys

    try:
        limit = float(request.config.getini("timeout") or 0.0)
    except (ValueError, TypeError):
        limit = 0.0
    marker = request.node.get_closest_marker("timeout")
    if marker is not None and marker.args:
        limit = float(marker.args[0])
    option = getattr(request.config.option, "timeout", None)
    if option:
        limit = float(option)
    if limit <= 0.0:
        yield
        return
    out = sys.stderr
    try:   # the real stderr (the capture would swallow the dump)
        from _pytest.faulthandler import fault_handler_stderr_fd_key
        out = request.config.stash[fault_handler_stderr_fd_key]
    except (ImportError, KeyError):
        pass
    faulthandler.dump_traceback_later(limit + WATCHDOG_MARGIN_S, exit=True,
                                      file=out)
    try:
        yield
    finally:
        faulthandler.cancel_dump_traceback_later()
