"""Issue 10: the restored core for everyday use (friction items)."""

import io
import json
import warnings
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import numpy as np
import pytest

import contactsep
from conftest import ROOT
from contactsep import beams, cli
from contactsep.errors import ContactsepWarning
from contactsep.restored import checks, formats, thesis_decks

DECKS = ROOT / "data" / "decks"


@pytest.fixture(scope="module")
def result():
    return contactsep.solve(thesis_decks.thesis_data_set(0.25), "double")


def run_cli(*argv):
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        try:
            status = cli.main(list(argv))
        except SystemExit as exit_:
            status = exit_.code
    return status, out.getvalue(), err.getvalue()


def test_version():
    status, out, _ = run_cli("--version")
    assert status == 0
    assert out.strip() == f"contactsep {contactsep.__version__}"


def test_py_typed_installed():
    package = Path(contactsep.__file__).parent
    assert (package / "py.typed").exists()
    build = (package / "meson.build")
    if build.exists():  # editable install: the source tree
        assert "'py.typed'" in build.read_text()


def test_result_help_documents_fields():
    doc = contactsep.Result.__doc__
    for name in ("t_impact", "ey", "history_ty3", "wm2", "listing"):
        assert name in doc
    assert "lb s" in doc and "rad/s" in doc


def test_result_repr_short(result):
    text = repr(result)
    assert len(text) < 300
    assert "t_impact" in text and "\n" not in text


def test_result_json_round_trip(result):
    data = json.loads(result.to_json())
    assert data["t_impact"] == result.t_impact
    assert data["history_ty3"] == result.history_ty3.tolist()
    assert data["inputs"]["xl2c"] == 3.60
    assert data["listing"] == result.listing


def test_with_modes_recomputes_constants():
    ds = thesis_decks.thesis_data_set(0.25)
    three = ds.with_modes(3)
    assert three.n == 3
    # independent path: the published cantilever eigenvalues
    np.testing.assert_allclose(three.v, [1.875104069, 4.694091133,
                                         7.854757438], rtol=1e-9)
    np.testing.assert_allclose(three.v2, beams.eigenvalues(
        "clamped-clamped", 3))
    r = contactsep.solve(three, "double")
    assert np.isfinite(r.t_impact)


def test_replace_n_points_at_with_modes():
    ds = thesis_decks.thesis_data_set(0.25)
    with pytest.raises(ValueError, match=r"with_modes\(3\)"):
        ds.replace(n=3)


def test_equivalent_length_rule():
    # Table III where the thesis gives it
    for d, lc in ((0.125, 3.60), (0.25, 3.60), (0.35, 3.81), (0.5, 4.07),
                  (0.75, 4.15)):
        assert thesis_decks.thesis_data_set(d).xl2c == lc
    # the stated rule: linear between neighbours, 3.60 below 0.125
    assert thesis_decks.equivalent_length(0.425) == pytest.approx(
        (3.81 + 4.07) / 2)
    assert thesis_decks.equivalent_length(0.1) == 3.60
    with pytest.raises(ValueError, match="Table III"):
        thesis_decks.equivalent_length(1.0)


def test_summary_labels_every_number(result):
    text = formats.summary(result)
    for name, unit, meaning in formats.SUMMARY_FIELDS:
        line = next(l for l in text.splitlines()
                    if l.strip().startswith(name + " "))
        assert unit in line and meaning in line
        value = float(line.split("=")[1].split()[0])
        assert value == pytest.approx(getattr(result, name), rel=1e-8)


def test_replay_formats_listing_default_unchanged(tmp_path):
    deck = str(DECKS / "thesis_d0250.dat")
    _, default, _ = run_cli("replay", deck)
    _, listing, _ = run_cli("replay", deck, "--format", "listing")
    assert default == listing
    legacy_results = contactsep.replay(deck)
    assert default == "".join(r.listing for r in legacy_results)
    _, js, _ = run_cli("replay", deck, "--format", "jsonl")
    assert json.loads(js.splitlines()[0])["t_impact_s"] == \
        legacy_results[0].t_impact
    _, table, _ = run_cli("replay", deck, "--format", "csv")
    rows = table.splitlines()
    assert rows[0].startswith("data_set,d_in,n_modes,t_impact_s,")
    assert len(rows) == 2


def test_density_in_lb_per_in3_warns():
    ds = thesis_decks.thesis_data_set(0.25).replace(rho=0.1, rho2=0.1, rho3=0.1)
    with pytest.warns(ContactsepWarning, match="lb/in\\^3"):
        contactsep.solve(ds, "double")


def test_thick_separator_warns():
    ds = thesis_decks.thesis_data_set(0.25).replace(h2=1.0)
    assert ds.h2 / ds.xl2 == 0.4
    with pytest.warns(ContactsepWarning, match="Bernoulli-Euler"):
        contactsep.solve(ds, "double")


def test_mode_card_precision_warning():
    # independent path: the A_j sensitivity delta e^v v^3/12 at the
    # published cantilever k_5 L = 14.137165491 with delta = 5e-10
    v5 = 14.137165491
    assert 5e-10 * np.exp(v5) * v5 ** 3 / 12 > 0.1
    ds = thesis_decks.thesis_data_set(0.25).with_modes(6)
    nine = ds.replace(alpha=np.round(ds.alpha, 9),
                      alph3=np.round(ds.alph3, 9))
    assert checks.input_messages(nine)
    assert not checks.input_messages(thesis_decks.thesis_data_set(0.25))


def test_thesis_decks_run_without_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ContactsepWarning)
        for d in (0.125, 0.25, 0.35, 0.5, 0.75):
            contactsep.solve(thesis_decks.thesis_data_set(d), "double")


