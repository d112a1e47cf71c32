"""The numbers docs/studies.md, docs/sweeps.md, docs/names-and-units.md,
docs/howto/resume.md and docs/model.md quote come from the
code (issue 30, item 8): each is read off the page by the sentence that
quotes it and compared, to the digits the page prints, with a committed
CSV of docs/studies (which tests/studies/test_committed_outputs.py holds
equal to the code) or with a fresh computation (cheap ones in the
default run, the costly ones slow).  A page that drifts from the code,
or a sentence reworded so that its number is no longer found, fails."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest

import contactsep
from conftest import ROOT
from contactsep.model import evaluate, thesis_design
from docs_text import (NUMBER, STUDIES, check, column, page, printed,
                       quoted, role, rows, says)


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


def test_figure_7_coefficients_and_the_node():
    """The c3_j of Figure 7's two designs (eq. 23 as printed, N = 4, the
    thesis rig), recomputed; the node of the cantilever's mode 2."""
    claims = quoted("studies.md", rf"c3_j \(in\) are {NUMBER}, {NUMBER}, "
                    rf"{NUMBER}, {NUMBER} at 0.98 and {NUMBER}, {NUMBER}, "
                    rf"{NUMBER}, {NUMBER} at 0.78: mode 2 is ([\d,]+) times "
                    rf"weaker \(the node of the cantilever's mode 2 is at "
                    rf"x/L = {NUMBER}\)")
    c3 = evaluate(thesis_design(x3=np.array([0.98, 0.78]) * 19.0,
                                lower_response="as-printed")).c3
    from contactsep.studies.thesis.mode_share import second_mode_node
    weaker = c3[0, 1] / c3[1, 1]
    check(claims[:8], c3.ravel())
    assert f"{round(weaker, -2):,.0f}" == claims[8]
    check(claims[9:], [second_mode_node()])


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
    low, high, peak, tip, mid = (re.escape(role(
        "conclusion8", key, fmt, **where))
        for key, fmt, where in (
            ("min(r)", ".2f", {"n_maxima": 1}),
            ("max(r)", ".2f", {"n_maxima": 1}),
            ("max(first_mode_share)", ".4f", {}),
            ("first_mode_share", ".3f", {"r": 1.0}),
            ("first_mode_share", ".3f", {"r": 0.5})))
    node, blevins, share, at = quoted(
        "studies.md", rf"second mode's node is at x3/L3 = {NUMBER} "
        rf"\(Blevins: {NUMBER}\)\. There the share is {NUMBER} and y3 "
        rf"swings once a period.*? every contact point from x3/L3 = "
        rf"{low} to {high} swings once, and the share peaks at "
        rf"{peak} at x3/L3 = {NUMBER} \(it is {tip} at the tip, with "
        rf"two swings, and {mid} at mid-length, with six\)")
    from contactsep.studies.thesis.mode_share import MODES, second_mode_node
    check([node], [second_mode_node()])
    assert abs(float(blevins) - second_mode_node()) < 5e-4
    c3 = evaluate(thesis_design(n_modes=MODES,
                                x3=second_mode_node() * 19.0)).c3
    check([share], [float(c3[0] ** 2 / np.sum(c3 ** 2))])
    r = column("conclusion8", "r")
    share_r = column("conclusion8", "first_mode_share")
    swings = column("conclusion8", "n_maxima")
    once = r[swings == 1]
    # one band: every point between them swings once
    assert np.all(swings[(r >= once.min()) & (r <= once.max())] == 1)
    check([at], [r[np.argmax(share_r)]])
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
        return re.escape(", ".join(cells))

    t1 = quoted("studies.md", r"\| I, contact frequencies \(cps\) \| "
                + roles("table1", "model_cps", zip((1, 2, 3, 4), (
                    ".3f", ".2f", ".2f", ".2f")), "mode") + r" \| "
                + roles("table1", "printed_theoretical_cps",
                        [(m, ".1f") for m in (1, 2, 3, 4)], "mode")
                + r" \| \*\*disagree by "
                + re.escape(role("table1", "min(relative_difference)", ".1%")
                            + "–" + role("table1", "max(relative_difference)",
                                         ".1%"))
                + rf"\*\*: the printed theory implies E/γ = {NUMBER} in, "
                rf"Table II {NUMBER} in")
    model = column("table1", "model_cps")
    # E/gamma the printed frequencies imply: frequencies go as its root
    material = 10.0e6 / 0.100
    implied = material * (column("table1", "printed_theoretical_cps")
                          / model) ** 2
    check(t1, [implied.mean(), material])
    t2 = quoted("studies.md", r"\| II, separator frequency \(cps\) \| "
                + roles("table2", "model_cps", [(d, ".0f") for d in ds],
                        "d_in") + r" \| "
                + roles("table2", "printed_theoretical_cps",
                        [(d, None) for d in ds], "d_in")
                + r" \| agree to \{datum\}`=100 \* max\(abs\(\[studies/"
                r"table2\.csv:max\(relative_difference\)\]\), abs\(\[studies/"
                r"table2\.csv:min\(relative_difference\)\]\)\):\.2f` %")
    assert t2 == ()
    assert re.search(
        r"\| III, L_c = √\(1.3e6 d/p\) \(in\) \| "
        + roles("table3", "Lc_formula_in", [(d, ".3f") for d in ds],
                "d_in", bold_last=True) + r" \| "
        + roles("table3", "printed_Lc_in", [(d, ".2f") for d in ds],
                "d_in", bold_last=True), page("studies.md"))


