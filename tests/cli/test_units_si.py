"""``--units si`` (issue 49, item 4): bare numbers on the command line
read in m, N, s, Pa, kg/m^3, and the --json of model, chatter and
preload in SI under SI key suffixes; refused in one line where an
output would stay in inch-pound units.  With the default ``us`` every
output is unchanged (the other tests of the commands hold that).

The factors are written here from the units' definitions (1 in = 0.0254
m, 1 lbf = 4.4482216152605 N, 1 lb = 0.45359237 kg), not taken from the
package's table."""

from __future__ import annotations

import json
import math

import pytest

from contactsep.cli import main
from contactsep.model import fields, names

M = 0.0254
N = 4.4482216152605
PA = N / M**2
KG_M3 = 0.45359237 / M**3


def run_json(argv, capsys) -> dict:
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_model_in_si_is_its_inch_pound_run_converted(capsys):
    us = run_json(["model", "--json", "--L1", "19", "--d", "0.25"], capsys)
    si = run_json(["model", "--json", "--units", "si", "--L1",
                   repr(19 * M), "--d", repr(0.25 * M)], capsys)
    assert si["design"]["units"] == "si"
    assert si["design"]["L1_m"] == pytest.approx(19 * M, rel=1e-14)
    assert si["design"]["d_m"] == pytest.approx(0.25 * M, rel=1e-14)
    assert si["design"]["E1_Pa"] == pytest.approx(
        us["design"]["E1_psi"] * PA, rel=1e-14)
    assert si["design"]["gamma2_kg_m3"] == pytest.approx(
        us["design"]["gamma2_lb_in3"] * KG_M3, rel=1e-14)
    assert si["design"]["mass1_N"] == 0.0
    expected = {"y3_max_m": us["y3_max_in"] * M,
                "t_max_s": us["t_max_s"],
                "v0_m_s": us["v0_in_s"] * M,
                "psi_N_s": us["psi_lb_s"] * N,
                "M1_kg": us["M1_lb_s2_in"] * N / M,
                "R": us["R"]}
    for key, value in expected.items():
        assert si[key] == pytest.approx(value, rel=1e-12), key
    assert si["p1_rad_s"] == pytest.approx(us["p1_rad_s"], rel=1e-12)
    assert si["c3_m"] == pytest.approx([c * M for c in us["c3_in"]],
                                       rel=1e-12)


def test_a_bare_si_number_equals_the_same_value_typed_with_its_unit(
        capsys):
    bare = run_json(["model", "--json", "--units", "si", "--L1", "0.4826",
                     "--E2", "200e9", "--gamma3", "7850"], capsys)
    typed = run_json(["model", "--json", "--units", "si", "--L1",
                      "482.6mm", "--E2", "200GPa", "--gamma3",
                      "7.85g/cm3"], capsys)
    assert bare == typed
    # a value typed with a unit is read as typed, whatever --units says
    inches = run_json(["model", "--json", "--units", "si", "--L1", "19in"],
                      capsys)
    assert inches["design"]["L1_m"] == pytest.approx(19 * M, rel=1e-14)


def test_chatter_in_si_reads_the_preload_in_newtons(capsys):
    argv = ["chatter", "--model", "hertz", "--n-modes", "4", "--t-end",
            "0.01", "--json"]
    us = run_json([*argv, "--preload", "1"], capsys)
    si = run_json([*argv, "--units", "si", "--preload", repr(N)], capsys)
    assert si["inputs"]["preload_N"] == pytest.approx(N, rel=1e-14)
    assert us["inputs"]["preload_lb"] == 1.0
    assert si["n_events"] == us["n_events"]
    assert si["max_lower_gap_m"] == pytest.approx(
        us["max_lower_gap_in"] * M, rel=1e-9)
    assert si["energy_initial_J"] == pytest.approx(
        us["energy_initial_lbin"] * N * M, rel=1e-9)
    assert si["inputs"]["button_radius_m"] == pytest.approx(
        us["inputs"]["button_radius_in"] * M, rel=1e-14)
    assert not any(key.endswith(("_in", "_lb", "_psi", "_lbin"))
                   for key in si)


