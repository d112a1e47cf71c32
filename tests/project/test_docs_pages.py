"""The numbers docs/studies.md, docs/sweeps.md and docs/model.md quote
from the committed data of docs/studies: each is the page's ``datum``
role (which tests/project/test_data_values.py resolves on every page)
for the CSV that tests/studies/test_committed_outputs.py holds equal to
the code, checked here with the sentence it stands in, and what the
CSV says of the physics checked on the CSV.  The single computed
numbers and the convergence table beyond N = 50 are in
test_docs_physics_values.py."""

from __future__ import annotations

import numpy as np
import pytest

import contactsep
from conftest import ROOT
from contactsep.model import thesis_design
from docs_text import STUDIES, column, page, role, rows, says


def test_figure_5_numbers_are_fig5_csv():
    """Each number is the role that selects the row its sentence names
    (the role's value is the CSV's: tests/project/test_data_values)."""
    y3 = {(ys, d): role("fig5", "y3_max_in", ".3f", ys_in=ys, d_in=d)
          for ys in (0.25, 0.5, 0.75) for d in (0.1, 0.25, 0.5, 1.0)}
    says("studies.md", f"y_s = 0.5 in: {y3[0.5, 0.1]} in at d = 0.10, "
         f"{y3[0.5, 0.25]} at 0.25, {y3[0.5, 0.5]} at 0.50, "
         f"{y3[0.5, 1.0]} at 1.00 in")
    says("studies.md", f"({y3[0.25, 0.1]}, {y3[0.5, 0.1]}, "
         f"{y3[0.75, 0.1]} in at d = 0.10 for y_s = 0.25, 0.5, 0.75 in)")


def test_figure_6_numbers_are_fig6_csv():
    y3 = {(c, r): role("fig6", "y3_max_in", ".3f", curve=c, r=r)
          for c in ("I", "II") for r in (1.0, 0.78, 0.7)}
    says("studies.md", f"Curve I: {y3['I', 1.0]} in at r = 1.00, "
         f"{y3['I', 0.78]} at 0.78, {y3['I', 0.7]} at 0.70; curve II: "
         f"{y3['II', 0.78]} at 0.78, {y3['II', 0.7]} at 0.70.")


def test_figure_8_ends_are_fig8_csv():
    says("studies.md", f"({role('fig8', 'y3_max_in', '.3f', R=0.05)} in "
         f"at R = 0.05, {role('fig8', 'y3_max_in', '.3f', R=5.0)} in at "
         "R = 5)")


def test_figure_23_numbers_are_fig23_csv():
    """The corrected curve at each d, and the uncorrected one at the
    first and last d (the chart's first and last rows)."""
    assert column("fig23", "d_in").tolist() == [0.125, 0.25, 0.35, 0.5,
                                                0.75]
    corrected = ", ".join(role("fig23", "y3_max_in", ".3f", d_in=d)
                          for d in (0.125, 0.25, 0.35, 0.5, 0.75))
    plain = [role("fig23", "y3_max_uncorrected_in", ".3f", d_in=d)
             for d in (0.125, 0.75)]
    says("studies.md", f"max y3 is {corrected} in for d = 0.125, 0.25, "
         f"0.35, 0.50, 0.75 in, against {plain[0]} ... {plain[1]} in "
         "without L_c")
    says("studies.md", "The 0.75 in row uses the printed L_c = "
         + role("fig23", "Lc_in", ".2f", d_in=0.75) + " in")


def test_the_new_convergence_value_is_convergence_csv():
    says("records/2026-12-history.md", "N = 50: max y3 0.105479 → "
         + role("convergence", "y3_max_in", ".6f", N=50) + " in")


