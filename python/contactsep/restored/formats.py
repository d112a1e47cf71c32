"""Output formats of ``contactsep replay --format``: the listing (default,
byte-identical to the program's), a labelled summary, JSON lines (one
object per data set and line), CSV (one row per data set).

Keys and columns are the listing's names, lower-cased, followed by their
unit (``ey_lb_s``, ``ty2dt_in_s``; dimensionless names bare), the
project's one convention; the deck's cards keep the deck's units
(``rho_lb_ft3``).  Numbers have the digits of the build's precision: the
shortest text that reads back to the same float32 or float64.  JSON is
strict (a NaN is null).
"""

from __future__ import annotations

import csv
import dataclasses
import io

import numpy as np

from contactsep.output import json_text
from contactsep.restored.dataset import DataSet
from contactsep.restored.result import Result

FORMATS = ("listing", "summary", "jsonl", "csv")

#: Key suffix of each unit as the summary prints it.
_SUFFIX = {"s": "_s", "in": "_in", "in/s": "_in_s", "lb s": "_lb_s",
           "lb s^2/in": "_lb_s2_in", "rad/s": "_rad_s", "1": ""}
#: Units of the Result's arrays (JSON lines).
_ARRAYS = (("p", "rad/s"), ("ape", "in"), ("trace_t", "s"),
           ("trace_ty", "in"), ("trace_tydtl", "in/s"), ("a1", "in"),
           ("b1", "in"), ("history_t", "s"), ("history_ty3", "in"),
           ("p2", "rad/s"), ("p3", "rad/s"))
#: Units of the deck's cards (dataset.py), as key suffixes.
_CARD_SUFFIX = {"rho": "_lb_ft3", "rho2": "_lb_ft3", "rho3": "_lb_ft3",
                "e": "_psi", "delt": "_s", "er": "", "n": "", "v": "",
                "c": "", "alpha": "", "v2": "", "c2": "", "alph2": "",
                "v3": "", "c3": "", "alph3": ""}

#: The summary's quantities: (name, unit, meaning), in listing order.
SUMMARY_FIELDS: tuple[tuple[str, str, str], ...] = (
    ("t_impact", "s", "time of the first impact"),
    ("tip_velocity_before", "in/s", "upper-contact tip velocity at impact"),
    ("ey", "lb s", "impulse EY (psi, eq. 20)"),
    ("ct", "1", "sum of squared upper-tip mode values CT"),
    ("ct2", "1", "sum of squared separator mid-span mode values CT2"),
    ("ct3", "1", "sum of squared lower-tip mode values CT3"),
    ("tip_ty", "in", "upper-contact tip displacement after impact"),
    ("tip_tydtl", "in/s", "upper-contact tip velocity after impact"),
    ("tip_act", "in/s", "ACT = sum P*B1*C"),
    ("ty2dt", "in/s", "separator mid-span velocity after impact"),
    ("extreme_ty3", "in", "largest-magnitude lower-contact tip "
                          "displacement up to TAU, either sign"),
    ("extreme_time", "s", "time of extreme_ty3"),
    ("separation_ty3", "in", "farthest lower-contact tip displacement in "
                             "the kick's direction (sign of TY2DT)"),
    ("separation_time", "s", "time of separation_ty3"),
    ("wm", "lb s^2/in", "upper-contact mass WM"),
    ("wm2", "lb s^2/in", "separator mass WM2 (after the XL2C correction)"),
    ("wm3", "lb s^2/in", "lower-contact mass WM3"),
    ("gr", "1", "GR = H2/XL2"),
    ("beta", "1", "BETA = WM/(WM2+WM3)"),
    ("mr1", "1", "MR1 = WM2/WM"),
    ("mr3", "1", "MR3 = WM2/WM3"),
)


def summary(result: Result, index: int = 1) -> str:
    """Every summary number on its own line: name = value unit  # meaning."""
    lines = [f"data set {index} ({result.precision}, N = {result.inputs.n})"]
    for name, unit, meaning in SUMMARY_FIELDS:
        value = getattr(result, name)
        lines.append(f"  {name:<20} = {value: .9g} {unit:<10} # {meaning}")
    for name, unit, meaning in (("p", "rad/s", "upper-contact frequencies"),
                                ("p2", "rad/s", "separator frequencies"),
                                ("p3", "rad/s", "lower-contact frequencies"),
                                ("ape", "in", "initial modal amplitudes")):
        values = ", ".join(f"{v:.9g}" for v in getattr(result, name))
        lines.append(f"  {name:<20} = [{values}] {unit} # {meaning}")
    return "\n".join(lines) + "\n"


def _number(result: Result, value) -> float | str:
    """The value with the digits its precision carries."""
    value = float(value)
    if result.precision == "single" and np.isfinite(value):
        return str(np.float32(value))
    return repr(value)


def _key(name: str, unit: str) -> str:
    return name + _SUFFIX[unit]


def csv_text(result: Result, index: int = 1, header: bool = True) -> str:
    """One CSV row of the summary's scalars, after the data set's number,
    its separator thickness d (H2) and N (with a header row first)."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    if header:
        writer.writerow(["data_set", "d_in", "n_modes"]
                        + [_key(name, unit)
                           for name, unit, _ in SUMMARY_FIELDS])
    writer.writerow([index, _number(result, result.inputs.h2),
                     result.inputs.n]
                    + [_number(result, getattr(result, name))
                       for name, _, _ in SUMMARY_FIELDS])
    return out.getvalue()


def json_record(result: Result, index: int = 1) -> dict:
    """One data set's results as a JSON object: its number, precision,
    the summary's scalars and the arrays under keys with units, and its
    cards (``inputs``, the deck's names and units).  The listing itself
    is the default format's."""
    record = {"data_set": index, "precision": result.precision,
              "tau_s": result.tau}
    for name, unit, _ in SUMMARY_FIELDS:
        record[_key(name, unit)] = float(getattr(result, name))
    for name, unit in _ARRAYS:
        record[_key(name, unit)] = np.asarray(getattr(result, name),
                                              dtype=float)
    record["inputs"] = {
        f.name + _CARD_SUFFIX.get(f.name, "_in"): getattr(result.inputs,
                                                          f.name)
        for f in dataclasses.fields(DataSet)}
    return record


def render(result: Result, fmt: str = "listing", index: int = 1) -> str:
    """The text ``replay --format fmt`` prints for the ``index``-th data set
    (JSON lines: one object per line; CSV: the header before the first
    row)."""
    if fmt == "listing":
        return result.listing
    if fmt == "summary":
        return summary(result, index)
    if fmt == "jsonl":
        return json_text(json_record(result, index), indent=None) + "\n"
    if fmt == "csv":
        return csv_text(result, index, header=index == 1)
    raise ValueError(f"unknown format {fmt!r}; expected one of {FORMATS}")
