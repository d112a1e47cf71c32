"""``contactsep chatter`` and the chatter layer's documented defaults."""

from __future__ import annotations

import csv
import dataclasses
import json
import re

import numpy as np
import pytest

import contactsep
from contactsep import chatter
from contactsep.chatter import circuit, numerics
from contactsep.chatter.laws import HertzLaw
from contactsep.chatter.rigid_stop import ZENO_SPEED
from contactsep.chatter.system import members
from contactsep.cli import main
from contactsep.model import Design, fields

pytest.importorskip("contactsep.chatter._chatter")


def test_the_documented_defaults():
    """docs/chatter.md's defaults, asserted where they act: a run with
    nothing given is the run with every documented value given, and
    each value, changed, changes the run (so none is ignored)."""
    assert circuit.OPEN_THRESHOLD == 1e-6
    assert circuit.MIN_OPEN == 1e-5
    assert ZENO_SPEED == 1e-4
    assert chatter.simulate.__kwdefaults__["open_threshold"] == 1e-6
    design = contactsep.thesis_design(n_modes=4, d=0.75)
    common = dict(t_end=0.03, samples=10)
    # the step: the design's own (numerics.design_step, rounded to a
    # whole number of steps in the window), the model: hertz
    law = HertzLaw.for_materials(float(design.E1), 0.33, 0.125)
    step = numerics.design_step(members(design), law.k).dt
    # (the halving when the energy check fails: tests/chatter/
    # test_numerics.py)
    steps = round(0.03 / step)
    documented = dict(model="hertz", dt=0.03 / steps, open_threshold=1e-6,
                      min_open=1e-5, nu=0.33, button_radius=0.125)
    plain = chatter.simulate(design, **common)
    given = chatter.simulate(design, **common, **documented)
    assert plain.numerics["dt_halvings"] == 0 and plain.status == 0

    def same(result):
        out = result.to_json_dict()
        del out["inputs"]["dt_source"]      # "design" against "given"
        return out
    assert same(plain) == same(given)
    assert plain.dt_source == "design" and given.dt_source == "given"
    assert plain.model == "hertz" and plain.dt == 0.03 / steps
    assert plain.open_threshold_in == 1e-6 and plain.min_open_s == 1e-5
    newton = chatter.simulate(design, model="newton", t_end=0.03,
                              samples=10)
    assert newton.dt == 0.03 / round(
        0.03 / numerics.design_step(members(design)).dt)
    # the window: the design's own, from its N-mode release flight
    window = chatter.simulate(design, samples=10)
    assert window.t_end_source == "design" and plain.t_end_source == "given"
    slowest = min(float(m.p[0]) for m in members(design))
    assert window.t_end_s == pytest.approx(
        window.first_impact_s + numerics.WINDOW_PERIODS * 2 * np.pi
        / slowest, abs=2 * window.dt)
    changes = dict(dt=1e-7, open_threshold=1e-5, min_open=2e-5, nu=0.3,
                   button_radius=0.25)
    for name, value in changes.items():
        other = chatter.simulate(design, **common,
                                 **{**documented, name: value})
        assert other.to_json_dict() != plain.to_json_dict(), name
    # Appendix E's Zeno threshold: the default run is the 1e-4 run
    from contactsep.chatter.event_driven import rigid_stop_from_design
    rest = [rigid_stop_from_design(design, t_end=0.03, **zeno)
            for zeno in ({}, {"zeno_speed": 1e-4}, {"zeno_speed": 1e-3})]
    assert rest[0].impact_t.tolist() == rest[1].impact_t.tolist()
    assert rest[0].impact_t.tolist() != rest[2].impact_t.tolist()
    # the Hertz constant of the defaults: 4/3 E/(2 (1 - nu^2)) sqrt(R)
    law = HertzLaw.for_materials(1e7)
    assert law.k == pytest.approx(4 / 3 * 1e7 / (2 * (1 - 0.33**2))
                                  * 0.125**0.5, rel=1e-15)


