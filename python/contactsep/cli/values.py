"""Types of the options that are not design fields (--seed, --samples,
--workers, --chunk-size, --threshold, --dpi, ...): each reads its text
and checks its range, so that argparse reports a bad value in one line,
``argument --seed: found '-1', expected an integer from 0 to ...``
(a NaN, an infinity or a size past 2^63 included)."""

from __future__ import annotations

import argparse
import math

from contactsep import units
from contactsep.errors import InputError


def integer(low: int, high: int):
    """An argparse type: a decimal integer from ``low`` to ``high``."""
    def convert(text: str) -> int:
        try:
            value = int(text, 10)
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise argparse.ArgumentTypeError(
                f"found {text!r}, expected an integer from {low:,} to "
                f"{high:,}")
        return value
    convert.__name__ = "integer"
    return convert


def finite(unit: str = ""):
    """An argparse type: a finite number (``unit`` named in the error),
    or a number with a unit of the same kind (``10us``, ``1.5N``,
    :mod:`contactsep.units`) where ``unit`` is one."""
    def convert(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if unit in units.TARGETS and units.split(text) is not None:
            try:
                value = units.convert(text, unit, "")
            except InputError as error:
                raise argparse.ArgumentTypeError(
                    str(error).removeprefix(": ")) from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(
                f"found {text!r}, expected a finite number"
                + (f" ({unit})" if unit else ""))
        if unit and units.split(text) is None:
            return Bare(value, unit)
        return value
    convert.__name__ = "number"
    return convert


class Bare(float):
    """A bare number an option read (no unit typed), with the package
    unit it was read in: ``--units si`` rereads it in SI
    (contactsep.cli.unit_system.apply_units); with the default
    ``us`` it is that float."""

    __slots__ = ("unit",)

    def __new__(cls, value: float, unit: str):
        number = super().__new__(cls, value)
        number.unit = unit
        return number

    def __reduce__(self):       # a plain float wherever it travels
        return float, (float(self),)
