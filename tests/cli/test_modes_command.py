"""``contactsep modes`` and ``contactsep.modes`` against a finite-element
beam of the tests' own (tests/shared/fe_beam.py), the frequencies made
physical here from the section's own formulas (not the package's)."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

import contactsep
from contactsep.cli import main

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "shared"))
import fe_beam as fe  # noqa: E402

G = 386.4                       # in/s^2
E, GAMMA, NU = 10.0e6, 0.100, 0.33
L2, B2 = 2.5, 0.5


def fe_separator_hz(d, count, timoshenko=True, kr=None, kt=None,
                    mass=0.0, x_mass=None):
    """The aluminium separator's frequencies (cps) by finite elements."""
    area, inertia = B2 * d, B2 * d**3 / 12.0
    rho_a = GAMMA * area / G
    ei = E * inertia
    options = {}
    if timoshenko:
        kappa = 10.0 * (1.0 + NU) / (12.0 + 11.0 * NU)
        shear = E / (2.0 * (1.0 + NU))
        options = {"r2": inertia / (area * L2**2),
                   "s2": ei / (kappa * shear * area * L2**2)}
    if kr is not None:
        options["kr"] = kr * L2 / ei
    if kt is not None:
        options["kt"] = kt * L2**3 / ei
    if mass:
        where = (L2 / 2.0 if x_mass is None else x_mass) / L2
        options["masses"] = ((where, mass / (GAMMA * area * L2)),)
    b, _ = fe.converged("clamped-clamped", count, **options)
    return b * np.sqrt(ei / rho_a) / L2**2 / (2.0 * np.pi)


