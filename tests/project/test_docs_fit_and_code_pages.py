"""The numbers docs/studies.md's Table II section, docs/model.md's
search constants and the code facts the pages state come from the
committed CSVs or from the code itself (see tests/project/
test_docs_pages.py for the figures and the convergence study)."""

from __future__ import annotations

import re

import numpy as np
import pytest

import contactsep
from conftest import ROOT
from docs_text import (NUMBER, STUDIES, check, printed, quoted, role, rows,
                       says)



#: The page's model labels and data versions, as the CSV names them.
FIT_MODELS = {"Bernoulli–Euler clamped": "bernoulli-euler-clamped",
              "Timoshenko clamped": "timoshenko-clamped",
              "Timoshenko + k_r2": "timoshenko-kr2",
              "Timoshenko + k_r2, k_t2": "timoshenko-kr2-kt2",
              "Timoshenko + k_r2, mid-span mass2": "timoshenko-kr2-mass2"}
FIT_DATA = {"printed": "printed", "9,000": "last-9000"}


def fit_rows() -> dict:
    return {(r["model"], r["data"]): r for r in rows("separator-fit")}


def residuals(row) -> list[float]:
    return [float(row[k]) for k in row if k.startswith("res_")]


def test_the_separator_fit_table_is_separator_fit_csv():
    text = (ROOT / "docs" / "studies.md").read_text()
    fits = fit_rows()
    seen = set()
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 5 or cells[0] not in FIT_MODELS:
            continue
        row = fits[(FIT_MODELS[cells[0]], FIT_DATA[cells[1]])]
        seen.add((row["model"], row["data"]))
        rms = cells[3].strip("*").removesuffix(" %").strip("*")
        check([rms], [float(row["rms_pct"])])
        if cells[4] == "as k_r2 alone":
            alone = fits[("timoshenko-kr2", row["data"])]
            np.testing.assert_allclose(residuals(row), residuals(alone),
                                       atol=1e-4)
        else:
            claims = cells[4].replace("−", "-").split(", ")
            check(claims, residuals(row))
        # the fitted parameters, to the digits the page gives
        for claim in re.findall(r"(\d[\d.e]*) (?:lb in/rad|lb/in)",
                                cells[2].replace("**", "")):
            found = [float(x) for x in re.findall(
                r"=([\d.e+]+) lb", row["parameters"])]
            assert any(printed(x, claim) for x in found), (claim, row)
    assert len(seen) == 8


def test_the_separator_fit_prose_is_separator_fit_csv():
    fits = fit_rows()
    mass = fits[("timoshenko-kr2-mass2", "last-9000")]
    rms = re.escape(role("separator-fit", "rms_pct", ".1f",
                         model="timoshenko-kr2-mass2", data="last-9000"))
    last = re.escape(role("separator-fit", "res_0750_pct", ".1f",
                          model="timoshenko-kr2-mass2", data="last-9000"))
    within, grams = quoted(
        "studies.md", rf"\(rows 1–4 within {NUMBER} %, the last {last} "
        rf"% against the analysis's −4.8 %, rms {rms} % against 2.3 %, "
        rf"{NUMBER} g\)")
    res = residuals(mass)
    check([within], [max(abs(r) for r in res[:4])])
    check([grams], [float(re.search(r"\(([\d.]+) g\)",
                                    mass["parameters"]).group(1))])
    low, high = (role("separator-fit", "rms_pct", ".1f",
                      model="timoshenko-kr2", data=d)
                 for d in ("last-9000", "printed"))
    says("studies.md", f"the one-stiffness fit's rms is {low}–{high} % "
         "here")
    one = [float(fits[("timoshenko-kr2", d)]["rms_pct"])
           for d in ("last-9000", "printed")]
    assert one[0] <= one[1]       # "low-high"
    thin, thick, over_low, over_high = quoted(
        "studies.md", rf"They lower the frequency by {NUMBER} % \(d = "
        rf"0.125\) to {NUMBER} % \(d = 0.75\).*?the clamped Timoshenko "
        rf"separator is still {NUMBER}–{NUMBER} % above every measurement")
    bernoulli = np.array(residuals(fits[("bernoulli-euler-clamped",
                                         "printed")]))
    timoshenko = np.array(residuals(fits[("timoshenko-clamped",
                                          "printed")]))
    lowered = 100 * (1 - (1 + timoshenko / 100) / (1 + bernoulli / 100))
    check([thin, thick], [lowered[0], lowered[-1]])
    check([over_low, over_high], [timoshenko.min(), timoshenko.max()])
    (fits_to,) = quoted("studies.md", rf"fits rows 1–4 to {NUMBER} %\*\*")
    check([fits_to], [max(abs(r) for r in res[:4])])
    (off,) = quoted("studies.md", rf"Against the printed 11,100 cps the "
                    rf"same fitted model is {NUMBER} % low in the last row")
    model_cps = 9000 * (1 + res[4] / 100)
    check([off], [100 * (1 - model_cps / 11100)])


