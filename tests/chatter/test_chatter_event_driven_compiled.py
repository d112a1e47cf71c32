"""Appendix E compiled (fortran/chatter/event_driven.f90) against its NumPy
twin (contactsep/chatter/event_driven.py), the analytic 1-DOF case, the
Jacobi eigensolver against numpy.linalg.eigh, and the bad-input statuses.

Error model.  Both solvers run one algorithm in double precision; they
differ in the order of sums and in the constrained (resting) modes, Jacobi
against LAPACK.  Either eigensolver is backward stable: its eigenvalues
are exact for K + E, |E| ~ eps |K|, so the lowest constrained omega^2 is
off by eps |K| / omega_min^2 relative, of order

    delta = eps * kappa,   kappa = (p_max / p_min)^2,

(1 for N = 1, 4.5e5 at N = 16).  That relative perturbation of the flow
moves an event time by ~ delta * t (the phase error accumulated to t), a
velocity or an impulse by ~ delta times the largest one, and the energy by
~ delta * E0; the root finder's own stopping rules (1e-15 relative) are
below delta.  Measured on the thesis designs (N = 1..16, e = 0.375 and
1): times and rest limits <= 1.05 delta t_end, impulses and contact
velocities <= 12.1 delta (|psi_1|, |u_1|), energies <= 0.7 delta E0.  The
tolerances are 10 delta t_end, 100 delta, 10 delta E0: a margin of ~8 or
more, and still < 1e-8 relative, where a wrong law (a missing (1+e), a
missed or extra impact, a wrong basis) moves these by > 1e-4.

Event counts.  Every recorded event is an impact with the contact
approaching (u- < 0, psi > 0; test_every_recorded_event_is_an_approach):
leaving a rest, where the displacement and its rate are both at
round-off, neither solver records an event any more.  So the two must
give the same impacts and rests one to one (for N <= 32; the smallest
impulse is >= zeno_speed * psi_1 / 2, far from any round-off).
"""

from __future__ import annotations

import numpy as np
import pytest

import contactsep
from contactsep.chatter import event_driven_compiled as compiled
from contactsep.chatter import status as chatter_status
from contactsep.chatter.event_driven import (
    rigid_stop_from_design,
    simulate_rigid_stop,
)
from contactsep.chatter.system import members

api = pytest.importorskip("contactsep.chatter._chatter").chatter_api

EPS = np.finfo(float).eps
T_END = 0.060


def kappa(p) -> float:
    return float((np.max(p) / np.min(p))**2)


@pytest.fixture(scope="module", params=[0.375, 1.0], ids=["e0.375", "e1"])
def restitution(request):
    return request.param


@pytest.mark.parametrize("n", [1, 2, 4, 8, 16])
def test_compiled_matches_the_numpy_twin(n, restitution):
    design = contactsep.thesis_design(n_modes=n, e=restitution)
    upper = members(design)[0]
    delta = EPS * kappa(upper.p)
    twin = rigid_stop_from_design(design, t_end=T_END)
    fast = rigid_stop_from_design(design, t_end=T_END, backend="fortran")
    assert len(fast.impact_t) == len(twin.impact_t) >= 1
    assert len(fast.rest_intervals) == len(twin.rest_intervals)
    if restitution == 1.0:
        assert len(fast.rest_intervals) == 0
    np.testing.assert_allclose(fast.impact_t, twin.impact_t, rtol=0,
                               atol=10 * delta * T_END)
    np.testing.assert_allclose(fast.rest_intervals, twin.rest_intervals,
                               rtol=0, atol=10 * delta * T_END)
    psi_1, u_1 = twin.impulse[0], abs(twin.v_before[0])
    np.testing.assert_allclose(fast.impulse, twin.impulse, rtol=0,
                               atol=100 * delta * psi_1)
    for name in ("v_before", "v_after"):
        np.testing.assert_allclose(getattr(fast, name),
                                   getattr(twin, name), rtol=0,
                                   atol=100 * delta * u_1)
    e0 = twin.initial_energy
    assert fast.initial_energy == pytest.approx(e0, rel=10 * EPS)
    np.testing.assert_allclose(fast.energy_after, twin.energy_after,
                               rtol=0, atol=10 * delta * e0)
    assert abs(fast.final_energy - twin.final_energy) <= 10 * delta * e0