@pytest.mark.parametrize("argv, words", [
    (["study", "fig5", "--units", "si"], "--units si: study writes in, lb, "
                                         "s; the commands that take it are "
                                         "model, chatter, preload, sweep"),
])
def test_units_si_is_refused_where_an_output_would_stay_inch_pound(
        argv, words, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
    assert not (tmp_path / "gaps.csv").exists()


def test_every_unit_suffix_of_the_outputs_has_an_si_twin():
    suffixes = {entry[0] for entry in fields.FIELDS.values()} | \
        {entry[0] for entry in fields.SETTINGS.values()}
    keys = [key for _, key, _, _ in names.RESULTS] + \
        [key for key, _, _ in names.ENERGY_BOOK + names.CONTACT_LAW] + \
        [key for _, key, _ in names.PER_MODE]
    for suffix in suffixes - {""}:
        assert suffix in names.SI_SUFFIXES, suffix
    for key in keys:
        if key in ("R", "contact"):
            assert names.si_key(key) is None
        else:
            assert names.si_key(key) is not None, key


def test_model_text_in_si_is_its_inch_pound_text_converted(capsys):
    def rows(argv):
        assert main(["model", *argv]) == 0
        return {line.split()[0]: (float(line.split()[2]), line.split()[3])
                for line in capsys.readouterr().out.splitlines()}
    us, si = rows([]), rows(["--units", "si"])
    assert si["y3_max_m"] == (pytest.approx(us["y3_max_in"][0] * M,
                                            rel=1e-5), "m")
    assert si["v0_m_s"] == (pytest.approx(us["v0_in_s"][0] * M, rel=1e-5),
                            "m/s")
    assert si["psi_N_s"][0] == pytest.approx(us["psi_lb_s"][0] * N,
                                             rel=1e-5)
    assert si["M2_kg"] == (pytest.approx(us["M2_lb_s2_in"][0] * N / M,
                                         rel=1e-5), "kg")
    assert si["t1_s"] == us["t1_s"] and si["R"] == us["R"]
    assert len(si) == len(us)


def test_an_si_design_file_reads_back_as_its_design(tmp_path, capsys):
    """Every design of the family through model --units si --json and
    back: the same Design (a bare SI number divided back and rounded to
    15 digits is the inch-pound number)."""
    from design_family import FAMILY, UNSEEN

    import contactsep
    for name, design in {**FAMILY, **UNSEEN}.items():
        us = tmp_path / f"{name}.json"
        design.to_file(us)
        si = tmp_path / f"{name}_si.json"
        si.write_text(json.dumps(run_json(
            ["model", "--json", "--units", "si", "--design", str(us)],
            capsys)))
        data = json.loads(si.read_text())
        assert data["design"]["units"] == "si"
        assert data["design"]["L1_m"] == pytest.approx(design.L1 * M,
                                                       rel=1e-14)
        back = contactsep.load_design(si)
        assert back == contactsep.load_design(us), name


def test_an_si_file_written_by_hand_is_read_in_si(tmp_path, capsys):
    path = tmp_path / "relay.json"
    path.write_text(json.dumps({"units": "si", "L1_m": 0.0305, "h1": 2.5e-4,
                                "E1_Pa": 200e9, "gamma1": 7850,
                                "b1_m": "6 mm", "ys": 0.0005}))
    got = run_json(["model", "--json", "--design", str(path)], capsys)
    design = got["design"]
    assert design["L1_in"] == pytest.approx(0.0305 / M, rel=1e-14)
    assert design["h1_in"] == pytest.approx(2.5e-4 / M, rel=1e-14)
    assert design["b1_in"] == pytest.approx(6 / 25.4, rel=1e-14)
    assert design["E1_psi"] == pytest.approx(200e9 / PA, rel=1e-14)
    assert design["gamma1_lb_in3"] == pytest.approx(7850 / KG_M3,
                                                    rel=1e-14)
    assert design["ys_in"] == pytest.approx(0.0005 / M, rel=1e-14)


def test_preload_in_si_is_its_inch_pound_answer_converted(planted_preload,
                                                          capsys):
    """The search planted (tests/planted_preload.py): the same answer,
    in newtons, and every window and tested preload with it."""
    argv = ["preload", "--n-modes", "4", "--workers", "1", "--progress",
            "never", "--json"]
    us = run_json([*argv, "--open-threshold", "1e-6"], capsys)
    si = run_json([*argv, "--units", "si", "--open-threshold",
                   repr(1e-6 * M)], capsys)
    assert us["inputs"]["settings"]["open_threshold"] == 1e-6
    assert si["inputs"]["settings"]["open_threshold_m"] == pytest.approx(
        1e-6 * M, rel=1e-14)
    assert si["inputs"]["design"]["E1_Pa"] == pytest.approx(
        us["inputs"]["design"]["E1"] * PA, rel=1e-14)
    assert si["min_preload_N"] == pytest.approx(us["min_preload_lb"] * N,
                                                rel=1e-14)
    assert len(si["event_windows_N"]) == len(us["event_windows_lb"])
    for window, twin in zip(si["event_windows_N"], us["event_windows_lb"]):
        assert window == pytest.approx([p * N for p in twin], rel=1e-14)
    assert [t["preload_N"] for t in si["tested"]] == pytest.approx(
        [t["preload_lb"] * N for t in us["tested"]], rel=1e-14)
    assert si["inputs"]["design"]["L1_m"] == pytest.approx(19 * M,
                                                           rel=1e-14)


@pytest.mark.parametrize("option, typed, key, si_value", [
    ("--L1", "25mm", "L1_m", 0.025),
    ("--b1", "5mm", "b1_m", 0.005),
    ("--h1", "0.3mm", "h1_m", 0.0003),
    ("--h1", "0.12mm", "h1_m", 0.00012),
    ("--d", "1.6mm", "d_m", 0.0016),
    ("--ys", "0.45mm", "ys_m", 0.00045),
    ("--E2", "200GPa", "E2_Pa", 200e9),
    ("--E1", "117GPa", "E1_Pa", 117e9),
])
def test_a_value_typed_in_si_is_written_as_typed(option, typed, key,
                                                 si_value, tmp_path,
                                                 capsys):
    """A design drawn in mm is written back in mm's own decimals (not
    0.00499999999999999 for 5 mm), and the file still reads back as the
    design the options gave, bit for bit."""
    import contactsep
    data = run_json(["model", "--json", "--units", "si", option, typed],
                    capsys)
    assert data["design"][key] == si_value
    path = tmp_path / "typed.json"
    path.write_text(json.dumps(data))
    us = run_json(["model", "--json", option, typed], capsys)
    plain = tmp_path / "plain.json"
    plain.write_text(json.dumps(us))
    assert contactsep.load_design(path) == contactsep.load_design(plain)


def _text_rows(text: str) -> dict:
    """'  first impulse   0.0123 lb s' -> {'first impulse': ('0.0123',
    'lb s')}: the summary's rows, read here as a person reads them."""
    import re
    rows = {}
    for line in text.splitlines():
        found = re.match(r"^  ([a-z].*?)\s{2,}(\S+)(?: (.*))?$", line)
        if found:
            rows[found[1]] = (found[2], (found[3] or "").strip())
    return rows


def _design_line(text: str) -> dict:
    line = next(s for s in text.splitlines() if s.startswith("design: "))
    parts = [p.split(" ") for p in line[len("design: "):].split(", ")]
    return {p[0]: (p[1], " ".join(p[2:])) for p in parts}


def test_chatter_text_in_si_is_its_inch_pound_text_converted(capsys):
    """The same run in us and in si: every quantity of the text in m,
    N, N s, Pa, kg/m^3, by the units' definitions (this file's factors),
    the counts and times unchanged."""
    common = ["chatter", "--n-modes", "4", "--t-end", "0.02"]
    assert main(common + ["--preload", "0.2", "--d", "0.3"]) == 0
    us = capsys.readouterr().out
    assert main(common + ["--units", "si", "--preload", repr(0.2 * N),
                          "--d", repr(0.3 * M)]) == 0
    si = capsys.readouterr().out
    factors = {"in": (M, "m"), "lb s": (N, "N s"), "s": (1.0, "s"),
               "": (1.0, "")}
    rows_us, rows_si = _text_rows(us), _text_rows(si)
    assert rows_us.keys() == rows_si.keys()
    checked = 0
    for label, (number, unit) in rows_us.items():
        if unit not in factors:
            continue
        factor, si_unit = factors[unit]
        assert rows_si[label][1] == si_unit, label
        try:
            value = float(number)
        except ValueError:      # '-', 'yes', a status
            assert rows_si[label][0] == number, label
            continue
        assert float(rows_si[label][0]) == pytest.approx(
            value * factor, rel=1e-5), label
        checked += 1
    assert checked >= 8
    design_us, design_si = _design_line(us), _design_line(si)
    for name, unit, factor, si_unit in [
            ("L1", "in", M, "m"), ("d", "in", M, "m"),
            ("E2", "psi", PA, "Pa"), ("gamma1", "lb/in^3", KG_M3, "kg/m^3")]:
        assert design_us[name][1] == unit and design_si[name][1] == si_unit
        assert float(design_si[name][0]) == pytest.approx(
            float(design_us[name][0]) * factor, rel=1e-5), name
    assert "preload 0.889644 N" in si and "preload 0.2 lb" in us


def test_preload_text_and_csv_in_si_are_its_inch_pound_ones_converted(
        planted_preload, capsys, tmp_path):
    """The planted search's text and CSV under --units si: every force in
    N (the us run's times N), every other column and count unchanged, no
    number left in lb or in (the grid's definition, "2^(k/4) lb", is a
    name of the search, not a value)."""
    import re
    argv = ["preload", "--n-modes", "4", "--workers", "1", "--progress",
            "never"]
    assert main([*argv, "--csv", str(tmp_path / "us.csv")]) == 0
    us_text = capsys.readouterr().out
    assert main([*argv, "--units", "si", "--open-threshold", repr(1e-6 * M),
                 "--csv", str(tmp_path / "si.csv")]) == 0
    si_text = capsys.readouterr().out

    def table(name):
        lines = (tmp_path / name).read_text().splitlines()
        comments = [line for line in lines if line.startswith("#")]
        rows = [line.split(",") for line in lines if not line.startswith("#")]
        return comments, rows[0], rows[1:]

    us_comments, us_header, us_rows = table("us.csv")
    si_comments, si_header, si_rows = table("si.csv")
    assert us_header[1] == "preload_lb" and si_header[1] == "preload_N"
    assert si_header[:1] + si_header[2:] == us_header[:1] + us_header[2:]
    assert len(si_rows) == len(us_rows) > 10
    for us, si in zip(us_rows, si_rows):
        assert float(si[1]) == pytest.approx(float(us[1]) * N, rel=1e-14)
        assert si[:1] + si[2:] == us[:1] + us[2:]
    answer_lb = float(next(c for c in us_comments
                           if c.startswith("# min_preload_lb = ")
                           ).rpartition("= ")[2])
    answer_n = float(next(c for c in si_comments
                          if c.startswith("# min_preload_N = ")
                          ).rpartition("= ")[2])
    assert answer_n == pytest.approx(answer_lb * N, rel=1e-5)
    # the verdict, last line of the text, with the answer in N
    assert f"{answer_lb:.4g} lb" in us_text.splitlines()[-1]
    assert f"{answer_lb * N:.4g} N" in si_text.splitlines()[-1]
    for text in (si_text, "\n".join(si_comments)):
        left = re.findall(r"[0-9.]+ (?:lb|in)\b", text)
        assert not left, left
        assert " lb" in us_text


def test_preload_tolerances_in_si_are_the_inch_pound_ones(planted_preload,
                                                          capsys):
    """--units si reads --tolerance's bare numbers in SI, as it reads
    every other option's: d uniform over 6.096-6.604 mm draws the designs
    0.24-0.26 in draws, and the robust answer is the same, in N."""
    argv = ["preload", "--n-modes", "4", "--workers", "1", "--progress",
            "never", "--json", "--samples", "20", "--seed", "1",
            "--p-target", "0.2"]
    us = run_json([*argv, "--tolerance", "d=uniform(0.24,0.26)"], capsys)
    si = run_json([*argv, "--units", "si", "--open-threshold",
                   repr(1e-6 * M), "--tolerance",
                   f"d=uniform({0.24 * M!r},{0.26 * M!r})"], capsys)
    assert math.isfinite(us["robust"]["min_preload_lb"])
    assert si["robust"]["min_preload_N"] == pytest.approx(
        us["robust"]["min_preload_lb"] * N, rel=1e-14)
    assert si["robust"]["n"] == us["robust"]["n"] > 0
    assert si["robust"]["n_open"] == us["robust"]["n_open"]


def _table(path):
    lines = path.read_text().splitlines()
    rows = [line.split(",") for line in lines if not line.startswith("#")]
    return [line for line in lines if line.startswith("#")], rows[0], rows[1:]


#: Each column's SI twin and factor, written here from the definitions.
SWEEP_TWINS = {"d_in": ("d_m", M), "y3_max_in": ("y3_max_m", M),
               "t_max_s": ("t_max_s", 1.0), "psi_lb_s": ("psi_N_s", N),
               "v0_in_s": ("v0_m_s", M), "status": ("status", None),
               "first_impact_s": ("first_impact_s", 1.0),
               "first_impulse_lb_s": ("first_impulse_N_s", N),
               "max_lower_gap_in": ("max_lower_gap_m", M),
               "circuit_open_s": ("circuit_open_s", 1.0),
               "first_circuit_open_s": ("first_circuit_open_s", 1.0),
               "n_events": ("n_events", None)}


def _same_table_converted(us_path, si_path):
    us_comments, us_header, us_rows = _table(us_path)
    si_comments, si_header, si_rows = _table(si_path)
    assert si_header == [SWEEP_TWINS[k][0] for k in us_header]
    assert len(si_rows) == len(us_rows) > 0
    for us, si in zip(us_rows, si_rows):
        for key, a, b in zip(us_header, us, si):
            factor = SWEEP_TWINS[key][1]
            if factor is None or a == "nan":
                assert a == b, key
            else:   # each written to 12 digits: 5e-12 of it apiece
                assert float(b) == pytest.approx(float(a) * factor,
                                                 rel=1e-11), key
    return us_comments, si_comments


def test_an_eq23_sweep_in_si_is_its_inch_pound_sweep_converted(
        tmp_path, capsys):
    """--vary's bare ends in m: the CSV, the Parquet table and the JSON
    summary are the inch-pound sweep's, under SI names, in SI; the
    comments name SI units and no inch-pound one."""
    import re
    us = run_json(["sweep", "--vary", "h2=0.1:0.8:8", "--workers", "1",
                   "--csv", str(tmp_path / "us.csv"), "--json"], capsys)
    si = run_json(["sweep", "--units", "si", "--vary",
                   f"h2={0.1 * M!r}:{0.8 * M!r}:8", "--workers", "1",
                   "--csv", str(tmp_path / "si.csv"), "--parquet",
                   str(tmp_path / "si.parquet"), "--json"], capsys)
    _, si_comments = _same_table_converted(tmp_path / "us.csv",
                                           tmp_path / "si.csv")
    text = "\n".join(si_comments)
    assert "vary d_m: 8 values from 0.00254 to 0.02032" in text
    assert not re.findall(r"_in\b|_lb|_psi|inch", text), text
    assert si["y3_max_mean_m"] == pytest.approx(us["y3_max_mean_in"] * M,
                                                rel=1e-14)
    assert si["inputs"]["vary"]["d_m"]["stop"] == pytest.approx(0.8 * M,
                                                               rel=1e-14)
    pq = pytest.importorskip("pyarrow.parquet")
    table = pq.read_table(tmp_path / "si.parquet")
    assert table.column_names == [SWEEP_TWINS[k][0] for k in
                                  _table(tmp_path / "us.csv")[1]]
    meta = json.loads(table.schema.metadata[b"contactsep"])
    assert "d_m" in meta["inputs"]["vary"]


def test_a_hertz_sweep_in_si_reads_its_preload_and_samples_in_si(
        tmp_path, capsys):
    """--preload in N and --sample's bare numbers in m draw the designs
    the inch-pound options draw: the same rows, converted."""
    common = ["sweep", "--model", "hertz", "--n-modes", "4", "--t-end",
              "0.05", "--samples", "3", "--workers", "1"]
    assert main([*common, "--preload", "0.2", "--sample",
                 "d=normal(0.25,0.005)", "--csv",
                 str(tmp_path / "us.csv")]) == 0
    assert main([*common, "--units", "si", "--preload", repr(0.2 * N),
                 "--sample", f"d=normal({0.25 * M!r},{0.005 * M!r})",
                 "--csv", str(tmp_path / "si.csv")]) == 0
    capsys.readouterr()
    us_comments, si_comments = _same_table_converted(
        tmp_path / "us.csv", tmp_path / "si.csv")
    assert any(c.startswith("# fixed preload_N = 0.889644") for c in
               si_comments)
    assert "a contact is open above 2.54e-08 m" in "\n".join(si_comments)
    events = [row[-2] for row in _table(tmp_path / "us.csv")[2]]
    assert any(int(e) > 0 for e in events)     # a sweep that opens


def test_chatter_csv_in_si_is_its_inch_pound_csv_converted(tmp_path,
                                                           capsys):
    """--units si --csv: the gaps in m (the us run's times 0.0254, to the
    9 digits written), the same times and openings, the inputs in SI."""
    common = ["chatter", "--model", "hertz", "--n-modes", "4", "--t-end",
              "0.03"]
    assert main([*common, "--csv", str(tmp_path / "us.csv")]) == 0
    assert main([*common, "--units", "si", "--csv",
                 str(tmp_path / "si.csv")]) == 0
    capsys.readouterr()
    us_comments, us_header, us_rows = _table(tmp_path / "us.csv")
    si_comments, si_header, si_rows = _table(tmp_path / "si.csv")
    assert us_header == ["t_s", "gap_upper_in", "gap_lower_in",
                         "circuit_open"]
    assert si_header == ["t_s", "gap_upper_m", "gap_lower_m",
                         "circuit_open"]
    assert len(si_rows) == len(us_rows) > 100
    for us, si in zip(us_rows, si_rows):
        assert si[0] == us[0] and si[3] == us[3]
        for a, b in zip(us[1:3], si[1:3]):     # 9 digits: 5e-9 apiece
            assert float(b) == pytest.approx(float(a) * M, rel=1e-8,
                                             abs=1e-300)
    assert "gap histories (m)" in si_comments[0]
    inputs = json.loads(si_comments[1].partition("# inputs: ")[2])
    assert inputs["design"]["L1_m"] == pytest.approx(19 * M, rel=1e-14)
