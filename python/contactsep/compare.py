"""``contactsep compare``: every implementation side by side.

For each data set of a deck, four columns: the original program in single
precision (its listing read back), the restored core in single and in
double precision, and the NumPy reference (float64, the listing's algorithm
choices).  Three checks, each with its own tolerance:

``restored single = legacy single``
    Identical printed digits: the restored core is bit-identical, so its
    listing, read back the same way, must give the same numbers (tolerance 0).
``restored double ~ NumPy``
    Two float64 implementations of the same equations, one translated from
    the listing and one written from the thesis: 1e-9 relative.  Quantities
    that depend on the impact time get an extra allowance, because the
    listing's search stops at the last point above the separator with a
    step of at most 1e-8 s while the reference finds the crossing itself:
    |dq/dt| * 1e-8 s.
``single ~ double``
    What the listing's REAL arithmetic loses.  The D1-D8 integrals subtract
    terms of size y_s e^{kL}/(kL) to get A_j, so float32 leaves an absolute
    error of about eps * y_s e^{kL}/(kL) in A_j; the tolerance is that bound
    (times 8 for the dozen roundings on the way), carried through to the
    quantities built from the A_j.
"""

from __future__ import annotations

import io
import os
from dataclasses import dataclass, field

import numpy as np

from contactsep import core, legacy, listing, reference
from contactsep.errors import DeckError
from contactsep.result import Result

#: The listing's impact-search resolution (its stopping rule), s.
SEARCH_STEP = 1e-8
#: Relative agreement required of the two float64 implementations.
DOUBLE_RTOL = 1e-9
_EPS32 = float(np.finfo(np.float32).eps)


@dataclass(frozen=True)
class Row:
    """One quantity of one data set across the implementations."""

    name: str
    #: NaN where the original program printed asterisks; None where it
    #: cannot run the data set (N > 4, its DIMENSION).
    legacy_single: float | None
    restored_single: float
    restored_double: float
    numpy_double: float
    #: Tolerances of the three checks (relative).
    tol_double: float
    tol_single: float

    @staticmethod
    def _rel(a: float, b: float) -> float:
        if a == b:
            return 0.0
        scale = max(abs(a), abs(b))
        return abs(a - b) / scale if scale else float("inf")

    @property
    def rel_legacy(self) -> float:
        if self.legacy_single is None:
            return float("nan")
        return self._rel(self.restored_single, self.legacy_single)

    @property
    def rel_double(self) -> float:
        return self._rel(self.restored_double, self.numpy_double)

    @property
    def rel_single(self) -> float:
        return self._rel(self.restored_single, self.restored_double)

    @property
    def passed(self) -> bool:
        if self.legacy_single is None:
            legacy_ok = True   # nothing to compare with
        elif np.isnan(self.legacy_single) and np.isnan(self.restored_single):
            legacy_ok = True   # both printed asterisks
        else:
            legacy_ok = self.rel_legacy == 0.0
        return (legacy_ok and self.rel_double <= self.tol_double
                and self.rel_single <= self.tol_single)


@dataclass
class Comparison:
    """The comparison of one deck."""

    tables: list[tuple[int, list[Row]]] = field(default_factory=list)
    error: DeckError | None = None

    @property
    def passed(self) -> bool:
        return self.error is None and all(
            row.passed for _, rows in self.tables for row in rows)

    @property
    def text(self) -> str:
        out = io.StringIO()
        header = (f"{'quantity':<14}{'legacy single':>16}{'restored sgl':>16}"
                  f"{'restored dbl':>16}{'numpy dbl':>16}  "
                  f"{'rs/ls':>7}  {'rd/np':>7} {'tol':>7}  "
                  f"{'rs/rd':>7} {'tol':>7}  ok")
        for index, rows in self.tables:
            out.write(f"data set {index}\n{header}\n")
            for r in rows:
                out.write(
                    f"{r.name:<14}"
                    f"{'n/a' if r.legacy_single is None else format(r.legacy_single, '.9g'):>16}"
                    f"{r.restored_single:>16.9g}{r.restored_double:>16.9g}"
                    f"{r.numpy_double:>16.9g}  {r.rel_legacy:7.1e}  "
                    f"{r.rel_double:7.1e} {r.tol_double:7.1e}  "
                    f"{r.rel_single:7.1e} {r.tol_single:7.1e}  "
                    f"{'yes' if r.passed else 'NO'}\n")
            out.write("\n")
        failed = sum(not r.passed for _, rows in self.tables for r in rows)
        total = sum(len(rows) for _, rows in self.tables)
        out.write(f"{total - failed} within tolerance, {failed} outside\n")
        return out.getvalue()


