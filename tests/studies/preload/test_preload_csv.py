"""The preload CSV, one layout for ``contactsep preload --csv F`` and the
Python API (``contactsep.preload(design).to_csv(F)``, the tutorial's
committed search): every simulation of the search a row, counted here
by a recording simulation, not by the code that writes the file; the
gallery's preload example reads a file the command wrote; the API's
file and the command's are the same."""

from __future__ import annotations

import csv
import io
import re
import warnings
from pathlib import Path

import pytest
from design_family import FAMILY
from planted_preload import CALLS, threshold

import contactsep
from contactsep.cli import main
from contactsep.model import thesis_design
from contactsep.studies.preload import chart as preload
ROOT = Path(__file__).resolve().parents[3]
GALLERY = ROOT / "examples" / "plot_02_preload.py"
#: The columns, written out here (not imported from the code under test).
COLUMNS = ["search", "preload_lb", "n", "n_open", "n_failed", "n_modes",
           "dt_s", "event"]
#: A real search short enough for a test: the thesis rig at N = 2 over
#: the first 30 ms (its answer is above zero there), no check at 4N.
REAL = ["--n-modes", "2", "--t-end", "0.03", "--no-converge"]


def _table(path):
    """(comment lines, header, rows as dicts) of a CSV the package
    wrote."""
    lines = Path(path).read_text().splitlines()
    comments = [line for line in lines if line.startswith("#")]
    assert lines[:len(comments)] == comments    # comments first
    header, *rows = list(csv.reader(io.StringIO("\n".join(
        lines[len(comments):]))))
    return comments, header, [dict(zip(header, r)) for r in rows]


@pytest.fixture
def recorded(monkeypatch):
    """Every simulation the search hands to its workers (one process:
    --workers 1), with its result, recorded around the real one."""
    runs = []
    real = preload._simulate_event

    def recording(task):
        event = real(task)
        runs.append((task, event))
        return event

    monkeypatch.setattr(preload, "_simulate_event", recording)
    return runs


def _command(capsys, *argv) -> None:
    status = main(["preload", "--workers", "1", "--progress", "never",
                   *argv])
    assert status == 0, capsys.readouterr().err
    capsys.readouterr()


def test_a_real_search_writes_every_simulation_it_ran(recorded, tmp_path,
                                                       capsys):
    path = tmp_path / "p.csv"
    _command(capsys, *REAL, "--csv", str(path))
    comments, header, rows = _table(path)
    assert header == COLUMNS
    assert len(rows) == len(recorded) > 100
    for row, (task, event) in zip(rows, recorded):
        assert float(row["preload_lb"]) == task.preload_lb  # every digit
        assert int(row["n_modes"]) == task.design.n_modes
        given = task.settings.get("dt")
        assert row["dt_s"] == ("" if given is None else repr(given))
        assert (row["n"], row["n_open"], row["n_failed"]) == (
            "1", str(int(event)), "0")
        assert row["event"] == str(int(event))
    # the search at N (its own step), then its repeat at 2N and dt/2
    names = [r["search"] for r in rows]
    k = names.count("nominal")
    assert names == ["nominal"] * k + ["verify"] * (len(rows) - k)
    assert {r["n_modes"] for r in rows[:k]} == {"2"}
    assert {r["n_modes"] for r in rows[k:]} == {"4"}
    assert {r["dt_s"] for r in rows[:k]} == {""}
    assert len({r["dt_s"] for r in rows[k:]}) == 1
    # the answer: a closed row, and no nominal event at or above it
    answer = float(next(c for c in comments
                        if c.startswith("# min_preload_lb = "))
                   .split(" = ")[1])
    nominal = [(float(r["preload_lb"]), r["event"] == "1")
               for r in rows[:k]]
    assert 0 < answer and any(e for _, e in nominal)
    assert not any(e for p, e in nominal if p >= answer * (1 - 1e-5))


def test_the_api_writes_the_file_the_command_writes(tmp_path, capsys):
    command, api = tmp_path / "command.csv", tmp_path / "api.csv"
    _command(capsys, *REAL, "--csv", str(command))
    answer = contactsep.preload(thesis_design(n_modes=2), workers=1,
                                converge=False, t_end=0.03)
    answer.to_csv(api)
    assert api.read_text() == command.read_text()
    assert _table(api)[1] == COLUMNS


def _gallery_cells(csv_path: Path) -> str:
    """The gallery example's reading and drawing (its first two cells;
    the third simulates) with its CSV replaced by ``csv_path``."""
    source = GALLERY.read_text()
    cells = source.split("\n# %%")
    code, count = re.subn(r"^CSV = .*$", f"CSV = Path({str(csv_path)!r})",
                          "\n# %%".join(cells[:2]), flags=re.MULTILINE)
    assert count == 1
    return code