def test_table_1s_model_is_above_the_printed_theory_for_every_mode():
    """The data behind the page's range of the Table I disagreement:
    relative_difference is model / printed - 1, and the model is above
    the printed theory for every mode by 3-4 % (one material ratio: the
    frequencies of one beam scale alike, so the spread is rounding of
    the printed values)."""
    model = column("table1", "model_cps")
    printed_cps = column("table1", "printed_theoretical_cps")
    relative = column("table1", "relative_difference")
    assert np.allclose(relative, model / printed_cps - 1, rtol=1e-9)
    assert np.all((relative > 0.03) & (relative < 0.04)), relative
    # the printed values carry 3 digits: the spread is within their step
    assert np.ptp(relative) < 0.1 / 10.6 + 1e-12


def test_the_formulas_constant_against_the_materials():
    """"1.3e6 is 2.4 % off the material's 1.270e6": (k1 L)^2 sqrt(E g /
    (12 gamma)) of the clamped-clamped aluminium separator."""
    off, constant = quoted("studies.md", rf"1.3e6 is {NUMBER} % off the "
                           rf"material's {NUMBER}\)")
    from contactsep.beams import eigenvalues
    from contactsep.constants import GRAVITY_IN_PER_S2 as G
    k1 = eigenvalues("clamped-clamped", 1)[0]
    material = k1 ** 2 * np.sqrt(10.0e6 * G / (12 * 0.100))
    check([off, constant], [100 * (1.3e6 / material - 1), material])


# -- docs/sweeps.md --------------------------------------------------------

def test_wilsons_z_and_the_largest_preload():
    (z,) = quoted("sweeps.md", rf"with z = {NUMBER} ")
    from scipy.stats import norm
    check([z], [norm.ppf(0.975)])
    from contactsep.studies.stats import wilson_interval
    # the interval's z is that z: k = 0 of n gives z^2/(n + z^2) on top
    low, high = wilson_interval(0, 100)
    assert low == 0 and high == pytest.approx(norm.ppf(0.975) ** 2
                                              / (100 + norm.ppf(0.975)
                                                 ** 2), rel=1e-5)
    (limit,) = quoted("sweeps.md", rf"by its length: {NUMBER} lb for the "
                      rf"thesis rig\)")
    from contactsep.chatter import DEFAULT_MODES
    from contactsep.chatter.stack import largest_preload
    check([limit], [largest_preload(thesis_design(n_modes=DEFAULT_MODES))])


def test_the_million_design_tolerance_sweep():
    """The second sweep example's summary (1e6 designs of eq. 23 as
    printed, seed 0; about 10 s on one core): the page's numbers are the
    committed summary's (docs/studies/tolerance_summary.json, the
    example's --json output), which the same sweep gives again: its
    counts exactly, its means to the last bits a chunking moves."""
    import json
    committed = json.loads((STUDIES / "tolerance_summary.json").read_text())
    for key in ("n", "y3_max_mean_in", "y3_max_sd_in", "p_exceed",
                "p_exceed_ci95[0]", "p_exceed_ci95[1]", "threshold_in"):
        assert f"{{datum}}`studies/tolerance_summary.json:{key}:" in \
            page("sweeps.md"), key
    assert committed["inputs"]["seed"] == 0
    assert committed["inputs"]["fixed"] == {"lower_response": "as-printed"}
    result = contactsep.sweep(sample=["d=normal(0.25,0.01)",
                                      "ys=uniform(0.45,0.55)"],
                              samples=1_000_000, threshold=0.12,
                              fixed={"lower_response": "as-printed"},
                              rows=False)
    s = result.summary
    assert s["inputs"] == committed["inputs"]
    for key in ("n", "n_failed", "threshold_in", "p_exceed",
                "p_exceed_ci95", "y3_max_min_in", "y3_max_max_in"):
        assert s[key] == committed[key], key
    for key in ("y3_max_mean_in", "y3_max_sd_in"):
        assert s[key] == pytest.approx(committed[key], rel=1e-12), key

