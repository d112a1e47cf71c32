"""The single computed numbers of docs/studies.md, docs/sweeps.md and
docs/model.md, and the convergence table beyond N = 50: the pages show
them with the ``datum`` role from docs/studies/page_numbers.json and
docs/studies/convergence_long.csv (each written by one script of
docs/studies, named in its docstring).  Each file is what its script
computes now; the page uses the role where it quotes the value; and
where a value has an independent check (a published value, another
study's table, a formula), the check is made on the file."""

from __future__ import annotations

import csv
import json
import subprocess
import sys

import numpy as np
import pytest

from conftest import ROOT
from docs_text import STUDIES, column, role, rows, says

JSON = "studies/page_numbers.json"
LONG = "studies/convergence_long.csv"


def committed() -> dict:
    return json.loads((STUDIES / "page_numbers.json").read_text())


def datum(key: str, fmt: str) -> str:
    """The role that shows ``key`` of page_numbers.json."""
    return f"{{datum}}`{JSON}:{key}:{fmt}`"


def script(name: str) -> str:
    """What ``python docs/studies/NAME.py`` prints now."""
    return subprocess.run([sys.executable, str(STUDIES / f"{name}.py")],
                          capture_output=True, text=True, check=True,
                          cwd=ROOT).stdout


def leaves(value, prefix=""):
    if isinstance(value, dict):
        for key, inner in value.items():
            yield from leaves(inner, f"{prefix}.{key}")
    elif isinstance(value, list):
        for index, inner in enumerate(value):
            yield from leaves(inner, f"{prefix}[{index}]")
    else:
        yield prefix, value


def test_page_numbers_json_is_what_its_script_computes():
    fresh = dict(leaves(json.loads(script("make_page_numbers"))))
    old = dict(leaves(committed()))
    assert fresh.keys() == old.keys()
    for key, value in old.items():
        assert fresh[key] == pytest.approx(value, rel=1e-10), key


@pytest.mark.parametrize("name", ["convergence_long", "energy_bound"])
def test_a_committed_csv_is_what_its_script_computes(name):
    text = script(f"make_{name}")
    committed_text = (STUDIES / f"{name}.csv").read_text()
    strip = [[line for line in t.splitlines() if line.startswith("#")]
             for t in (text, committed_text)]
    assert strip[0] == strip[1]
    fresh = list(csv.DictReader(line for line in text.splitlines()
                                if not line.startswith("#")))
    old = rows(name)
    assert [list(r) for r in fresh] == [list(r) for r in old]
    for key in fresh[0]:
        try:
            values = [float(r[key]) for r in fresh]
        except ValueError:          # a text column
            assert [r[key] for r in fresh] == [r[key] for r in old], key
            continue
        assert np.allclose([float(r[key]) for r in old], values,
                           rtol=1e-10, atol=0), key


# -- docs/studies.md ----------------------------------------------------------

def test_figure_7_coefficients_and_the_node():
    c098 = ", ".join(datum(f"figure7.c3_098_in[{i}]", ".4f")
                     for i in range(4))
    c078 = ", ".join(datum(f"figure7.c3_078_in[{i}]", fmt)
                     for i, fmt in enumerate((".4f", ".1sci", ".4f", ".4f")))
    says("studies.md", f"c3_j (in) are {c098} at 0.98 and {c078} at 0.78: "
         f"mode 2 is {{datum}}`=round([{JSON}:figure7.mode2_weaker], -2):"
         ",.0f` times weaker (the node of the cantilever's mode 2 is at "
         f"x/L = {datum('figure7.second_mode_node', '.4f')})")
    figure7 = committed()["figure7"]
    assert figure7["mode2_weaker"] == pytest.approx(
        figure7["c3_098_in"][1] / figure7["c3_078_in"][1], rel=1e-12)


