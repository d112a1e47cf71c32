"""The numbers docs/studies.md's Table II section, docs/model.md's
search constants and the code facts the pages state come from the
committed data or from the code itself (see tests/project/
test_docs_pages.py for the figures and the convergence study)."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

import contactsep
from conftest import ROOT
from docs_text import STUDIES, role, rows, says, script_module

#: The page's model labels, as the CSV names them.
FIT_MODELS = {"Bernoulli–Euler clamped": "bernoulli-euler-clamped",
              "Timoshenko clamped": "timoshenko-clamped",
              "Timoshenko + k_r2": "timoshenko-kr2",
              "Timoshenko + k_r2, k_t2": "timoshenko-kr2-kt2",
              "Timoshenko + k_r2, mid-span mass2": "timoshenko-kr2-mass2"}
#: The five separators, as the columns name them.
SEPARATORS = ("0125", "0250", "0350", "0500", "0750")
NOTES = "studies/separator_notes.json"
LAST = "last-9000"


def fit_rows() -> dict:
    return {(r["model"], r["data"]): r for r in rows("separator-fit")}


def residuals(row) -> list[float]:
    return [float(row[k]) for k in row if k.startswith("res_")]


def notes_script():
    """docs/studies/make_separator_notes.py, loaded as a module."""
    return script_module(STUDIES / "make_separator_notes.py")


def committed_notes() -> dict:
    return json.loads((STUDIES / "separator_notes.json").read_text())


def note(key: str, fmt: str) -> str:
    """The datum role of one value of separator_notes.json."""
    return f"{{datum}}`{NOTES}:{key}:{fmt}`"


def fit_value(model: str, data: str, column: str) -> str:
    """An expression's value: COLUMN of the fit's separator-fit.csv row."""
    return f"[studies/separator-fit.csv:{column}@model={model},data={data}]"


def cells(model: str, data: str, fmt: str) -> str:
    return ", ".join(role("separator-fit", f"res_{k}_pct", fmt, model=model,
                          data=data) for k in SEPARATORS)


def test_the_separator_notes_are_what_the_script_computes():
    """docs/studies/separator_notes.json is what its script computes now
    (to 1e-10 relative; None where no clamp fits the row)."""
    def leaves(value, path=""):
        if isinstance(value, dict):
            for key, inner in value.items():
                yield from leaves(inner, f"{path}.{key}")
        else:
            yield path, value

    fresh = dict(leaves(json.loads(json.dumps(notes_script().notes()))))
    committed = dict(leaves(committed_notes()))
    assert fresh.keys() == committed.keys()
    for key, value in committed.items():
        if value is None:
            assert fresh[key] is None, key
        else:
            assert fresh[key] == pytest.approx(value, rel=1e-10), key


def test_the_separator_notes_are_the_studys():
    """The script's fitted parameters and bare separator are the study's
    (the CSV's parameters column and its '#' lines, a second
    computation of the same numbers)."""
    n = committed_notes()
    fits = fit_rows()
    for key, values in n["fits"].items():
        model = key.removesuffix("_last_9000").removesuffix("_printed")\
            .replace("_", "-")
        data = LAST if key.endswith("_last_9000") else "printed"
        text = fits[(model, data)]["parameters"]
        assert f"kr2={values['kr2']:.4g} lb in/rad" in text, (key, text)
        if "mass2_g" in values and "at its bound" not in text:
            assert f"({values['mass2_g']:.3g} g)" in text
    comments = contactsep.read(STUDIES / "separator-fit.csv").attrs[
        "comments"]
    for data, name in (("printed", "bare_printed"), (LAST, "bare_last_9000")):
        b = n[name]
        line = next(c for c in comments
                    if c.startswith(f"bare separator ({data} fit"))
        assert f"kr2 = {b['kr2']:.4g} lb in/rad" in line
        assert "f1 = " + ", ".join(f"{b[f'f1_{k}_cps']:.0f}" for k in
                                   SEPARATORS) + " cps" in line
        assert "L_c = " + ", ".join(f"{b[f'Lc_{k}_in']:.2f}" for k in
                                    SEPARATORS) + " in" in line
    t = n["table_i"]
    line = next(c for c in comments if c.startswith("Table I ("))
    for key, name in (("bernoulli_euler", "Bernoulli-Euler"),
                      ("timoshenko", "Timoshenko")):
        assert f"{name} " + ", ".join(f"{t[f'{key}_{k}_cps']:.2f}" for k in
                                      range(1, 5)) + " cps" in line
    assert f"({t['shift_min_pct']:.3f} to {t['shift_max_pct']:.3f} %)" \
        in line


def table_rows() -> list[str]:
    """The table's eight rows as the page writes them, each cell a datum
    of separator-fit.csv or separator_notes.json."""
    f = "fits.timoshenko_kr2"
    mass = f"{f}_mass2_last_9000"

    def row(label, model, data, parameters, rms_fmt, res_fmt, bold=""):
        rms = role("separator-fit", "rms_pct", rms_fmt, model=model,
                   data=data)
        shown = {"printed": "printed", LAST: "9,000"}[data]
        residual = "as k_r2 alone" if res_fmt is None else \
            cells(model, data, res_fmt)
        return (f"| {label} | {shown} | {parameters} | {bold}{rms} %{bold} "
                f"| {residual} |")

    labels = {model: label for label, model in FIT_MODELS.items()}
    stiffness = "{datum}`=[" + NOTES + f":{mass}.kr2] / 1e4:.2f`e4"
    return [
        row(labels["bernoulli-euler-clamped"], "bernoulli-euler-clamped",
            "printed", "—", ".0f", "+.0f"),
        row(labels["timoshenko-clamped"], "timoshenko-clamped", "printed",
            "—", ".0f", "+.0f"),
        row(labels["timoshenko-kr2"], "timoshenko-kr2", "printed",
            note(f"{f}_printed.kr2", ".0f") + " lb in/rad", ".1f", "+.1f"),
        row(labels["timoshenko-kr2"], "timoshenko-kr2", LAST,
            note(f"{f}_last_9000.kr2", ".0f") + " lb in/rad", ".1f",
            "+.1f"),
        row(labels["timoshenko-kr2-kt2"], "timoshenko-kr2-kt2", "printed",
            note(f"{f}_kt2_printed.kr2", ".0f") + "; k_t2 rigid (bound)",
            ".1f", None),
        row(labels["timoshenko-kr2-kt2"], "timoshenko-kr2-kt2", LAST,
            note(f"{f}_kt2_last_9000.kr2", ".0f") + " lb in/rad; {datum}`=["
            + NOTES + f":{f}_kt2_last_9000.kt2] / 1e6:.1f`e6 lb/in", ".1f",
            "+.1f"),
        row(labels["timoshenko-kr2-mass2"], "timoshenko-kr2-mass2",
            "printed", note(f"{f}_mass2_printed.kr2", ".0f")
            + "; mass → 0 (bound)", ".1f", None),
        row(labels["timoshenko-kr2-mass2"], "timoshenko-kr2-mass2", LAST,
            f"{stiffness} lb in/rad; " + note(f"{mass}.mass2", ".4f")
            + " lb = **" + note(f"{mass}.mass2_g", ".1f") + " g**", ".1f",
            "+.1f", bold="**")]


def test_the_separator_fit_table_is_separator_fit_csv():
    """Every cell of the table is a datum of separator-fit.csv or of
    separator_notes.json, in the row of its model and data; the two
    "as k_r2 alone" rows are (the data say so) the one-stiffness fit's,
    with the second parameter at its bound."""
    lines = [line.strip() for line in
             (ROOT / "docs" / "studies.md").read_text().splitlines()]
    for line in table_rows():
        assert line in lines, line
    fits = fit_rows()
    for model in ("timoshenko-kr2-kt2", "timoshenko-kr2-mass2"):
        np.testing.assert_allclose(
            residuals(fits[(model, "printed")]),
            residuals(fits[("timoshenko-kr2", "printed")]), atol=1e-4)
        assert "at its bound" in fits[(model, "printed")]["parameters"]


def within(fmt: str) -> str:
    """The sensor-mass fit's worst residual of rows 1-4, as a datum."""
    return "{datum}`=max(" + ", ".join(
        f"abs({fit_value('timoshenko-kr2-mass2', LAST, f'res_{k}_pct')})"
        for k in SEPARATORS[:4]) + f"):{fmt}`"


