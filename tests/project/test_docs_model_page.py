"""docs/model.md's remaining numbers (issue 30, item 8), beside
test_docs_pages.py.  The computed ones (the domain table's limits in
other units, the round-off of a mode near a clamp, the deck's alpha
sensitivity) are ``datum`` roles of docs/studies/model_numbers.json:
the file is checked against its command, and its numbers against
independent values (published material constants with pint, mpmath,
the restored reference).  The counts of tests the page describes are
still found by the sentence that quotes them and read from the tests
themselves; a reworded sentence fails."""

from __future__ import annotations

import dataclasses
import json
import re

import numpy as np
import pytest
from docs_text import quoted, says, script_module

import contactsep
from conftest import ROOT, THESIS_DECKS
from contactsep.model import compiled
from contactsep.model import design_domain as design_module

pint = pytest.importorskip("pint")
UNITS = pint.UnitRegistry()


MODEL_NUMBERS = ROOT / "docs" / "studies" / "model_numbers.json"


def _model_numbers() -> dict:
    return json.loads(MODEL_NUMBERS.read_text())


def _datum(path: str, fmt: str) -> str:
    return f"{{datum}}`studies/model_numbers.json:{path}:{fmt}`"


def _make_model_numbers():
    return script_module(ROOT / "docs" / "studies" / "make_model_numbers.py")


def test_the_model_numbers_are_what_their_command_prints():
    """docs/studies/model_numbers.json is what `python
    docs/studies/make_model_numbers.py` prints now: the domain's
    conversions and the deck's alpha move to 1e-10 relative (the move is
    a difference of two near amplitudes: 1e-8), the round-off at a clamp
    (itself round-off, so not reproducible to more) to the digit the
    page shows."""
    committed, now = _model_numbers(), _make_model_numbers().main()
    assert set(committed) == set(now)
    assert committed["domain"].keys() == now["domain"].keys()
    for key, value in now["domain"].items():
        assert committed["domain"][key] == pytest.approx(value, rel=1e-10)
    assert committed["deck_alpha"]["deck"] == now["deck_alpha"]["deck"]
    assert committed["deck_alpha"]["change"] == now["deck_alpha"]["change"]
    assert committed["deck_alpha"]["a3_relative_move"] == pytest.approx(
        now["deck_alpha"]["a3_relative_move"], rel=1e-8)
    assert f"{committed['clamp_roundoff']:.0e}" == \
        f"{now['clamp_roundoff']:.0e}"


def test_the_domain_tables_limits_in_other_units():
    """The domain table's limits are the code's own (``constant`` roles,
    tests/project/test_code_constants.py); what the table says they are
    in other units and against published materials (the committed
    model_numbers.json's, shown by ``datum`` roles) is checked here
    against pint."""
    domain = _model_numbers()["domain"]
    says("model.md", f"{_datum('domain.size_min_um', '.2g')} µm to "
         "{datum}`=round([studies/model_numbers.json:domain.size_max_ft], "
         "-1):.0f` ft:")
    micro = (design_module.SIZE_RANGE[0] * UNITS.inch).to("um").magnitude
    feet = (design_module.SIZE_RANGE[1] * UNITS.inch).to("ft").magnitude
    assert domain["size_min_um"] == pytest.approx(micro, rel=1e-12)
    assert domain["size_max_ft"] == pytest.approx(feet, rel=1e-12)
    says("model.md", "aerogel to "
         f"{_datum('domain.density_max_over_osmium', '.0f')} times osmium; "
         "aluminium's {datum}`=round([studies/model_numbers.json:domain."
         "aluminium_lb_ft3], -1):.0f` lb/ft³ typed as lb/in³ is refused")
    high = design_module.DENSITY_RANGE[1]
    # osmium 22.59 g/cm^3, aluminium 2.70 g/cm^3 (CRC Handbook)
    osmium = (22.59 * UNITS("g/cm^3")).to("lb/in^3").magnitude
    assert domain["density_max_over_osmium"] == pytest.approx(
        high / osmium, rel=1e-9)
    aluminium = (2.70 * UNITS("g/cm^3")).to("lb/ft^3").magnitude
    assert domain["aluminium_lb_ft3"] == pytest.approx(aluminium, rel=1e-9)
    assert round(domain["aluminium_lb_ft3"], -1) > high
    says("model.md", "the softest rubber to "
         f"{_datum('domain.modulus_max_over_diamond', '.0f')} times diamond")
    # diamond's Young's modulus: 1050-1220 GPa in the literature
    top = (design_module.MODULUS_RANGE[1] * UNITS.psi).to("GPa").magnitude
    shown = float(f"{domain['modulus_max_over_diamond']:.0f}")
    assert top / 1220 <= shown <= top / 1050
    assert domain["modulus_max_over_diamond"] == pytest.approx(
        top / 1220, rel=1e-6)
    assert design_module.DEFLECTION_RANGE[1] == 1.0    # "≤ L1"


