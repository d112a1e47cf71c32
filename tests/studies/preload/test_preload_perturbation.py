"""``contactsep preload --perturbation R`` (issue 25: how well-posed the
answer is): the same search on y_s (1 + R) and y_s (1 - R) with the
same settings.  A planted threshold of known sensitivity to
y_s, the command's outputs and refusals, and on the steel relay direct
runs showing that its threshold is ill-conditioned: designs whose y_s
differ by parts per billion disagree, 3-11 % above the answer, on
whether the circuit opens (docs/preload-family.md, "How well-posed the answer
is")."""

from __future__ import annotations

import csv
import io
import json
import types
import warnings

import pytest
from design_family import FAMILY

import contactsep
from contactsep.chatter import simulate
from contactsep.chatter.stack import largest_preload
from contactsep.cli import main
from contactsep.errors import InputError
from contactsep.studies.preload import command as design_preload
from contactsep.studies.preload import chart as preload
DT, T_END = 4e-8, 0.05


def _planted(monkeypatch, gain):
    """A fake simulation whose threshold is a quarter of the largest
    preload, times (1 + gain (y_s / y_s0 - 1)): a relative change r of
    y_s moves it by gain r.  Records the (y_s, dt, t_end) of every run."""
    ys0 = FAMILY["steel_relay"].ys
    seen = []

    def threshold(design):
        return 0.25 * largest_preload(design) * (
            1.0 + gain * (design.ys / ys0 - 1.0))

    def fake_event(task):
        design, load = task.design, task.preload_lb
        settings = task.settings
        seen.append((design.ys, settings.get("dt"), settings.get("t_end")))
        return load < threshold(design)

    def fake_simulate(design, model, preload=0.0, **settings):
        return types.SimpleNamespace(
            dt=settings.get("dt", DT), open_threshold_in=1e-6,
            min_open_s=1e-5, t_end_s=settings.get("t_end", T_END),
            longest_open_s=5e-6)

    monkeypatch.setattr(preload, "_simulate_event", fake_event)
    monkeypatch.setattr(design_preload, "simulate", fake_simulate)
    return threshold, seen


def test_a_planted_sensitivity_is_measured_and_warned(monkeypatch):
    """gain 1e8: a change of 1e-9 in y_s moves the threshold by 10 %."""
    threshold, seen = _planted(monkeypatch, gain=1e8)
    design = FAMILY["steel_relay"].replace(n_modes=8)
    with pytest.warns(UserWarning, match="ill-conditioned"):
        answer = contactsep.preload(design, workers=1, verify=False,
                                    perturbation=1e-9)
    up, down = answer.perturbed_min_preload_lb
    for found, sign in ((up, 1.0), (down, -1.0)):
        t = threshold(design.replace(ys=design.ys * (1.0 + sign * 1e-9)))
        assert t <= found <= t * 1.01
    # 10 %, to the search's 1 %
    assert answer.min_preload_spread == pytest.approx(0.10, abs=0.011)
    assert answer.perturbation == 1e-9
    # only y_s differs: the perturbed runs have the nominal's settings
    perturbed = [s for s in seen if s[0] != design.ys]
    assert {s[0] for s in perturbed} == {design.ys * (1 + 1e-9),
                                         design.ys * (1 - 1e-9)}
    assert {s[1:] for s in seen} == {(None, None)}
    assert len(answer.perturbed_tested) == 2
    assert answer.simulations == len(seen)


def test_a_well_conditioned_threshold_has_no_spread(monkeypatch):
    _planted(monkeypatch, gain=1.0)
    design = FAMILY["steel_relay"].replace(n_modes=8)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        answer = contactsep.preload(design, workers=1, verify=False,
                                    perturbation=1e-9)
    assert not [w for w in caught if "ill-conditioned" in str(w.message)]
    assert answer.min_preload_spread <= 0.0101