@dataclass(frozen=True)
class _ErrorModel:
    """What rounding at unit roundoff ``eps`` can do to each quantity of a
    data set, relative (module docstring): the listing's A_j lose
    ~ y_s e^{kL}/(kL) * eps absolutely, and everything built from them
    inherits that; sums and products add a few dozen ulp."""

    amplitude: np.ndarray  # relative error bound of each A_j
    act: float             # of ACT = sum -P A C, hence EY, TY2DT, y3
    t_impact: float        # of the impact time (search step included)
    velocity: float        # of the tip velocities at impact

    @classmethod
    def of(cls, result: Result, eps: float) -> "_ErrorModel":
        ds = result.inputs
        v = np.asarray(ds.v, dtype=float)
        ape = np.asarray(result.ape, dtype=float)
        p, c = np.asarray(result.p, dtype=float), np.asarray(ds.c, dtype=float)
        d_ape = 8 * eps * 1.5 * abs(ds.ystat) * np.exp(v) / v
        act = abs(float(np.sum(p * ape * c)))
        rel_act = float(np.sum(p * np.abs(c) * d_ape)) / act + 16 * eps
        t1 = result.t_impact
        speed = abs(result.tip_velocity_before)
        d_t = (SEARCH_STEP + float(np.sum(np.abs(c) * d_ape)) / speed
               + 64 * eps * t1)
        accel = float(np.sum(p**2 * np.abs(ape * c)))
        return cls(amplitude=d_ape / np.abs(ape) + 16 * eps, act=rel_act,
                   t_impact=d_t / t1,
                   velocity=rel_act + accel * d_t / speed)


def _rows(printed: listing.DataSetListing | None,
          single_printed: listing.DataSetListing, double: Result,
          ref: reference.ReferenceResult) -> list[Row]:
    """The rows of one data set; ``printed`` is the original program's
    listing read back, None where it cannot run the data set."""
    # where the original program cannot run, `add` leaves its column empty;
    # the restored single listing only stands in so the code reads alike
    legacy_printed = printed if printed is not None else single_printed
    rows: list[Row] = []
    f64 = _ErrorModel.of(double, float(np.finfo(np.float64).eps))
    f32 = _ErrorModel.of(double, _EPS32)

    def add(name, legacy_value, single_value, double_value, ref_value,
            tol_double, tol_single):
        legacy_value = float(legacy_value) if printed is not None else None
        rows.append(Row(name, legacy_value, float(single_value),
                        float(double_value), float(ref_value),
                        max(DOUBLE_RTOL, float(tol_double)),
                        float(tol_single)))

    n = double.inputs.n
    for j in range(n):
        add(f"p_{j + 1}", legacy_printed.modal_table[j, 3],
            single_printed.modal_table[j, 3], double.p[j], ref.p[j],
            DOUBLE_RTOL, 16 * _EPS32)
    for j in range(n):
        add(f"A_{j + 1}", legacy_printed.modal_table[j, 4],
            single_printed.modal_table[j, 4], double.ape[j], ref.ape[j],
            f64.amplitude[j], f32.amplitude[j])
    add("t_impact", legacy_printed.impact[0], single_printed.impact[0],
        double.t_impact, ref.t_impact, f64.t_impact, f32.t_impact)
    add("impulse", legacy_printed.impact[1], single_printed.impact[1], double.ey,
        ref.ey, f64.act, f32.act)
    add("v_before", legacy_printed.tip[3], single_printed.tip[3], double.tip_act,
        ref.impact_velocity, f64.velocity, f32.velocity)
    add("v_after", legacy_printed.tip[2], single_printed.tip[2], double.tip_tydtl,
        ref.tip_tydtl, 2 * f64.velocity, 2 * f32.velocity)
    add("v_separator", legacy_printed.ty2dt, single_printed.ty2dt, double.ty2dt,
        ref.ty2dt, f64.act, f32.act)
    extreme = [int(np.argmax(np.abs(h))) for h in (
        legacy_printed.history[:, 1], single_printed.history[:, 1],
        double.history_ty3, ref.history_ty3)]
    add("y3_extreme", legacy_printed.history[extreme[0], 1],
        single_printed.history[extreme[1], 1],
        double.history_ty3[extreme[2]], ref.history_ty3[extreme[3]],
        f64.act, f32.act)
    add("t_extreme", legacy_printed.history[extreme[0], 0],
        single_printed.history[extreme[1], 0], double.history_t[extreme[2]],
        ref.history_t[extreme[3]], DOUBLE_RTOL, 64 * _EPS32)
    return rows


def compare_deck(path: str | os.PathLike) -> Comparison:
    """Compare all implementations on every data set of the deck at
    ``path``.  A bad data set ends the comparison with its error; the
    tables of the data sets before it are kept.  The original program runs
    each data set on its own cards (one listing per data set, as it prints
    them back to back), and only where N <= 4."""
    comparison = Comparison()
    text = core.read_text(path)
    lines = text.split("\n")
    try:
        for s_item, d_item in zip(core.iter_deck(text, precision="single"),
                                  core.iter_deck(text, precision="double")):
            where = dict(data_set_index=d_item.index,
                         first_card=d_item.first_card)
            single = core.solve(s_item.data_set, "single", **where)
            double = core.solve(d_item.data_set, "double", **where)
            ref = reference.run(d_item.data_set)
            printed = None
            if d_item.data_set.n <= legacy.LEGACY_MAX_MODES:
                cards = "".join(line + "\n" for line in
                                lines[d_item.first_card - 1:d_item.last_card])
                printed = listing.parse(legacy.run_cards(cards, "single"))[0]
            comparison.tables.append((d_item.index, _rows(
                printed, listing.parse(single.listing)[0], double, ref)))
    except DeckError as error:
        comparison.error = error
    return comparison