def test_conclusion_8s_node_and_share():
    """The node against Blevins' published 0.783 (Formulas for Natural
    Frequency and Mode Shape, Table 8-1, clamped-free mode 2)."""
    says("studies.md", "second mode's node is at x3/L3 = "
         f"{datum('figure7.second_mode_node', '.6f')} (Blevins: 0.783). "
         f"There the share is {datum('conclusion8.share_at_node', '.4f')} "
         "and y3 swings once a period")
    from contactsep.studies.thesis.mode_share import second_mode_node
    assert abs(second_mode_node() - 0.783) < 5e-4
    # the share at the node is the study's grid's, interpolated there
    share = committed()["conclusion8"]["share_at_node"]
    r = column("conclusion8", "r")
    order = np.argsort(r)
    assert np.interp(second_mode_node(), r[order], column(
        "conclusion8", "first_mode_share")[order]) == pytest.approx(
            share, abs=2e-3)
    # the grid's peak is where the page puts it
    peak = r[np.argmax(column("conclusion8", "first_mode_share"))]
    says("studies.md", "max(first_mode_share):.4f` at x3/L3 = "
         f"{peak:.2f} (it is")


def test_the_formulas_constant_against_the_materials():
    """(k1 L)^2 sqrt(E g/(12 gamma)) of the clamped-clamped aluminium
    separator against the formula's rounded 1.3e6, and against the
    model's separator frequencies: L_c = sqrt(C d/p) at the model's p
    is Table III's Lc_model_in."""
    constant = f"[{JSON}:separator_constant]"
    says("studies.md", f"(1.3e6 is {{datum}}`=100 * (1.3e6 / {constant} - "
         f"1):.1f` % off the material's {{datum}}`={constant} / 1e6:.3f`"
         "·10⁶)")
    c = committed()["separator_constant"]
    assert 0.02 < 1.3e6 / c - 1 < 0.03
    d = column("table2", "d_in")
    p = 2 * np.pi * column("table2", "model_cps")
    lc = np.sqrt(c * d / p)
    assert np.allclose(lc, 2.5, rtol=1e-6), lc


def test_the_n_4_error_on_the_studies_and_sweeps_pages():
    y3 = [f"[{LONG}:y3_max_in@N={n}]" for n in (4, 800, 1600)]
    says("studies.md", f"max y3 is {{datum}}`=100 * ({y3[0]} / (2 * "
         f"{y3[2]} - {y3[1]}) - 1):.1f` % above its N → ∞ limit")
    says("sweeps.md", f"is {{datum}}`=100 * ({y3[0]} / (2 * {y3[2]} - "
         f"{y3[1]}) - 1):.1f` % high at N = 4)")


# -- docs/sweeps.md --------------------------------------------------------

def test_wilsons_z_and_the_largest_preload():
    from scipy.stats import norm

    from contactsep.studies.stats import Z95, wilson_interval
    says("sweeps.md", "with z = {constant}`contactsep.studies.stats.Z95:.6g`")
    assert Z95 == pytest.approx(norm.ppf(0.975), rel=1e-14)
    # the interval's z is that z: k = 0 of n gives z^2/(n + z^2) on top
    low, high = wilson_interval(0, 100)
    assert low == 0 and high == pytest.approx(
        norm.ppf(0.975) ** 2 / (100 + norm.ppf(0.975) ** 2), rel=1e-5)
    says("sweeps.md", f"by its length: {datum('largest_preload_lb', '.2f')}"
         " lb for the thesis rig)")


# -- docs/model.md ------------------------------------------------------------

def test_the_lower_response_factor_window_and_periods():
    says("model.md", f"S2 M3/(M2 L3) ({datum('lower_response_factor', '.1f')}"
         " for the thesis rig, N = 4, d = 0.25 in)")
    says("model.md", "where the truth is "
         f"{datum('one_second_y3_max_in', '.5f')} in at τ = 1 s")
    says("model.md", "(τ = 10⁴ s is {datum}`="
         f"[{JSON}:long_window_periods] / 1e6:.1f`·10⁶ periods of the fastest of y3's 4 modes")


