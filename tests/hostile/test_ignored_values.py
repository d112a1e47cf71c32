"""Issue 31's silent, ignored and traceback cases, each now a one-line
refusal naming the option or field (exit 2; an InputError subclass from
the API) or a correct result: chatter sweeps, the search studies,
--set, the newer API."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hostile_cli import main, refusal

from contactsep.chatter import simulate
from contactsep.errors import ContactsepWarning, InputError
from contactsep.model import thesis_design
from contactsep.studies.thesis.conclusions import conclusion
from contactsep.studies.preload.chart import min_preloads, preload_chart
from contactsep.studies.sweep.spec import make_spec, parse_vary


@pytest.mark.parametrize("args, start", [
    (["--vary", "tau=0.01,0.05"], "tau: not used by the chatter"),
    (["--tau", "1", "--vary", "h2=0.2,0.3"], "tau: not used"),
    (["--sample", "tau=uniform(0.01,0.05)"], "tau: not used"),
    (["--lower-response", "impulse", "--vary", "h2=0.2,0.3"],
     "lower_response: not used"),
    (["--vary", "e=0.2,0.5"], "e: not used by elastic Hertz contact"),
])
def test_a_chatter_sweep_refuses_fields_its_simulation_ignores(
        capsys, args, start):
    """tau (eq. 23's window) gave two equal rows under --model hertz."""
    code, _, err = main(capsys, "sweep", "--model", "hertz", *args)
    assert refusal(code, err).startswith(start)


def test_study_preload_refuses_tau(capsys):
    """It was ignored while the CSV noted 'tau = 1 s'."""
    code, _, err = main(capsys, "study", "preload", "--tau", "1")
    assert refusal(code, err).startswith("--tau: study preload runs only")


@pytest.mark.parametrize("name", ["preload", "conclusion3"])
def test_search_studies_refuse_too_many_modes_before_any_work(capsys, name):
    """conclusion3 --n-modes 100000 ran eq. 23 for minutes first."""
    code, _, err = main(capsys, "study", name, "--n-modes", "100000")
    assert refusal(code, err).startswith("--n-modes: found 100000, "
                                         "expected an integer from 1 "
                                         "to 1024")


def test_sample_range_that_overflows_is_refused(capsys):
    code, _, err = main(capsys, "sweep", "--model", "hertz", "--sample",
                        "h2=uniform(-1e308,1e308)", "--samples", "3")
    assert refusal(code, err).startswith(
        "--sample h2=uniform(-1e308,1e308): HI - LO overflows")


def test_a_whole_float_range_axis_is_exact_without_a_warning():
    """-1e308:1e308:3 is -1e308, 0, 1e308 (numpy.linspace gives NaN and
    a RuntimeWarning: STOP - START overflows)."""
    _, axis = parse_vary("h2=-1e308:1e308:3")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        values = axis[[0, 1, 2]]
    assert values.tolist() == [-1e308, 0.0, 1e308]
    _, small = parse_vary("h2=0.1:0.8:8")
    assert small[np.arange(8)].tolist() == np.linspace(0.1, 0.8,
                                                       8).tolist()


def test_the_overflowing_axis_prints_no_numpy_warning(capsys):
    code, _, err = main(capsys, "sweep", "--vary", "h2=-1e308:1e308:3")
    refusal(code, err)
    assert "invalid value" not in err and "RuntimeWarning" not in err


@pytest.mark.parametrize("option, named", [
    (["--preload", "1e300"], "--preload: found 1e+300"),
    (["--gap", "0.1"], "--gap: found 0.1"),
])
def test_an_all_invalid_chatter_sweep_names_the_option(capsys, option,
                                                       named):
    code, _, err = main(capsys, "sweep", "--model", "hertz", "--n-modes",
                        "2", "--vary", "h2=0.2,0.3", *option,
                        "--workers", "1")
    message = refusal(code, err)
    assert message.startswith("2 of 2 designs failed (2 invalid input)")
    assert f"the first design: {named}" in message


def test_a_chatter_sweep_refuses_n_modes_past_the_limit_up_front(capsys):
    code, _, err = main(capsys, "sweep", "--model", "hertz", "--n-modes",
                        "2000", "--vary", "h2=0.2,0.3")
    assert refusal(code, err).startswith("--n-modes: found 2000, expected "
                                         "at most 1024")


def test_set_preload_points_to_the_chatter_option(capsys):
    code, _, err = main(capsys, "chatter", "--set", "preload=1")
    message = refusal(code, err)
    assert "give it as --preload" in message and "contactsep chatter" \
        in message


def test_eq23_figures_null_say_why(capsys):
    """--tau 1e300: every eq. 23 figure null, and a warning why."""
    code, out, err = main(capsys, "chatter", "--model", "hertz", "--tau",
                          "1e300", "--json", "--n-modes", "2")
    assert code == 0
    assert "contactsep: warning: single impulse (eq. 23): tau: found " \
        "1e+300 s" in err


@pytest.mark.parametrize("call, start", [
    (lambda: simulate(thesis_design(), model="hertz", preload=10**400),
     "preload: found an integer of about 401 digits"),
    (lambda: preload_chart(thicknesses=[]), "thicknesses: found none"),
    (lambda: preload_chart(heights=[math.nan]), "heights: found [nan]"),
    (lambda: preload_chart(workers="two"), "workers: found 'two'"),
    (lambda: preload_chart(tau=1.0), "tau: study preload runs only"),
    (lambda: min_preloads([None]), "designs: item 0 is NoneType"),
    (lambda: conclusion("conclusion4"), "name: found 'conclusion4'"),
    (lambda: conclusion("conclusion3", n_modes=10**6),
     "n_modes: found 1000000"),
    (lambda: make_spec(model="hertz", settings={"dt": math.nan}),
     "--dt: found nan"),
    (lambda: make_spec(model="hertz", settings={"dt": "abc"}),
     "--dt: found 'abc'"),
    (lambda: make_spec(model="hertz", settings={"bogus": 1}),
     "settings: bogus: not a chatter setting"),
    (lambda: make_spec(model="hertz", base={"bogus": 1.0}),
     "base: bogus: not a design field"),
    (lambda: make_spec(base={"h2": "thick"}), "base: h2: found 'thick'"),
    (lambda: make_spec(base={"h2": -1.0}), "base: "),
    (lambda: make_spec(base=[1]), "base: found list"),
])
def test_the_api_refuses_in_one_line(call, start):
    with pytest.raises(InputError) as caught:
        call()
    message = str(caught.value)
    assert message.startswith(start), message
    assert "\n" not in message and message.isprintable()


def test_make_spec_keeps_a_valid_base_by_field_name():
    spec = make_spec(base={"d": 0.3, "n_modes": np.int64(4)})
    assert spec.base == {"h2": 0.3, "n_modes": 4}


def test_contactsep_warning_is_the_category_of_the_eq23_note():
    with pytest.warns(ContactsepWarning, match="single impulse"):
        simulate(thesis_design(tau=1e300, n_modes=2), model="hertz")


def test_e_is_swept_where_it_is_read(capsys):
    """Flores damping reads e (calibrated to it): the sweep runs."""
    code, out, err = main(capsys, "sweep", "--model", "hertz", "--vary",
                          "e=0.2,0.5", "--damping", "flores", "--n-modes",
                          "2", "--json", "--workers", "1")
    assert code == 0, err