def run_json(capsys, *argv):
    assert main(["modes", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_done_when_timoshenko_separator_matches_finite_elements(capsys):
    data = run_json(capsys, "--member", "2", "--beam2", "timoshenko",
                    "--d", "0.75")
    expected = fe_separator_hz(0.75, 4)
    np.testing.assert_allclose(data["f_hz"], expected, rtol=1e-6)
    np.testing.assert_allclose(np.array(data["p_rad_s"]) / (2 * np.pi),
                               data["f_hz"], rtol=1e-15)


def test_elastic_supports_and_mass_match_finite_elements(capsys):
    data = run_json(capsys, "--member", "2", "--beam2", "timoshenko",
                    "--d", "0.25", "--kr2", "2000", "--kt2", "5e5",
                    "--mass2", "0.015", "--x-mass2", "0.9", "--count", "3")
    expected = fe_separator_hz(0.25, 3, kr=2000.0, kt=5e5, mass=0.015,
                               x_mass=0.9)
    np.testing.assert_allclose(data["f_hz"], expected, rtol=1e-6)


def test_bernoulli_euler_default_is_the_closed_form(capsys):
    data = run_json(capsys, "--member", "1", "--count", "3")
    kl = np.array([1.87510407, 4.69409113, 7.85475744])    # published
    a = np.sqrt(E * 0.125**2 / 12.0 * G / GAMMA)
    np.testing.assert_allclose(data["f_hz"],
                               kl**2 * a / 19.0**2 / (2 * np.pi), rtol=1e-8)
    # the cantilever's tip value is 2 (-1)^(j+1)
    np.testing.assert_allclose(np.ravel(data["X_contact"]), [2, -2, 2],
                               atol=1e-12)


def test_python_api_and_csv(capsys):
    design = contactsep.thesis_design(d=0.5, beam2="timoshenko")
    result = contactsep.modes(design, 2, 2)
    assert result.f_hz.shape == (2,) and result.x_in == (1.25,)
    assert main(["modes", "--member", "2", "--d", "0.5", "--beam2",
                 "timoshenko", "--count", "2", "--csv"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("#") and lines[1] == "j,p_rad_s,f_hz,X_contact"
    assert float(lines[2].split(",")[2]) == result.f_hz[0]


def published_clamped_mode(j, xi):
    """X_j(xi L) of the clamped-clamped beam from the published k_jL and
    sigma_j (beam-constants.md: Blevins Table 8-1), normalised to a
    mean square of 1 over the span."""
    kl, sigma = {1: (4.73004074, 0.982502215),
                 2: (7.85320462, 1.000777312),
                 3: (10.9956078, 0.999966450)}[j]
    z = kl * xi
    return np.cosh(z) - np.cos(z) - sigma * (np.sinh(z) - np.sin(z))


def test_the_separator_s_lower_contact_point_has_its_own_values(capsys):
    """--x2-lower 0.8 (L2 = 2.5 in, the upper contact at mid-span): the
    mode values at both points against the published mode shapes."""
    design = contactsep.thesis_design(x2_lower=0.8)
    result = contactsep.modes(design, 2, 3)
    assert result.x_in == (1.25, 0.8) and result.values.shape == (3, 2)
    for j in (1, 2, 3):
        np.testing.assert_allclose(
            result.values[j - 1],
            [published_clamped_mode(j, 0.5), published_clamped_mode(j, 0.32)],
            rtol=1e-7, atol=1e-7)
    assert main(["modes", "--member", "2", "--x2-lower", "0.8", "--count",
                 "3", "--csv"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert "x2_lower = 0.8 in" in lines[0]
    assert lines[1] == "j,p_rad_s,f_hz,X_contact,X_lower"
    assert float(lines[3].split(",")[4]) == result.values[1, 1]
    assert main(["modes", "--member", "2", "--x2-lower", "0.8", "--count",
                 "2"]) == 0
    text = capsys.readouterr().out.splitlines()
    assert text[1].split() == ["j", "p_rad_s", "f_hz", "X_contact",
                               "X_lower"]
    # without x2_lower (or with it at x2) one point, as before
    assert contactsep.modes(contactsep.thesis_design(x2_lower=1.25), 2,
                            2).x_in == (1.25,)


@pytest.mark.parametrize("argv, message", [
    (["--member", "2", "--count", "0"], "count"),
    (["--member", "2", "--beam2", "timoshenko", "--count", "500"], "count"),
    (["--member", "2", "--kr2", "-1"], "--kr2"),
    (["--member", "2", "--beam2", "rayleigh"], "--beam2"),
])
def test_bad_input_is_one_line(capsys, argv, message):
    assert main(["modes", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("contactsep: error:") and message in err
    assert len(err.strip().splitlines()) == 1


def test_evaluate_takes_the_members_modes():
    """Eq. 23 with other beam physics (issue 27) uses the modes that
    contactsep.modes prints, in both backends."""
    design = contactsep.thesis_design(kr2=1000.0, beam3="timoshenko",
                                      mass3=0.01)
    for backend in ("compiled", "numpy"):
        result = contactsep.evaluate(design, backend=backend)
        assert int(result.status) == 0
        for member, p in ((2, result.p2), (3, result.p3)):
            np.testing.assert_allclose(
                p, contactsep.modes(design, member).p_rad_s, rtol=1e-14)


def test_separator_physical_is_the_fitted_supports(capsys):
    physical = run_json(capsys, "--member", "2", "--separator", "physical",
                        "--count", "2")
    spelled = run_json(capsys, "--member", "2", "--beam2", "timoshenko",
                       "--kr2", "21900", "--count", "2")
    assert physical["theory"] == "timoshenko"
    assert physical["f_hz"] == spelled["f_hz"]
    # a typed field wins over the shortcut's
    own = run_json(capsys, "--member", "2", "--separator", "physical",
                   "--kr2", "5000", "--count", "2")
    assert own["f_hz"][0] < physical["f_hz"][0]


@pytest.mark.parametrize("argv", [
    ["model", "--beam2", "timoshenko"],
    ["study", "table2", "--separator", "physical"],
    ["sweep", "--mass3", "0.01", "--vary", "d=0.2:0.3:2"],
])
def test_eq_23_commands_take_other_beams(capsys, argv):
    assert main(argv) == 0
    assert capsys.readouterr().err == ""
