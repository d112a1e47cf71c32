"""``contactsep compare``: every implementation side by side.

For each data set of a deck, four columns: the original program in single
precision (its listing read back), the restored core in single and in
double precision, and the NumPy reference (float64, the listing's algorithm
choices).  Three checks, each with its own tolerance:

``restored single = legacy single``
    Identical printed digits (asterisks included): the restored core is
    bit-identical, so its listing, read back the same way, must give the
    same numbers.  Not available where the original program cannot run
    the data set (N > 4, its DIMENSION): "n/a".
``restored double ~ NumPy``
    Two float64 implementations of the same equations, one translated from
    the listing and one written from the thesis: 1e-9 relative, widened
    where the listing's own formulas cannot do better (below), never beyond
    1e-6: where the listing's double arithmetic cannot give 1e-6 (its D1-D8
    amplitudes past mode ~10), the comparison fails rather than pass a
    meaningless check.  Quantities that depend on the impact time get
    abs(dq/dt) * 1e-8 s, because the listing's search stops at the last point
    above the separator with a step of at most 1e-8 s while the reference
    finds the crossing itself.  Where the listing's DELT steps over an
    earlier crossing, the two find different impacts and this check fails.
``single ~ double``
    What the listing's REAL arithmetic loses.  The D1-D8 integrals subtract
    terms of size y_s e^{kL}/(kL) to get A_j, so rounding at unit roundoff
    eps leaves an absolute error of about 12 eps y_s e^{kL}/(kL) in A_j
    (the bound), carried through to the quantities built from the A_j;
    history times carry the drift of T = T + DELT.  Where the bound reaches
    100 %, float32 cannot compute the quantity at all: the tolerance shows
    "none" and the check is not made.
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator, TextIO

import numpy as np

from contactsep.errors import DeckError
from contactsep.restored import core, legacy, listing, reference
from contactsep.restored.result import Result

#: The listing's impact-search resolution (its stopping rule), s.
SEARCH_STEP = 1e-8
#: Relative agreement required of the two float64 implementations ...
DOUBLE_RTOL = 1e-9
#: ... and the most any error bound may widen it to.
MAX_DOUBLE_RTOL = 1e-6
_EPS32 = float(np.finfo(np.float32).eps)
_EPS64 = float(np.finfo(np.float64).eps)


def _rel(a: float, b: float) -> float:
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    scale = max(abs(a), abs(b))
    return abs(a - b) / scale if scale else math.inf


@dataclass(frozen=True)
class Row:
    """One quantity of one data set across the implementations."""

    name: str
    #: As printed by the original program (NaN for asterisks); None where
    #: it cannot run the data set.
    legacy_single: float | None
    #: As printed by the restored core in single precision.
    restored_printed: float
    #: The restored core's values (the dataclasses, full precision).
    restored_single: float
    restored_double: float
    numpy_double: float
    #: Tolerances (relative) of the double and single checks; None: float32
    #: cannot compute this quantity, no check.
    tol_double: float
    tol_single: float | None

    @property
    def rel_legacy(self) -> float:
        if self.legacy_single is None:
            return math.nan
        return _rel(self.restored_printed, self.legacy_single)

    @property
    def rel_double(self) -> float:
        return _rel(self.restored_double, self.numpy_double)

    @property
    def rel_single(self) -> float:
        return _rel(self.restored_single, self.restored_double)

    @property
    def passed(self) -> bool:
        legacy_ok = self.legacy_single is None or self.rel_legacy == 0.0
        single_ok = self.tol_single is None or \
            self.rel_single <= self.tol_single
        return legacy_ok and self.rel_double <= self.tol_double and single_ok


@dataclass
class Comparison:
    """The comparison of one deck."""

    tables: list[tuple[int, list[Row]]] = field(default_factory=list)
    #: Data sets that could not be compared, and why.
    notes: list[tuple[int, str]] = field(default_factory=list)
    #: The bad data set that ended the comparison, if any.
    error: DeckError | None = None
    #: Rows within and outside tolerance, and data sets not compared (so
    #: far; also counted when the tables were written out, not kept).
    within: int = 0
    outside: int = 0
    not_compared: int = 0

    @property
    def passed(self) -> bool:
        return self.error is None and not self.not_compared and \
            not self.outside

    def add_table(self, index: int, rows: list[Row],
                  stream: TextIO | None = None) -> None:
        """Count the table; keep it, or write it to ``stream``."""
        failed = sum(not r.passed for r in rows)
        self.within += len(rows) - failed
        self.outside += failed
        if stream is None:
            self.tables.append((index, rows))
        else:
            stream.write(_table_text(index, rows))

    def add_note(self, index: int, note: str,
                 stream: TextIO | None = None) -> None:
        """Count the note; keep it, or write it to ``stream``."""
        self.not_compared += 1
        if stream is None:
            self.notes.append((index, note))
        else:
            stream.write(_note_text(index, note))

    @property
    def summary(self) -> str:
        line = f"{self.within} within tolerance, {self.outside} outside"
        if self.not_compared:
            line += (f", {self.not_compared} data set"
                     f"{'s' if self.not_compared > 1 else ''} not compared")
        return line + "\n"

    @property
    def compared_nothing(self) -> bool:
        """True when no row was compared at all (every data set was
        refused): not a disagreement, nothing to judge."""
        return self.within + self.outside == 0

    @property
    def text(self) -> str:
        out = io.StringIO()
        for index, rows in self.tables:
            out.write(_table_text(index, rows))
        for index, note in self.notes:
            out.write(_note_text(index, note))
        out.write(self.summary)
        return out.getvalue()


def _note_text(index: int, note: str) -> str:
    return f"data set {index}: not compared: {note}\n"


def _table_text(index: int, rows: list[Row]) -> str:
    out = io.StringIO()
    header = (f"{'quantity':<14}{'legacy single':>16}{'restored sgl':>16}"
              f"{'restored dbl':>16}{'numpy dbl':>16}  "
              f"{'rs/ls':>7}  {'rd/np':>7} {'tol':>7}  "
              f"{'rs/rd':>7} {'tol':>7}  ok")
    out.write(f"data set {index}\n{header}\n")
    for r in rows:
        legacy_text = "n/a" if r.legacy_single is None \
            else f"{r.legacy_single:.9g}"
        tol_single = "none" if r.tol_single is None \
            else f"{r.tol_single:7.1e}"
        out.write(
            f"{r.name:<14}{legacy_text:>16}"
            f"{r.restored_single:>16.9g}{r.restored_double:>16.9g}"
            f"{r.numpy_double:>16.9g}  {r.rel_legacy:7.1e}  "
            f"{r.rel_double:7.1e} {r.tol_double:7.1e}  "
            f"{r.rel_single:7.1e} {tol_single:>7}  "
            f"{'yes' if r.passed else 'NO'}\n")
    out.write("\n")
    return out.getvalue()


@dataclass(frozen=True)
class _ErrorModel:
    """What rounding at unit roundoff ``eps`` can do to each quantity of a
    data set, relative (module docstring)."""

    amplitude: np.ndarray  # of each A_j
    act: float             # of ACT = sum -P A C, hence EY, TY2DT
    t_impact: float        # of the impact time (search step included)
    velocity_drift: float  # absolute error of the tip velocities at
                           # impact from the error in the impact time
    history_time: float    # of a history time T (accumulated)
    history: float         # of y3: ACT's, plus the phase p3 * (T drift)

    @classmethod
    def of(cls, result: Result, eps: float) -> "_ErrorModel":
        ds = result.inputs
        v = np.asarray(ds.v, dtype=float)
        ape = np.asarray(result.ape, dtype=float)
        p, c = np.asarray(result.p, dtype=float), np.asarray(ds.c, dtype=float)
        d_ape = 12 * eps * abs(ds.ystat) * np.exp(v) / v
        act = abs(float(np.sum(p * ape * c)))
        speed = abs(result.tip_velocity_before)
        t1 = result.t_impact
        accel = float(np.sum(p**2 * np.abs(ape * c)))
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            amplitude = d_ape / np.abs(ape) + 16 * eps
            rel_act = float(np.sum(p * np.abs(c) * d_ape)) / act + 16 * eps
            d_t = (SEARCH_STEP + float(np.sum(np.abs(c) * d_ape)) / speed
                   + 64 * eps * t1)
        history_time = eps * core.TAU / ds.delt + 64 * eps
        drift = history_time * core.TAU
        history = rel_act + float(np.max(result.p3)) * drift
        return cls(amplitude, rel_act, d_t / t1, accel * d_t, history_time,
                   history)


def _tolerances(bound64: float, bound32: float, allowance: float = 0.0
                ) -> tuple[float, float | None]:
    """The tolerances of the double and single checks from the rounding
    bounds, plus ``allowance`` for the listing's search step (not capped:
    it is not arithmetic)."""
    tol_double = min(max(DOUBLE_RTOL, bound64), MAX_DOUBLE_RTOL)
    if math.isnan(tol_double):
        tol_double = MAX_DOUBLE_RTOL
    tol_double += allowance
    tol_single = bound32 if bound32 < 1.0 else None
    return tol_double, tol_single


def _rows(printed: listing.DataSetListing | None, single: Result,
          single_printed: listing.DataSetListing, double: Result,
          ref: reference.ReferenceResult) -> list[Row]:
    """The rows of one data set; ``printed`` is the original program's
    listing read back, None where it cannot run the data set."""
    rows: list[Row] = []
    f64 = _ErrorModel.of(double, _EPS64)
    f32 = _ErrorModel.of(double, _EPS32)

    def add(name, pick, single_value, double_value, ref_value, bound64,
            bound32, allowance=0.0):
        """``pick`` reads the quantity from a parsed listing."""
        tol_double, tol_single = _tolerances(bound64, bound32, allowance)
        rows.append(Row(
            name, None if printed is None else float(pick(printed)),
            float(pick(single_printed)), float(single_value),
            float(double_value), float(ref_value), tol_double, tol_single))

    for j in range(double.inputs.n):
        add(f"p_{j + 1}", lambda out: out.modal_table[j, 3], single.p[j],
            double.p[j], ref.p[j], DOUBLE_RTOL, 16 * _EPS32)
    for j in range(double.inputs.n):
        add(f"A_{j + 1}", lambda out: out.modal_table[j, 4], single.ape[j],
            double.ape[j], ref.ape[j], f64.amplitude[j], f32.amplitude[j])
    add("t_impact", lambda out: out.impact[0], single.t_impact,
        double.t_impact, ref.t_impact, 0.0, f32.t_impact, f64.t_impact)
    add("impulse", lambda out: out.impact[1], single.ey, double.ey, ref.ey,
        f64.act, f32.act)
    # the tip velocities move with the impact time at the tip's
    # acceleration: an absolute error, relative to each velocity
    for name, pick, values in (
            ("v_before", lambda out: out.tip[3],
             (single.tip_act, double.tip_act, ref.impact_velocity)),
            ("v_after", lambda out: out.tip[2],
             (single.tip_tydtl, double.tip_tydtl, ref.tip_tydtl))):
        size = abs(values[1])
        add(name, pick, *values, f64.act,
            f32.act + f32.velocity_drift / size, f64.velocity_drift / size)
    add("v_separator", lambda out: out.ty2dt, single.ty2dt, double.ty2dt,
        ref.ty2dt, f64.act, f32.act)
    # every column at the grid point of the double extreme (two nearly
    # equal peaks must not make the columns compare different points),
    # among the points all have: accumulating T = T + DELT may give one
    # point more near TAU than the reference's i * DELT
    common = min(len(single.history_t), len(double.history_t),
                 len(ref.history_t), len(single_printed.history),
                 len(printed.history) if printed is not None else math.inf)
    k = int(np.argmax(np.abs(double.history_ty3[:common])))

    def at(values: np.ndarray) -> float:
        return values[k]

    add("y3_extreme", lambda out: at(out.history[:, 1]),
        at(single.history_ty3), at(double.history_ty3), at(ref.history_ty3),
        f64.history, f32.history)
    add("t_extreme", lambda out: at(out.history[:, 0]),
        at(single.history_t), at(double.history_t), at(ref.history_t),
        f64.history_time, f32.history_time)
    return rows


def compare_deck(path: core.Deck, stream: TextIO | None = None
                 ) -> Comparison:
    """Compare all implementations on every data set of the deck at
    ``path`` (or any deck :func:`contactsep.restored.core.iter_deck` takes).  A bad
    data set ends the comparison with its error; the tables of the data
    sets before it are kept.  The original program runs each data set on
    its own cards (one listing per data set, as it prints them back to
    back), and only where N <= 4.

    The deck is read a data set at a time.  With ``stream``, each table
    (or note) is written there as soon as it is made, then the summary
    line, and the returned comparison only counts them: memory does not
    grow with the deck."""
    comparison = Comparison()
    if isinstance(path, str):        # a file name, as before
        path = Path(path)
    try:
        for index, kind, payload in iter_compare(path):
            if kind == "note":
                comparison.add_note(index, payload, stream)
            else:
                comparison.add_table(index, payload, stream)
            if stream is not None:
                stream.flush()
    except DeckError as error:
        comparison.error = error
    if stream is not None:
        stream.write(comparison.summary)
    return comparison


def iter_compare(source: core.Deck) -> Iterator[tuple[int, str, object]]:
    """(data set, "table", rows) or (data set, "note", why it could not
    be compared) for each data set of the deck, as they are made; raises
    :class:`DeckError` at the first bad data set."""
    for d_item in core.iter_deck(source, precision="double"):
        s_item = core.reread(d_item, "single")
        where = dict(data_set_index=d_item.index,
                     first_card=d_item.first_card)
        single = core.solve(s_item.data_set, "single", **where)
        double = core.solve(d_item.data_set, "double", **where)
        slowest = 2 * math.pi / float(np.min(double.p))
        try:
            ref = reference.run(d_item.data_set, search_horizon=max(
                4 * slowest, double.t_impact + slowest))
        except ValueError as error:
            yield d_item.index, "note", str(error)
            continue
        printed = None
        if d_item.data_set.n <= legacy.LEGACY_MAX_MODES:
            printed = listing.parse(
                legacy.run_cards(d_item.cards, "single"))[0]
        single_printed = listing.parse(single.listing)[0]
        # the same program in the same precision prints the same lines: a
        # history shorter or longer than the legacy one is a failure
        if printed is not None and len(printed.history) != len(
                single_printed.history):
            yield d_item.index, "note", (
                f"history has {len(single_printed.history)} lines, the "
                f"legacy program's {len(printed.history)}")
        yield d_item.index, "table", _rows(
            printed, single, single_printed, double, ref)