def test_a_mode_near_a_clamp_against_mpmath():
    """The round-off at the limit, 'measured against mpmath' (the
    committed model_numbers.json's, its own 120-digit solve): the
    compiled mode values at SUPPORT_CLEARANCE from each clamped end
    (every end condition with a clamp, N = 32) against the tests'
    independent 120-digit mpmath, to the digit the page shows."""
    pytest.importorskip("mpmath")
    module = script_module(ROOT / "tests" / "model" /
                           "test_model_compiled_cases.py")
    _mp_modes = module._mp_modes      # 120-digit roots and mode values
    says("model.md", "1e-16/(x/L)² relative round-off ("
         f"{_datum('clamp_roundoff', '.0sci')} at the limit, measured "
         "against mpmath)")
    claim = _model_numbers()["clamp_roundoff"]
    clear = design_module.SUPPORT_CLEARANCE
    worst = 0.0
    for end in (1, 2, 3):             # clamped-free, -clamped, -pinned
        xi = [clear, 1.0 - clear] if end == 2 else [clear]
        _, want = _mp_modes(end, 32, xi)
        _, got = compiled.mode_values(end, 32, xi)
        worst = max(worst, float(np.max(np.abs(got - want) / np.abs(want))))
    assert f"{worst:.0e}" == f"{claim:.0e}", (worst, claim)
    assert worst < 1e-16 / clear**2        # the page's estimate bounds it


def test_the_decks_alpha_moves_a3():
    """'A_3 moves by ~4e-5 for a 5e-10 change of alpha_3' (the committed
    model_numbers.json's): the restored reference's closed form on a
    thesis deck, alpha_3 moved by the committed change."""
    from contactsep.restored import reference
    says("model.md", "A_3 moves by ~"
         f"{_datum('deck_alpha.a3_relative_move', '.0sci')} for a "
         f"{_datum('deck_alpha.change', '.0sci')} change of alpha_3")
    committed = _model_numbers()["deck_alpha"]
    assert committed["deck"] == THESIS_DECKS[0].name
    ds = contactsep.replay(THESIS_DECKS[0], precision="double")[0].inputs
    before = reference.initial_amplitudes(ds, "closed-form")[2]
    alpha = np.array(ds.alpha, dtype=np.float64)
    alpha[2] += committed["change"]
    after = reference.initial_amplitudes(
        dataclasses.replace(ds, alpha=type(ds.alpha)(alpha) if
                            isinstance(ds.alpha, tuple) else alpha),
        "closed-form")[2]
    assert abs(after / before - 1) == pytest.approx(
        committed["a3_relative_move"], rel=1e-8)