def test_the_json_echoes_the_inputs_and_carries_the_answers(capsys):
    """Values, not only keys: the inputs as given, the answers equal to
    simulate() of the same design and settings, the first impact after
    the model's own first impact t1 (eq. 23, an independent path) by at
    most the contact's closing, the totals equal to their intervals."""
    assert main(["chatter", "--model", "hertz", "--n-modes", "4",
                 "--d", "0.35", "--restitution", "0.5", "--L3", "18",
                 "--t-end", "0.03", "--min-open", "2e-5", "--dt", "5e-8",
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    inputs = data["inputs"]
    assert inputs["model"] == "hertz" and inputs["n_modes"] == 4
    assert inputs["dt_s"] == 5e-8 and inputs["t_end_s"] == 0.03
    assert inputs["min_open_s"] == 2e-5
    assert inputs["open_threshold_in"] == 1e-6
    design = Design(h2=0.35, e=0.5, L3=18.0, n_modes=4)
    # the design under the output names (one name per quantity), and
    # read back by the input side's reader into the same design
    echoed = inputs["design"]
    assert (echoed["d_in"], echoed["e"], echoed["L3_in"]) == (0.35, 0.5,
                                                              18.0)
    # every field but those shown only when given (x2_lower: None)
    assert len(echoed) == len(dataclasses.fields(Design)) - len(
        fields.SHOWN_WHEN_GIVEN)
    assert Design(**{fields.field_name(k): v
                     for k, v in echoed.items()}) == design
    # the e given and no law named: Flores's law, calibrated to it
    assert inputs["damping"] == "flores"
    r = chatter.simulate(design, model="hertz", t_end=0.03, min_open=2e-5,
                         dt=5e-8, damping="flores")
    for key in ("first_impact_s", "first_impulse_lb_s", "max_lower_gap_in",
                "circuit_open_s", "first_circuit_open_s", "longest_open_s",
                "n_events", "chatters", "energy_ratio"):
        assert data[key] == getattr(r, key), key
    t1 = float(contactsep.evaluate(design).t1)
    assert 0.0 <= data["first_impact_s"] - t1 < 1e-7
    spans = np.array(data["circuit_open_intervals"])
    assert data["circuit_open_s"] == pytest.approx(
        float(np.sum(spans[:, 1] - spans[:, 0])), rel=1e-12)
    events = np.array(data["events"]).reshape(-1, 2)
    assert len(events) == data["n_events"] > 0
    assert np.all(events[:, 1] - events[:, 0] >= 2e-5)
    assert data["chatters"] is True


def test_bad_input_is_one_line_naming_the_option(capsys):
    assert main(["chatter", "--dt", "-1"]) == 2
    assert "dt: found -1.0" in capsys.readouterr().err
    assert main(["chatter", "--d", "-0.1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("contactsep: error: --d: found -0.1")
    assert err.count("\n") == 1
    assert main(["chatter", "--min-open", "-1"]) == 2
    assert "--min-open: found -1.0" in capsys.readouterr().err


@pytest.mark.parametrize("field", [f.name for f in
                                   dataclasses.fields(Design)])
def test_every_design_field_is_an_option(field):
    """Each Design field is accepted by the chatter command as by the
    model command (the parser, not a run: parse_args)."""
    from contactsep.cli import build_parser
    from contactsep.cli.design_options import design_overrides
    value = {"end1": "clamped-free", "end2": "pinned-pinned",
             "end3": "clamped-free", "n_modes": "3",
             "impact_velocity": "listing", "lower_response": "impulse",
             "lc_reading": "frequencies", "release": "contact",
             "e": "0.5", "x1": "18", "x2": "1.0", "x3": "18", "Lc": "2.0",
             "gap": "0.0", "L1": "18", "E1": "3e7", "E2": "3e7",
             "E3": "3e7", "beam1": "timoshenko", "beam2": "timoshenko",
             "beam3": "timoshenko"}.get(field, "0.3")
    option = {"h2": "--d", "n_modes": "--n-modes",
              "impact_velocity": "--impact-velocity",
              "lower_response": "--lower-response",
              "lc_reading": "--lc-reading",
              "x2_lower": "--x2-lower"}.get(
                  field, f"--{field.replace('x_mass', 'x-mass')}")
    args = build_parser().parse_args(["chatter", option, value])
    overrides = design_overrides(args)
    assert list(overrides) == [field]
    expected = type(getattr(Design(), field) or 0.0)(value) \
        if field not in ("end1", "end2", "end3") else value
    assert overrides[field] == (int(value) if field == "n_modes"
                                else expected)


def test_text_output_has_units_short_numbers_and_the_intervals(capsys):
    assert main(["chatter", "--model", "hertz", "--n-modes", "4",
                 "--t-end", "0.03", "--dt", "5e-8"]) == 0
    out = capsys.readouterr().out
    r = chatter.simulate(contactsep.thesis_design(n_modes=4),
                         model="hertz", t_end=0.03, dt=5e-8)
    assert "model hertz, N = 4, dt = 5e-08 s" in out
    assert "window 0 to 0.03 s" in out and "d 0.25 in" in out
    assert re.search(r"first impact\s+0\.022\d+ s", out)
    assert re.search(r"max lower gap\s+[\d.e-]+ in", out)
    assert not re.search(r"[1-9]\d{7,}", out)     # no 17-digit floats
    assert "{" not in out                          # no dict repr
    listed = re.findall(r"^ +[* ] +([\d.e-]+) to +([\d.e-]+)", out, re.M)
    assert len(listed) == len(r.circuit_open_intervals) > 0
    np.testing.assert_allclose(np.array(listed, dtype=float),
                               r.circuit_open_intervals, rtol=1e-5)
    assert out.count(" * ") + out.count("  * ") >= r.n_events


@pytest.mark.parametrize("model", ["newton", "hertz"])
def test_only_newtons_open_time_carries_its_caveat(model, capsys):
    assert main(["chatter", "--model", model, "--n-modes", "2",
                 "--t-end", "0.03"]) == 0
    out = capsys.readouterr().out
    caveat = "one Newton run's open time is ill-conditioned"
    lines = [line for line in out.splitlines() if caveat in line]
    assert len(lines) == (model == "newton")
    assert all(len(line) <= 79 for line in lines)


def test_csv_exports_the_gap_histories(tmp_path, capsys):
    path = tmp_path / "gaps.csv"
    path.write_text("old\n")
    assert main(["chatter", "--model", "hertz", "--n-modes", "2",
                 "--t-end", "0.03", "--csv", str(path)]) == 0
    capsys.readouterr()
    text = path.read_text().splitlines()
    comments = [line for line in text if line.startswith("#")]
    assert len(comments) == 2 and text[:2] == comments
    assert json.loads(comments[1].split(": ", 1)[1])["t_end_s"] == 0.03
    rows = list(csv.reader(text[2:]))
    assert rows[0] == ["t_s", "gap_upper_in", "gap_lower_in",
                       "circuit_open"]
    body = np.array(rows[1:], dtype=float)
    assert all(len(row) == 4 for row in rows)
    r = chatter.simulate(contactsep.thesis_design(n_modes=2),
                         model="hertz", t_end=0.03)
    assert len(body) == len(r.t)
    np.testing.assert_allclose(body[:, :3], np.column_stack(
        [r.t, r.gap_upper, r.gap_lower]), rtol=1e-8, atol=1e-15)
    both_open = (body[:, 1] > 1e-6) & (body[:, 2] > 1e-6)
    np.testing.assert_array_equal(body[:, 3], both_open)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["gaps.csv"]


def test_png_has_its_dpi_and_a_lower_gap_panel(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    path = tmp_path / "gaps.png"
    assert main(["chatter", "--model", "hertz", "--n-modes", "2",
                 "--t-end", "0.03", "--png", str(path), "--dpi", "50"]) == 0
    capsys.readouterr()
    header = path.read_bytes()[:24]
    width, height = (int.from_bytes(header[16:20], "big"),
                     int.from_bytes(header[20:24], "big"))
    assert (width, height) == (350, 250)            # 7 x 5 in at 50 dpi
    assert sorted(p.name for p in tmp_path.iterdir()) == ["gaps.png"]


def test_a_far_coarse_dt_warns_in_one_line(capsys):
    assert main(["chatter", "--model", "newton", "--n-modes", "2",
                 "--dt", "5e-4", "--t-end", "0.03"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 2 and err[0].startswith("contactsep: warning: dt:")
    assert err[1].startswith("contactsep: note: preload 0")


def test_the_repr_is_short():
    r = chatter.simulate(contactsep.thesis_design(n_modes=2),
                         model="hertz", t_end=0.03)
    text = repr(r)
    assert len(text) < 300 and "\n" not in text and "array" not in text
    assert "n_events=" in text and "hertz" in text


def test_the_single_impulse_figures_can_be_skipped():
    """single_impulse=False changes nothing but the eq. 23 figures (the
    Flores V_ref still comes from the model)."""
    design = contactsep.thesis_design(n_modes=2)
    for damping in ("none", "flores"):
        full = chatter.simulate(design, model="hertz", t_end=0.03,
                                damping=damping).to_json_dict()
        lean = chatter.simulate(design, model="hertz", t_end=0.03,
                                damping=damping,
                                single_impulse=False).to_json_dict()
        assert full.pop("single_impulse")["y3_max_in"] > 0
        assert lean.pop("single_impulse") == {}
        assert full == lean
