"""Chatter sweeps: each design of a sweep through the three-beam
simulation (``contactsep sweep --model hertz|newton``).

A design is one call of :func:`contactsep.chatter.simulate` with the
summary only (``samples=1``, ``single_impulse=False``: the answers do not
depend on the sampling, docs/chatter.md) and the default steppers.  Its
row is the varied inputs, then :data:`RESULT_COLUMNS`.  A design the
model or the simulation refuses, or whose stepper cannot finish, is a
status in its row (:data:`MESSAGES`), never an exception that loses the
chunk.  The summary (:class:`ChatterSummary`) counts the designs with a
discontinuity event: ``p_open`` and its Wilson interval.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from contactsep.chatter import simulate
from contactsep.chatter import status as chatter_status
from contactsep.chatter.circuit import MIN_OPEN, OPEN_THRESHOLD
from contactsep.chatter.runners import StepperError
from contactsep.chatter.simulate import UnconvergedWarning
from contactsep.chatter.stack import CoarseStepWarning
from contactsep.errors import InputError
from contactsep.model import thesis_design
from contactsep.model.names import shown_key, shown_text, units_note
from contactsep.output import ComputationLost
from contactsep.model import fields as design_fields
from contactsep.studies.stats import RunningMoments, wilson_interval
from contactsep.studies.sweep.spec import SweepSpec, chunk_inputs, count_failures

#: Output columns after the varied inputs (a contract: issue 16).
RESULT_COLUMNS = ("first_impact_s", "first_impulse_lb_s",
                  "max_lower_gap_in", "circuit_open_s",
                  "first_circuit_open_s", "n_events", "status")
#: Designs per chunk: a design takes 10-400 ms, so a chunk of 8 keeps
#: the progress bar moving and the workers evenly loaded.
CHUNK_SIZE = 8
#: The simulation's settings when a sweep neither fixes nor varies them.
DEFAULT_SETTINGS = {"preload": 0.0, "min_open": MIN_OPEN,
                    "damping": "none", "dt": None, "t_end": None}

#: Per-design status codes of a chatter sweep (0, 2 and 3 mean what
#: they mean in an eq23 sweep, contactsep.model.status).
OK = 0
INVALID_INPUT = 2
NOT_FINITE = 3
STEPPER_FAILED = 4
#: The stepper stopped at its energy bound (contactsep.chatter.status).
ENERGY_BOUND = chatter_status.ENERGY_BOUND
#: The run finished but failed its energy check (the chatter layer's own
#: code, contactsep.chatter.status.UNCONVERGED): its results are in the
#: row, but it is left out of p_open and the statistics.
UNCONVERGED = chatter_status.UNCONVERGED
MESSAGES = {
    OK: "ok",
    INVALID_INPUT: "invalid input: a value out of range, or one the "
                   "chatter simulation does not take",
    NOT_FINITE: "a result is not finite (overflow)",
    STEPPER_FAILED: "stepper failed: the contact LCP had no solution, or "
                    "the gaps hover at the open threshold",
    ENERGY_BOUND: "energy bound: the stepper stopped, its energy past "
                  "twice the release's (dt too coarse for the contact)",
    UNCONVERGED: "unconverged, left out of p_open: the run failed its "
                 "energy check (elastic: energy ratio more than 1e-6 from "
                 "1; damped: energy gained) at the design's step halved "
                 "up to 3 times, or at the given dt",
}


def title(model: str) -> str:
    """The first comment line of a chatter sweep's CSV."""
    return (f"contactsep sweep of the three-beam chatter simulation "
            f"({model}) on the thesis design")


