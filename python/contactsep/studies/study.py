"""A study's result: labelled columns with units, and how to write them."""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Study:
    """Columnar results of one study.

    ``columns`` maps a column name (its unit is the name's suffix:
    ``_in``, ``_s``, ``_lb_s``, ``_in_s``, ``_cps`` ...) to a 1-D NumPy
    array; ``notes`` are the conventions and inputs, written as ``#``
    lines before a CSV's header.
    """

    #: Short name (``fig5``).
    name: str
    #: Title, with the thesis's figure or table number.
    title: str
    #: Column name -> values (all of one length).
    columns: dict = field(default_factory=dict)
    #: Conventions and inputs, one line each.
    notes: tuple = ()

    def __len__(self) -> int:
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def to_pandas(self):
        """The columns as a pandas DataFrame (needs pandas)."""
        try:
            import pandas
        except ImportError:  # pragma: no cover - depends on the install
            from contactsep.errors import InputError
            raise InputError("to_pandas needs pandas: pip install "
                             "'contactsep[tables]'") from None
        return pandas.DataFrame(self.columns)

    def csv_text(self) -> str:
        """'#' lines (title, notes), a header row with units, the rows."""
        out = io.StringIO()
        out.write(f"# {self.title}\n")
        for note in self.notes:
            out.write(f"# {note}\n")
        writer = csv.writer(out, lineterminator="\n")
        writer.writerow(list(self.columns))
        for row in zip(*self.columns.values()):
            writer.writerow([_format(v) for v in row])
        return out.getvalue()

    def table_text(self) -> str:
        """An aligned, labelled table for a terminal."""
        names = list(self.columns)
        cells = [[_format(v, 6) for v in self.columns[n]] for n in names]
        widths = [max([len(n)] + [len(c) for c in col])
                  for n, col in zip(names, cells)]
        lines = [self.title, "  ".join(n.rjust(w)
                                       for n, w in zip(names, widths))]
        for row in zip(*cells):
            lines.append("  ".join(c.rjust(w) for c, w in zip(row, widths)))
        return "\n".join(lines) + "\n"


def _format(value, digits: int = 12) -> str:
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (bool, np.bool_)):
        return "1" if value else "0"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return f"{float(value):.{digits}g}"
