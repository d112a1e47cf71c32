"""What the preload chart and the conclusion studies (three-beam
simulations with the preload search) must be given, checked before any
work (issue 31): one line naming the argument, never an IndexError,
TypeError, KeyError or AttributeError from inside the search, and never
minutes of eq. 23 before the chatter simulation's mode limit applies."""

from __future__ import annotations

import numpy as np

from contactsep.errors import InputError, shown
from contactsep.studies.sweep.checks import CHATTER_UNUSED


class SearchError(InputError):
    """An argument of the preload chart or a conclusion study refused."""


def check_workers(workers) -> None:
    """None (the usable cores), a whole number of processes >= 1, or a
    ``distributed.Client`` (the simulations on its Dask cluster)."""
    if workers is None:
        return
    from contactsep.runs.dask_run import is_client
    if is_client(workers):
        return
    if isinstance(workers, (bool, np.bool_)) or not isinstance(
            workers, (int, np.integer)) or workers < 1:
        raise SearchError(f"workers: found {shown(workers)}, expected a "
                          f"whole number of processes >= 1 (or None: the "
                          f"usable cores, or a distributed.Client)")


def check_modes(n_modes) -> None:
    """One N per member, from 1 to the chatter simulation's limit."""
    from contactsep.chatter.limits import MAX_MODES
    if isinstance(n_modes, (bool, np.bool_)) or not isinstance(
            n_modes, (int, np.integer)) or not 1 <= n_modes <= MAX_MODES:
        raise SearchError(f"n_modes: found {shown(n_modes)}, expected an "
                          f"integer from 1 to {MAX_MODES} (the chatter "
                          f"simulation's modes per member)")


def check_values(name: str, values, unit: str) -> tuple:
    """A non-empty sequence of finite numbers (a study's rows)."""
    try:
        items = tuple(float(v) for v in values)
    except (TypeError, ValueError, OverflowError):
        raise SearchError(f"{name}: found {shown(values)}, expected a "
                          f"sequence of numbers ({unit})") from None
    if not items:
        raise SearchError(f"{name}: found none, expected at least one "
                          f"value ({unit})")
    if not all(np.isfinite(items)):
        raise SearchError(f"{name}: found {shown(values)}, expected finite "
                          f"numbers ({unit})")
    return items


def check_search(study: str, model, models, n_modes, workers,
                 overrides: dict, simulation_only: bool) -> None:
    """The arguments every search study shares (``models`` the contact
    models it runs); ``simulation_only`` (the preload chart: no eq. 23
    column) refuses the fields only the single-impulse model reads
    (tau, ...), which it would ignore."""
    if model not in models:
        raise SearchError(f"model: found {shown(model)}, expected one of "
                          f"{', '.join(models)}")
    check_modes(n_modes)
    check_workers(workers)
    unused = sorted(set(overrides) & set(CHATTER_UNUSED))
    if simulation_only and unused:
        raise SearchError(f"{', '.join(unused)}: study {study} runs only "
                          f"the three-beam simulation (window 0-0.06 s from "
                          f"the release), which does not read it; leave it "
                          f"out")


def check_designs(designs) -> list:
    """A list of contactsep.Design (min_preloads' designs)."""
    from contactsep.model import Design
    designs = list(designs)
    for i, design in enumerate(designs):
        if not isinstance(design, Design):
            raise SearchError(f"designs: item {i} is "
                              f"{type(design).__name__}, expected a "
                              f"contactsep.Design")
    return designs