def test_conclusion_8_numbers_are_conclusion8_csv():
    low, high, peak, tip, mid = (role("conclusion8", key, fmt, **where)
        for key, fmt, where in (
            ("min(r)", ".2f", {"n_maxima": 1}),
            ("max(r)", ".2f", {"n_maxima": 1}),
            ("max(first_mode_share)", ".4f", {}),
            ("first_mode_share", ".3f", {"r": 1.0}),
            ("first_mode_share", ".3f", {"r": 0.5})))
    says("studies.md", "every contact point from x3/L3 = "
         f"{low} to {high} swings once, and the share peaks at {peak} at "
         f"x3/L3 = ")
    says("studies.md", f"(it is {tip} at the tip, with two swings, and "
         f"{mid} at mid-length, with six)")
    r = column("conclusion8", "r")
    share_r = column("conclusion8", "first_mode_share")
    swings = column("conclusion8", "n_maxima")
    once = r[swings == 1]
    # one band: every point between them swings once
    assert np.all(swings[(r >= once.min()) & (r <= once.max())] == 1)
    # the peak's x3/L3: test_docs_physics_values
    assert share_r.max() > share_r[r == 1.0][0]
    assert swings[r == 1.0][0] == 2 and swings[r == 0.5][0] == 6


# -- docs/studies.md, the tables ----------------------------------------------

def test_tables_1_to_3_are_their_csvs():
    """Each table's model and printed values are the roles that select
    their rows; the differences and E/γ (derived, not columns) are
    checked against the CSVs."""
    ds = (0.125, 0.25, 0.35, 0.5, 0.75)

    def roles(name, key, fmts, where, bold_last=False):
        cells = [role(name, key, fmt, **{where: v}) for v, fmt in fmts]
        if bold_last:
            cells[-1] = f"**{cells[-1]}**"
        return ", ".join(cells)

    ratio = " + ".join(
        f"([studies/table1.csv:printed_theoretical_cps@mode={m}] / "
        f"[studies/table1.csv:model_cps@mode={m}]) ** 2" for m in (1, 2, 3, 4))
    says("studies.md", "| I, contact frequencies (cps) | "
         + roles("table1", "model_cps", zip((1, 2, 3, 4), (
             ".3f", ".2f", ".2f", ".2f")), "mode") + " | "
         + roles("table1", "printed_theoretical_cps",
                 [(m, ".1f") for m in (1, 2, 3, 4)], "mode")
         + " | **disagree by "
         + role("table1", "min(relative_difference)", ".1%") + "–"
         + role("table1", "max(relative_difference)", ".1%")
         + "**: the printed theory implies E/γ = {datum}`=1e8 * ("
         + ratio + ") / 4 / 1e7:.2f`·10⁷ in, Table II 1.00·10⁸ in")
    # the E/gamma the printed frequencies imply (they go as its root):
    # the thesis rig's, 1e7 psi / 0.1 lb/in^3, over (1 + difference)^2
    rig = thesis_design()
    assert rig.E2 / rig.gamma2 == rig.E3 / rig.gamma3 == pytest.approx(1e8)
    implied = 1e8 * np.mean((column("table1", "printed_theoretical_cps")
                             / column("table1", "model_cps")) ** 2)
    assert implied == pytest.approx(1e8 * np.mean(
        (1 + column("table1", "relative_difference")) ** -2.0), rel=1e-9)
    says("studies.md", "| II, separator frequency (cps) | "
         + roles("table2", "model_cps", [(d, ".0f") for d in ds], "d_in")
         + " | " + roles("table2", "printed_theoretical_cps",
                         [(d, None) for d in ds], "d_in")
         + " | agree to {datum}`=100 * max(abs([studies/table2.csv:max("
         "relative_difference)]), abs([studies/table2.csv:min("
         "relative_difference)])):.2f` %")
    says("studies.md", "| III, L_c = √(1.3e6 d/p) (in) | "
         + roles("table3", "Lc_formula_in", [(d, ".3f") for d in ds],
                 "d_in", bold_last=True) + " | "
         + roles("table3", "printed_Lc_in", [(d, ".2f") for d in ds],
                 "d_in", bold_last=True))


# -- docs/model.md ------------------------------------------------------------

def convergence_table() -> dict:
    """N -> the row's cells, as model.md prints them."""
    text = (ROOT / "docs" / "model.md").read_text()
    table = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 7 and cells[0].isdigit():
            table[int(cells[0])] = cells[1:]
    return table


#: model.md's columns of the convergence table the study writes, and the
#: page's formats (ψ·N is an expression of the row's ψ).
CONVERGENCE_COLUMNS = (("t1_s", ".6g"), ("v_impact_in_s", ".3f"),
                       ("psi_lb_s", ".4sci"), (None, None),
                       ("v0_in_s", ".3f"), ("y3_max_in", ".6f"))


