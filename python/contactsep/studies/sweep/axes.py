"""What ``--vary`` and ``--sample`` take: a sweep's axes (lists, or
START:STOP:COUNT ranges held as :class:`LinearAxis`) and distributions,
parsed from their texts and checked, each refusal one line naming the
option; :func:`contactsep.studies.sweep.spec.make_spec` builds the sweep from
them.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from contactsep import units
from contactsep.errors import InputError
from contactsep.model.design import MAX_MODES
from contactsep.chatter import settings as chatter_settings
from contactsep.model import fields as design_fields
from contactsep.studies.sweep.checks import SweepError

#: Most designs a sweep may have: 1e12 takes weeks on a hundred cores
#: and writes a 100 TB CSV; the designs are counted in Python integers
#: (a grid of 2^32 x 2^32 points wrapped to 0 in int64 and ran nothing).
MAX_DESIGNS = 10**12

#: What --vary and --sample take: design fields, and chatter settings
#: (make_spec refuses the settings for eq23).
_VARIABLE = design_fields.VARIABLE + chatter_settings.VARIABLE_SETTINGS
_SAMPLED = design_fields.SAMPLED + chatter_settings.SAMPLED_SETTINGS
#: What --vary takes as START:STOP:COUNT: the numbers.
_LINEAR = _SAMPLED + ("dt", "alpha", "yield_pressure")


def _field(name: str, option: str, allowed: tuple) -> str:
    field = design_fields.field_name(name, f"{option} {name.strip()}",
                                     settings=True)
    if field not in allowed:
        raise SweepError(f"{option} {name.strip()}: {field} cannot be "
                         f"{'varied' if option == '--vary' else 'sampled'}"
                         f" (one of {', '.join(allowed)})")
    return field


@dataclass(frozen=True)
class LinearAxis:
    """START:STOP:COUNT values, exactly as numpy.linspace gives them
    (k * step + START, the last one STOP), without holding the array:
    a grid of a billion points costs nothing until its chunks are made,
    and the spec that travels to every worker stays small."""

    start: float
    stop: float
    count: int

    def __len__(self) -> int:
        return self.count

    def __getitem__(self, k):
        k = np.asarray(k, dtype=np.int64)
        k = np.where(k < 0, k + self.count, k)
        if np.any((k < 0) | (k >= self.count)):
            raise IndexError("axis index out of range")
        if self.count == 1:
            return np.full(k.shape, self.start)[()]
        # ends a whole float range apart (-1e308:1e308) overflow STOP -
        # START: the halves' axis, doubled (exact), is the same grid
        scale = 1.0 if math.isfinite(self.stop - self.start) else 0.5
        step = (scale * self.stop - scale * self.start) / (self.count - 1)
        values = (k * step + scale * self.start) / scale
        return np.where(k == self.count - 1, self.stop, values)[()]


def parse_vary(text: str) -> tuple[str, object]:
    """'h2=0.1:1.0:19' (START:STOP:COUNT, numeric fields), 'd=0.1,0.25'
    (a list) or 'end2=clamped-clamped,pinned-pinned'; the name may be
    any name of the field (h2, d, d_in).  Returns (field, values)."""
    name, sep, values_text = text.partition("=")
    field = _field(name, "--vary", _VARIABLE)
    label = f"--vary {name.strip()}"
    if not sep:
        raise SweepError(f"--vary {text}: expected NAME=START:STOP:COUNT or "
                         f"NAME=V1,V2,...")
    if ":" in values_text and field in _LINEAR:
        try:
            start, stop, count = values_text.split(":")
            start, stop, count = float(start), float(stop), int(count)
        except ValueError:
            raise SweepError(f"--vary {text}: expected NAME=START:STOP:COUNT"
                             f" or NAME=V1,V2,...") from None
        if not (math.isfinite(start) and math.isfinite(stop)):
            raise SweepError(f"--vary {text}: found START {start!r} and "
                             f"STOP {stop!r}, expected finite numbers")
        if not 1 <= count <= MAX_DESIGNS:
            raise SweepError(f"--vary {text}: found COUNT {count}, expected "
                             f"1 to {MAX_DESIGNS:,} values")
        values = LinearAxis(start, stop, count)
        if field in design_fields.SETTINGS:
            # a linear axis lies between its ends: checking them checks it
            for end in (values.start, values.stop):
                chatter_settings.parse_value(field, end, label)
    else:
        items = [chatter_settings.parse_value(field, item, label)
                 for item in values_text.split(",")]
        for item in items:
            if isinstance(item, float) and not math.isfinite(item):
                raise SweepError(f"{label}: found {item!r}, expected "
                                 f"finite numbers")
        values = np.array(items)
        if field == "n_modes" and np.any(values > MAX_MODES):
            raise SweepError(f"{label}: found {np.max(values)}, expected "
                             f"at most {MAX_MODES:,} modes")
    return field, values


_SAMPLE = re.compile(r"^\s*(normal|uniform)\(\s*([^,]+),\s*([^)]+)\)\s*$")


def _sample_number(text: str, field: str, label: str) -> float:
    """One parameter of a distribution: a bare number in the field's
    unit, or a number with a unit converted as the design options
    convert theirs (contactsep.units: '1mm' is 1/25.4 in); ValueError
    for what is not a number."""
    if units.split(text) is not None:
        return units.convert(text, design_fields.unit(field), label)
    return float(text)


def parse_sample(text: str) -> tuple[str, str, float, float]:
    """'h2=normal(0.25,0.005)' or 'ys=uniform(0.45,0.55)' (numeric
    fields, any of their names); each number may carry a unit,
    'd=normal(1mm,0.02mm)'."""
    name, _, spec = text.partition("=")
    field = _field(name, "--sample", _SAMPLED)
    match = _SAMPLE.match(spec)
    label = f"--sample {name.strip()}"
    try:
        kind = match.group(1)
        a = _sample_number(match.group(2), field, label)
        b = _sample_number(match.group(3), field, label)
    except InputError as error:     # a unit pint refuses: its own line
        raise SweepError(str(error)) from None
    except (AttributeError, ValueError):
        raise SweepError(f"--sample {text}: expected NAME=normal(MEAN,SD) or "
                         f"NAME=uniform(LO,HI)") from None
    if not (math.isfinite(a) and math.isfinite(b)) or (
            kind == "normal" and b < 0) or (kind == "uniform" and b < a):
        raise SweepError(f"--sample {text}: the parameters are out of range")
    if kind == "uniform" and not math.isfinite(b - a):
        raise SweepError(f"--sample {text}: HI - LO overflows (more than "
                         f"the largest float); expected a narrower range")
    return field, kind, a, b


def _si_unit(field: str) -> tuple[str, str] | None:
    """(suffix, SI unit as printed) of a field whose SI unit differs
    from the package's; None for one SI shares (s) or without a unit."""
    from contactsep.model.names import SI_SUFFIXES
    suffix = (design_fields.FIELDS.get(field)
              or design_fields.SETTINGS[field])[0]
    if SI_SUFFIXES.get(suffix, (0, 0, 1.0))[2] == 1.0:
        return None
    return suffix, SI_SUFFIXES[suffix][1]


