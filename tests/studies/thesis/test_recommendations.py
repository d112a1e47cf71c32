"""The studies of the thesis's recommendations 3 and 4 (issue 28, items
4 and 5): ``study contact-points`` and ``study materials``, and the
material presets.

Independent paths: the mirror identity of a symmetric separator (the
study's own rows must hold it), the presets against the handbooks' SI
values converted by pint (contactsep.units), and the command line's
"last given wins" against the Design built by hand."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from contactsep.cli import main
from contactsep.errors import InputError
from contactsep.model import Design, materials
from contactsep.studies.thesis import contact_points as cp
from contactsep.studies.thesis import materials as mat
from contactsep.studies.plots import save_png
from contactsep import units

# the committed studies' comparison lives one folder up (tests/studies)
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))


def test_the_contact_points_study_is_its_own_mirror():
    """(a, b) and (L2 - a, L2 - b) are one system on the clamped-clamped
    separator: the study's rows pair up to round-off."""
    study = cp.contact_points(n_modes=4, ratios=(0.3, 0.5, 0.7),
                              preloads=(0.0,), workers=1)
    length = 2.5
    rows = {(round(a, 9), round(b, 9)): k for k, (a, b) in enumerate(
        zip(study["x2_in"], study["x2_lower_in"]))}
    assert len(rows) == 9
    for (a, b), k in rows.items():
        m = rows[(round(length - a, 9), round(length - b, 9))]
        assert study["n_events"][k] == study["n_events"][m]
        assert study["circuit_open_s"][k] == pytest.approx(
            study["circuit_open_s"][m], rel=1e-9)
        assert study["max_lower_gap_in"][k] == pytest.approx(
            study["max_lower_gap_in"][m], rel=1e-9)
    # and the positions matter: not every row is the same
    assert np.ptp(study["max_lower_gap_in"]) > 0.1 * np.max(
        study["max_lower_gap_in"])


def test_the_studies_refuse_the_fields_they_set():
    with pytest.raises(InputError, match="x2_lower"):
        cp.contact_points(x2_lower=1.0)
    with pytest.raises(InputError, match="E2"):
        mat.materials(E2=3e7)


#: Handbook values in SI (the ASM / CDA / MatWeb tables docs/model.md
#: cites): E, density.
HANDBOOK = {"steel": ("205 GPa", "7.87 g/cm^3"),
            "brass": ("110 GPa", "8.53 g/cm^3"),
            "beryllium-copper": ("128 GPa", "8.25 g/cm^3"),
            "aluminium": ("68.9 GPa", "2.70 g/cm^3"),
            "phosphor-bronze": ("110 GPa", "8.86 g/cm^3")}


@pytest.mark.parametrize("name", list(HANDBOOK))
def test_the_presets_are_the_handbook_values_in_the_packages_units(name):
    preset = materials.material(name)
    modulus, density = HANDBOOK[name]
    assert preset.E_psi == pytest.approx(units.convert(modulus, "psi", "E"),
                                         rel=0.005)
    # a weight density: mass density times g, in lb/in^3 (lbf)
    assert preset.gamma_lb_in3 == pytest.approx(
        units.convert(density, "lb/in^3", "gamma"), rel=0.005)
    assert 0.0 < preset.nu < 0.5
    assert preset.yield_pressure_psi == 1.6 * preset.yield_strength_psi


