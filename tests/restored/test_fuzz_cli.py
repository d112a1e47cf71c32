"""The commands under byte-level mutations of the thesis decks (issue 9).

Each example runs ``contactsep replay`` or ``legacy`` in a subprocess under
a memory limit (RLIMIT_AS) and a time limit: it must exit 0 with the
listing on stdout and nothing on stderr but one-line warnings (issue 10),
or exit 2 with one printable line ``contactsep: error: ...`` (and the
listings of the data sets before the bad one).  Never a traceback, a
hang, another status, or more memory than the bound.  Kept to ~25 s in
CI (derandomized, few examples); set HYPOTHESIS_PROFILE=thorough for a
long run.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from conftest import THESIS_DECKS

#: Address space any one run may use: the interpreter, NumPy and the
#: extension modules take ~0.5 GiB of it; a deck held several times over
#: or an unbounded allocation would not fit.
MEMORY_BOUND = 1 << 30
#: Seconds any one run may take (a thesis deck takes under one).
TIME_BOUND = 30
DECKS = [path.read_bytes() for path in THESIS_DECKS]
THOROUGH = os.environ.get("HYPOTHESIS_PROFILE") == "thorough"


def _bounded():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_BOUND, MEMORY_BOUND))


@st.composite
def mutated(draw) -> bytes:
    deck = bytearray(draw(st.sampled_from(DECKS)))
    for _ in range(draw(st.integers(1, 6))):
        kind = draw(st.sampled_from(
            ["flip", "set", "insert", "delete", "duplicate", "truncate",
             "append"]))
        at = draw(st.integers(0, max(0, len(deck) - 1)))
        byte = draw(st.integers(0, 255))
        if kind == "flip" and deck:
            deck[at] ^= 1 << draw(st.integers(0, 7))
        elif kind == "set" and deck:
            deck[at] = byte
        elif kind == "insert":
            deck[at:at] = bytes([byte]) * draw(st.integers(1, 100))
        elif kind == "delete":
            del deck[at:at + draw(st.integers(1, 200))]
        elif kind == "duplicate":
            span = draw(st.integers(1, 2000))
            deck[at:at] = deck[at:at + span]
        elif kind == "truncate":
            del deck[at:]
        else:
            deck += draw(st.binary(min_size=1, max_size=200))
    return bytes(deck)


def check_run(command: str, deck: bytes, tmp_path) -> None:
    path = tmp_path / "deck.dat"
    path.write_bytes(deck)
    done = subprocess.run(
        [sys.executable, "-m", "contactsep", command, str(path)],
        capture_output=True, timeout=TIME_BOUND, preexec_fn=_bounded)
    # honest warnings (issue 10) come first, each one printable line
    lines = done.stderr.decode("latin-1").splitlines(keepends=True)
    warned = [line for line in lines
              if line.startswith("contactsep: warning: ")]
    for line in warned:
        assert line.endswith("\n") and all(
            " " <= char <= "~" for char in line[:-1]), repr(line)
    text = "".join(lines[len(warned):])
    assert lines[:len(warned)] == warned, repr(lines)
    if done.returncode == 0:
        assert text == ""
        assert done.stdout.strip(), "exit 0 without a listing"
        return
    assert done.returncode == 2, done.stderr[-2000:]
    assert text.startswith("contactsep: error: ") and text.endswith("\n")
    assert text.count("\n") == 1, repr(text)
    assert all(" " <= char <= "~" for char in text[:-1]), repr(text)


@settings(max_examples=400 if THOROUGH else 24, deadline=None,
          derandomize=not THOROUGH,
          suppress_health_check=[HealthCheck.too_slow,
                                 HealthCheck.function_scoped_fixture,
                                 HealthCheck.data_too_large])
@given(deck=mutated(), command=st.sampled_from(["replay", "legacy"]))
def test_commands_on_mutated_decks(deck, command, tmp_path):
    check_run(command, deck, tmp_path)