def over(function: str, model: str, ratio: bool = False) -> str:
    """min or max of the printed fit's five residuals, as a datum (as a
    ratio model/measured when ``ratio``)."""
    values = ", ".join(fit_value(model, "printed", f"res_{k}_pct")
                       for k in SEPARATORS)
    if ratio:
        return f"{{datum}}`=1 + {function}({values}) / 100:.1f`"
    return f"{{datum}}`={function}({values}):.0f`"


def test_the_separator_fit_prose_is_separator_fit_csv():
    """The section's prose shows the fits' numbers as data (a cell, or
    arithmetic on cells: a worst residual, the shear's lowering, a
    ratio); the analysis's numbers beside them stay text."""
    mass = "timoshenko-kr2-mass2"
    grams = "fits.timoshenko_kr2_mass2_last_9000.mass2_g"
    says("studies.md", f"A stiff clamp plus a {note(grams, '.0f')} g point "
         "mass at mid-span")
    says("studies.md", "k_r2 leaves " + "–".join(
        role("separator-fit", "rms_pct", ".0f", model="timoshenko-kr2",
             data=d) for d in (LAST, "printed")) + " % rms")
    says("studies.md", "no sensor mass and a soft clamp (" + note(
        "fits.timoshenko_kr2_mass2_printed.kr2", ".0f") + " lb in/rad)")
    says("studies.md", f"(rows 1–4 within {within('.2f')} %, the last "
         + role("separator-fit", "res_0750_pct", ".1f", model=mass,
                data=LAST) + " % against the analysis's −4.8 %, rms "
         + role("separator-fit", "rms_pct", ".1f", model=mass, data=LAST)
         + " % against 2.3 %, "
         + note("fits.timoshenko_kr2_mass2_last_9000.mass2_g", ".1f")
         + " g)")
    low, high = (role("separator-fit", "rms_pct", ".1f",
                      model="timoshenko-kr2", data=d)
                 for d in (LAST, "printed"))
    says("studies.md", f"the one-stiffness fit's rms is {low}–{high} % "
         "here")
    fits = fit_rows()
    one = [float(fits[("timoshenko-kr2", d)]["rms_pct"])
           for d in (LAST, "printed")]
    assert one[0] <= one[1]       # "low-high"

    def lowered(k, fmt):
        t, b = (fit_value(m, "printed", f"res_{k}_pct") for m in
                ("timoshenko-clamped", "bernoulli-euler-clamped"))
        return f"{{datum}}`=100 * (1 - (1 + {t} / 100) / (1 + {b} / 100))" \
            f":{fmt}`"

    says("studies.md", f"They lower the frequency by {lowered('0125', '.1f')}"
         f" % (d = 0.125) to {lowered('0750', '.0f')} % (d = 0.75)")
    says("studies.md", "the clamped Timoshenko separator is still "
         + over("min", "timoshenko-clamped") + "–"
         + over("max", "timoshenko-clamped") + " % above every measurement")
    says("studies.md", "were measured "
         + over("min", "bernoulli-euler-clamped", True) + "–"
         + over("max", "bernoulli-euler-clamped", True) + " times below")
    says("studies.md", f"fits rows 1–4 to {within('.1f')} %**")
    says("studies.md", "Against the printed 11,100 cps the same fitted "
         "model is {datum}`=100 * (1 - 9000 * (1 + "
         + fit_value(mass, LAST, "res_0750_pct") + " / 100) / 11100):.0f` "
         "% low in the last row")