# -- docs/model.md ------------------------------------------------------------

def test_the_lower_response_factor():
    """"v0 M3/(psi L3) (3.6 for the thesis rig, N = 4, d = 0.25 in)"."""
    (factor,) = quoted("model.md", rf"S2 M3/\(M2 L3\) \({NUMBER} for the "
                       rf"thesis rig, N = 4, d = 0.25 in\)")
    ev = evaluate(thesis_design(n_modes=4, d=0.25))
    check([factor], [float(ev.v0 * ev.M3 / (ev.psi * 19.0))])


def test_the_one_second_window_truth():
    """The old search's "0.10953 in where the truth is 0.11662 in at
    tau = 1 s" (eq. 23 as printed, the thesis design, N = 4)."""
    (truth,) = quoted("model.md", rf"where the truth is {NUMBER} in at "
                      rf"τ = 1 s")
    ev = evaluate(thesis_design(tau=1.0, lower_response="as-printed"))
    check([truth], [float(ev.y3_max)])


def convergence_table() -> dict:
    """N -> the row's cells, as model.md prints them."""
    text = (ROOT / "docs" / "model.md").read_text()
    table = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 7 and cells[0].isdigit():
            table[int(cells[0])] = cells[1:]
    return table


def check_rows(table, ns, computed) -> None:
    for n in ns:
        for claim, value in zip(table[n], computed[n]):
            assert printed(value, claim), (n, claim, value)


#: model.md's columns of the convergence table the study writes, and the
#: page's formats (ψ·N, a product of two columns, is typed).
CONVERGENCE_COLUMNS = (("t1_s", ".6g"), ("v_impact_in_s", ".3f"),
                       ("psi_lb_s", ".4e"), (None, None),
                       ("v0_in_s", ".3f"), ("y3_max_in", ".6f"))