def notes(model: str, dt=None) -> list[str]:
    """How the designs were simulated (``dt`` the fixed step, None for
    the default, "per row" where it is varied) and how to read the
    columns."""
    law = ("Hertz contact" if model == "hertz"
           else "Newton's impact law with e")
    step = ("each design's own step" if dt is None else
            f"dt {dt}" if isinstance(dt, str) else f"dt {dt:g} s")
    return [
        f"model {model}: the three beams, {law}; the adaptive stepper at "
        f"{step}; the window from the release each design's own unless "
        f"t_end_s is fixed (contactsep.chatter.numerics); a contact is "
        f"open above {shown_text(OPEN_THRESHOLD, 'in')}; the circuit is "
        f"open while both are",
        f"settings unless fixed or varied: {shown_key('preload_lb')} = 0, "
        f"min_open_s = {MIN_OPEN:g}"
        + (", damping = none" if model == "hertz" else ""),
        units_note(("in", "s", "lb_s", "lb")) + "; n_events = "
        "discontinuity events (openings >= min_open_s); "
        "first_circuit_open_s nan: never open",
        "status 0 = ok, 2 invalid input, 3 overflow, 4 stepper failed, "
        "7 energy bound, 9 unconverged (energy check failed; results "
        "kept, left out of p_open) (contactsep.studies.sweep.chatter); "
        "failed designs have nan results and n_events -1",
    ]


def simulate_design(fields: dict, model: str, settings: dict) -> tuple:
    """One design's row values (RESULT_COLUMNS order): the design made
    from ``fields`` (thesis_design overrides) and simulated with
    ``settings`` (preload, min_open, damping, dt; a coarse dt is warned
    of once, by the sweep, not by every design)."""
    try:
        design = thesis_design(**fields)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", CoarseStepWarning)
            warnings.simplefilter("ignore", UnconvergedWarning)
            result = simulate(design, model=model, samples=1,
                              single_impulse=False, **settings)
    except StepperError:
        return _failed(STEPPER_FAILED)
    except ComputationLost:
        raise           # the machine's fault, not the design's: no row
    except InputError:
        return _failed(INVALID_INPUT)
    except (ArithmeticError, np.linalg.LinAlgError):
        return _failed(NOT_FINITE)
    if result.status == ENERGY_BOUND:
        return _failed(ENERGY_BOUND)
    values = (result.first_impact_s, result.first_impulse_lb_s,
              result.max_lower_gap_in, result.circuit_open_s,
              result.first_circuit_open_s)
    if not (math.isfinite(result.energy_ratio) and math.isfinite(
            result.max_lower_gap_in) and math.isfinite(
            result.circuit_open_s)):
        return _failed(NOT_FINITE)
    return (*values, result.n_events,
            UNCONVERGED if result.status == chatter_status.UNCONVERGED
            else OK)


def _row(spec: SweepSpec, varied: dict, i: int) -> tuple[dict, dict]:
    """Design i's fields (thesis_design overrides) and settings."""
    fields, settings = dict(spec.base), {**DEFAULT_SETTINGS,
                                         **spec.settings}
    for name, values in varied.items():
        target = settings if name in design_fields.SETTINGS else fields
        target[name] = _plain(values[i])
    if spec.model != "hertz":
        settings.pop("damping")
        settings.pop("static_correction", None)
        for name in ("alpha", "contact", "yield_pressure"):
            settings.pop(name, None)
    elif "static_correction" in settings:
        settings["static_correction"] = \
            settings["static_correction"] == "on"
    return fields, settings


def first_refusal(spec: SweepSpec) -> str | None:
    """Why the sweep's first design is refused, naming the option
    (``--preload: found 1e+300, expected at most ...``; a varied field
    as ``--vary NAME``), or None if it is not: the message a sweep whose
    every design failed as invalid input adds (issue 31)."""
    fields, settings = _row(spec, chunk_inputs(spec, 0, 1), 0)
    try:
        design = thesis_design(**fields)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            simulate(design, model=spec.model, samples=1,
                     single_impulse=False, **settings)
    except StepperError:
        return None
    except InputError as error:
        name, sep, rest = str(error).partition(":")
        if not sep:
            return str(error)
        swept = {s[0] for s in spec.sample} | {n for n, _ in spec.vary}
        option = f"--vary {name}" if name in swept else \
            "--" + name.replace("_", "-")
        return f"{option}:{rest}"
    except (ArithmeticError, np.linalg.LinAlgError):
        return None
    return None