def test_the_sensor_mass_fit_misses_the_last_row_as_the_analysis_did():
    """The data behind the page's last-row residual of the sensor-mass
    fit (9,000 cps version): low, within 0.5 % of the analysis's
    -4.8 %, and the fit's rms below every one-stiffness fit's."""
    fits = fit_rows()
    last = residuals(fits[("timoshenko-kr2-mass2", LAST)])[4]
    assert last < 0 and abs(last - (-4.8)) < 0.5, last
    mass_rms = float(fits[("timoshenko-kr2-mass2", LAST)]["rms_pct"])
    assert all(mass_rms < float(fits[("timoshenko-kr2", d)]["rms_pct"])
               for d in (LAST, "printed"))


def test_the_bare_separator_and_table_1_lines():
    """The bare separator's frequencies and lengths and Table I under
    both theories are data of separator_notes.json; the measured
    frequencies of Table I are the package's tables."""
    from contactsep.studies.tables import (TABLE_I_LOWER, TABLE_I_UPPER,
                                           TABLE_III_LC)
    says("studies.md", "in, beside Table III's " + ", ".join(
        f"{v:.2f}" for v in TABLE_III_LC) + ":")
    says("studies.md", "(k_r2 = {datum}`=[" + NOTES + ":bare_last_9000.kr2]"
         " / 1e4:.2f`e4 lb in/rad) its first frequencies are " + ", ".join(
             note(f"bare_last_9000.f1_{k}_cps", ".0f") for k in SEPARATORS)
         + " cps")
    for data in ("last_9000", "printed"):
        says("studies.md", ", ".join(note(f"bare_{data}.Lc_{k}_in", ".2f")
                                     for k in SEPARATORS) + " in")
    says("studies.md", "fit (k_r2 = " + note("bare_printed.kr2", ".0f")
         + ", no mass)")
    measured = " upper, ".join("/".join(f"{f:g}" for f in table) for table
                               in (TABLE_I_UPPER, TABLE_I_LOWER))
    says("studies.md", "lowers the first four frequencies by {datum}`=-["
         + NOTES + ":table_i.shift_max_pct]:.3f`–{datum}`=-[" + NOTES
         + ":table_i.shift_min_pct]:.2f` % only (" + ", ".join(
             note(f"table_i.timoshenko_{k}_cps", ".2f") for k in range(1, 5))
         + " cps against Bernoulli–Euler's " + ", ".join(
             note(f"table_i.bernoulli_euler_{k}_cps", ".2f")
             for k in range(1, 5)) + f"; measured {measured} lower): the "
         "contacts' " + note("table_i.gap_min_pct", ".0f") + "–"
         + note("table_i.gap_max_pct", ".0f") + " % gap")
    t = committed_notes()["table_i"]
    model = np.array([t[f"timoshenko_{k}_cps"] for k in range(1, 5)])
    gaps = 100 * (model / np.array([TABLE_I_UPPER, TABLE_I_LOWER]) - 1)
    np.testing.assert_allclose([gaps.min(), gaps.max()],
                               [t["gap_min_pct"], t["gap_max_pct"]],
                               rtol=1e-12)