@pytest.mark.parametrize("n", [2, 4, 8, 16, 32])
@pytest.mark.parametrize("backend", ["numpy", "fortran"])
def test_every_recorded_event_is_an_approach(n, backend):
    """No false re-contacts: every event is an impact with the contact
    approaching (u- < 0, psi > 0).  Leaving a rest, y and y' are at the
    modal sum's round-off: before the flight starts clear of it and
    events with no approach were skipped, the twin recorded 240 such
    events at N = 4 and killed their separating velocity; an unguarded
    Newton shortcut jumped over a real impact (N = 8)."""
    design = contactsep.thesis_design(n_modes=n)
    r = rigid_stop_from_design(design, t_end=T_END, backend=backend)
    assert np.all(r.v_before < 0.0) and np.all(r.impulse > 0.0)
    energies = np.concatenate([[r.initial_energy], r.energy_after])
    assert np.all(np.diff(energies) <= 1e-14 * energies[0])


def test_compiled_one_mode_against_the_stop_is_analytic():
    """tests/chatter/test_chatter.py's 1-DOF case through the Fortran: impacts at
    pi/(2p) + (n-1) pi/p, each rebound e times the last."""
    p, x, e = 10.0, 2.0, 0.5
    r = simulate_rigid_stop([p], [x], 1.0, [0.1], [0.0], e, 2.0,
                            backend="fortran")
    n = np.arange(len(r.impact_t))
    assert len(n) == 6
    # np.allclose's default atol (1e-8) would hide a wrong law: none here
    close = lambda a, b, rtol: np.testing.assert_allclose(a, b, rtol=rtol,
                                                          atol=0)
    close(r.impact_t, np.pi / (2 * p) + n * np.pi / p, 1e-13)
    close(r.v_before, -0.1 * p * x * e**n, 1e-12)
    close(r.v_after, -e * r.v_before, 1e-12)
    # psi = (1+e) M |u-| / X^2; the energy after the n-th impact
    close(r.impulse, 1.5 * np.abs(r.v_before) / x**2, 1e-12)
    close(r.energy_after, 0.5 * (0.1 * p)**2 * e**(2 * n + 2), 1e-12)
    assert r.initial_energy == pytest.approx(0.5, rel=1e-15)


@pytest.mark.parametrize("n", [4, 16])
def test_compiled_displacement_matches_and_never_penetrates(n):
    design = contactsep.thesis_design(n_modes=n)
    delta = EPS * kappa(members(design)[0].p)
    twin = rigid_stop_from_design(design, t_end=T_END)
    fast = rigid_stop_from_design(design, t_end=T_END, backend="fortran")
    t = np.linspace(0.0, T_END, 200_001)
    y_twin, y = twin.displacement(t), fast.displacement(t)
    # an event shifted by dt moves y by |u| dt near it
    speed = abs(twin.v_before[0])
    scale = np.max(np.abs(y_twin))
    assert np.max(np.abs(y - y_twin)) <= 10 * delta * (speed * T_END + scale)
    assert y.min() > -1e-12
    start, end = fast.rest_intervals[0]
    inside = (t > start) & (t < end)
    assert np.all(np.abs(y[inside]) < 1e-12)


def test_replay_ends_at_the_fortran_state():
    """The segments are rebuilt from the events; their end is the state
    the Fortran itself ended with."""
    design = contactsep.thesis_design(n_modes=16)
    upper = members(design)[0]
    delta = EPS * kappa(upper.p)
    r = rigid_stop_from_design(design, t_end=T_END, backend="fortran")
    out = api.run_rigid_stop(upper.p, upper.x, upper.mass, upper.q0,
                             upper.v0, 0.375, T_END, 1e-4, 4096, 4096)
    q_end, v_end, status = out[5], out[6], out[8]
    assert status == chatter_status.OK
    q, v = compiled.replayed_end_state(r, T_END)
    amp = np.sqrt(upper.q0**2 + (upper.v0 / upper.p)**2)
    assert np.max(np.abs(q - q_end)) <= 10 * delta * np.max(amp)
    assert np.max(np.abs(v - v_end)) <= 10 * delta * np.max(upper.p * amp)
    energy = 0.5 * upper.mass * np.sum(v_end**2 + (upper.p * q_end)**2)
    assert energy == pytest.approx(r.final_energy, rel=1e-14)