def test_the_phosphor_bronze_preset_is_the_c51000_data_sheet():
    """Converted by hand: 110 GPa / (4.4482216152605 N / 0.0254^2 m^2)
    = 15.954e6 psi (the sheet's own 16,000 ksi is that to 0.3 %);
    8.86 g/cm^3 = 8860 kg/m^3 / (0.45359237 kg / 0.0254^3 m^3) =
    0.32009 lb/in^3 (the sheet's 0.320)."""
    bronze = materials.material("C51000")
    psi_pa = 4.4482216152605 / 0.0254**2
    assert bronze.name == "phosphor-bronze"
    assert (bronze.E_psi, bronze.gamma_lb_in3, bronze.nu) == \
        (16.0e6, 0.320, 0.34)
    assert bronze.E_psi == pytest.approx(110e9 / psi_pa, rel=0.003)
    assert bronze.gamma_lb_in3 == pytest.approx(
        8860.0 / (0.45359237 / 0.0254**3), rel=0.0005)
    assert materials.material_fields("phosphor-bronze", "13") == {
        "E1": 16.0e6, "gamma1": 0.320, "nu1": 0.34,
        "E3": 16.0e6, "gamma3": 0.320, "nu3": 0.34}


def test_the_materials_study_keeps_its_four_presets():
    """Its committed rows are of four presets; one added for designs
    does not change the study."""
    assert materials.STUDY_MATERIALS == (
        "steel", "brass", "beryllium-copper", "aluminium")
    assert "phosphor-bronze" not in \
        mat.materials.__kwdefaults__["contacts"]


def test_material_names_and_aliases():
    assert materials.material("Aluminum").name == "aluminium"
    assert materials.material("becu").name == "beryllium-copper"
    with pytest.raises(materials.MaterialError, match="one of steel"):
        materials.material("copper")