def test_the_physical_separator_is_the_9000_fits_clamp():
    """--separator physical is the bare separator of the 9,000 cps fit,
    its clamp to the 3 digits the constant gives."""
    from contactsep.studies.thesis.separator_fit import PHYSICAL_SEPARATOR
    fitted = committed_notes()["bare_last_9000"]["kr2"]
    assert PHYSICAL_SEPARATOR["kr2"] == float(f"{fitted:.3g}")
    says("studies.md", "`beam2 = timoshenko`, `kr2` = {constant}`contactsep"
         ".studies.thesis.separator_fit.PHYSICAL_SEPARATOR[\"kr2\"]:sci`")


def test_cowpers_kappa_is_the_published_formula():
    """The page's ν and κ are the notes'; κ is Cowper's (1966)
    10 (1 + ν) / (12 + 11 ν) of a rectangle, and the study's '#' line
    gives the same."""
    nu, kappa = (committed_notes()["timoshenko"][k]
                 for k in ("nu", "cowper_kappa"))
    assert kappa == pytest.approx(10 * (1 + nu) / (12 + 11 * nu),
                                  rel=1e-15)
    comments = contactsep.read(STUDIES / "separator-fit.csv").attrs[
        "comments"]
    assert any(f"nu = {nu:g}, Cowper's kappa = {kappa:.4f}" in c
               for c in comments)
    says("studies.md", "Timoshenko with ν = " + note("timoshenko.nu", "g")
         + " and Cowper's κ = " + note("timoshenko.cowper_kappa", ".3f"))


