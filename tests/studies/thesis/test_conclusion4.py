"""``contactsep study conclusion4`` (issue 28 item 2): e_apparent of the
three contact laws against impact velocity and separator thickness."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from contactsep.cli import main
from contactsep.model import evaluate
from contactsep.studies.thesis import restitution
from contactsep.studies.study import thesis_study_design


@pytest.fixture(scope="module")
def study():
    return restitution.conclusion4(n_modes=4)


def test_the_columns_and_rows_are_the_contract(study):
    assert tuple(study.columns) == ("law", "d_in", "ys_in",
                                    "impact_velocity_in_s", "e_apparent")
    assert len(study) == 3 * restitution.ROWS
    assert set(study["law"]) == {"elastic", "hunt-crossley", "thornton"}
    assert np.all(np.isfinite(study["e_apparent"]))
    assert np.all(np.abs(study["e_apparent"]) <= 1.0)


def test_the_impact_velocity_is_the_release_flight_s(study):
    # the free flight is linear in y_s, and the general model finds the
    # same first impact (abs(dy1/dt) at t1) by its own search
    for d, ys, speed in zip(study["d_in"], study["ys_in"],
                            study["impact_velocity_in_s"]):
        ev = evaluate(thesis_study_design(d=d, ys=ys, n_modes=4))
        assert speed == pytest.approx(float(ev.v_impact), rel=1e-6)
    on_one = np.isclose(study["d_in"], 0.25)
    ratio = study["impact_velocity_in_s"][on_one] / study["ys_in"][on_one]
    assert np.ptp(ratio) < 1e-9 * ratio.max()


def test_read_early_the_first_mode_still_approaches():
    # 1 ms after the impact the upper contact's first mode has not
    # turned (its sub-impacts take several ms): e_apparent < 0
    design = thesis_study_design(d=0.25, ys=0.5, n_modes=4)
    for law in restitution.LAWS:
        _, early = restitution.e_apparent(design, law, 1e-3)
        _, late = restitution.e_apparent(design, law, 0.02)
        assert early < 0.0 < late


def test_the_first_mode_s_energy_is_within_the_upper_member_s():
    # e_apparent^2 times the first mode's energy at release is its
    # energy at the reading: no more than the energy book leaves in the
    # upper contact's modes
    from contactsep.chatter import simulate
    from contactsep.chatter.system import members
    design = thesis_study_design(d=0.25, ys=0.5, n_modes=8)
    upper = members(design)[0]
    first = 0.5 * upper.mass * (upper.p[0] * upper.q0[0])**2
    t1, _ = restitution.first_impact(design)
    for law in restitution.LAWS:
        r = simulate(design, t_end=t1 + 0.02, samples=1,
                     single_impulse=False,
                     **restitution.law_settings(law))
        _, e = restitution.e_apparent(design, law, 0.02)
        assert e**2 * first <= r.energy_book["energy_member1_lbin"] \
            * (1.0 + 1e-9)


@pytest.mark.slow
def test_e_apparent_converges_in_n():
    # docs/circuit-opening.md, Conclusion 4, its convergence rows:
    # N = 16 and 32 within 0.02
    design16 = thesis_study_design(d=0.25, ys=0.5, n_modes=16)
    design32 = design16.replace(n_modes=32)
    for law in restitution.LAWS:
        _, coarse = restitution.e_apparent(design16, law)
        _, fine = restitution.e_apparent(design32, law)
        assert coarse == pytest.approx(fine, abs=0.02)


def test_the_command_writes_the_csv(tmp_path):
    path = tmp_path / "c4.csv"
    assert main(["study", "conclusion4", "--n-modes", "4",
                 "--reading-time", "0.02", "--csv", str(path)]) == 0
    lines = path.read_text().splitlines()
    assert all(line.startswith("#") for line in lines[:5])
    header = next(csv.reader([lines[5]]))
    assert header == ["law", "d_in", "ys_in", "impact_velocity_in_s",
                      "e_apparent"]


@pytest.mark.parametrize("argv", [
    ["study", "conclusion4", "--reading-time", "0"],
    ["study", "conclusion4", "--alpha", "-1"],
    ["study", "conclusion4", "--d", "0.5"],
    ["study", "fig5", "--alpha", "0.1"],
])
def test_bad_options_are_refused_in_one_line(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("contactsep: error:")
