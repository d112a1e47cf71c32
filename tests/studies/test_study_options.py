"""Studies that honour or refuse their options (issue 19, item 7), and
their figures (item 6): --ys for Figure 5, refused overrides, --out for
one study, --dpi, study all without matplotlib, study chatter --png, the
convergence CSV's header."""

from __future__ import annotations

import functools
import struct

import numpy as np
import pytest

from contactsep import studies
from contactsep.cli import main
from contactsep.errors import InputError
from contactsep.model import evaluate

# the thesis studies' design: eq. 23's lower response as printed
from contactsep.studies.study import thesis_study_design

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def png_size(path) -> tuple[int, int]:
    data = path.read_bytes()
    assert data[:8] == PNG_MAGIC
    return struct.unpack(">II", data[16:24])


def test_fig5_draws_the_one_curve_it_is_given():
    one = studies.fig5(ys=0.4)
    assert np.all(one["ys_in"] == 0.4)
    three = studies.fig5()
    at_half = three["y3_max_in"][three["ys_in"] == 0.5]
    # eq. 23 is linear in the release height: y3 scales with y_s exactly
    np.testing.assert_allclose(one["y3_max_in"], at_half * 0.8, rtol=1e-13)
    assert np.array_equal(one["d_in"], three["d_in"][three["ys_in"] == 0.5])


def test_fig6_honours_the_thickness():
    s = studies.fig6(h2=0.5)
    at_tip = s["y3_max_in"][(s["curve"] == "I") & (s["r"] == 1.0)]
    assert at_tip[0] == float(evaluate(thesis_study_design(d=0.5)).y3_max)


@pytest.mark.parametrize("name, argv, message", [
    ("fig5", ["--d", "0.3"], "study fig5 sets d/h2 itself"),
    ("fig6", ["--x3", "15"], "study fig6 sets x3 itself"),
    ("fig6", ["--L3", "20"], "study fig6 sets L3 itself"),
    ("fig7", ["--x3", "15"], "study fig7 sets x3 itself"),
    ("fig8", ["--gamma2", "0.2"], "study fig8 sets gamma2 itself"),
    ("fig8", ["--x1", "18"], "study fig8 sets x1 itself"),
    ("fig23", ["--Lc", "4"], "study fig23 sets Lc itself"),
    ("fig23", ["--h2", "0.3"], "study fig23 sets d/h2 itself"),
    ("convergence", ["--n-modes", "8"], "sets n_modes itself"),
    ("table1", ["--n-modes", "8"], "sets n_modes itself"),
    ("table2", ["--d", "0.3"], "study table2 sets d/h2 itself"),
    ("table3", ["--set", "d=0.3"], "study table3 sets d/h2 itself"),
    ("chatter", ["--d", "0.3"], "study chatter takes no design options"),
    ("chatter", ["--backend", "numpy"], "takes no design options"),
    ("all", ["--out", "x", "--d", "0.3"], "study fig5 sets d/h2 itself"),
])
def test_a_study_refuses_what_it_sets(name, argv, message, capsys,
                                      tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["study", name, *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and message in err, err
    assert list(tmp_path.iterdir()) == []        # nothing written


def test_out_writes_one_studys_csv_and_png_at_its_dpi(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    assert main(["study", "fig8", "--out", str(tmp_path / "o"), "--dpi",
                 "50"]) == 0
    assert sorted(p.name for p in (tmp_path / "o").iterdir()) == [
        "fig8.csv", "fig8.png"]
    assert png_size(tmp_path / "o" / "fig8.png") == (300, 200)
    assert main(["study", "table2", "--png", str(tmp_path / "t.png")]) == 0
    assert png_size(tmp_path / "t.png") == (600, 500)
    assert main(["study", "fig5", "--dpi", "5"]) == 2
    capsys.readouterr()


def test_study_all_says_what_it_skips(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    assert main(["study", "all", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[-1].startswith("chatter: skipped")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        f"{n}.{e}" for n in studies.STUDIES for e in ("csv", "png"))


def test_without_matplotlib_nothing_is_computed_or_written(
        tmp_path, capsys, monkeypatch):
    from contactsep.studies import plots

    def missing():
        raise InputError("--png needs matplotlib: pip install "
                         "'contactsep[plot]'")

    computed = []
    monkeypatch.setattr(plots, "_pyplot", missing)
    for name, study in list(studies.STUDIES.items()):
        monkeypatch.setitem(studies.STUDIES, name,
                            lambda *a, _s=study, **k: computed.append(1)
                            or _s(*a, **k))
    out = tmp_path / "figs"
    for argv in (["all", "--out", str(out)], ["fig5", "--out", str(out)],
                 ["fig5", "--png", str(tmp_path / "f.png"), "--csv",
                  str(tmp_path / "f.csv")]):
        assert main(["study", *argv]) == 2
        assert "needs matplotlib" in capsys.readouterr().err
    assert computed == [] and list(tmp_path.iterdir()) == []


def test_study_chatter_draws_its_table(tmp_path, capsys, monkeypatch):
    pytest.importorskip("matplotlib")
    from contactsep.studies.thesis import chatter_table as chatter
    small = functools.partial(chatter.chatter_table, thicknesses=(0.25, 0.5),
                              modes=(4,), models=("appE", "newton"))
    monkeypatch.setattr(chatter, "chatter_table", small)
    assert main(["study", "chatter", "--png", str(tmp_path / "c.png"),
                 "--csv", str(tmp_path / "c.csv")]) == 0
    # a column per model, 9 x 5.4 in at 100 dpi (plot_panels.CHATTER_FIGSIZE)
    assert png_size(tmp_path / "c.png") == (900, 540)
    lines = (tmp_path / "c.csv").read_text().splitlines()
    assert len([line for line in lines if not line.startswith("#")]) == 5


def test_the_convergence_csv_says_which_n_is_which():
    text = studies.convergence().csv_text()
    comments = [line for line in text.splitlines() if line.startswith("#")]
    assert any("n_modes = per row" in line for line in comments)
    assert not any("N=4" in line or "n_modes = 4" in line
                   for line in comments)


def test_notes_give_the_design_that_was_evaluated():
    s = studies.fig8(e=0.5, L1=18.0)
    comments = s.csv_text().splitlines()[:len(s.notes) + 1]
    assert any("e = 0.5," in line for line in comments)
    assert any("L1 = 18 in" in line for line in comments)
    assert any("gamma2 = per row" in line for line in comments)
    assert all(line.startswith("# ") for line in comments)


def test_a_design_file_gives_way_to_the_studys_own_fields(tmp_path,
                                                          capsys):
    saved = tmp_path / "saved.json"
    assert main(["model", "--d", "0.3", "--restitution", "0.25",
                 "--lower-response", "as-printed", "--json"]) == 0
    saved.write_text(capsys.readouterr().out)
    csv_path = tmp_path / "f.csv"
    assert main(["study", "fig5", "--design", str(saved), "--csv",
                 str(csv_path)]) == 0
    capsys.readouterr()
    expected = studies.fig5(e=0.25).csv_text()
    assert csv_path.read_text() == expected
    assert main(["study", "fig5", "--design", str(saved), "--d",
                 "0.2"]) == 2
    assert "sets d/h2 itself" in capsys.readouterr().err
