"""Where a sweep's rows go: a CSV (``#`` lines saying what the sweep is,
a header, 12-digit rows) or a Parquet file, each written to a temporary
file beside its target and put in place when the sweep ends
(:class:`contactsep.output.Replacement`), with a lock against a second
sweep writing the same file."""

from __future__ import annotations

import contextlib
import csv

import numpy as np

from contactsep import output
from contactsep.errors import InputError, printable
from contactsep.model.names import shown_columns, shown_data, units_note
from contactsep.output import json_text
from contactsep.studies.sweep import chatter as chatter_sweep
from contactsep.studies.study import csv_comments
from contactsep.studies.sweep.spec import SweepSpec

#: The first comment line of a sweep's CSV and its Parquet metadata.
TITLE = "contactsep sweep of the general model (eq. 23) on the thesis design"
#: The suffixes of an eq. 23 sweep's columns, as its note lists them.
EQ23_UNITS = ("in", "s", "lb_s", "in_s", "lb_in3", "psi")
#: How to read the columns (a comment line of the CSV), after the units.
COLUMNS_NOTE = ("status 0 = ok, 1 no impact, 2 invalid input, 3 overflow "
                "(contactsep.model.status); failed designs have nan results")

#: Significant digits of the CSV's numbers: the compiled kernel and its
#: NumPy twin agree to 1e-12 relative (tests/model), so later digits are
#: round-off; Parquet keeps every bit.
CSV_DIGITS = 12


def title(spec: SweepSpec | None, design: str | None = None) -> str:
    """The sweep's title (first CSV comment, Parquet metadata).

    Parameters
    ----------
    spec : SweepSpec or None
        The sweep (None: an eq. 23 sweep of unknown inputs).
    design : str, optional
        The ``--design`` file the sweep's designs start from; the title
        then names it instead of the thesis design.

    Returns
    -------
    str
        One line, e.g. "contactsep sweep of the general model (eq. 23)
        on the design of relay.json".
    """
    text = (TITLE if spec is None or spec.model == "eq23"
            else chatter_sweep.title(spec.model))
    if design is not None:
        text = text.replace("on the thesis design",
                            f"on the design of {printable(str(design))}")
    return text


def column_notes(spec: SweepSpec | None) -> list[str]:
    """How to read the columns (CSV comments, Parquet metadata), in the
    unit system shown."""
    if spec is None or spec.model == "eq23":
        return [f"{units_note(EQ23_UNITS)}; {COLUMNS_NOTE}"]
    dt = "per row" if "dt" in spec.fields else spec.settings.get("dt")
    return chatter_sweep.notes(spec.model, dt)


def _row_format(columns: dict) -> str:
    """%-format of one CSV row, from the columns' kinds."""
    formats = []
    for values in columns.values():
        kind = np.asarray(values).dtype.kind
        formats.append("%d" if kind in "iub" else "%s" if kind in "USO"
                       else f"%.{CSV_DIGITS}g")
    return ",".join(formats) + "\n"


class CsvWriter:
    """Streams chunks to a CSV file: '#' lines (what the sweep is), a
    header, the rows.  The rows go to a temporary file beside ``path``
    as the sweep goes, renamed into place by :meth:`close`; :meth:`abort`
    (a failed sweep) and the close of one that stopped early leave
    ``path`` as it was (its finished chunks are the sweep's store's).
    A second sweep writing ``path`` meanwhile is refused (a lock).
    ``design``: the ``--design`` file the designs start from (the first
    comment line names it)."""

    def __init__(self, path: str, spec: SweepSpec, notes=(),
                 design: str | None = None):
        self.path = path
        self._file = output.Replacement(path, lock=True)
        self._handle = self._file.stream
        try:
            self._handle.write(csv_comments([title(spec, design),
                                             *spec.describe(),
                                             *column_notes(spec), *notes]))
        except BaseException:
            self._file.discard()
            raise
        self._writer = csv.writer(self._handle, lineterminator="\n")
        self._line = None

    def write(self, columns: dict) -> None:
        columns = shown_columns(columns)
        if self._line is None:
            self._writer.writerow(list(columns))
            self._line = _row_format(columns)
        # Python's own %-formatting, row by row: numpy.char.mod is slower
        # (~15 us a row) and swallows a signal raised while it runs, so
        # Ctrl-C and SIGTERM went unheard during a long write
        rows = zip(*(np.asarray(v).tolist() for v in columns.values()))
        self._handle.writelines(self._line % row for row in rows)
        self._handle.flush()

    def close(self, interrupted: str | None = None) -> None:
        """Finish the file and put it in place; a sweep that stopped
        early (``interrupted``: how far it got) drops it instead, so
        that a file under the final name is always a finished one."""
        if interrupted:
            self._file.discard()
            return
        self._file.commit()

    def abort(self) -> None:
        """Drop the file: ``path`` stays as it was."""
        self._file.discard()