def _failed(status: int) -> tuple:
    return (math.nan,) * 5 + (-1, status)


def _plain(value):
    """A NumPy scalar as the Python value simulate() and Design take."""
    return value.item() if isinstance(value, np.generic) else value


def evaluate_chunk(spec: SweepSpec, first: int, last: int) -> dict:
    """Simulate designs first..last-1 of a chatter sweep; returns the
    output columns: the varied and sampled inputs (output names), then
    RESULT_COLUMNS."""
    inputs = chunk_inputs(spec, first, last)
    size = last - first
    varied = {name: np.broadcast_to(values, (size,))
              for name, values in inputs.items()}
    rows = []
    for i in range(size):
        fields, settings = _row(spec, varied, i)
        try:
            rows.append(simulate_design(fields, spec.model, settings))
        except ComputationLost as error:
            # the sweep stops (its finished chunks kept, resumable), never
            # a row saying "invalid input" for a design that was not
            raise ComputationLost(f"design {first + i}: {error}; the sweep "
                                  f"stopped (rerun with --resume to "
                                  f"continue)") from None
    out = {design_fields.column_name(n): varied[n] for n in spec.fields}
    results = list(zip(*rows)) if rows else [()] * len(RESULT_COLUMNS)
    for name, values in zip(RESULT_COLUMNS, results):
        kind = np.int64 if name in ("n_events", "status") else np.float64
        out[name] = np.array(values, dtype=kind)
    return out


@dataclass
class ChatterSummary:
    """Running statistics of a chatter sweep over its designs with status
    0; failed designs are counted by status."""

    #: Designs with at least one discontinuity event.
    opened: int = 0
    gap: RunningMoments = field(default_factory=RunningMoments)
    open_time: RunningMoments = field(default_factory=RunningMoments)
    #: status code -> designs that ended with it (0 excluded).
    failed: dict = field(default_factory=dict)

    def add(self, columns: dict) -> None:
        ok = count_failures(self.failed, columns["status"])
        self.opened += int(np.sum(np.asarray(columns["n_events"])[ok] > 0))
        self.gap.add(np.asarray(columns["max_lower_gap_in"])[ok])
        self.open_time.add(np.asarray(columns["circuit_open_s"])[ok])

    def merge(self, other: "ChatterSummary") -> None:
        """Add another chunk's summary (a worker's)."""
        self.opened += other.opened
        self.gap.merge(other.gap)
        self.open_time.merge(other.open_time)
        for code, count in other.failed.items():
            self.failed[code] = self.failed.get(code, 0) + count

    @property
    def n(self) -> int:
        return self.gap.count

    @property
    def n_failed(self) -> int:
        return sum(self.failed.values())

    def as_dict(self) -> dict:
        """n (designs with status 0: the statistics are theirs),
        n_failed and n_failed_by_status, n_unconverged (designs that
        failed their energy check, status 9: among n_failed, left out of
        p_open), n_open (designs with a
        discontinuity event), p_open = n_open / n and its 95 % Wilson
        interval p_open_ci95, and the mean and sample sd of the largest
        lower gap (in) and of the circuit's total open time (s); None
        where there is nothing to compute them from."""
        n = self.n
        return {"n": n, "n_failed": self.n_failed,
                "n_failed_by_status": dict(sorted(self.failed.items())),
                "n_unconverged": self.failed.get(UNCONVERGED, 0),
                "n_open": self.opened,
                "p_open": self.opened / n if n else None,
                "p_open_ci95": list(wilson_interval(self.opened, n))
                if n else None,
                "max_lower_gap_mean_in": self.gap.mean,
                "max_lower_gap_sd_in": self.gap.sd,
                "circuit_open_mean_s": self.open_time.mean,
                "circuit_open_sd_s": self.open_time.sd}