def test_the_extremes_tests_are_as_described():
    """The counts docs/model.md gives of tests/model/test_model_extremes.py
    are that file's."""
    source = (ROOT / "tests" / "model" / "test_model_extremes.py") \
        .read_text()
    default, slow = quoted("model.md", r"within 1e-12 S on (\d+) random "
                           r"designs in one test and (\d+) in another")
    assert f"random_cases({default}, seed=1" in source
    assert re.search(rf"def \w+\(\):\s+\"\"\"[^\"]*"
                     rf"\"\"\"\s+design = random_cases\({slow}, ", source)
    low, high = quoted("model.md", r"every end condition, contact points, "
                       r"lengths, thicknesses, materials, N (\d+)–(\d+), τ "
                       r"up to 1 s\)")
    assert low == "1" and f"math.log({high}.49)" in source
    assert "tau = np.exp(u(math.log(1e-3), 0.0))" in source   # to 1 s
    n_low, n_high, taus = quoted("model.md", r"on the thesis design for "
                                 r"N = (\d+)–(\d+) and τ = ([\d., and]+) s,")
    ns = re.search(r"parametrize\(\"n\", \[([\d, ]+)\]\)", source).group(1)
    ns = [int(n) for n in ns.split(",")]
    assert (min(ns), max(ns)) == (int(n_low), int(n_high))
    listed = [float(t) for t in re.split(r", | and ", taus.strip())]
    written = re.search(r"parametrize\(\"tau\", \[([\d., ]+)\]\)",
                        source).group(1)
    assert listed == [float(t) for t in written.split(",")]


def test_the_beam_and_energy_tests_are_as_described():
    """'Romberg from 16, 32, 64 elements ... for four end conditions',
    '30-digit mpmath', 'at N = 4 and 32 ... modal sums at N = 400': the
    tests' own meshes, precision and parameters."""
    from contactsep import beams
    tests = ROOT / "tests"
    coarse, middle, fine, ends = quoted(
        "model.md", r"Romberg from (\d+), (\d+), (\d+) elements: first three "
        r"modes to [\d.e-]+, six to [\d.e-]+, for (\w+) end conditions")
    fe_beam = (tests / "shared" / "fe_beam.py").read_text()
    assert f"def converged(end, count, elements={coarse}," in fe_beam
    assert "for k in range(3)" in fe_beam              # n, 2n and 4n
    assert [int(middle), int(fine)] == [2 * int(coarse), 4 * int(coarse)]
    timoshenko = (tests / "shared" / "test_beams_timoshenko.py").read_text()
    assert "@pytest.mark.parametrize(\"end\", beams.END_CONDITIONS)\n" \
        "def test_frequencies_match_a_converged_finite_element_beam" in \
        timoshenko
    assert {"four": 4}[ends] == len(beams.END_CONDITIONS)
    (digits,) = quoted("model.md", r"frequency equation in (\d+)-digit "
                       r"mpmath")
    assert f"mpmath.mp.dps = {digits}" in timoshenko
    low, high, big = quoted("model.md", r"default never does on the family "
                            r"at N = (\d+) and (\d+), and the bound's "
                            r"flexibilities against the modal sums at "
                            r"N = (\d+)\.")
    numerics = (tests / "chatter" / "test_numerics.py").read_text()
    assert f"@pytest.mark.parametrize(\"n\", [{low}, {high}])\n" \
        "def test_the_default_lower_response_stays_within" in numerics
    assert f"design.replace(n_modes={big})" in numerics


def test_the_extremum_references_grid():
    """'a grid of 1/40 of the shortest period': tests/extremum_reference.py's
    POINTS_PER_PERIOD."""
    (points,) = quoted("model.md", r"sign changes of y3' on a grid of "
                       r"1/(\d+) of the shortest period")
    source = (ROOT / "tests" / "extremum_reference.py").read_text()
    assert f"\nPOINTS_PER_PERIOD = {points}\n" in source


def test_the_mode_functions_test_is_as_described():
    """'tested against 150-digit mpmath to N = 50': test_beams_general.py."""
    digits, most = quoted("model.md", r"accurate to a few ulps for any j "
                          r"\(tested against (\d+)-digit mpmath to N = "
                          r"(\d+)\)")
    source = (ROOT / "tests" / "shared" / "test_beams_general.py") \
        .read_text()
    assert f"with mpmath.workdps({digits}):" in source
    js = re.search(r"parametrize\(\"j\", \[([\d, ]+)\]\)\n"
                   r"def test_eigenvalue_and_mode_against_mpmath",
                   source).group(1)
    assert max(int(j) for j in js.split(",")) == int(most)
