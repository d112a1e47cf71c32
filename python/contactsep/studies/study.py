"""A study's result: labelled columns with units, and how to write them."""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass, field, fields

import numpy as np

from contactsep.errors import InputError
from contactsep.model.fields import OUTPUT_NAMES, unit


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


def evaluate_all(design, backend: str):
    """The evaluation of every design of a study, or an InputError that
    names the first design that failed and why (a study's rows are all
    or nothing): 'study design d = 0.55 in: h2: found 0.55, expected at
    most L2 = 0.5 in'."""
    from contactsep.model import evaluate, status
    evaluation = evaluate(design, backend=backend)
    failed = evaluation.status != 0
    if not np.any(failed):
        return evaluation
    where = np.unravel_index(int(np.argmax(failed)), failed.shape)
    one = {}
    for name in design.__dataclass_fields__:
        value = getattr(design, name)
        if isinstance(value, np.ndarray) and value.ndim:
            value = np.broadcast_to(value, failed.shape)[where].item()
            one[name] = value
    code = int(evaluation.status[where])
    shown = ", ".join(f"{OUTPUT_NAMES.get(k, k)} = {v:.6g} {unit(k)}"
                      .rstrip() if isinstance(v, float) else f"{k} = {v}"
                      for k, v in one.items())
    problems = _problems(design, one)
    why = problems[0] if problems else \
        status.explain(code, design.replace(**one))
    raise InputError(f"{int(np.sum(failed))} of {failed.size} designs of "
                     f"the study failed"
                     + (f"; the first ({shown})" if shown else "")
                     + f": {why}")


def _problems(design, one: dict) -> list[str]:
    """The problems of the one design ``one`` picks out of a batch."""
    from contactsep.model import DesignError
    try:
        design.replace(**one)
    except DesignError as error:
        return [str(error)]
    return []


def refuse_fixed(study: str, overrides: dict, fixed: dict,
                 arrays: tuple = ()) -> None:
    """A study sets some fields itself (``fixed``: field -> why); an
    override of one is refused with an InputError naming it, and so is
    an array for any other field (a study's rows are its own axes; a
    sweep varies any field), but those in ``arrays``."""
    for name, value in overrides.items():
        if name not in arrays and not isinstance(value, tuple) and \
                np.ndim(value) != 0:
            raise InputError(f"study {study}: {name}: found {value!r}, "
                             f"expected one value (a study varies its own "
                             f"axes; contactsep sweep varies any field)")
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


def thesis_study_design(d=0.25, **overrides):
    """The thesis experiment as the thesis studies take it
    (:func:`contactsep.model.thesis_design`, whose default is the
    physically consistent "impulse"), with eq. 13/23's lower
    response as printed (the listing's v0/L3) unless ``lower_response``
    is given: the studies reproduce the thesis, so their outputs do not
    change with the model's physically consistent default ("impulse")."""
    from contactsep.model import thesis_design as experiment
    overrides.setdefault("lower_response", "as-printed")
    return experiment(d, **overrides)


class StudyRun:
    """The base of a study's typed runs (frozen dataclasses, one
    simulation each, handed to its workers): a run is named in a journal
    by its fields in order (:meth:`key_tuple`: the plain tuple the study
    handed out before its runs were typed, so that a journal kept then
    is still answered from); its cost, the batch's order (costliest
    first), is its preload (``preload_lb``, lb) where it has one."""

    def key_tuple(self) -> tuple:
        """The run's fields in order: what names it in a journal."""
        return tuple(getattr(self, f.name) for f in fields(self))

    @property
    def cost(self) -> float:
        """The preload (lb); 0 for a run without one, or whose preload
        is not a number."""
        value = getattr(self, "preload_lb", 0.0)
        return float(value) if isinstance(value, (int, float)) else 0.0
