"""Output formats of ``contactsep replay --format``: the listing (default,
byte-identical to the program's), a labelled summary, JSON lines, CSV."""

from __future__ import annotations

import csv
import io

from contactsep.restored.result import Result

FORMATS = ("listing", "summary", "json", "csv")

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


def csv_text(result: Result, index: int = 1, header: bool = True) -> str:
    """One CSV row of the summary's scalars (with a header row first)."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    if header:
        writer.writerow(["data_set"] + [f"{name} [{unit}]"
                                        for name, unit, _ in SUMMARY_FIELDS])
    writer.writerow([index] + [repr(float(getattr(result, name)))
                               for name, _, _ in SUMMARY_FIELDS])
    return out.getvalue()


def render(result: Result, fmt: str = "listing", index: int = 1) -> str:
    """The text ``replay --format fmt`` prints for the ``index``-th data set
    (JSON: one object per line; CSV: the header before the first row)."""
    if fmt == "listing":
        return result.listing
    if fmt == "summary":
        return summary(result, index)
    if fmt == "json":
        return result.to_json() + "\n"
    if fmt == "csv":
        return csv_text(result, index, header=index == 1)
    raise ValueError(f"unknown format {fmt!r}; expected one of {FORMATS}")
