"""One name per quantity in every output (issue 30 item 5): a walk over
the JSON, CSV, Parquet, to_dict() and DataFrame outputs of every command
and result type, every key checked against one table — the unit
suffixes of docs/names-and-units.md ("The names"), the dimensionless names
listed there, and the structures (interval lists) named there — and the
same quantity under the same name wherever it appears."""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import re
from pathlib import Path

import numpy as np
import pytest

import contactsep
from contactsep.chatter import simulate
from contactsep.cli import main
from contactsep.model import Design, evaluate, fields

ROOT = Path(__file__).resolve().parents[2]
#: The table (docs/names-and-units.md, "The names").
SUFFIX = re.compile(r"^[A-Za-z0-9_]+_(in|s|lb|lb_s|in_s|psi|lb_in3|rad_s|"
                    r"cps|lb_s2_in|in_lb|lbin|s_per_in|lb_per_in|lb_in_rad|hz|pct)$")
DIMENSIONLESS = {
    "e", "R", "r", "N", "n_modes", "energy_ratio", "relative_difference",
    "bound_ratio", "above_bound",
    "p_exceed", "p_open", "status", "n", "n_failed", "n_open", "n_events",
    "seed", "samples", "designs", "count", "chatters", "at_window_end",
    "t_max_tied", "t_min_tied", "fixed_steps", "flight_steps",
    "flow_evaluations", "impacts", "circuit_open", "mode", "n_unconverged",
    "n_exceed", "model", "damping", "stepper", "backend", "precision",
    "end1", "end2", "end3", "impact_velocity", "lower_response",
    "lc_reading", "release", "data_set", "title", "event", "curve",
    "first_mode_share", "n_maxima", "data", "parameters", "static_correction", "dt_source",
    "contact", "law", "e_apparent", "button",
    "t_end_source", "verify", "dt_halvings", "energy_tolerance",
    "alias_share", "units", "n_modes_source",
    "verify_n_modes", "verify_status", "check_n_modes", "converged",
    "converged_n_modes", "converged_check_n_modes", "simulations",
    "contact_material",
    "separator_material", "law", "perturbation", "min_preload_spread",
    "ys_change", "change_from_unperturbed", "ys_tolerance",
    "p_open_ci95_high", "robust_tested", "robust_band", "samples_needed",
    "simulations_saved", "verdict", "search"}
#: Structures: lists of [start, end] intervals (s) or confidence
#: intervals (of a dimensionless probability), and groups of keys.
STRUCTURES = {"events", "circuit_open_intervals", "rest_intervals",
              "p_open_ci95", "p_exceed_ci95", "inputs", "design",
              "single_impulse", "work", "vary", "sample", "fixed",
              "settings", "impacts", "n_failed_by_status", "numerics",
              "changes", "converge_history"}
#: Attribute names that carry a unit: never an output key.
RAW = {f.name for f in dataclasses.fields(Design)
       if fields.unit(f.name)} | {
    "t1", "v_impact", "psi", "v0", "y3_max", "t_max", "y3_min", "t_min",
    "M1", "M2", "M3", "p1", "p2", "p3", "c3"}


#: The parts of a varied or sampled axis (in the axis's own unit, which
#: its key carries: vary.d_in.start).
AXIS_PARTS = {"start", "stop", "count", "values", "distribution", "mean",
              "sd", "low", "high"}


def leaves(value, path=()):
    """(key, value) of every key of a JSON value, nested; an axis's
    parts under its key are named by that key."""
    if isinstance(value, dict):
        for key, item in value.items():
            axis = len(path) >= 2 and path[-2] in ("vary", "sample")
            if not (axis and key in AXIS_PARTS):
                yield key, item, path
            yield from leaves(item, (*path, key))
    elif isinstance(value, list) and value and isinstance(value[0], dict):
        for item in value:
            yield from leaves(item, path)


#: The design's fields under their output names (the one table,
#: contactsep.model.fields).
DESIGN_KEYS = {fields.column_name(f) for f in fields.FIELDS}


def checked(keys) -> None:
    for key in keys:
        if key in DESIGN_KEYS:
            continue
        assert key not in RAW, f"{key}: a quantity with a unit, bare"
        assert SUFFIX.match(key) or key in DIMENSIONLESS or \
            key in STRUCTURES or _is_statistic(key), \
            f"{key}: not in the table of names"


def _is_statistic(key: str) -> bool:
    # a statistic puts the unit last: y3_max_mean_in, circuit_open_sd_s;
    # a relative change is dimensionless: first_impulse_change
    return bool(SUFFIX.match(key)) or key.endswith("_change")


