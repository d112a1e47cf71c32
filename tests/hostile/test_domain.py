"""Silently wrong numbers (issue 18, class 1): the general model's domain.

Outside it the kernel returned status 0 with garbage (E1 = 1e100 or
ys = 1e-200: t1 = 0 and every result 0.0; ys = 1e200: "no impact").  A
scalar design outside the domain is refused when it is made, naming the
field; a batch's design gets status 2.  Inside, the results are checked
against the model's exact symmetries (dimensional analysis, not the code
under test): scaling every length by lambda, the forces (E and gamma) by
kappa, time by 1/mu (E by mu^2) or the release height by sigma maps the
thesis design's results to the scaled design's by known powers."""

from __future__ import annotations

import math

import numpy as np
import pytest

from contactsep.errors import InputError
from contactsep.model import (
    Design,
    DesignError,
    evaluate,
    status,
    thesis_design,
)
from contactsep.model import design_domain as design_module
from contactsep.model.design_domain import REAL_COLUMNS

EXTREMES = (math.nan, math.inf, -math.inf, 0.0, -1.0, 1e-300, 1e300,
            2.0**63)

#: Fields in inches (scaled by lambda).
LENGTHS = ("L1", "b1", "h1", "x1", "L2", "b2", "h2", "x2", "L3", "b3",
           "h3", "x3", "ys", "gap")
#: The results checked.
RESULTS = ("t1", "t_max", "t_min", "v_impact", "v0", "psi", "y3_max",
           "y3_min", "R", "M1", "M2", "M3")


def _base(**changes) -> Design:
    return thesis_design(**{"x1": 0.98 * 19, "x2": 1.25, "x3": 0.9 * 19,
                            "n_modes": 12, "lower_response": "impulse",
                            **changes})


def _scaled(design, lam=1.0, kappa=1.0, mu=1.0, sigma=1.0) -> Design:
    """Lengths x lam, forces x kappa, times x 1/mu, ys x sigma."""
    changes = {f: getattr(design, f) * lam for f in LENGTHS}
    changes["ys"] *= sigma
    for m in "123":
        changes[f"E{m}"] = getattr(design, f"E{m}") * kappa * mu**2
        changes[f"gamma{m}"] = getattr(design, f"gamma{m}") * kappa
    changes["tau"] = design.tau * lam / mu
    return design.replace(**changes)


def _factor(key, lam, kappa, mu, sigma, impulse) -> float:
    """How result ``key`` scales.  Frequencies go as h/L^2 sqrt(E g /
    gamma): x mu/lam; masses gamma V/g: x kappa lam^3; velocities ys p:
    x mu sigma; the impulse M V; y3 = (psi/M3) sum X^2/p sin(p t) scales
    as V/p, but eq. 13 as printed, (v0/L3) sum X^2/p sin(p t), as V/(L p)
    (it has no unit: docs/model.md, "The unit problem of eq. 13")."""
    time, mass, speed = lam / mu, kappa * lam**3, mu * sigma
    return {"t1": time, "t_max": time, "t_min": time, "v_impact": speed,
            "v0": speed, "psi": mass * speed,
            "y3_max": sigma * (lam if impulse else 1.0),
            "y3_min": sigma * (lam if impulse else 1.0), "R": 1.0,
            "M1": mass, "M2": mass, "M3": mass}[key]


#: Each transformation pushed to the domain's edges (the thesis design's
#: thinnest member is 0.125 in, its longest 19 in; E 1e7 psi, gamma
#: 0.1 lb/in^3, ys 0.5 in of L1 = 19 in), alone and together.
CORNERS = [dict(lam=8e-4), dict(lam=500.0), dict(kappa=1e-4),
           dict(kappa=100.0), dict(mu=10.0), dict(mu=10**-3.5),
           dict(sigma=37.9), dict(sigma=3.9e-8),
           dict(lam=8e-4, kappa=1e-4, mu=10.0, sigma=3.9e-8),
           dict(lam=500.0, kappa=100.0, mu=10**-3.5, sigma=37.9),
           dict(lam=8e-4, kappa=100.0, mu=10**-3.5),
           dict(lam=500.0, kappa=1e-4, mu=10.0)]


@pytest.mark.parametrize("backend", ["compiled", "numpy"])
@pytest.mark.parametrize("response", ["impulse", "as-printed"])
@pytest.mark.parametrize("corner", CORNERS, ids=str)
def test_results_at_the_domain_edges_obey_the_models_symmetries(
        corner, response, backend):
    base = _base().replace(lower_response=response)
    scaled = _scaled(base, **corner)
    assert scaled.problems() == []
    a = evaluate(base, backend=backend)
    b = evaluate(scaled, backend=backend)
    assert int(b.status) == 0
    params = {"lam": 1.0, "kappa": 1.0, "mu": 1.0, "sigma": 1.0, **corner}
    for key in RESULTS:
        want = float(getattr(a, key)) * _factor(
            key, impulse=response == "impulse", **params)
        got = float(getattr(b, key))
        # a few ulp per operation of a chain of some tens
        assert got == pytest.approx(want, rel=1e-12), key


