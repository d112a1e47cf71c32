"""The model's domain: which designs it takes (docs/model.md, "Domain").

The packed columns of a design (the compiled kernel's contract), the
ranges of its fields, and the rules a design must pass: a scalar
:class:`~contactsep.model.design.Design` is checked when it is made
(:class:`DesignError`, naming the field), a design of a batch outside
them gets status 2 at evaluation (:func:`outside_domain`,
:func:`invalid_rows`).  Units: in, lb, s; lb/in^3; psi.
"""

from __future__ import annotations

import numpy as np

from contactsep import beams
from contactsep.constants import CUBIC_INCHES_PER_CUBIC_FOOT
from contactsep.errors import InputError

#: Columns of the packed real array (CONTRACT with the compiled kernel).
REAL_COLUMNS = ("L1", "b1", "h1", "gamma1", "E1", "x1",
                "L2", "b2", "h2", "gamma2", "E2", "x2", "Lc",
                "L3", "b3", "h3", "gamma3", "E3", "x3",
                "ys", "e", "tau", "gap")
#: Columns of the packed integer array.
INT_COLUMNS = ("end1", "end2", "end3", "n1", "n2", "n3")

_POSITIVE = ("L1", "b1", "h1", "gamma1", "E1", "L2", "b2", "h2", "gamma2",
             "E2", "L3", "b3", "h3", "gamma3", "E3", "tau")
_OPTIONAL = ("x1", "x2", "x3", "Lc")

#: The model's domain (docs/model.md, "Domain"): a design outside it is
#: refused (a scalar design when it is made, a design of a batch with
#: status 2), because the beams are no longer beams there, or the
#: kernel's arithmetic (squared displacements, a time resolution of
#: 1e-16 s, mode shapes near a support) no longer gives true digits.
#: Lengths, widths and thicknesses (in): 2.5 um to 830 ft.
SIZE_RANGE = (1e-4, 1e4)
#: Weight densities (lb/in^3): aerogel to 12 times osmium (aluminium is
#: 0.1; its 170 lb/ft^3 typed here is refused).
DENSITY_RANGE = (1e-5, 10.0)
#: Young's moduli (psi): the softest rubber to 6 times diamond.
MODULUS_RANGE = (1.0, 1e9)
#: The release deflection |ys| as a fraction of L1 (the gap: |gap| <= L1).
DEFLECTION_RANGE = (1e-9, 1.0)
#: A contact point's least distance from a clamped end, as a fraction of
#: the member's length: the mode shapes there (~ (x/L)^2) lose
#: 1e-16 / (x/L)^2 of their value to round-off (3e-11 at the limit).
SUPPORT_CLEARANCE = 1e-3
_MEMBER_NAMES = {"1": "upper contact", "2": "separator",
                 "3": "lower contact"}


def _check_number(name: str, value) -> None:
    """A real field holds a number or an array of numbers (None only for
    the optional fields): never a string, a bool or a complex number."""
    if value is None:
        if name in _OPTIONAL:
            return
        raise DesignError(f"{name}: found None, expected a number")
    try:
        kind = np.asarray(value).dtype.kind
    except (TypeError, ValueError, OverflowError):
        kind = "O"
    if kind not in "iuf":
        raise DesignError(f"{name}: found {value!r}, expected a number or "
                          f"an array of numbers")


def _between(low, high, unit: str):
    return lambda row: f"{low:.6g} to {high:.6g} {unit}".rstrip()


def _rules(real: np.ndarray, ints: np.ndarray):
    """(field, wrong rows, expected(row) -> text) of every check: each
    field on its own first (the kernel's ranges, then the domain's), then
    the relations between fields."""
    col = {name: real[:, k] for k, name in enumerate(REAL_COLUMNS)}
    with np.errstate(invalid="ignore"):
        yield from _field_rules(col)
        yield from _relation_rules(col, ints)