def test_the_kappa_five_sixths_and_per_row_clamps():
    """The residuals with kappa = 5/6 are the earlier analysis's (to its
    digits); each row's own clamp stiffness (separator_notes.json, by
    scipy's root finder) puts the study's model on the measurement, and
    none does for d = 0.5; the page shows both from the data."""
    from contactsep.studies.thesis import separator_fit as sf
    n = committed_notes()
    kappa = [n["kappa_5_6"][f"res_{k}_pct"] for k in SEPARATORS]
    np.testing.assert_array_equal(np.round(kappa), [99, 89, 100, 107, 46])
    says("studies.md", "the clamped Timoshenko residuals are " + ", ".join(
        note(f"kappa_5_6.res_{k}_pct", "+.1f") for k in SEPARATORS) + " %")
    stiffness = [n["per_row"][f"kr2_{k}"] for k in SEPARATORS]
    assert stiffness[3] is None
    low, high = sf.BOUNDS["kr2"]
    for d, f, kr2 in zip(sf.TABLE_II_D, sf.TABLE_II_EXPERIMENTAL, stiffness):
        if kr2 is None:           # pinned (low) already too stiff
            assert sf.first_frequency(float(d), "timoshenko-kr2", (low,)) > f
            continue
        model = sf.first_frequency(float(d), "timoshenko-kr2",
                                   (float(np.log10(kr2)),))
        assert model == pytest.approx(f, rel=1e-6)
    three = ", ".join(note(f"per_row.kr2_{k}", ".0f")
                      for k in SEPARATORS[:3])
    last = "{datum}`=[" + NOTES + ":per_row.kr2_0750] / 1e5:.1f`e5"
    says("studies.md", f"the per-row clamp stiffnesses too ({three} lb "
         f"in/rad, none, {last} with Cowper's κ")
    says("studies.md", f"the stiffness scatters ({three} lb in/rad, none "
         f"for d = 0.5")
    says("studies.md", f"and {last}): that scatter")


def fortran_parameters() -> dict:
    """name -> value text of the extremes search's Fortran parameters."""
    found = {}
    for path in sorted((ROOT / "fortran" / "model").glob("extremes*.f90")):
        for name, value in re.findall(
                r"parameter(?:, public)? :: (\w+) = ([^\n!]+)",
                path.read_text()):
            found[name] = value.strip()
    return found


#: Superscript digits, for a power of two as the page writes one.
SUPERSCRIPT = str.maketrans("0123456789", "⁰¹²³⁴⁵⁶⁷⁸⁹")


def power_of_two(text: str) -> int:
    """The exponent of a Fortran power of two: "2_int64**31" -> 31."""
    (exponent,) = re.fullmatch(r"2(?:_int64|\.0_wp)?\*\*(\d+)",
                               text).groups()
    return int(exponent)


def two_to(exponent: int) -> str:
    return "2" + str(exponent).translate(SUPERSCRIPT)


def test_the_searchs_constants_are_the_fortrans():
    """The budgets and tolerances docs/model.md states are the Python
    search's constants (shown by the constant role), each equal to its
    parameter of fortran/model/extremes*.f90; the ones the Python side
    has no constant for are the Fortran's, as the page writes them."""
    from contactsep.model import twin_extremes as python
    from contactsep.model import twin_extremes_cells as cells
    f = fortran_parameters()
    module = "contactsep.model.twin_extremes"
    for name, value in (("WORK_BUDGET", python.WORK_BUDGET),
                        ("BLOCK_CELL_BUDGET", python.BLOCK_CELL_BUDGET),
                        ("CELL_BUDGET", python.CELL_BUDGET)):
        exponent = power_of_two(f[name.lower()])
        assert value == 2 ** exponent, name
        says("model.md", f"{{constant}}`{module}.{name}:,` "
             f"({two_to(exponent)})")
    assert python.TIE == float(f["tie"].removesuffix("_wp"))
    assert cells.CONVERGED == float(f["converged"].removesuffix("_wp"))
    assert cells.POLISH_STEPS == int(f["polish_steps"])
    assert cells.PHI_POLISH == float(f["phi_polish"].removesuffix("_wp"))
    says("model.md", f"cannot come within the tie ({{constant}}`{module}"
         f".TIE:sci` S) of the best value found is dropped; one whose "
         f"bound is within {{constant}}`{module}_cells.CONVERGED:sci` S "
         f"of a value it holds is finished")
    says("model.md", f"Cells with p_max r ≤ {{constant}}`{module}_cells."
         f"PHI_POLISH:g` (every mode low) are first polished ({{constant}}"
         f"`{module}_cells.POLISH_STEPS:words` Newton steps")
    says("model.md", f"when p_max τ ≥ {two_to(power_of_two(f['two_52']))} "
         "rad")
    modes, size = int(f["block_modes"]), int(f["block_size"])
    says("model.md", f"blocks of about {modes} modes ({min(size, modes // 4)}"
         f" designs of 4 modes, {modes // 32} of 32; 8 to {size} designs)")
    # the sine's Taylor series: each factor 1/((2k)(2k+1)) one more term
    bounds = (ROOT / "fortran" / "model" / "extremes_bounds.f90").read_text()
    factors = int(re.search(r"inv_sin\((\d+)\)", bounds).group(1))
    says("model.md", "Taylor series of the small angles, to x"
         + str(2 * factors + 1).translate(SUPERSCRIPT) + ")")