def test_the_gallery_reads_a_file_the_command_wrote(tmp_path, capsys,
                                                    monkeypatch):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    monkeypatch.setattr(plt, "show", lambda *a, **k: None)
    path = tmp_path / "p.csv"
    _command(capsys, *REAL, "--csv", str(path))
    namespace = {"__file__": str(GALLERY), "__name__": "gallery"}
    exec(compile(_gallery_cells(path), str(GALLERY), "exec"), namespace)
    printed = capsys.readouterr().out
    plt.close("all")
    _, _, rows = _table(path)
    nominal = [r for r in rows if r["search"] == "nominal"]
    opened = sum(r["event"] == "1" for r in nominal)
    assert printed.startswith(f"{len(nominal)} preloads simulated, "
                              f"{opened} with an event")
    assert 0 < opened < len(nominal)
    # the committed tutorial file, as the gallery runs it, reads alike
    exec(compile(GALLERY.read_text().split("\n# %%")[0], str(GALLERY),
                 "exec"), {"__file__": str(GALLERY), "__name__": "g"})
    assert "preloads simulated" in capsys.readouterr().out


def test_contactsep_read_takes_the_file(tmp_path, capsys):
    path = tmp_path / "p.csv"
    _command(capsys, *REAL, "--csv", str(path))
    frame = contactsep.read(path)
    assert frame.columns.tolist() == COLUMNS
    assert {str(frame[c].dtype) for c in ("n", "n_open", "n_failed",
                                          "n_modes", "event")} == {"int64"}
    assert str(frame["preload_lb"].dtype) == "float64"
    assert str(frame["dt_s"].dtype) == "float64"
    assert frame["event"].isin([0, 1]).all()
    assert frame["dt_s"][frame["search"] == "nominal"].isna().all()
    assert any(c.startswith("min_preload_lb = ")
               for c in frame.attrs["comments"])
    assert any(c.startswith("ceiling_lb = ")
               for c in frame.attrs["comments"])


def test_every_search_and_check_is_in_the_file(planted_preload, tmp_path,
                                               capsys):
    """With the check at 4N (the default), the perturbed searches and the
    robust answer (planted physics: tests/planted_preload.py, which
    keeps every run it makes): a row for every simulation, the robust
    rows' n + n_failed their samples; the event of each planted row is
    the planted threshold's at the row's N and step."""
    path = tmp_path / "p.csv"
    CALLS.clear()
    _command(capsys, "--n-modes", "8", "--csv", str(path),
             "--perturbation", "1e-6", "--tolerance", "d=normal(0.25,0.01)",
             "--samples", "20", "--p-target", "0.2")
    _, header, rows = _table(path)
    assert header == COLUMNS
    single = [r for r in rows if not r["search"].startswith("robust")]
    robust = [r for r in rows if r["search"].startswith("robust")]
    events = [load for kind, load, *_ in CALLS if kind == "event"]
    samples = [load for kind, load, *_ in CALLS if kind == "sample"]
    assert [float(r["preload_lb"]) for r in single] == events
    assert sum(int(r["n"]) + int(r["n_failed"]) for r in robust) == len(
        samples) > 0
    assert {r["search"] for r in rows} == {
        "nominal", "verify", "converge", "perturbed_up", "perturbed_down",
        "robust", "robust_check"}
    design = thesis_design(n_modes=8)
    for r in single:
        if r["search"].startswith("perturbed"):
            continue
        at = design.replace(n_modes=int(r["n_modes"]))
        settings = {} if r["dt_s"] == "" else {"dt": float(r["dt_s"])}
        below = float(r["preload_lb"]) < threshold(at, settings)
        assert r["event"] == r["n_open"] == str(int(below)), r
    assert {r["n_modes"] for r in single
            if r["search"] in ("nominal", "perturbed_up", "perturbed_down")
            } == {"8"}
    assert {r["n_modes"] for r in single if r["search"] == "verify"} == {
        "16"}
    assert all(int(r["n_modes"]) >= 32 for r in single
               if r["search"] == "converge")
    assert {r["n_modes"] for r in robust if r["search"] == "robust"} == {"8"}
    assert {r["n_modes"] for r in robust
            if r["search"] == "robust_check"} == {"16"}
    for r in robust:
        assert r["event"] == str(int(int(r["n_open"]) > 0))


def test_the_family_files_have_one_row_a_simulation(planted_preload,
                                                     tmp_path):
    """On designs of the family (planted physics): the API's file has a
    row for every planted run, whatever the design."""
    for name in ("steel_relay", "becu_light", "thesis_thick"):
        CALLS.clear()
        path = tmp_path / f"{name}.csv"
        with warnings.catch_warnings():
            # the planted threshold moves with N: "not converged"
            warnings.simplefilter("ignore", UserWarning)
            answer = contactsep.preload(FAMILY[name].replace(n_modes=8),
                                        workers=1)
        answer.to_csv(path)
        _, header, rows = _table(path)
        assert header == COLUMNS
        assert [float(r["preload_lb"]) for r in rows] == [
            load for kind, load, *_ in CALLS if kind == "event"], name
        assert len(rows) == answer.simulations, name