def test_the_sensor_mass_fit_misses_the_last_row_as_the_analysis_did():
    """The data behind the page's last-row residual of the sensor-mass
    fit (9,000 cps version): low, within 0.5 % of the analysis's
    -4.8 %, and the fit's rms below every one-stiffness fit's."""
    fits = fit_rows()
    last = residuals(fits[("timoshenko-kr2-mass2", "last-9000")])[4]
    assert last < 0 and abs(last - (-4.8)) < 0.5, last
    mass_rms = float(fits[("timoshenko-kr2-mass2", "last-9000")]["rms_pct"])
    assert all(mass_rms < float(fits[("timoshenko-kr2", d)]["rms_pct"])
               for d in ("last-9000", "printed"))


def test_the_bare_separator_and_table_1_lines():
    """The study's notes (the committed CSV's '#' lines) carry the bare
    separator's L_c and the Timoshenko contacts; the page quotes them."""
    notes = contactsep.read(STUDIES / "separator-fit.csv").attrs["comments"]
    bare = next(n for n in notes if n.startswith("bare separator (printed"))
    lengths = quoted("studies.md", rf"no mass\) they are {NUMBER}, "
                     rf"{NUMBER}, {NUMBER}, {NUMBER}, {NUMBER} in\.")
    assert "L_c = " + ", ".join(lengths) + " in" in bare
    table1 = next(n for n in notes if n.startswith("Table I ("))
    lowest, highest, *cps = quoted(
        "studies.md", rf"Timoshenko lowers the first four frequencies by "
        rf"{NUMBER}–{NUMBER} % only \({NUMBER}, {NUMBER}, {NUMBER}, "
        rf"{NUMBER} cps against Bernoulli–Euler's {NUMBER}, {NUMBER}, "
        rf"{NUMBER}, {NUMBER}; measured ([\d./]+) upper, ([\d./]+) lower\): "
        rf"the contacts' {NUMBER}–{NUMBER} % gap")
    timoshenko = ", ".join(cps[:4])
    bernoulli = ", ".join(cps[4:8])
    assert f"Timoshenko {timoshenko} cps" in table1
    assert f"Bernoulli-Euler {bernoulli} cps" in table1
    assert f"measured upper {cps[8]}, lower {cps[9]}" in table1
    change = re.search(r"\(-([\d.]+) to -([\d.]+) %\)", table1).groups()
    check([lowest, highest], [float(change[1]), float(change[0])])
    model = np.array([float(x) for x in cps[:4]])
    measured = np.array([[float(x) for x in cps[k].split("/")]
                         for k in (8, 9)])
    gaps = 100 * (model / measured - 1)
    check(cps[10:], [gaps.min(), gaps.max()])


def test_the_bare_separator_of_the_9000_fit_and_its_clamp():
    notes = contactsep.read(STUDIES / "separator-fit.csv").attrs["comments"]
    bare = next(n for n in notes if n.startswith("bare separator "
                                                 "(last-9000"))
    kr2, *numbers = quoted(
        "studies.md", rf"9,000 cps fit \(k_r2 = {NUMBER} lb in/rad\) its "
        rf"first frequencies are {NUMBER}, {NUMBER}, {NUMBER}, {NUMBER}, "
        rf"{NUMBER} cps and its equivalent lengths .*? {NUMBER}, "
        rf"{NUMBER}, {NUMBER}, {NUMBER}, {NUMBER} in, beside Table III's")
    assert "f1 = " + ", ".join(numbers[:5]) + " cps" in bare
    assert "L_c = " + ", ".join(numbers[5:]) + " in" in bare
    fitted = float(re.search(r"kr2 = ([\d.e+]+)", bare).group(1))
    check([kr2], [fitted])
    # --separator physical is that clamp
    from contactsep.studies.thesis.separator_fit import PHYSICAL_SEPARATOR
    (physical,) = quoted("studies.md", rf"`beam2 = timoshenko`, "
                         rf"`kr2 = {NUMBER}`")
    check([physical], [PHYSICAL_SEPARATOR["kr2"]])
    check([physical], [fitted])
    # "measured 2.0-2.6 times below the clamped Bernoulli-Euler theory"
    low, high = quoted("studies.md", rf"were measured {NUMBER}–{NUMBER} "
                       rf"times below the thesis's clamped Bernoulli–Euler "
                       rf"theory")
    ratio = 1 + np.array(residuals(fit_rows()[("bernoulli-euler-clamped",
                                                "printed")])) / 100
    check([low, high], [ratio.min(), ratio.max()])


