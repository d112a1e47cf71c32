"""A sweep from Python (issue 30, item 5): :func:`sweep` runs what
``contactsep sweep`` runs and returns a :class:`SweepResult`, its rows
and summary together, whose :meth:`SweepResult.to_pandas` is the
DataFrame ``contactsep.read`` gives of the command's CSV."""

from __future__ import annotations

from dataclasses import dataclass

from contactsep import output
from contactsep.studies.sweep.frames import DataFrameWriter
from contactsep.studies.sweep.run import run_sweep
from contactsep.studies.sweep.spec import make_spec
from contactsep.studies.sweep.writers import column_notes, title


@dataclass(frozen=True)
class SweepResult:
    """What a sweep computed.

    Attributes
    ----------
    summary : dict
        What ``contactsep sweep --json`` prints: ``n``, ``n_failed``,
        ``n_failed_by_status``, the statistics (``y3_max_mean_in``,
        ``p_exceed`` and ``p_exceed_ci95`` with a threshold; a chatter
        model's ``n_open``, ``p_open``, ``p_open_ci95``,
        ``max_lower_gap_mean_in``, ...), ``elapsed_s`` and ``inputs``
        (docs/sweeps.md).
    columns : dict of str to numpy.ndarray, or None
        The rows, one array per CSV column, in the CSV's order and under
        its names (the varied and sampled fields as ``d_in``, ``ys_in``,
        ..., then ``y3_max_in, t_max_s, psi_lb_s, v0_in_s, status`` or a
        chatter model's ``first_impact_s, ..., n_events, status``),
        designs in sweep order; None when the sweep was run with
        ``rows=False``.
    comments : tuple of str
        The comment lines of the sweep's CSV, without their ``#``: its
        title, the inputs in words and how to read the columns.
    """

    summary: dict
    columns: dict | None
    comments: tuple

    def to_pandas(self, what: str = "rows"):
        """A pandas DataFrame (needs pandas, ``pip install
        'contactsep[tables]'``).

        Parameters
        ----------
        what : {"rows", "summary"}
            ``"rows"``: one row per design, the columns of the sweep's
            CSV under its names (``contactsep.read`` of the CSV gives the
            same frame, to the CSV's 12 digits), ``attrs["comments"]``
            its ``#`` lines and ``attrs["summary"]`` the summary;
            ``"summary"``: one row, every number of :attr:`summary`
            (``n``, ``p_open``, ``y3_max_mean_in``, ``elapsed_s``, ...;
            the intervals, the failures by status and the inputs stay in
            :attr:`summary`).

        Returns
        -------
        pandas.DataFrame

        Examples
        --------
        >>> import contactsep
        >>> result = contactsep.sweep(vary=["d=0.1:0.5:5"], workers=1)
        >>> result.to_pandas().columns.tolist()
        ['d_in', 'y3_max_in', 't_max_s', 'psi_lb_s', 'v0_in_s', 'status']
        >>> int(result.to_pandas("summary")["n"][0])
        5
        """
        pandas = output.require_pandas()
        if what == "summary":
            return pandas.DataFrame([{
                key: value for key, value in self.summary.items()
                if not isinstance(value, (dict, list, tuple))}])
        if what != "rows":
            raise ValueError(f"what: found {what!r}, expected 'rows' or "
                             f"'summary'")
        if self.columns is None:
            raise ValueError("the sweep was run with rows=False: only its "
                             "summary was kept")
        frame = pandas.DataFrame(self.columns)
        frame.attrs["comments"] = list(self.comments)
        frame.attrs["summary"] = self.summary
        return frame


def sweep(vary=(), sample=(), *, samples: int | None = None, seed: int = 0,
          fixed: dict | None = None, model: str = "eq23",
          settings: dict | None = None, threshold: float | None = None,
          workers: int | None = None, chunk_size: int | None = None,
          scheduler=None, progress: bool | None = False,
          rows: bool = True, backend: str = "compiled") -> SweepResult:
    """Run a sweep, as ``contactsep sweep`` does, and keep its rows.

    Parameters
    ----------
    vary : sequence of str
        The ``--vary`` axes: ``"d=0.1:1.0:19"`` (START:STOP:COUNT),
        ``"ys=0.25,0.5,0.75"``, ``"end2=clamped-clamped,pinned-pinned"``.
    sample : sequence of str
        The ``--sample`` distributions: ``"d=normal(0.25,0.01)"``,
        ``"ys=uniform(0.45,0.55)"``.
    samples : int, optional
        Designs drawn per grid point (default 1000 with ``sample``, else
        1).
    seed : int
        The draw's seed (the command's ``--seed``).
    fixed : dict, optional
        Design fields fixed for every design (``{"n_modes": 16}``; the
        rest is :func:`contactsep.thesis_design`'s).
    model : {"eq23", "hertz", "newton"}
        The general model, or the chatter simulation of each design.
    settings : dict, optional
        A chatter model's fixed settings (``preload`` in lb,
        ``min_open`` in s, ``damping``, ``dt``, ``t_end``).
    threshold : float, optional
        eq23 only: also report ``p_exceed`` = P(max y3 > threshold), in.
    workers, chunk_size, scheduler, progress
        As ``--workers``, ``--chunk-size``, ``--scheduler`` (an address
        or a Dask Client) and ``--progress`` (None: a bar on a
        terminal).
    rows : bool
        Keep every design's row (default); False keeps the summary only
        (each worker then reduces its own chunks: less memory and
        traffic for a large sweep).
    backend : {"compiled", "numpy"}
        eq23's backend.

    Returns
    -------
    SweepResult
        The summary, the rows and the CSV's comment lines.

    Raises
    ------
    contactsep.studies.sweep.spec.SweepError
        A bad axis, distribution, field or setting (an InputError).

    Examples
    --------
    >>> import contactsep
    >>> result = contactsep.sweep(sample=["d=normal(0.25,0.01)"],
    ...                           samples=200, threshold=0.12, workers=1)
    >>> result.summary["n"], result.to_pandas().shape
    (200, (200, 6))
    """
    spec = make_spec(vary=vary, sample=sample, samples=samples, seed=seed,
                     base=fixed, backend=backend, model=model,
                     settings=settings)
    writer = DataFrameWriter() if rows else None
    summary = run_sweep(spec, writers=[writer] if rows else (),
                        threshold=threshold, chunk_size=chunk_size,
                        workers=workers, scheduler=scheduler,
                        progress=progress)
    comments = (title(spec), *spec.describe(), *column_notes(spec))
    return SweepResult(summary=summary,
                       columns=writer.columns() if rows else None,
                       comments=tuple(comments))