def test_impact_cap_and_table_growth_match_the_twin(monkeypatch):
    design = contactsep.thesis_design(n_modes=8)
    twin = rigid_stop_from_design(design, max_impacts=12)
    capped = rigid_stop_from_design(design, max_impacts=12,
                                    backend="fortran")
    assert len(twin.impact_t) == len(capped.impact_t) == 12
    np.testing.assert_allclose(capped.impact_t, twin.impact_t, rtol=1e-12)
    assert capped.final_energy == pytest.approx(twin.final_energy,
                                                rel=1e-10)
    whole = rigid_stop_from_design(design, backend="fortran")
    monkeypatch.setattr(compiled, "FIRST_TABLE", 3)
    grown = rigid_stop_from_design(design, backend="fortran")
    assert len(whole.impact_t) > 3 * 4
    np.testing.assert_array_equal(grown.impact_t, whole.impact_t)
    np.testing.assert_array_equal(grown.rest_intervals, whole.rest_intervals)
    assert grown.final_energy == whole.final_energy


def _run(**change):
    args = dict(p=np.array([10.0, 40.0]), x=np.array([1.0, -0.5]),
                mass=1.0, q0=np.array([0.1, 0.0]), v0=np.zeros(2), e=0.5,
                t_end=1.0, zeno_speed=1e-4, max_impacts=64, max_rests=64)
    args.update(change)
    return api.run_rigid_stop(**args)


def test_good_input_runs():
    out = _run()
    assert out[-1] == chatter_status.OK and out[1] > 0


@pytest.mark.parametrize("change", [
    dict(p=np.array([10.0, 0.0])), dict(p=np.array([-1.0, 4.0])),
    dict(mass=0.0), dict(mass=-1.0), dict(x=np.zeros(2)),
    dict(q0=np.array([np.nan, 0.0])), dict(v0=np.array([0.0, np.inf])),
    dict(t_end=np.inf), dict(t_end=-1.0), dict(e=-0.1), dict(e=1.5),
    dict(e=np.nan), dict(zeno_speed=-1.0), dict(max_impacts=0),
    dict(max_rests=0)], ids=repr)
def test_bad_input_status(change):
    out = _run(**change)
    assert out[-1] == chatter_status.BAD_INPUT
    assert out[1] == 0 and out[4] == 0


def test_full_tables_status():
    out = _run(max_impacts=2)
    assert out[-1] == chatter_status.IMPACTS_FULL and out[1] == 2
    # N = 4 rests twice in 0.06 s: room for one rest only
    upper = members(contactsep.thesis_design(n_modes=4))[0]
    args = (upper.p, upper.x, upper.mass, upper.q0, upper.v0, 0.375, T_END,
            1e-4, 4096)
    whole = api.run_rigid_stop(*args, 4096)
    assert whole[-1] == chatter_status.OK and whole[4] == 2
    second = int(np.flatnonzero(whole[2][:whole[1]] == 1)[1]) + 1
    full = api.run_rigid_stop(*args, 1)
    assert full[-1] == chatter_status.RESTS_FULL
    assert full[4] == 1 and full[1] == second
    np.testing.assert_array_equal(full[0][:, :second],
                                  whole[0][:, :second])


def test_python_rejects_bad_input():
    with pytest.raises(ValueError, match="bad input"):
        simulate_rigid_stop([10.0], [1.0], 0.0, [0.1], [0.0], 0.5, 1.0,
                            backend="fortran")
    # n < 1 is status 2 in Fortran, but f2py cannot pass n = 0 (it sizes
    # the output from the arrays): the Python layer refuses first
    with pytest.raises(ValueError, match="at least one mode"):
        simulate_rigid_stop([], [], 1.0, [], [], 0.5, 1.0, backend="fortran")
    with pytest.raises(ValueError, match="one length"):
        simulate_rigid_stop([10.0, 20.0], [1.0], 1.0, [0.1], [0.0], 0.5,
                            1.0, backend="fortran")
    with pytest.raises(ValueError, match="stop"):
        simulate_rigid_stop([10.0], [1.0], 1.0, [0.1], [0.0], 0.5, 1.0,
                            stop=1.0, backend="fortran")
    with pytest.raises(ValueError, match="backend"):
        simulate_rigid_stop([10.0], [1.0], 1.0, [0.1], [0.0], 0.5, 1.0,
                            backend="cuda")


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_jacobi_matches_eigh(seed):
    rng = np.random.default_rng(seed)
    n = 12
    a = rng.normal(size=(n, n))
    a = a + a.T
    w, v, status = api.symmetric_eigen(a)
    assert status == 0
    norm = np.linalg.norm(a, 2)
    np.testing.assert_allclose(w, np.linalg.eigvalsh(a), rtol=0,
                               atol=10 * n * EPS * norm)
    assert np.all(np.diff(w) >= 0)
    np.testing.assert_allclose(v.T @ v, np.eye(n), rtol=0, atol=10 * n * EPS)
    np.testing.assert_allclose(v @ np.diag(w) @ v.T, a, rtol=0,
                               atol=10 * n * EPS * norm)


