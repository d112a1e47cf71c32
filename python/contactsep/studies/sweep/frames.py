"""Tables as pandas DataFrames (issue 30, item 5): ``contactsep.read``
reads any CSV or Parquet file the package writes (and a design file,
as a Design), and :class:`DataFrameWriter` collects a sweep's rows in
memory.

Every CSV the package writes starts (and, if a sweep was interrupted,
ends) with comment lines that begin with ``#``; ``pandas.read_csv``
without ``comment="#"`` fails on them.  :func:`read` keeps them in the
frame's ``attrs["comments"]`` (without the ``# ``), and a Parquet file's
``contactsep`` metadata (title, notes, inputs) in ``attrs["contactsep"]``
with the same lines in ``attrs["comments"]``.  Needs pandas (and pyarrow
for Parquet): ``pip install 'contactsep[tables]'``.
"""

from __future__ import annotations

import io
import json
import os

import numpy as np

from contactsep import output
from contactsep.errors import InputError

#: Parquet files start with these bytes.
_PARQUET_MAGIC = b"PAR1"
#: How much of a file read() looks at to tell its kind (white space
#: before a design file's "{" included).
_SNIFF_BYTES = 4096


def read(path):
    """The table in ``path`` (a CSV or Parquet file that contactsep
    wrote: a study, a sweep, ``chatter --csv``) as a DataFrame, with its
    comment lines in ``attrs["comments"]``; or the design in a design
    file (``Design.to_file``, ``contactsep model --json``), as
    :func:`contactsep.load_design` reads it.

    Parameters
    ----------
    path : str or os.PathLike
        The file.  Parquet is recognised by its first bytes, a design
        file by its first character other than white space, ``{`` (a
        CSV file the package writes starts with ``#`` or a column name);
        anything else is read as CSV.

    Returns
    -------
    pandas.DataFrame or contactsep.Design
        A table: one column per column of the file, under the file's
        own names (the quantity and its unit: ``y3_max_in``, ``t_s``);
        ``attrs["comments"]``: the ``#`` lines, in order, without the
        ``# `` (for Parquet: its title, notes and inputs);
        ``attrs["contactsep"]`` (Parquet only): its metadata as a dict.
        A design file: the Design (pandas not needed).

    Examples
    --------
    >>> import contactsep
    >>> frame = contactsep.read("docs/studies/fig5.csv")
    >>> frame.attrs["comments"][0]
    'Figure 5: maximum lower-contact displacement vs separator thickness'
    >>> frame.columns.tolist()
    ['ys_in', 'd_in', 'y3_max_in', 't_max_s']
    """
    try:
        with open(path, "rb") as handle:
            head = handle.read(_SNIFF_BYTES)
    except OSError as error:
        raise InputError(f"{os.fspath(path)}: {output.one_line(error)}") \
            from None
    if head.lstrip()[:1] == b"{":
        from contactsep.model.design_file_read import load_design
        return load_design(path)
    pandas = output.require_pandas()
    if head[:len(_PARQUET_MAGIC)] == _PARQUET_MAGIC:
        return _read_parquet(pandas, path)
    return _read_csv(pandas, path)


def _read_csv(pandas, path):
    comments, body = [], io.StringIO()
    try:
        with open(path, encoding="utf-8", newline="") as handle:
            for line in handle:
                if line.startswith("#"):
                    comments.append(line[1:].strip())
                else:
                    body.write(line)
    except (OSError, UnicodeDecodeError) as error:
        raise InputError(f"{os.fspath(path)}: {output.one_line(error)}") \
            from None
    body.seek(0)
    try:
        frame = pandas.read_csv(body)
    except (ValueError, pandas.errors.ParserError) as error:
        raise InputError(f"{os.fspath(path)}: not a table contactsep "
                         f"wrote ({output.one_line(error)})") from None
    frame.attrs["comments"] = comments
    return frame


def _read_parquet(pandas, path):
    try:
        import pyarrow.parquet as pq
    except ImportError:
        raise InputError("reading Parquet needs pyarrow: pip install "
                         "'contactsep[tables]'") from None
    try:
        table = pq.read_table(path)
    except Exception as error:        # pyarrow's own error classes
        raise InputError(f"{os.fspath(path)}: not a Parquet file contactsep "
                         f"wrote ({output.one_line(error)})") from None
    frame = table.to_pandas()
    raw = (table.schema.metadata or {}).get(b"contactsep")
    meta = json.loads(raw) if raw else {}
    lines = [meta["title"]] if meta.get("title") else []
    lines += list(meta.get("notes") or [])
    if meta.get("inputs") is not None:
        lines.append("inputs: " + output.json_text(meta["inputs"],
                                                    indent=None))
    frame.attrs["comments"] = lines
    frame.attrs["contactsep"] = meta
    return frame


class DataFrameWriter:
    """A sweep's rows in memory, as :func:`contactsep.studies.run_sweep`
    hands them to its writers; :meth:`to_pandas` gives the DataFrame the
    sweep's CSV would read back as.

    Examples
    --------
    >>> from contactsep.studies.sweep.frames import DataFrameWriter
    >>> from contactsep.studies.sweep.run import run_sweep
    >>> from contactsep.studies.sweep.spec import make_spec
    >>> rows = DataFrameWriter()
    >>> summary = run_sweep(make_spec(vary=["h2=0.1:0.5:5"]),
    ...                     writers=[rows], workers=1, progress=False)
    >>> rows.to_pandas().columns.tolist()
    ['d_in', 'y3_max_in', 't_max_s', 'psi_lb_s', 'v0_in_s', 'status']
    """

    def __init__(self) -> None:
        self._chunks: list[dict] = []

    def write(self, columns: dict) -> None:
        self._chunks.append({k: np.array(v, copy=True)
                             for k, v in columns.items()})

    def close(self, interrupted: str | None = None) -> None:
        self.interrupted = interrupted

    def abort(self) -> None:
        self._chunks = []

    def columns(self) -> dict:
        """The rows written so far, one array per column ({} if none)."""
        if not self._chunks:
            return {}
        return {k: np.concatenate([c[k] for c in self._chunks])
                for k in self._chunks[0]}

    def to_pandas(self):
        """The rows written so far, one DataFrame."""
        pandas = output.require_pandas()
        return pandas.DataFrame(self.columns())
