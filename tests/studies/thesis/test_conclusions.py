"""The thesis's conclusions re-examined for circuit opening (issue 16,
item 6): each study's rows against eq. 23 and simulate() computed here,
its preloads against simulate() 3 % either side, the command."""

from __future__ import annotations

import numpy as np
import pytest

from contactsep.chatter import simulate
from contactsep.chatter.stack import largest_preload
from contactsep.cli import main
from contactsep.model import evaluate
from contactsep.studies.thesis import conclusions
from contactsep.studies.preload import chart as preload
from contactsep.studies.preload import scan as preload_scan
from contactsep.studies.study import thesis_study_design

#: The design each study's rows change, and how.
ROWS = {
    "conclusion3": lambda v: {"e": v},
    "conclusion5": lambda v: {"h2": v},
    "conclusion6": lambda v: {"gamma2": v},
    "conclusion7": lambda v: {"x3": v},
}
#: The studies' step and window: the thesis's, given (conclusions.py).
THESIS = {"dt": 5e-8, "t_end": 0.06}
#: The column that holds each study's field.
FIELD_COLUMNS = {"conclusion3": "e", "conclusion5": "d_in",
                 "conclusion6": "gamma2_lb_in3", "conclusion7": "x3_in"}


@pytest.mark.slow
@pytest.mark.parametrize("name", list(ROWS))
def test_each_row_is_eq23_and_simulate_and_holds_3_percent(name):
    n = 4
    study = conclusions.conclusion(name, n_modes=n, workers=2)
    damping = "flores" if name == "conclusion3" else "none"
    values = study[FIELD_COLUMNS[name]]
    for i, value in enumerate(values):
        design = thesis_study_design(n_modes=n, **ROWS[name](float(value)))
        assert evaluate(design).y3_max == pytest.approx(
            study["y3_max_in"][i], rel=1e-12)
        free = simulate(design, model="hertz", damping=damping, samples=1,
                        single_impulse=False, **THESIS)
        assert free.max_lower_gap_in == study["max_lower_gap_in"][i]
        assert free.circuit_open_s == study["circuit_open_s"][i]
        assert free.n_events == study["n_events"][i]
        answer = study["min_preload_lb"][i]
        if np.isnan(answer):
            # no answer: an event at the highest grid preload the
            # simulation takes (at N = 4 the thin separators need more
            # than the lower contact's 27 lb)
            top = preload_scan.grid(preload_scan.top_index(largest_preload(design)))
            assert simulate(design, model="hertz", damping=damping,
                            preload=top, samples=1, single_impulse=False,
                            **THESIS).n_events > 0
            assert any(note.startswith("no answer at ")
                       for note in study.notes)
            continue
        # 3 % above: closed (3 % below is often closed too at N = 4,
        # where "closed" is far from monotone: docs/preload-family.md)
        above = simulate(design, model="hertz", damping=damping,
                         preload=1.03 * answer, samples=1,
                         single_impulse=False, **THESIS)
        assert above.n_events == 0, (name, value)
    if name == "conclusion6":
        # R of eq. 24 grows in proportion to the separator's density
        assert np.allclose(study["R"] / study["R"][0],
                           study["gamma2_lb_in3"] / study["gamma2_lb_in3"][0],
                           rtol=1e-12)
    if name == "conclusion7":
        assert np.allclose(study["r"] * 19.0, study["x3_in"], rtol=1e-15)


def test_a_study_table_around_known_simulations(monkeypatch):
    """conclusion7's table with the simulations replaced by known
    functions: an event below 2 lb per unit x3/L3, a free run's gap equal
    to x3 / 1000: the columns, eq. 23 from the model itself, the search
    to 1 %."""
    def event(task):
        design, load = task.design, task.preload_lb
        return load < 2.0 * float(design.x3) / float(design.L3)

    def free(task):
        design = task.design
        return float(design.x3) / 1000.0, 0.03, 3

    monkeypatch.setattr(preload, "_simulate_event", event)
    monkeypatch.setattr(conclusions, "_zero_preload", free)
    study = conclusions.conclusion("conclusion7", n_modes=4, workers=1)
    assert list(study.columns) == [
        "r", "x3_in", "y3_max_in", "max_lower_gap_in", "circuit_open_s",
        "n_events", "min_preload_lb"]
    r = np.array(conclusions.CONTACT_RATIOS)
    assert np.array_equal(study["r"], r)
    assert np.allclose(study["max_lower_gap_in"], 19.0 * r / 1000.0)
    ratio = study["min_preload_lb"] / (2.0 * r)
    assert np.all((ratio >= 1.0) & (ratio <= 1.01))
    for x3, y3 in zip(study["x3_in"], study["y3_max_in"]):
        assert evaluate(thesis_study_design(n_modes=4, x3=float(x3))).y3_max \
            == pytest.approx(y3, rel=1e-12)


@pytest.mark.parametrize("argv, message", [
    (["study", "conclusion5", "--d", "0.3"],
     "study conclusion5 sets d/h2 itself"),
    (["study", "conclusion3", "--e", "0.3"],
     "study conclusion3 sets e itself"),
    (["study", "conclusion7", "--backend", "numpy"],
     "study conclusion7 runs the chatter simulation"),
])
def test_the_studies_refuse_what_they_set(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
