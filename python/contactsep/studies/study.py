"""A study's result: labelled columns with units, and how to write them."""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field

import numpy as np

from contactsep.errors import InputError
from contactsep.studies.fields import OUTPUT_NAMES


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
            raise InputError("to_pandas needs pandas: pip install "
                             "'contactsep[tables]'") from None
        return pandas.DataFrame(self.columns)

    def csv_text(self) -> str:
        """'#' lines (title, notes), a header row with units, the rows."""
        out = io.StringIO()
        out.write(csv_comments([self.title, *self.notes]))
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


def check_status(evaluation):
    """The evaluation, if every design of the study was evaluated; else
    an InputError (a study's rows are all or nothing)."""
    if np.any(evaluation.status != 0):
        raise InputError("a design of the study failed (status "
                         f"{int(np.max(evaluation.status))}); check the "
                         "design options")
    return evaluation


def refuse_fixed(study: str, overrides: dict, fixed: dict) -> None:
    """A study sets some fields itself (``fixed``: field -> why); an
    override of one is refused with an InputError naming it."""
    for name, why in fixed.items():
        if name in overrides:
            label = f"{OUTPUT_NAMES[name]}/{name}" if name in OUTPUT_NAMES \
                else name
            raise InputError(f"study {study} sets {label} itself ({why}); "
                             f"leave it out")


def csv_comments(lines) -> str:
    """Comment lines for the top of a CSV: each line of each text its own
    line starting with '# ' (a reader told that '#' starts a comment
    then never sees a stray line)."""
    return "".join(f"# {line}\n" for text in lines
                   for line in str(text).splitlines() or [""])


def _format(value, digits: int = 12) -> str:
    if isinstance(value, (str, np.str_)):
        return str(value)
    if isinstance(value, (bool, np.bool_)):
        return "1" if value else "0"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return f"{float(value):.{digits}g}"