def run_json(argv) -> dict:
    buffer = io.StringIO()
    with contextlib.redirect_stdout(buffer):
        assert main([*argv, "--json"]) == 0
    return json.loads(buffer.getvalue())


def csv_header(path: Path) -> list[str]:
    for line in path.read_text().splitlines():
        if not line.startswith("#"):
            return line.split(",")
    raise AssertionError(f"{path}: no header")


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("names")
    out = {"model": run_json(["model", "--n-modes", "6"]),
           "chatter": run_json(["chatter", "--model", "hertz",
                                "--n-modes", "4", "--dt", "5e-8",
                                "--t-end", "0.03", "--csv",
                                str(tmp / "gaps.csv")]),
           "appE": run_json(["chatter", "--model", "appE", "--n-modes",
                             "4", "--t-end", "0.03"]),
           "sweep": run_json(["sweep", "--vary", "h2=0.1:0.5:3",
                              "--workers", "1", "--threshold", "0.1",
                              "--csv", str(tmp / "sweep.csv")]),
           "chatter_sweep": run_json(["sweep", "--model", "hertz",
                                      "--vary", "h2=0.1:0.5:2",
                                      "--n-modes", "4", "--workers", "1",
                                      "--csv", str(tmp / "hertz.csv")])}
    out["csv"] = {name: csv_header(tmp / f"{name}.csv")
                  for name in ("gaps", "sweep", "hertz")}
    return out


def test_every_json_key_is_in_the_table(outputs):
    for name in ("model", "chatter", "appE", "sweep", "chatter_sweep"):
        checked(key for key, _, _ in leaves(outputs[name]))


def test_every_csv_column_is_in_the_table(outputs):
    for header in outputs["csv"].values():
        checked(header)
    for path in sorted((ROOT / "docs" / "studies").glob("*.csv")):
        checked(csv_header(path))


def test_the_design_has_one_set_of_names(outputs):
    model_design = dict(outputs["model"]["design"])
    # a design file's unit system, then its fields (n_modes given here)
    assert model_design.pop("units") == "us"
    chatter_design = outputs["chatter"]["inputs"]["design"]
    assert set(model_design) == set(chatter_design)
    # every field, but those shown only when given (x2_lower: None
    # keeps the outputs of designs without it unchanged)
    assert len(model_design) == len(dataclasses.fields(Design)) - len(
        fields.SHOWN_WHEN_GIVEN)
    assert fields.design_keys(Design(x2_lower=1.0))["x2_lower_in"] == 1.0
    assert "d_in" in model_design and "h2" not in model_design
    fixed = outputs["chatter_sweep"]["inputs"]["fixed"]
    assert set(fixed) <= set(model_design)


def test_the_models_results_have_one_set_of_names(outputs):
    ev = evaluate(contactsep.thesis_design(n_modes=6))
    as_dict = ev.to_dict()
    checked(as_dict)
    json_keys = set(outputs["model"]) - {"design"}
    assert json_keys == set(as_dict)
    frame = ev.to_pandas()
    assert set(frame.columns) <= json_keys
    assert set(ev.to_pandas(modes=True).columns) <= json_keys
    single = outputs["chatter"]["single_impulse"]
    assert set(single) - {"y3_max_impulse_form_in"} <= json_keys
    assert set(outputs["csv"]["sweep"]) - {"d_in"} <= json_keys


def test_a_python_sweep_has_the_commands_names(outputs):
    result = contactsep.sweep(vary=["h2=0.1:0.5:3"], threshold=0.1,
                              workers=1)
    assert result.to_pandas().columns.tolist() == outputs["csv"]["sweep"]
    summary = result.to_pandas("summary").columns
    checked(summary)
    assert set(summary) <= set(outputs["sweep"])


def test_chatter_outputs_share_their_names(outputs):
    r = simulate(contactsep.thesis_design(n_modes=4), model="hertz",
                 dt=5e-8, t_end=0.03)
    summary = r.to_pandas()
    checked(summary.columns)
    data = outputs["chatter"]
    scalars = {k for k, v in data.items() if not isinstance(v, (dict,
                                                                list))}
    assert scalars <= set(summary.columns)
    assert set(outputs["csv"]["hertz"]) - {"d_in"} <= scalars
    assert outputs["csv"]["gaps"] == r.to_pandas("gaps").columns.tolist()
    checked(r.to_pandas("openings").columns)
    assert np.isfinite(summary["first_impact_s"][0])