def test_the_convergence_table_to_n_50_is_convergence_csv():
    """Each row of the study (N <= 50): its values the roles that select
    the row, ψ·N the row's product as text."""
    table = convergence_table()
    assert sorted(table) == [1, 2, 3, 4, 8, 16, 32, 50, 100, 200, 400, 800,
                             1600]
    for r in rows("convergence"):
        n = int(r["N"])
        if n not in table:
            continue
        assert table[n] == [
            role("convergence", key, fmt, N=n) if key else
            f"{float(r['psi_lb_s']) * n:.4e}"
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


def test_the_convergence_table_beyond_n_50_and_its_limits():
    """The rows N = 100-1600 (eq. 23 as printed, the convergence study's
    design), the falls of max y3, the Richardson limits and the errors
    at N = 4."""
    table = convergence_table()
    ns = np.array([4, 100, 200, 400, 800, 1600])
    design = thesis_design(n_modes=ns, lower_response="as-printed")
    ev = evaluate(design)
    computed = {int(n): [ev.t1[i], ev.v_impact[i], ev.psi[i],
                         ev.psi[i] * n, ev.v0[i], ev.y3_max[i]]
                for i, n in enumerate(ns)}
    check_rows(table, [100, 200, 400, 800, 1600], computed)
    y3 = dict(zip(ns.tolist(), ev.y3_max))
    v0 = dict(zip(ns.tolist(), ev.v0))
    (t_max,) = quoted("model.md", rf"t_max settles at {NUMBER} s")
    check([t_max], [ev.t_max[-1]])
    (psi_n,) = quoted("model.md", rf"ψ·N → {NUMBER} lb s")
    check([psi_n], [ev.psi[-1] * 1600])
    falls = quoted("model.md", rf"max y3 falls by {NUMBER}, {NUMBER}, "
                   rf"{NUMBER} in from N = 200 to 1600")
    check(falls, [y3[200] - y3[400], y3[400] - y3[800],
                  y3[800] - y3[1600]])

    def richardson(values, n):      # O(1/N): 2 f(2n) - f(n)
        return 2 * values[2 * n] - values[n]

    v0_limit, y3_limit, y3_limit_more, pair1, pair2 = quoted(
        "model.md", rf"\*\*v0 → {NUMBER} in/s, max y3 → {NUMBER} in\*\* "
        rf"\({NUMBER}; the pairs 200/400 and 400/800 give {NUMBER} and "
        rf"{NUMBER}\)")
    check([v0_limit, y3_limit, y3_limit_more, pair1, pair2],
          [richardson(v0, 800), richardson(y3, 800), richardson(y3, 800),
           richardson(y3, 200), richardson(y3, 400)])
    v0_error, y3_error = quoted("model.md", rf"At the listing's N = 4 the "
                                rf"errors are {NUMBER} % \(v0\) and "
                                rf"{NUMBER} % \(max y3\)")
    check([v0_error, y3_error],
          [100 * (v0[4] / richardson(v0, 800) - 1),
           100 * (y3[4] / richardson(y3, 800) - 1)])
    (high,) = quoted("studies.md", rf"max y3 is {NUMBER} % above its N → ∞ "
                     rf"limit there")
    check([high.lstrip("+")], [100 * (y3[4] / richardson(y3, 800) - 1)])


def test_the_energy_bound_numbers():
    """"0.026 in from a 0.02 in release of an identical spring (1.3-3.2
    times the bound on four of the nine designs of the test suite's
    design family at N = 4)": tests/design_family.py's FAMILY and UNSEEN."""
    from design_family import FAMILY, UNSEEN

    from contactsep.model.energy import y3_energy_bound
    gives, release, low, high, count, total = quoted(
        "model.md", rf"it gives {NUMBER} in from a {NUMBER} in release of "
        rf"an identical spring \({NUMBER}-{NUMBER} times the bound on "
        rf"(\w+) of the (\w+) designs of the test suite's design family "
        rf"at N = 4\)")
    words = {"three": 3, "four": 4, "five": 5, "seven": 7, "nine": 9}
    designs = {**FAMILY, **UNSEEN}
    assert words[total] == len(designs)
    ratios = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for design in designs.values():
            printed_form = design.replace(lower_response="as-printed")
            ratios.append(float(evaluate(printed_form).y3_max
                                / y3_energy_bound(printed_form)))
        relay = FAMILY["steel_relay"].replace(lower_response="as-printed")
        check([gives, release], [float(evaluate(relay).y3_max),
                                 float(relay.ys)])
    over = [r for r in ratios if r > 1]
    assert len(over) == words[count]
    check([low, high], [min(over), max(over)])


def test_cowpers_kappa():
    (kappa,) = quoted("model.md", rf"for a rectangle \({NUMBER} at ν = "
                      rf"0.33\)")
    nu = 0.33
    check([kappa], [10 * (1 + nu) / (12 + 11 * nu)])


def test_the_long_window_in_periods():
    """"tau = 10^4 s is 3.8e6 periods of the fastest of y3's 4 modes"."""
    (periods,) = quoted("model.md", r"\(τ = 10⁴ s is ([\d.]+)·10⁶ periods "
                        r"of the fastest of y3's 4 modes, the thesis design")
    ev = evaluate(thesis_design(n_modes=4))
    check([periods], [float(ev.p3.max()) * 1e4 / (2 * np.pi) / 1e6])


@pytest.mark.parametrize("field, value, claim", [
    ("tau", 1e8, r"the thesis design at τ = 10⁸ s gives status 4"),
    ("n_modes", 10_000, r"gives status 4, and so does N = 10⁴")])
def test_the_searchs_limits_give_status_4(field, value, claim):
    quoted("model.md", f"({claim})")
    from contactsep.model import status
    ev = evaluate(thesis_design(**{field: value}))
    assert int(np.ravel(ev.status)[0]) == status.UNRESOLVED


def test_the_png_sizes():
    """"default 100: 600 x 400 pixels, the tables 600 x 500"."""
    import struct
    size, table = quoted("studies.md", r"default 100: (\d+ × \d+) pixels, "
                         r"the tables (\d+ × \d+)\)")
    for name, claim in (("fig5", size), ("table1", table)):
        head = (STUDIES / f"{name}.png").read_bytes()[16:24]
        assert "{} × {}".format(*struct.unpack(">II", head)) == claim


# -- docs/studies.md, Table II explained --------------------------------------
