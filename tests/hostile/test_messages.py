"""Tracebacks, invalid JSON and unclear messages (issue 18, classes 4 and
5): every refusal is one printable line, exit 2, naming the option or
field, what was found and what is expected; every JSON output is strict;
nothing else reaches stderr."""

from __future__ import annotations

import socket
import time

import pytest
from hostile_cli import main, refusal, run, strict_json

import contactsep
from contactsep import studies
from contactsep.errors import InputError
from contactsep.restored import cards, thesis_decks


@pytest.mark.parametrize("args, message", [
    # argparse's own errors were a usage line and 'contactsep CMD: error:'
    (["model", "--bogus", "1"], "model: unrecognized arguments: --bogus 1 "
                                "(contactsep model --help lists the "
                                "options)"),
    (["model", "--n-modes"], "--n-modes: expected one argument"),
    (["replay"], "replay: the following arguments are required: deck"),
    (["frob"], "COMMAND: invalid choice: 'frob'"),
    (["sweep", "--seed", "1e3"], "--seed: found '1e3', expected an "
                                 "integer from 0 to"),
    # '-inf' was taken for an option: '--d: expected one argument'
    (["model", "--d", "-inf"], "--d: found -inf, expected a finite number"),
    (["model", "--gap", "-1e300"], "--gap: found -1e+300, expected |gap| "
                                   "<= L1 = 19 in"),
    # tracebacks
    (["sweep", "--sample", "h2=normal(0.25,0.01)", "--seed", "-1"],
     "--seed: found '-1', expected an integer from 0 to"),
    (["sweep", "--sample", "h2=normal(0.25,0.01)", "--samples",
      "9223372036854775808"], "--samples: found '9223372036854775808', "
                              "expected an integer from 1 to"),
    (["sweep", "--vary", "h2=0.1:0.2:2", "--scheduler", "not an address"],
     "--scheduler: found 'not an address', expected a scheduler address "
     "such as tcp://HOST:8786"),
    (["chatter", "--d", "1e300"], "--d: found 1e+300, expected 0.0001 to "
                                  "10000 in"),
    (["chatter", "--model", "hertz", "--damping", "flores", "--e", "0"],
     "e: found 0.0, expected e > 0 with Flores damping"),
    # unclear
    (["model", "--end1", "pinned-pinned"], "x1: found 19.0 (its default), "
                                           "expected 0 < x1 < 19 in: inside "
                                           "the span of the pinned-pinned "
                                           "upper contact (end1)"),
    (["model", "--gap", "0.7"], "no impact: the upper contact released "
                                "from ys = 0.5 in never reaches the "
                                "separator's surface at gap = 0.7 in"),
    (["study", "fig5", "--e", "2"], "--e: found 2.0, expected 0 <= e <= 1"),
    (["study", "chatter", "--e", "0.5"], "study chatter takes no design "
                                         "options"),
    (["study", "chatter", "--e", "5", "--n-modes", "0"],
     "--n-modes: found '0', expected an integer >= 1"),
])
def test_a_refusal_is_one_line_naming_what_was_wrong(capsys, args, message):
    status, out, err = main(capsys, *args)
    assert refusal(status, err).startswith(message)
    assert out == ""


def test_an_unreachable_scheduler_is_one_line(capsys):
    """A port nobody listens on: refused at once by the probe (before it,
    Dask's own connect waited its 10 s timeout)."""
    pytest.importorskip("distributed")
    with socket.socket() as closed:
        closed.bind(("127.0.0.1", 0))
        port = closed.getsockname()[1]
    start = time.monotonic()
    status, _, err = main(capsys, "sweep", "--vary", "h2=0.1:0.2:2",
                          "--scheduler", f"tcp://127.0.0.1:{port}")
    assert refusal(status, err) == (f"--scheduler tcp://127.0.0.1:{port}: "
                                    f"no scheduler answered (Connection "
                                    f"refused)")
    assert time.monotonic() - start < 5


@pytest.mark.parametrize("args", [
    ["model", "--json"], ["model", "--tau", "1e-30", "--json"],
    ["sweep", "--sample", "h2=normal(0.25,0.01)", "--samples", "20",
     "--threshold", "1e300", "--json", "--workers", "1"],
    ["sweep", "--vary", "d=-0.1,0.25", "--json", "--workers", "1"],
    ["chatter", "--n-modes", "2", "--json"],
    ["chatter", "--model", "appE", "--n-modes", "2", "--json"],
])
def test_json_is_strict(capsys, args):
    """--json printed Infinity and -Infinity: every number is finite or
    null."""
    status, out, err = main(capsys, *args)
    assert status == 0, err
    strict_json(out)


def test_an_unwritable_home_adds_nothing_to_stderr(tmp_path):
    """With an unwritable HOME matplotlib added two lines to stderr."""
    pytest.importorskip("matplotlib")
    home = tmp_path / "home"
    home.write_text("a file, not a directory\n")
    env = {"HOME": str(home), "PATH": "/usr/bin:/bin"}
    done = run("study", "fig5", "--png", str(tmp_path / "fig5.png"),
               env=env)
    assert done.returncode == 0 and done.stderr == "", done.stderr
    assert (tmp_path / "fig5.png").read_bytes()[:4] == b"\x89PNG"


def test_compare_with_nothing_comparable_says_so(tmp_path):
    """All lengths 1e-6 in: it printed '0 within tolerance, 0 outside',
    exited 1 (a disagreement) and printed its warning twice."""
    ds = thesis_decks.thesis_data_set(0.25).replace(
        xl=1e-6, xl2=1e-6, xl3=1e-6, xl2c=1e-6)
    deck = tmp_path / "tiny.dat"
    deck.write_text(cards.format_deck([ds]))
    done = run("compare", str(deck))
    assert refusal(done.returncode, done.stderr) == (
        f"nothing compared: no data set of {deck} could be compared (the "
        f"lines above say why)")
    assert done.stderr.count("warning") == 1
    assert done.stdout.splitlines()[-1] == \
        "0 within tolerance, 0 outside, 1 data set not compared"


@pytest.mark.parametrize("kwargs, message", [
    (dict(dt="abc"), "dt: found 'abc', expected a number (s)"),
    (dict(preload=None), "preload: found None, expected a number (lb)"),
    (dict(model="hertz", nu=2.0), "nu: found 2.0, expected -1 < nu <= 0.5"),
])
def test_simulate_names_its_argument(kwargs, message):
    from contactsep.chatter import simulate
    from contactsep.model import thesis_design
    with pytest.raises(InputError) as info:
        simulate(thesis_design(n_modes=2), **kwargs)
    assert str(info.value) == message or str(info.value).startswith(message)


@pytest.mark.parametrize("call, message", [
    (lambda: contactsep.thesis_design(bogus=1),
     "bogus: not a design field"),
    (lambda: studies.fig8(ys=[0.3, 0.6]),
     "study fig8: ys: found [0.3, 0.6], expected one value"),
    (lambda: studies.table2(e="abc"),
     "e: found 'abc', expected a number"),
    (lambda: contactsep.evaluate("a design"),
     "design: expected a contactsep.Design, found str"),
])
def test_the_api_names_what_it_refuses(call, message):
    """Studies and thesis_design raised TypeErrors from deep inside
    (Design.__init__() got an unexpected keyword argument; only
    0-dimensional arrays can be converted to Python scalars)."""
    with pytest.raises(InputError) as info:
        call()
    assert str(info.value).startswith(message), str(info.value)