def listing_script():
    """docs/studies/make_listing_difference.py, loaded as a module."""
    return script_module(STUDIES / "make_listing_difference.py")


def test_the_listings_difference():
    """"not to 1e-8 but to 3.5e-5": the listing integrates the deck's
    9-decimal mode function; the worst ratio of its impact sum to the
    exact one over the thesis decks (the reference's two closed forms,
    independent of the model) is docs/studies/listing_difference.json,
    what its script computes now over every thesis deck, and the page
    shows it."""
    from conftest import THESIS_DECKS
    committed = json.loads((STUDIES / "listing_difference.json")
                           .read_text())
    fresh = listing_script().difference()
    assert fresh["decks"] == committed["decks"] == len(THESIS_DECKS)
    assert fresh["worst_ratio_minus_1"] == pytest.approx(
        committed["worst_ratio_minus_1"], rel=1e-10)
    assert 1e-8 < committed["worst_ratio_minus_1"] < 1e-4
    says("model.md", "not to 1e-8 but to {datum}`=[studies/listing_"
         "difference.json:worst_ratio_minus_1] / 1e-5:.1f`e-5,")


def shortest(number: float) -> str:
    """A number as the page writes it: 8e-4, 500, 3.9e-8, 37.9."""
    mantissa, _, exponent = f"{number:.15e}".partition("e")
    power = f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"
    plain = f"{number:.15g}"
    return power if "e" in plain or len(power) < len(plain) else plain


def test_the_domains_symmetry_corners_are_the_tests():
    """model.md's ranges of the exact symmetries are the corners
    tests/hostile/test_domain.py checks (its CORNERS, written as the
    page writes them)."""
    import math
    module = script_module(ROOT / "tests" / "hostile" / "test_domain.py")

    def extremes(name):
        values = [c[name] for c in module.CORNERS if name in c]
        return min(values), max(values)

    (lam, lam_high), (kappa, kappa_high), (sigma, sigma_high) = (
        extremes(name) for name in ("lam", "kappa", "sigma"))
    mu, mu_high = extremes("mu")
    says("model.md", f"every length times λ ({shortest(lam)} to "
         f"{shortest(lam_high)}), E and γ times κ ({shortest(kappa)} to "
         f"{shortest(kappa_high)}), E times μ² with τ / μ (μ from "
         f"10^{math.log10(mu):g} to {mu_high:g}), y_s times σ "
         f"({shortest(sigma)} to {shortest(sigma_high)})")


def test_the_fe_tolerances_are_the_tests():
    """The page's FE tolerances are the thresholds the tests assert."""
    source = (ROOT / "tests" / "shared" / "test_beams_timoshenko.py"
              ).read_text()
    three, six = (re.search(pattern, source).group(1) for pattern in (
        r"\[:3\] < ([\d.e-]+)\)", r"exact - 1\.0\) < ([\d.e-]+)\)"))
    says("model.md", f"first three modes to {three}, six to {six},")


def test_the_simulation_counts_of_the_long_studies():
    """The commands' "# N simulations" (a code block, where no role
    reaches): the chatter table's rows and the count the preload
    chart's notes give."""
    notes = contactsep.read(STUDIES / "preload.csv").attrs["comments"]
    (chart,) = (int(n.split()[0]) for n in notes
                if re.fullmatch(r"\d+ simulations", n))
    says("studies.md", "contactsep study chatter --out docs/studies # "
         f"{len(rows('chatter'))} simulations contactsep study preload "
         f"--converge --out docs/studies # {chart} simulations")
    says("studies.md", "Not a batch of eq. 23 but "
         + role("chatter", "rows", None) + " three-beam simulations")


def test_a_converted_value_as_the_page_says():
    """"a converted value is rounded to 15 significant digits (`10us` is
    exactly 1e-05 s)": the page says so and the code does so."""
    pytest.importorskip("pint")
    from contactsep import units
    says("names-and-units.md", "a converted value is rounded to 15 "
         "significant digits (`10us` is exactly 1e-05 s)")
    assert units.convert("10us", "s", "--min-open") == 1e-05
    inches = units.convert("30.5mm", "in", "--L1")
    assert inches == float(f"{30.5 / 25.4:.15g}")