def fortran_parameters() -> dict:
    """name -> value text of the extremes search's Fortran parameters."""
    found = {}
    for path in sorted((ROOT / "fortran" / "model").glob("extremes*.f90")):
        for name, value in re.findall(
                r"parameter(?:, public)? :: (\w+) = ([^\n!]+)",
                path.read_text()):
            found[name] = value.strip()
    return found


SUPERSCRIPT = str.maketrans("⁰¹²³⁴⁵⁶⁷⁸⁹", "0123456789")
#: An exponent written in superscript digits.
POWER = "([⁰¹²³⁴⁵⁶⁷⁸⁹]+)"


def test_the_searchs_constants_are_the_fortrans():
    """The budgets and tolerances docs/model.md states are the
    parameters of fortran/model/extremes*.f90."""
    f = fortran_parameters()

    def power(text):                  # "2_int64**31" -> 2**31
        (exponent,) = re.fullmatch(r"2(?:_int64|\.0_wp)?\*\*(\d+)",
                                   text).groups()
        return 2 ** int(exponent)

    work, turns = quoted("model.md", rf"gives up after 2{POWER} cell-mode "
                         rf"evaluations .*? when p_max τ ≥ 2{POWER} rad")
    assert 2 ** int(work.translate(SUPERSCRIPT)) == power(f["work_budget"])
    assert 2 ** int(turns.translate(SUPERSCRIPT)) == power(f["two_52"])
    modes, designs, fewest, most, block, segment = quoted(
        "model.md", r"blocks of about (\d+) modes \((\d+) designs of 4 "
        r"modes, 16 of 32; (\d+) to (\d+) designs\), each with at most "
        rf"2{POWER} live cell-modes.*?more than 2{POWER} live cell-modes")
    assert int(modes) == int(f["block_modes"])
    assert int(designs) == min(int(f["block_size"]), int(modes) // 4)
    assert (int(fewest), int(most)) == (8, int(f["block_size"]))
    assert 2 ** int(block.translate(SUPERSCRIPT)) == power(
        f["block_cell_budget"])
    assert 2 ** int(segment.translate(SUPERSCRIPT)) == power(
        f["cell_budget"])
    tie, finished = quoted("model.md", r"cannot come within the tie "
                           r"\(([\d.e-]+) S\) of the best value found is "
                           r"dropped; one whose bound is within ([\d.e-]+) "
                           r"S of a value it holds is finished")
    assert float(tie) == float(f["tie"].removesuffix("_wp"))
    assert float(finished) == float(f["converged"].removesuffix("_wp"))
    steps, order = quoted("model.md", rf"first polished \((\w+) Newton "
                          rf"steps .*? to x{POWER}\)")
    words = {"two": 2, "three": 3, "four": 4}
    assert words[steps] == int(f["polish_steps"])
    # the sine's Taylor series: each factor 1/((2k)(2k+1)) one more term
    bounds = (ROOT / "fortran" / "model" / "extremes_bounds.f90").read_text()
    factors = int(re.search(r"inv_sin\((\d+)\)", bounds).group(1))
    assert int(order.translate(SUPERSCRIPT)) == 2 * factors + 1


def test_the_listings_difference():
    """"not to 1e-8 but to 3.5e-5": the listing integrates the deck's
    9-decimal mode function; the worst ratio of its impact sum to the
    exact one over the thesis decks (the reference's two closed forms,
    independent of the model)."""
    from conftest import THESIS_DECKS
    from contactsep.restored import reference
    (claim,) = quoted("model.md", rf"not to 1e-8 but to {NUMBER},")
    worst = 0.0
    for deck in THESIS_DECKS:
        for r in contactsep.replay(deck, precision="double"):
            ds = r.inputs
            p = reference.frequencies(ds)[0]
            ratio = np.sum(p * ds.c * reference.initial_amplitudes(
                ds, "closed-form")) / np.sum(p * ds.c * reference
                                             .initial_amplitudes(
                                                 ds, "exact-mode"))
            worst = max(worst, abs(ratio - 1))
    check([claim], [worst])


def test_the_domains_symmetry_corners_are_the_tests():
    """model.md's ranges of the exact symmetries are the corners
    tests/hostile/test_domain.py checks."""
    import importlib.util
    path = ROOT / "tests" / "hostile" / "test_domain.py"
    spec = importlib.util.spec_from_file_location("_domain_corners", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    lam, kappa, mu, sigma = (quoted("model.md", pattern) for pattern in (
        rf"every length times λ \({NUMBER} to {NUMBER}\)",
        rf"E and γ times κ \({NUMBER} to {NUMBER}\)",
        r"\(μ from 10\^([-\d.]+) to (\d+)\)",
        rf"y_s times σ \({NUMBER} to {NUMBER}\)"))
    for name, (low, high) in (("lam", lam), ("kappa", kappa),
                              ("sigma", sigma)):
        values = [c[name] for c in module.CORNERS if name in c]
        assert (min(values), max(values)) == (float(low), float(high))
    values = [c["mu"] for c in module.CORNERS if "mu" in c]
    assert (min(values), max(values)) == (10 ** float(mu[0]), float(mu[1]))


def test_the_fe_tolerances_are_the_tests():
    three, six = quoted("model.md", r"first three modes to ([\d.e-]+), six "
                        r"to ([\d.e-]+),")
    source = (ROOT / "tests" / "shared" / "test_beams_timoshenko.py"
              ).read_text()
    assert f"[:3] < {three})" in source and f"< {six})" in source


def test_the_simulation_counts_of_the_long_studies():
    """"study chatter ... # 45 simulations", "study preload --converge ...
    # 2353 simulations": the chatter table's rows, the preload chart's count."""
    chatter, chart = quoted("studies.md", r"contactsep study chatter --out "
                            r"docs/studies # (\d+) simulations.*?contactsep "
                            r"study preload --converge --out docs/studies # (\d+) "
                            r"simulations")
    assert int(chatter) == len(rows("chatter"))
    notes = contactsep.read(STUDIES / "preload.csv").attrs["comments"]
    assert f"{chart} simulations" in notes
    says("studies.md", "Not a batch of eq. 23 but "
         + role("chatter", "rows", None) + " three-beam simulations")


def test_the_kappa_five_sixths_and_per_row_clamps():
    """"with kappa = 5/6 the clamped Timoshenko residuals are +98.6, ...
    %" and the per-row clamp stiffnesses "(233, 2157, 1310 lb in/rad,
    none, 1.0e5 with Cowper's kappa ...)": recomputed, each row's
    stiffness by scipy's root finder on the study's separator."""
    import dataclasses

    from scipy.optimize import brentq

    from contactsep.studies.thesis import separator_fit as sf
    def first(d, kappa=None, kr2=None):
        beam = sf.separator(d, "timoshenko-clamped",
                            {} if kr2 is None else {"kr2": kr2})
        beam = dataclasses.replace(beam, kappa=kappa)
        return float(sf.modal_model(beam, 1, [beam.length / 2]).f_hz[0])

    claims = quoted("studies.md", rf"with κ = 5/6 the clamped Timoshenko "
                    rf"residuals are {NUMBER}, {NUMBER}, {NUMBER}, "
                    rf"{NUMBER}, {NUMBER} %")
    check(claims, [100 * (first(d, 5 / 6) / f - 1) for d, f in
                   zip(sf.TABLE_II_D, sf.TABLE_II_EXPERIMENTAL)])
    stiffness = []
    for d, f in zip(sf.TABLE_II_D, sf.TABLE_II_EXPERIMENTAL):
        def gap(log_kr, d=d, f=f):
            return first(d, None, 10.0 ** log_kr) / f - 1

        soft, stiff = gap(sf.BOUNDS["kr2"][0]), gap(sf.BOUNDS["kr2"][1])
        stiffness.append(None if soft * stiff > 0 else 10.0 ** brentq(
            gap, *sf.BOUNDS["kr2"], xtol=1e-8))
    rows = quoted("studies.md", rf"the per-row clamp stiffnesses too "
                  rf"\({NUMBER}, ([\d,]+), {NUMBER} lb in/rad, none, "
                  rf"{NUMBER} with Cowper's κ")
    assert stiffness[3] is None
    check([rows[0], rows[1], rows[2], rows[3]],
          [stiffness[0], stiffness[1], stiffness[2], stiffness[4]])
    again = quoted("studies.md", rf"the stiffness scatters \({NUMBER}, "
                   rf"{NUMBER}, {NUMBER} lb in/rad, none for d = 0.5")
    for claim, value in zip(again, stiffness):
        assert float(f"{value:.3g}") == float(claim), (claim, value)


def test_a_converted_value_as_the_page_says():
    """"a converted value is rounded to 15 significant digits (`10us` is
    exactly 1e-05 s)"."""
    pytest.importorskip("pint")
    from contactsep import units
    digits, typed, exact = quoted(
        "names-and-units.md", r"a converted value is rounded to (\d+) "
        r"significant digits \(`(\w+)` is exactly ([\d.e-]+) s\)")
    assert units.convert(typed, "s", "--min-open") == float(exact)
    inches = units.convert("30.5mm", "in", "--L1")
    assert inches == float(f"{30.5 / 25.4:.{digits}g}")