def test_jacobi_constrained_basis_is_the_twins():
    """P K P of the N = 16 thesis member: the same frequencies as eigh's,
    the frozen direction X, the same constrained flow."""
    upper = members(contactsep.thesis_design(n_modes=16))[0]
    p, x = upper.p, upper.x
    projector = np.eye(p.size) - np.outer(x, x) / (x @ x)
    stiff = projector @ np.diag(p**2) @ projector
    w, v, status = api.symmetric_eigen(stiff)
    assert status == 0
    vectors, omega = compiled.constrained_basis(p, x)
    np.testing.assert_allclose(w, omega**2 * (omega > 0), rtol=0,
                               atol=10 * p.size * EPS * p.max()**2)
    frozen = np.argmax(np.abs(v.T @ x))
    assert frozen == np.argmax(np.abs(vectors.T @ x)) == 0
    assert abs(v[:, 0] @ x) == pytest.approx(np.linalg.norm(x), rel=1e-12)


@pytest.mark.parametrize("name", [
    "event_driven.f90", "adaptive.f90", "adaptive_state.f90",
    "adaptive_flow.f90", "adaptive_gap_max.f90", "adaptive_crossings.f90",
    "adaptive_laws.f90"])
def test_fortran_source_keeps_the_project_rules(name):
    """event_driven.f90 and adaptive*.f90: never stop or print, <= 80
    columns, one module, implicit none, intent on every dummy argument, a
    doc comment on every procedure and public parameter (test_sources.py's
    rules, which cover the restored core only)."""
    import importlib.util
    import re

    from conftest import ROOT

    spec = importlib.util.spec_from_file_location(
        "project_sources", ROOT / "tests" / "project" / "test_sources.py")
    sources = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(sources)
    code_lines, procedures = sources.code_lines, sources.procedures
    path = ROOT / "fortran" / "chatter" / name
    text = path.read_text()
    lines = text.splitlines()
    assert all(len(line) <= 80 for line in lines)
    assert not [line for _, line in code_lines(path) if re.search(
        r"^\s*(stop|error\s+stop|print|pause)\b|write\s*\(|\bgo\s*to\b",
        line, re.I)]
    assert len(re.findall(r"^\s*module\s+\w+\s*$", text, re.I | re.M)) == 1
    assert re.search(r"^\s*implicit none", text, re.I | re.M)
    undocumented, missing = [], []
    for number, line in enumerate(lines):
        if re.match(r"\s*(pure\s+|logical\s+|integer\s+|real\(wp\)\s+)?"
                    r"(subroutine|function)\s+\w+|"
                    r"\s*integer, parameter ::", line, re.I):
            if not lines[number - 1].lstrip().startswith("!>"):
                undocumented.append(line.strip())
    assert not undocumented
    for name, args, body in procedures(text):
        declared = set()
        for line in body.splitlines():
            line = line.split("!", 1)[0]
            if re.search(r"intent\s*\(", line, re.I) and "::" in line:
                names = re.sub(r"\([^()]*\)", "", re.sub(
                    r"\([^()]*\)", "", line.split("::", 1)[1]))
                declared |= {n.strip().lower() for n in names.split(",")}
        missing += [f"{name}({a})" for a in args if a.lower() not in declared]
    assert not missing


def test_simulate_appE_runs_the_compiled_solver_by_default(monkeypatch):
    """simulate(model='appE') takes the Fortran events (backend
    'compiled', the default) and the twin's with backend='numpy'; both
    answer alike (N = 8: delta ~ 1e-13, see the tolerances above)."""
    from contactsep.chatter import event_driven_compiled, simulate
    calls = []
    original = event_driven_compiled.simulate_rigid_stop_compiled

    def spy(*args, **kwargs):
        calls.append(1)
        return original(*args, **kwargs)

    monkeypatch.setattr(event_driven_compiled,
                        "simulate_rigid_stop_compiled", spy)
    design = contactsep.thesis_design(n_modes=8)
    fast = simulate(design, model="appE")
    assert calls
    twin = simulate(design, model="appE", backend="numpy")
    assert len(calls) == 1
    assert fast.first_impact_s == pytest.approx(twin.first_impact_s,
                                                rel=1e-12)
    assert fast.first_impulse_lb_s == pytest.approx(
        twin.first_impulse_lb_s, rel=1e-10)
    assert fast.energy_ratio == pytest.approx(twin.energy_ratio, rel=1e-9)
    np.testing.assert_allclose(fast.gap_upper, twin.gap_upper, rtol=0,
                               atol=1e-10)