def _design(argv, capsys) -> dict:
    assert main(["model", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)["design"]


def test_a_preset_fills_a_member_and_the_last_given_wins(capsys, tmp_path):
    steel = materials.material("steel")
    d = _design(["--material2", "steel"], capsys)
    assert (d["E2_psi"], d["gamma2_lb_in3"], d["nu2"]) == (
        steel.E_psi, steel.gamma_lb_in3, steel.nu)
    assert d["E1_psi"] == Design().E1
    assert _design(["--material2", "steel", "--E2", "25e6"],
                   capsys)["E2_psi"] == 25e6
    assert _design(["--E2", "25e6", "--material2", "steel"],
                   capsys)["E2_psi"] == steel.E_psi
    every = _design(["--material", "brass"], capsys)
    assert every["E1_psi"] == every["E2_psi"] == every["E3_psi"] == 16e6
    path = tmp_path / "d.json"
    path.write_text('{"material2": "brass", "E2_psi": 1.2e7}')
    from_file = _design(["--design", str(path)], capsys)
    assert (from_file["E2_psi"], from_file["gamma2_lb_in3"]) == (1.2e7,
                                                                 0.308)
    assert main(["model", "--material3", "copper"]) == 2
    assert "--material3: found 'copper'" in capsys.readouterr().err


def test_the_materials_study_runs_and_draws(tmp_path):
    study = mat.materials(n_modes=2, contacts=("aluminium",),
                          separators=("aluminium", "steel"),
                          preloads=(0.0,), workers=1)
    laws = 2 if mat.thornton_available() else 1
    assert len(study) == 2 * laws
    assert list(study["separator_material"]) == ["aluminium", "steel"] * laws
    # the yield-pressure column comes with Thornton's law, only
    assert ("yield_pressure_psi" in study.columns) == \
        mat.thornton_available()
    pytest.importorskip("matplotlib")
    save_png(study, tmp_path / "m.png")
    assert (tmp_path / "m.png").read_bytes()[:4] == b"\x89PNG"
    points = cp.contact_points(n_modes=2, ratios=(0.4, 0.6),
                               preloads=(0.0,), workers=1)
    save_png(points, tmp_path / "p.png")
    assert (tmp_path / "p.png").read_bytes()[:4] == b"\x89PNG"


def _one_row_again(name, row):
    """The study run again on the one row's grid point, as its function
    builds it: contact-points on the ratios of the row's two contact
    points (four simulations), materials on the row's two materials and
    preload (one simulation a law)."""
    if name == "contact-points":
        length = float(cp.thesis_study_design().L2)
        ratios = tuple(dict.fromkeys(
            (float(row["x2_in"]) / length,
             float(row["x2_lower_in"]) / length)))
        study = cp.contact_points(ratios=ratios,
                                  preloads=(float(row["preload_lb"]),),
                                  workers=1)
        keys = ("x2_in", "x2_lower_in")
    else:
        study = mat.materials(contacts=(row["contact_material"],),
                              separators=(row["separator_material"],),
                              preloads=(float(row["preload_lb"]),),
                              workers=1)
        keys = ("law",) if "law" in row else ()
    columns = study.columns
    (k,) = [i for i in range(len(study))
            if all(str(columns[key][i]) == row[key]
                   or (key != "law"
                       and float(columns[key][i]) == float(row[key]))
                   for key in keys)]
    return study, k


@pytest.mark.parametrize("name", ["contact-points", "materials"])
def test_one_committed_row_is_what_the_code_computes(name):
    """The committed CSVs of docs/studies (50 and 64 three-beam
    simulations; regenerate with `contactsep study NAME --out
    docs/studies`, the command docs/circuit-opening.md names), fast:
    one row, chosen by the study's name, simulated again by the study's
    own function on that row's grid point; each column to 1e-10 of its
    column's largest magnitude (the files hold 12 significant digits),
    the '#' lines that do not count the grid's simulations or list its
    presets the same."""
    import zlib

    from conftest import ROOT
    from test_committed_outputs import COMMITTED, parse
    assert f"contactsep study {name}" in \
        (ROOT / "docs" / "circuit-opening.md").read_text()
    comments, header, rows = parse((COMMITTED / f"{name}.csv").read_text())
    k = zlib.crc32(name.encode()) % len(rows)
    row = dict(zip(header, rows[k]))
    study, i = _one_row_again(name, row)
    fresh_comments, fresh_header, fresh_rows = parse(study.csv_text())
    assert fresh_header == header

    def kept(lines):
        return [line for line in lines
                if not line.endswith(" simulations")
                and not line.startswith("# presets ")]
    assert kept(fresh_comments) == kept(comments)
    for j, column in enumerate(header):
        old, new = rows[k][j], fresh_rows[i][j]
        try:
            a, b = float(old), float(new)
        except ValueError:
            assert old == new, (name, column)
            continue
        scale = max(abs(float(r[j])) for r in rows)
        assert a == b or abs(a - b) <= 1e-10 * scale, (name, column, a, b)
    assert (COMMITTED / f"{name}.png").read_bytes()[:8] == \
        b"\x89PNG\r\n\x1a\n"


def _csv_rows(name):
    import csv
    from test_committed_outputs import COMMITTED
    lines = [line for line in (COMMITTED / f"{name}.csv").read_text()
             .splitlines() if not line.startswith("#")]
    return list(csv.DictReader(lines))


def _doc_table(heading):
    """The first Markdown table after ``heading`` in docs/circuit-opening.md:
    {row label: [cells]}."""
    from conftest import ROOT
    text = (ROOT / "docs" / "circuit-opening.md").read_text().split(heading, 1)[1]
    rows = [line for line in text.split("\n\n| ", 1)[1].split("\n\n")[0]
            .splitlines()]
    out = {}
    for line in rows[2:]:
        cells = [c.strip().strip("*") for c in line.strip("| ").split("|")]
        out[cells[0]] = cells[1:]
    return out


def _gap_and_open(spec: str, formats: tuple[str, str]) -> str:
    """A table cell: the datum roles of the largest lower gap with no
    preload and the open time at 6 lb, both scaled by 1000 (0.001 in,
    ms), of the row ``spec`` (``FILE:{}@FILTERS,preload_lb={}``)."""
    gap = spec.format("max_lower_gap_in", 0)
    opened = spec.format("circuit_open_s", 6)
    return (f"{{datum}}`=1000 * [{gap}]:{formats[0]}` / "
            f"{{datum}}`=1000 * [{opened}]:{formats[1]}`")


def test_the_docs_tables_are_the_committed_studies():
    """docs/circuit-opening.md's two tables (gap in 0.001 in / open ms at
    6 lb): every cell the datum roles of its grid point's rows of
    docs/studies/contact-points.csv and materials.csv (the roles resolve
    to the files' values: tests/project/test_data_values.py), and every
    grid point of the files in a cell."""
    table = _doc_table("open time at 6 lb (ms), upper contact's x2 across")
    rows = _csv_rows("contact-points")
    x2s = ("0.5", "0.875", "1.25", "1.625", "2")
    assert sorted(map(float, table)) == sorted(
        {float(r["x2_lower_in"]) for r in rows})
    assert sorted({r["x2_in"] for r in rows}, key=float) == list(x2s)
    for label, cells in table.items():
        assert cells == [_gap_and_open(
            "studies/contact-points.csv:{}@"
            f"x2_in={x2},x2_lower_in={label},preload_lb={{}}",
            (".3g", ".2f")) for x2 in x2s], label
    table = _doc_table("Largest lower\ngap with no preload (0.001 in) / "
                       "open time at 6 lb (ms):")
    rows = _csv_rows("materials")
    names = {"steel": "steel", "brass": "brass", "aluminium": "aluminium",
             "beryllium copper": "beryllium-copper"}
    separators = ("steel", "brass", "beryllium-copper", "aluminium")
    assert {names[label] for label in table} == \
        {r["contact_material"] for r in rows} == set(separators)
    for label, cells in table.items():
        assert cells == [_gap_and_open(
            "studies/materials.csv:{}@law=hertz,"
            f"contact_material={names[label]},separator_material={sep},"
            "preload_lb={}", (".1f", ".1f")) for sep in separators], label
    # the prose on Thornton's rows: closed at 6 lb but for BeCu on BeCu
    thornton = [r for r in rows if r.get("law") == "thornton"]
    assert len(thornton) == 32
    pressed = [r for r in thornton if float(r["preload_lb"]) == 6.0]
    opened = [(r["contact_material"], r["separator_material"])
              for r in pressed if int(r["n_events"]) > 0]
    assert opened == [("beryllium-copper", "beryllium-copper")]
    becu = next(r for r in pressed if int(r["n_events"]) > 0)
    assert (round(1e3 * float(becu["circuit_open_s"]), 1),
            int(becu["n_events"])) == (2.4, 51)
    free = [r for r in thornton if float(r["preload_lb"]) == 0.0]
    assert (round(1e3 * min(float(r["circuit_open_s"]) for r in free)),
            round(1e3 * max(float(r["circuit_open_s"]) for r in free))) \
        == (22, 33)
    assert (min(int(r["n_events"]) for r in free),
            max(int(r["n_events"]) for r in free)) == (6, 17)


def test_the_materials_study_runs_thorntons_law_where_simulate_has_it(
        monkeypatch):
    """The hook for issue 28 item 1's law: a simulate() that takes
    ``contact`` and ``yield_pressure`` gets the Thornton rows, at the
    lower of the two materials' yield pressures (a stand-in simulate
    records what it is asked; the Hertz rows still run the real one)."""
    from contactsep.chatter import simulate as real
    asked = []

    def simulate(design, contact="hertz", yield_pressure=None, **kw):
        asked.append((contact, yield_pressure, kw["nu"]))
        return real(design, **kw)

    monkeypatch.setattr(mat, "simulate", simulate)
    assert mat.thornton_available()
    study = mat.materials(n_modes=2, contacts=("beryllium-copper",),
                          separators=("aluminium",), preloads=(0.0,),
                          workers=1)
    assert list(study["law"]) == ["hertz", "thornton"]
    becu, al = materials.material("becu"), materials.material("aluminium")
    assert list(study["yield_pressure_psi"]) == [al.yield_pressure_psi] * 2
    assert asked == [("hertz", None, becu.nu),
                     ("thornton", 1.6 * al.yield_strength_psi, becu.nu)]
