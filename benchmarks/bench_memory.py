"""Peak memory of the commands on huge decks (issue 9; not run by the tests).

    python benchmarks/bench_memory.py [--mb 200] [--seconds 60] [--save]

1. A deck of ``--mb`` megabytes (the thesis decks repeated), generated in a
   temporary directory and removed afterwards: peak RSS of ``replay``,
   ``legacy`` and ``compare`` with the listing sent to /dev/null.  Each runs
   at most ``--seconds`` and is then stopped with SIGTERM (a whole 200 MB
   deck takes minutes for replay and hours for compare); memory that grew
   with the deck would show within the first seconds, as reading is the
   first thing a command does.
2. The thesis data set with DELT = 6e-8 s (the smallest the core allows,
   a million history lines): peak RSS of ``replay`` and ``legacy`` against
   the size of the listing.

Peak RSS is the child's ru_maxrss (os.wait4), so it includes the
interpreter, NumPy and the extension modules (the baseline is printed).
``--save``: also into benchmarks/results/bench_memory.md, the run
docs/performance.md quotes.
"""

from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from results import Report  # this folder: run as a script

DECKS = Path(__file__).resolve().parent.parent / "data" / "decks"


def peak(args: list[str], seconds: float | None = None,
         stdout=subprocess.DEVNULL) -> tuple[float, float, int]:
    """(peak RSS in MB, seconds run, exit status) of one command."""
    started = time.monotonic()
    process = subprocess.Popen(args, stdout=stdout,
                               stderr=subprocess.DEVNULL)
    stopped = False
    while True:
        pid, status, usage = os.wait4(process.pid, os.WNOHANG)
        if pid:
            break
        if not stopped and seconds is not None and \
                time.monotonic() - started > seconds:
            process.send_signal(signal.SIGTERM)
            stopped = True
        time.sleep(0.05)
    process.returncode = 0     # reaped here
    elapsed = time.monotonic() - started
    code = os.waitstatus_to_exitcode(status)
    return usage.ru_maxrss / 1024, elapsed, -1 if stopped else code


def command(*args: str) -> list[str]:
    return [sys.executable, "-m", "contactsep", *args]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mb", type=float, default=200.0)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--save", action="store_true",
                        help="also write benchmarks/results/bench_memory.md")
    args = parser.parse_args()
    say = Report()
    base, _, _ = peak([sys.executable, "-c",
                       "import contactsep.cli, contactsep.restored.compare, "
                       "contactsep.restored.core as c; c._api('single'); "
                       "c._api('double')"])
    say(f"baseline (interpreter, NumPy, extensions): {base:.0f} MB")
    with tempfile.TemporaryDirectory() as tmp:
        deck = Path(tmp) / "big.dat"
        unit = (DECKS / "thesis_all.dat").read_bytes()
        copies = int(args.mb * 1e6 / len(unit)) + 1
        with open(deck, "wb") as out:
            for _ in range(copies):
                out.write(unit)
        size = deck.stat().st_size / 1e6
        say()
        say(f"| {size:.0f} MB deck ({copies:,} x thesis_all.dat), at most "
            f"{args.seconds:g} s each | peak RSS | ran | status |")
        say("|---|---:|---:|---|")
        for name in ("replay", "legacy", "compare"):
            rss, ran, code = peak(command(name, str(deck)), args.seconds)
            state = "stopped (SIGTERM)" if code == -1 else f"exit {code}"
            say(f"| `contactsep {name}` | {rss:.0f} MB | {ran:.1f} s | "
                f"{state} |")
        deck.unlink()

        lines = (DECKS / "thesis_d0250.dat").read_text().split("\n")
        lines[3] = "    0.000000060" + lines[3][15:]
        small = Path(tmp) / "delt.dat"
        small.write_text("\n".join(lines))
        listing = Path(tmp) / "listing.txt"
        with open(listing, "wb") as out:
            peak(command("replay", str(small)), stdout=out)
        size = listing.stat().st_size / 1e6
        say()
        say(f"| DELT = 6e-8 s data set (thesis d = 0.250 in), listing "
            f"{size:.1f} MB | peak RSS | / listing | ran |")
        say("|---|---:|---:|---|")
        for name in ("replay", "legacy"):
            rss, ran, code = peak(command(name, str(small)))
            say(f"| `contactsep {name}` | {rss:.0f} MB | {rss / size:.1f}x | "
                f"exit {code}, {ran:.1f} s |")
    if args.save:
        say.save("bench_memory", "python benchmarks/bench_memory.py "
                 + " ".join(sys.argv[1:]))


if __name__ == "__main__":
    main()