def test_no_perturbation_unless_asked(monkeypatch):
    _, seen = _planted(monkeypatch, gain=1e8)
    design = FAMILY["steel_relay"].replace(n_modes=8)
    answer = contactsep.preload(design, workers=1, verify=False)
    assert answer.perturbation is None and answer.min_preload_spread is None
    assert {s[0] for s in seen} == {design.ys}
    assert "perturbed" not in answer.csv_text()


@pytest.mark.parametrize("value", [0, -1e-9, 2e-3, float("nan"), "x",
                                   True])
def test_bad_perturbations_are_input_errors(value):
    with pytest.raises(InputError, match=r"^perturbation: found .*"
                                         r"relative change of y_s"):
        contactsep.preload(FAMILY["thesis"], workers=1, perturbation=value)


@pytest.mark.parametrize("text", ["0", "abc", "0.01", "inf"])
def test_bad_command_lines_are_one_line_errors(text, capsys):
    assert main(["preload", "--n-modes", "2", "--perturbation", text]) == 2
    err = capsys.readouterr().err
    assert err.startswith("contactsep: error: --perturbation: found ")
    assert err.count("\n") == 1


def test_the_command_writes_the_spread(monkeypatch, tmp_path, capsys):
    _planted(monkeypatch, gain=1e8)
    path = tmp_path / "p.csv"
    code = main(["preload", "--n-modes", "8", "--workers", "1",
                 "--json", "--csv", str(path), "--no-converge",
                 "--perturbation", "1e-9", "--progress", "never",
                 "--L1", "1.2", "--b1", "0.25", "--h1", "0.01",
                 "--L3", "1.2", "--b3", "0.25", "--h3", "0.01",
                 "--L2", "0.3", "--b2", "0.1", "--h2", "0.05",
                 "--ys", "0.02"])
    assert code == 0
    out, err = capsys.readouterr()
    # the command's warning: one line on stderr
    assert err.startswith("contactsep: warning: the smallest preload "
                          "moves by ") and "ill-conditioned" in err
    assert err.count("\n") == 1
    data = json.loads(out,
                      parse_constant=lambda c: pytest.fail(c))
    assert data["perturbation"] == 1e-9
    assert data["min_preload_spread"] == pytest.approx(0.10, abs=0.011)
    assert len(data["perturbed_min_preload_lb"]) == 2
    assert [len(t) > 0 for t in data["perturbed_tested"]] == [True, True]
    lines = path.read_text().splitlines()
    assert any(line.startswith("# min_preload_spread = ") for line in lines)
    body = [line for line in lines if not line.startswith("#")]
    rows = list(csv.DictReader(io.StringIO("\n".join(body))))
    assert {r["search"] for r in rows} == {"nominal", "verify",
                                          "perturbed_up", "perturbed_down"}


# the real simulation: the steel relay at N = 32 and its own step

#: A preload of the search's fine grid 2.9 % above the steel relay's
#: N = 32 answer (0.1586 lb), at which the searches of designs with y_s
#: changed by 1e-9 and 1e-6 of itself found events
#: (docs/studies/preload_conditioning.csv).
ABOVE_ANSWER = 0.1632223082200554


@pytest.mark.slow
def test_parts_per_billion_of_ys_decide_whether_the_relay_opens():
    """Direct runs, no search: at a preload 2.9 % above the answer,
    designs whose y_s differ by k 1e-9 of itself (k = 0 ... 15), each
    run as the search runs it, do not agree on whether the circuit
    opens -- a threshold no N or step can pin down to 2 %.  (On the
    machine of docs/chatter.md 5 of the first 12 open; the test asks
    only that some do and some do not.)"""
    base = FAMILY["steel_relay"].replace(n_modes=32)
    opened = [simulate(base.replace(ys=base.ys * (1 + k * 1e-9)),
                       preload=ABOVE_ANSWER, samples=1,
                       single_impulse=False).n_events > 0
              for k in range(16)]
    # the design itself is closed there, as its search found
    assert not opened[0]
    assert set(opened) == {True, False}