@pytest.mark.parametrize("field", REAL_COLUMNS)
@pytest.mark.parametrize("value", EXTREMES, ids=repr)
def test_every_field_at_every_extreme_is_refused_or_true(field, value):
    """Each real field alone at NaN, +-inf, 0, -1, 1e-300, 1e300, 2^63:
    refused with a one-line message naming the field, or evaluated with
    a status that is true (status 1 only where the release cannot reach
    the gap; status 0 only with every result finite and t1 > 0)."""
    try:
        design = _base(**{field: value})
    except DesignError as error:
        message = str(error)
        assert isinstance(error, InputError)
        assert message.startswith(f"{field}: found ")
        assert "\n" not in message and "expected" in message
        return
    result = evaluate(design)
    code = int(result.status)
    if code == status.UNRESOLVED:
        # a window whose extremes cannot be resolved says so (issue 17)
        assert field == "tau" and value > 1.0, (field, value)
        return
    ys, gap = float(design.ys), float(design.gap)
    if code == 1:
        # released at or below the gap, or a gap beyond the swing
        assert gap >= ys or abs(gap) >= abs(ys), (field, value)
        return
    assert code == 0, (field, value, code)
    for key in RESULTS:
        assert math.isfinite(float(getattr(result, key))), key
    assert float(result.t1) > 0 and float(result.v_impact) > 0


@pytest.mark.parametrize("changes, message", [
    (dict(E1=1e100), "E1: found 1e+100, expected 1 to 1e+09 psi"),
    (dict(ys=1e-200), "ys: found 1e-200, expected 1.9e-08 <= |ys| <= 19 in"),
    (dict(ys=1e200), "ys: found 1e+200, expected 1.9e-08 <= |ys| <= 19 in"),
    (dict(gamma2=170.0), "gamma2: found 170.0, expected 1e-05 to 10 "
                         "lb/in^3 (a density in lb/ft^3 is 1728 times"),
    (dict(h2=3.0), "h2: found 3.0, expected at most L2 = 2.5 in"),
    (dict(end1="pinned-pinned"), "x1: found 19.0 (its default), expected "
                                 "0 < x1 < 19 in: inside the span of the "
                                 "pinned-pinned upper contact (end1)"),
    (dict(x1=1e-30), "x1: found 1e-30, expected 0.019 < x1 <= 19 in"),
    (dict(Lc=1e-300), "Lc: found 1e-300, expected 0.0001 to 10000 in"),
])
def test_the_issues_examples_are_refused_naming_the_field(changes, message):
    with pytest.raises(DesignError) as info:
        thesis_design(**changes)
    assert str(info.value).startswith(message)


def test_a_batch_marks_designs_outside_the_domain_with_status_2():
    """Every backend: the kernel would compute them (E1 = 1e100 gave
    t1 = 0 and status 0), the domain gives them status 2 and NaN."""
    e1 = np.array([1e7, 1e100, 2e7, 1e-300])
    for backend in ("compiled", "numpy"):
        r = evaluate(thesis_design(E1=e1), backend=backend)
        assert r.status.tolist() == [0, 2, 0, 2]
        assert np.all(np.isnan(r.t1[[1, 3]]) & np.isnan(r.y3_max[[1, 3]]))
        assert np.all(np.isnan(r.p1[[1, 3]]))
        assert not np.any(r.at_window_end[[1, 3]])
        assert np.all(np.isfinite(r.y3_max[[0, 2]]))
    design = thesis_design(E1=e1)
    assert design.problems()[0].startswith("E1: found 1e+100")


def test_the_domain_limits_are_the_documented_ones():
    """docs/model.md's domain table shows each limit from the code itself
    (the docs' ``constant`` role, resolved by
    tests/project/test_code_constants.py): no limit is typed in."""
    from conftest import ROOT
    text = (ROOT / "docs" / "model.md").read_text()
    role = "{constant}`contactsep.model.design_domain."
    for name in ("SIZE_RANGE", "DENSITY_RANGE", "MODULUS_RANGE"):
        for index in range(len(getattr(design_module, name))):
            assert f"{role}{name}[{index}]:g`" in text, (name, index)
    # the deflection's upper limit is L1 itself, written as "≤ L1"
    assert design_module.DEFLECTION_RANGE[1] == 1.0
    assert f"{role}DEFLECTION_RANGE[0]:g` L1 ≤ \\|ys\\| ≤ L1" in text
    assert f"{role}SUPPORT_CLEARANCE:g` L from a clamped end" in text


@pytest.mark.parametrize("changes, message", [
    (dict(L1=None), "L1: found None, expected a number"),
    (dict(L1="19"), "L1: found '19', expected a number"),
    (dict(e=True), "e: found True, expected a number"),
    (dict(gap=1j), "gap: found 1j, expected a number"),
    (dict(x3=[None, 1.0]), "x3: found [None, 1.0], expected a number"),
    (dict(n_modes=2**63), "n_modes: found 9223372036854775808, expected "
                          "at most 100,000"),
    (dict(n_modes=(4, 4, 2**70)), "n_modes: found 1180591620717411303424, "
                                  "expected at most 100,000"),
    (dict(n_modes=math.inf), "n_modes: found inf, expected an integer"),
    (dict(n_modes="4"), "n_modes: found '4', expected an integer"),
])
def test_wrong_types_are_refused_naming_the_field(changes, message):
    """Design(L1=None) raised KeyError: 'L1'; a string or a bool was
    read as a number."""
    with pytest.raises(DesignError) as info:
        Design(**changes)
    assert str(info.value).startswith(message)