def _given(number: str, unit: str) -> str:
    """A number of an option's text with ``unit`` where it has none."""
    number = number.strip()
    return number if units.split(number) is not None else number + unit


def sample_in_si(text: str) -> str:
    """A ``--sample``/``--tolerance`` text whose bare numbers are SI
    (``--units si``) -> the same text with each bare number given its
    SI unit ('d=normal(0.001,2e-05)' -> 'd=normal(0.001m,2e-05m)'), so
    that :func:`parse_sample` reads it as every other option's SI
    number is read.  A number typed with its unit, a field whose unit
    SI shares (s) or that has none, and text that is not a distribution
    (parse_sample refuses it in its own words) are left as they are."""
    name, _, spec = text.partition("=")
    match = _SAMPLE.match(spec)
    try:
        field = _field(name, "--sample", _SAMPLED)
    except SweepError:
        return text
    si = _si_unit(field)
    if match is None or si is None:
        return text
    return (f"{name}={match.group(1)}({_given(match.group(2), si[1])},"
            f"{_given(match.group(3), si[1])})")


def vary_in_si(text: str) -> str:
    """A ``--vary`` text whose bare numbers are SI (``--units si``) ->
    the same grid in the field's own unit: a START:STOP:COUNT axis with
    its ends converted (rounded to 15 digits, as a value typed with its
    unit is), a list with each bare item given its SI unit
    ('d=0.001,0.002' -> 'd=0.001m,0.002m').  Anything else, and a field
    whose unit SI shares or that has none, is left to parse_vary."""
    from contactsep.model.names import from_si_number
    name, sep, values_text = text.partition("=")
    try:
        field = _field(name, "--vary", _VARIABLE)
    except SweepError:
        return text
    si = _si_unit(field)
    if not sep or si is None:
        return text
    parts = values_text.split(":")
    if len(parts) == 3 and field in _LINEAR:
        try:
            ends = [from_si_number(float(p), si[0]) for p in parts[:2]]
        except ValueError:
            return text
        return f"{name}={ends[0]!r}:{ends[1]!r}:{parts[2]}"
    return f"{name}=" + ",".join(_given(item, si[1])
                                 for item in values_text.split(","))