def test_the_convergence_table_beyond_n_50():
    """The rows N = 100-1600 are roles of convergence_long.csv, whose N = 4
    row is the convergence study's (two routes to one evaluation)."""
    for n in (100, 200, 400, 800, 1600):
        says("model.md", f"| {n} | " + " | ".join([
            role("convergence_long", "t1_s", ".6g", N=n),
            role("convergence_long", "v_impact_in_s", ".3f", N=n),
            role("convergence_long", "psi_lb_s", ".4sci", N=n),
            f"{{datum}}`=[{LONG}:psi_lb_s@N={n}] * {n}:.4sci`",
            role("convergence_long", "v0_in_s", ".3f", N=n),
            role("convergence_long", "y3_max_in", ".6f", N=n)]) + " |")
    study = rows("convergence")[[int(r["N"]) for r in
                                 rows("convergence")].index(4)]
    for key, value in study.items():
        assert float(value) == pytest.approx(
            column("convergence_long", key, N=4)[0], rel=1e-10), key
    # the falls of max y3 shrink about as 1/2 a doubling (O(1/N))
    falls = -np.diff(column("convergence_long", "y3_max_in")[1:])
    assert np.all(falls > 0)
    assert np.all((falls[1:] / falls[:-1] > 0.45)
                  & (falls[1:] / falls[:-1] < 0.6)), falls


def test_the_convergence_limits_are_expressions_of_the_table():
    def y(n):
        return f"[{LONG}:y3_max_in@N={n}]"

    def v(n):
        return f"[{LONG}:v0_in_s@N={n}]"

    def expr(text, fmt):
        return f"{{datum}}`={text}:{fmt}`"

    says("model.md", "(t_max settles at "
         + role("convergence_long", "t_max_s", ".6f", N=1600) + " s.)")
    says("model.md", "(ψ·N → "
         + expr(f"[{LONG}:psi_lb_s@N=1600] * 1600", ".2sci") + " lb s)")
    says("model.md", "max y3 falls by " + ", ".join(
        expr(f"{y(n)} - {y(2 * n)}", ".2sci") for n in (200, 400, 800))
        + " in from N = 200 to 1600")
    says("model.md", "**v0 → " + expr(f"2 * {v(1600)} - {v(800)}", ".3f")
         + " in/s, max y3 → " + expr(f"2 * {y(1600)} - {y(800)}", ".5f")
         + " in** (" + expr(f"2 * {y(1600)} - {y(800)}", ".6f")
         + "; the pairs 200/400 and 400/800 give "
         + expr(f"2 * {y(400)} - {y(200)}", ".6f") + " and "
         + expr(f"2 * {y(800)} - {y(400)}", ".6f") + ")")
    says("model.md", "At the listing's N = 4 the errors are "
         + expr(f"100 * ({v(4)} / (2 * {v(1600)} - {v(800)}) - 1)", "+.1f")
         + " % (v0) and "
         + expr(f"100 * ({y(4)} / (2 * {y(1600)} - {y(800)}) - 1)", "+.1f")
         + " % (max y3)")


def test_cowpers_kappa_is_cowpers():
    """Cowper (1966), J. Appl. Mech. 33, 335, Table 1: a rectangle's
    10(1 + nu)/(12 + 11 nu), 0.851 at nu = 0.33 (a formula with its
    source: the page states it as text)."""
    from contactsep.beams.member import cowper_kappa
    for nu in (0.0, 0.3, 0.33, 0.5):
        assert cowper_kappa(nu) == pytest.approx(10 * (1 + nu)
                                                 / (12 + 11 * nu), rel=1e-14)
    assert round(cowper_kappa(0.33), 3) == 0.851


@pytest.mark.parametrize("field, value, claim", [
    ("tau", 1e8, "the thesis design at τ = 10⁸ s gives status 4"),
    ("n_modes", 10_000, "gives status 4, and so does N = 10⁴")])
def test_the_searchs_limits_give_status_4(field, value, claim):
    says("model.md", claim)
    from contactsep.model import evaluate, status, thesis_design
    ev = evaluate(thesis_design(**{field: value}))
    assert int(np.ravel(ev.status)[0]) == status.UNRESOLVED