#: Rows of a Parquet row group: fixed, so that the file does not depend
#: on how the sweep was chunked (a resumed sweep's is byte-identical).
ROW_GROUP = 65536


class ParquetWriter:
    """Streams chunks to a Parquet file (needs pyarrow), in row groups of
    ROW_GROUP rows; the file's metadata key ``contactsep`` holds what the
    CSV's comments say, as JSON (``title``, ``inputs``, ``notes``).
    Written, locked and put in place as :class:`CsvWriter`'s file.
    ``design`` as for :class:`CsvWriter`."""

    def __init__(self, path: str, spec: SweepSpec | None = None,
                 design: str | None = None):
        require_pyarrow()
        self.path = path
        self._about = {"title": title(spec, design),
                       "notes": column_notes(spec),
                       "inputs": shown_data(spec.inputs())
                       if spec is not None else None}
        self._metadata = {"contactsep": json_text(self._about, indent=None)}
        self._file = output.Replacement(path, binary=True, lock=True)
        self._writer = None
        self._pending = []
        self._pending_rows = 0

    def write(self, columns: dict) -> None:
        import pyarrow as pa
        table = pa.table({k: np.ascontiguousarray(v)
                          for k, v in shown_columns(columns).items()})
        self._pending.append(table)
        self._pending_rows += table.num_rows
        if self._pending_rows >= ROW_GROUP:
            self._flush(whole_groups=True)

    def _flush(self, whole_groups: bool) -> None:
        import pyarrow as pa
        import pyarrow.parquet as pq
        if not self._pending:
            return
        table = pa.concat_tables(self._pending)
        rows = table.num_rows
        end = rows - rows % ROW_GROUP if whole_groups else rows
        if self._writer is None:
            schema = table.schema.with_metadata(self._metadata)
            self._writer = pq.ParquetWriter(self._file.stream, schema)
        for start in range(0, end, ROW_GROUP):
            group = table.slice(start, min(ROW_GROUP, end - start))
            self._writer.write_table(
                group.combine_chunks().replace_schema_metadata(
                    self._metadata), row_group_size=ROW_GROUP)
        rest = table.slice(end)
        self._pending = [rest] if rest.num_rows else []
        self._pending_rows = rest.num_rows

    def close(self, interrupted: str | None = None) -> None:
        if interrupted:
            self.abort()        # as CsvWriter's: the old file stays
            return
        try:
            self._flush(whole_groups=False)
            if self._writer is not None:
                self._writer.close()
        except BaseException:
            self._file.discard()
            raise
        self._file.commit()

    def abort(self) -> None:
        with contextlib.suppress(Exception):
            if self._writer is not None:
                self._writer.close()
        self._file.discard()


def require_pyarrow() -> None:
    """The InputError --parquet gives without pyarrow, before any work."""
    try:
        import pyarrow  # noqa: F401
        import pyarrow.parquet  # noqa: F401
    except ImportError:
        raise InputError("--parquet needs pyarrow: pip install "
                         "'contactsep[tables]'") from None