def test_the_convergence_table_to_n_50_is_convergence_csv():
    """Each row of the study (N <= 50): its values the roles that select
    the row, ψ·N the role of the row's product (N > 50:
    test_docs_physics_values)."""
    table = convergence_table()
    assert sorted(table) == [1, 2, 3, 4, 8, 16, 32, 50, 100, 200, 400, 800,
                             1600]
    for r in rows("convergence"):
        n = int(r["N"])
        if n not in table:
            continue
        assert table[n] == [
            role("convergence", key, fmt, N=n) if key else
            f"{{datum}}`=[studies/convergence.csv:psi_lb_s@N={n}] * {n}:.4sci`"
            for key, fmt in CONVERGENCE_COLUMNS], n


def test_the_convergence_study_converges_but_its_impulse_does_not():
    """What the page says of the table, on the committed study: t1 is
    settled to 1e-6 from N = 16, ψ falls like 1/N (ψ·N grows from N = 3
    on and stays within 10 % from N = 16), max y3 falls monotonically from
    N = 4, its falls over N = 4, 8, 16, 32 shrinking at least as 0.6 a
    doubling (O(1/N) halves them)."""
    n = column("convergence", "N")
    t1 = column("convergence", "t1_s")
    psi_n = column("convergence", "psi_lb_s") * n
    y3 = column("convergence", "y3_max_in")
    assert np.all(np.abs(t1[n >= 16] / t1[-1] - 1) < 1e-6)
    assert np.all(np.diff(psi_n[n >= 3]) > 0)
    assert np.all(psi_n[n >= 16] / psi_n[-1] > 0.9)
    assert np.all(np.diff(y3[n >= 4]) < 0)
    falls = -np.diff(y3[np.isin(n, (4, 8, 16, 32))])
    assert np.all(falls[1:] < 0.6 * falls[:-1]), falls


def test_the_energy_bound_numbers():
    """"0.026 in from a 0.02 in release of an identical spring (1.3-3.2
    times the bound on four of the nine designs ...)": roles of
    docs/studies/energy_bound.csv, which is its script's output now
    (tests/project/test_docs_physics_values.py) and has one row per
    design of tests/design_family.py's FAMILY and UNSEEN."""
    from design_family import FAMILY, UNSEEN
    table = rows("energy_bound")
    assert [r["design"] for r in table] == list({**FAMILY, **UNSEEN})
    ratio = column("energy_bound", "bound_ratio")
    assert np.allclose(ratio, column("energy_bound", "y3_max_in")
                       / column("energy_bound", "bound_in"), rtol=1e-12)
    assert np.array_equal(column("energy_bound", "above_bound"), ratio > 1)
    # an identical spring: the bound is the release itself
    relay = FAMILY["steel_relay"]
    assert (relay.E1, relay.L1, relay.h1) == (relay.E3, relay.L3, relay.h3)
    assert column("energy_bound", "bound_in", design="steel_relay") == \
        pytest.approx(relay.ys, rel=1e-9)
    e = "studies/energy_bound.csv"
    says("model.md", f"it gives {{datum}}`{e}:y3_max_in@design=steel_relay"
         f":.3f` in from a {{datum}}`{e}:ys_in@design=steel_relay:.2f` in "
         "release of an identical spring ("
         f"{{datum}}`{e}:min(bound_ratio)@above_bound=1:.1f`-"
         f"{{datum}}`{e}:max(bound_ratio)@above_bound=1:.1f` times the "
         f"bound on {{datum}}`{e}:rows@above_bound=1` of the "
         f"{{datum}}`{e}:rows` designs of "
         "the test suite's design family at N = 4")


def test_the_png_sizes():
    """"default 100: 600 x 400 pixels, the tables 600 x 500": the dpi is
    the package's constant, the sizes the committed PNGs' headers."""
    import struct
    size = {}
    for name in ("fig5", "table1"):
        head = (STUDIES / f"{name}.png").read_bytes()[16:24]
        size[name] = "{} × {}".format(*struct.unpack(">II", head))
    says("studies.md", "(default {constant}`contactsep.cli.studies."
         f"DEFAULT_DPI`: {size['fig5']} pixels, the tables {size['table1']})")


# -- docs/studies.md, Table II explained --------------------------------------