def test_extreme_at_end_of_window_warns():
    """The thesis lower contact peaks at 0.017 s (eq. 13's first swing):
    a window ending at 0.005 s has its largest |TY3| on the last line and
    says so; the listing's 0.06 s window does not."""
    ds = thesis_decks.thesis_data_set(0.25)
    with pytest.warns(ContactsepWarning, match="last history line.*"
                      r"TAU = 0\.005 s"):
        short = contactsep.solve(ds, "double", tau=0.005)
    assert np.argmax(np.abs(short.history_ty3)) == short.history_ty3.size - 1
    with warnings.catch_warnings():
        warnings.simplefilter("error", ContactsepWarning)
        contactsep.solve(ds, "double")


def test_cli_warning_one_line_listing_unchanged(tmp_path):
    text = (DECKS / "thesis_d0250.dat").read_text()
    lines = text.splitlines(keepends=True)
    # card 2, columns 46-60 is RHO2: 172.8 lb/ft^3 -> 0.1 (lb/in^3)
    card = lines[1]
    lines[1] = card[:45] + f"{0.1:15.9f}" + card[60:]
    deck = tmp_path / "rho.dat"
    deck.write_text("".join(lines))
    status, out, err = run_cli("replay", str(deck))
    assert status == 0
    assert err.count("\n") == 1
    assert err.startswith("contactsep: warning: RHO2 = 0.1 looks like")
    assert out == "".join(r.listing for r in contactsep.replay(str(deck)))


def test_solve_without_listing_same_numbers(result):
    lean = contactsep.solve(thesis_decks.thesis_data_set(0.25), "double",
                            listing=False)
    assert lean.listing == ""
    for name in ("p", "ape", "trace_t", "trace_ty", "trace_tydtl", "a1",
                 "b1", "history_t", "history_ty3", "p2", "p3"):
        assert np.array_equal(getattr(lean, name), getattr(result, name))
    for name in ("t_impact", "ey", "tip_act", "ty2dt", "wm2", "beta"):
        assert getattr(lean, name) == getattr(result, name)


@pytest.mark.parametrize("seed", range(4))
def test_the_mode_card_shortcut_never_hides_a_warning(seed):
    """checks skips the per-mode estimate when even the coarsest rounding
    at the largest kL cannot reach MODE_ERROR; wherever it skips, the full
    estimate (mode_card_error) stays below MODE_ERROR."""
    rng = np.random.default_rng(seed)
    skipped = 0
    for _ in range(2000):
        n = int(rng.integers(1, 12))
        v = np.sort(rng.uniform(0.5, rng.uniform(2.0, 40.0), n))
        alpha = rng.uniform(-3.0, 3.0, n) * 10.0 ** rng.integers(0, 8)
        if rng.random() < 0.5:
            alpha = np.round(alpha, checks.CARD_DECIMALS)
        if not checks._may_exceed(v, alpha):
            skipped += 1
            assert np.all(checks.mode_card_error(v, alpha)
                          <= checks.MODE_ERROR)
    assert skipped > 100


def test_tau_extends_the_history_window():
    """solve(tau=...) runs the same history loop to another end: the
    first 0.06 s are the listing's lines bit for bit, and every line is
    eq. 13 (TY3 = TY2DT sum C3^2 sin(P3 T) / (XL3 P3)) on T < tau."""
    ds = thesis_decks.thesis_data_set(0.25)
    base = contactsep.solve(ds, "double")
    assert base.tau == 0.060
    long = contactsep.solve(ds, "double", tau=0.2)
    assert long.tau == 0.2
    k = base.history_t.size
    np.testing.assert_array_equal(long.history_t[:k], base.history_t)
    np.testing.assert_array_equal(long.history_ty3[:k], base.history_ty3)
    assert long.history_t[-1] < 0.2 <= long.history_t[-1] + ds.delt * 1.001
    t = long.history_t[:, None]
    eq13 = long.ty2dt * np.sum(ds.c3**2 * np.sin(long.p3 * t)
                               / (ds.xl3 * long.p3), axis=1)
    np.testing.assert_allclose(long.history_ty3, eq13, rtol=1e-12,
                               atol=1e-15)
    short = contactsep.solve(ds, "double", tau=0.02, listing=False)
    assert short.history_t[-1] < 0.02 and short.history_t.size == 40


@pytest.mark.parametrize("tau, match", [
    (0.0, "TAU = 0.0.*positive"), (float("nan"), "TAU = NaN.*positive"),
    (-1.0, "positive"), (1.0, "at most 1000000 history lines")])
def test_a_bad_tau_is_refused(tau, match):
    ds = thesis_decks.thesis_data_set(0.25).replace(delt=1e-7)
    with pytest.raises(contactsep.DeckError, match=match):
        contactsep.solve(ds, "double", tau=tau)


def test_separation_is_in_the_kick_direction_extreme_is_either_sign():
    """Over 0.2 s the thesis lower contact (kicked down: TY2DT < 0) swings
    back up through the separator farther than it went down: extreme_ty3
    reports that swing, separation_ty3 the separation (the most negative
    TY3 on the grid)."""
    r = contactsep.solve(thesis_decks.thesis_data_set(0.25), "double", tau=0.2)
    assert r.ty2dt < 0
    assert r.extreme_ty3 == r.history_ty3.max() > 0
    assert r.separation_ty3 == r.history_ty3.min() < 0
    assert r.history_ty3[r.history_t == r.separation_time][0] \
        == r.separation_ty3
    base = contactsep.solve(thesis_decks.thesis_data_set(0.25), "double")
    assert base.separation_ty3 == base.extreme_ty3 == base.history_ty3.min()