def _field_rules(col: dict):
    def outside(v, low, high):
        return ~((v >= low) & (v <= high))

    limits = {}
    for m in "123":
        limits.update({f"L{m}": SIZE_RANGE, f"b{m}": SIZE_RANGE,
                       f"h{m}": SIZE_RANGE, f"gamma{m}": DENSITY_RANGE,
                       f"E{m}": MODULUS_RANGE})
    units = {"L": "in", "b": "in", "h": "in", "E": "psi",
             "g": f"lb/in^3 (a density in lb/ft^3 is "
                  f"{CUBIC_INCHES_PER_CUBIC_FOOT:g} times larger)"}
    for name in REAL_COLUMNS:
        v = col[name]
        if name in _POSITIVE:
            yield name, ~(np.isfinite(v) & (v > 0.0)), \
                lambda row: "a finite number > 0"
            if name in limits:
                yield name, outside(v, *limits[name]), \
                    _between(*limits[name], units[name[0]])
        elif name == "Lc":
            yield name, ~(np.isfinite(v) & (v >= 0.0)), \
                lambda row: "a length > 0 (or None)"
            yield name, ~((v == 0.0) | ~outside(v, *SIZE_RANGE)), \
                _between(*SIZE_RANGE, "in (or None)")
        elif name == "e":
            yield name, ~(np.isfinite(v) & (v >= 0.0) & (v <= 1.0)), \
                lambda row: "0 <= e <= 1"
        elif name not in ("x1", "x2", "x3"):
            yield name, ~np.isfinite(v), lambda row: "a finite number"


def _relation_rules(col: dict, ints: np.ndarray):
    for k, m in enumerate("123"):
        length = col[f"L{m}"]
        yield f"h{m}", ~(col[f"h{m}"] <= length), \
            lambda row, m=m, L=length: (
                f"at most L{m} = {L[row]:.6g} in (a beam is longer than "
                f"it is thick)")
        end = ints[:, k]
        x = col[f"x{m}"]
        yield f"x{m}", ~(np.isfinite(x) & (x > 0.0) & (x <= length)), \
            lambda row, m=m, L=length: f"0 < x{m} <= L{m} = {L[row]:.6g} in"
        # a clamped end's modes grow like (x/L)^2: nearer than the
        # clearance they are round-off (1e-16 / (x/L)^2 relative)
        low = np.where(end == END_CODES["pinned-pinned"], 0.0,
                       SUPPORT_CLEARANCE * length)
        high = np.where(end == END_CODES["clamped-clamped"],
                        length - SUPPORT_CLEARANCE * length, length)
        supported = end != END_CODES["clamped-free"]
        wrong = ~((x > low) & ((x < high) | (~supported & (x <= high))))
        yield f"x{m}", wrong, \
            lambda row, m=m, low=low, high=high, end=end: (
                f"{low[row]:.6g} < x{m} "
                f"{'<=' if end[row] == END_CODES['clamped-free'] else '<'} "
                f"{high[row]:.6g} in: "
                f"inside the span of the {_end_name(end[row])} "
                f"{_MEMBER_NAMES[m]} (end{m}), at least "
                f"{SUPPORT_CLEARANCE:g} L{m} from a clamped end")
    length = col["L1"]
    low, high = DEFLECTION_RANGE
    ys = np.abs(col["ys"])
    yield "ys", ~((ys >= low * length) & (ys <= high * length)), \
        lambda row: (f"{low * length[row]:.6g} <= |ys| <= "
                     f"{high * length[row]:.6g} in ({low:g} L1 to L1)")
    yield "gap", ~(np.abs(col["gap"]) <= length), \
        lambda row: f"|gap| <= L1 = {length[row]:.6g} in"


def _end_name(code) -> str:
    return beams.END_CONDITIONS[int(code) - 1] if 1 <= code <= 4 \
        else str(code)


#: End condition name -> the kernel's code.
END_CODES = {name: k + 1 for k, name in enumerate(beams.END_CONDITIONS)}


def outside_domain(real: np.ndarray, ints: np.ndarray) -> np.ndarray:
    """Boolean (M,): designs that fail a check of :meth:`Design.problems`
    (the kernel's own checks and the model's domain); evaluate gives them
    status 2, as the kernel gives the designs it refuses itself."""
    bad = np.zeros(real.shape[0], dtype=bool)
    for _, wrong, _ in _rules(real, ints):
        bad |= wrong
    return bad


class DesignError(InputError):
    """A design the model cannot take; the message names the field."""



def invalid_rows(real: np.ndarray, ints: np.ndarray) -> np.ndarray:
    """Boolean (M,): designs with a value out of range (status 2)."""
    col = {name: real[:, k] for k, name in enumerate(REAL_COLUMNS)}
    with np.errstate(invalid="ignore"):
        ok = np.all(np.isfinite(real), axis=1)
        for name in _POSITIVE:
            ok &= col[name] > 0.0
        for m in "123":
            ok &= (col["x" + m] > 0.0) & (col["x" + m] <= col["L" + m])
        ok &= col["Lc"] >= 0.0
        ok &= (col["e"] >= 0.0) & (col["e"] <= 1.0)
        ok &= np.all((ints[:, :3] >= 1) & (ints[:, :3] <= 4), axis=1)
        ok &= np.all(ints[:, 3:] >= 1, axis=1)
    return ~ok
