"""One solve() call, before and now, side by side in one run.

    pip install meson-python meson ninja    # once: the build tools
    python benchmarks/bench_lean.py [--before REV] [--repeat N]

Builds the package at git revision REV (default 2027d9f, the restored
core before solve(listing=False): the listing always formatted, 10,000
zero-filled trace rows on the first try) with ``pip install
--no-build-isolation`` (the build tools must be installed; the script
checks first and says which are missing) into a temporary
directory, then times, each in its own interpreter and alternating so
that machine load hits both alike:

* ``solve(ds, "double")`` at REV;
* ``solve(ds, "double")`` and ``solve(ds, "double", listing=False)`` now;
* ``numpy.sin`` on 1,064 elements (the call's sin/cos count) in both, the
  yardstick that makes the numbers comparable across machines.

ds is thesis_d0250 (N = 4).  Best of N repeats of 200 calls.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

TIMER = r"""
import json, sys, timeit, warnings
import numpy as np
warnings.simplefilter("ignore")
try:                    # the layout since commit 7931a31
    from contactsep.restored import core
except ImportError:     # the 2027d9f build
    from contactsep import core
ds = core.replay(sys.argv[1], "double")[0].inputs
repeat = int(sys.argv[2])
def best(case, number=200):
    return min(timeit.repeat(case, number=number, repeat=repeat)) \
        / number * 1e6
x = np.linspace(0.0, 100.0, 1064)
out = {"module": core.__file__,
       "sin": best(lambda: np.sin(x), 2000),
       "listing": best(lambda: core.solve(ds, "double"))}
try:
    core.solve(ds, "double", listing=False)
    out["lean"] = best(lambda: core.solve(ds, "double", listing=False))
except TypeError:
    pass
print(json.dumps(out))
"""


def build(revision: str, where: Path) -> Path:
    """The package at ``revision`` installed into ``where``/site."""
    source = where / "src"
    subprocess.run(["git", "-C", str(ROOT), "worktree", "add", "--detach",
                    str(source), revision], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        # the revision's layout may need ../shared as the checkout has it
        site = where / "site"
        subprocess.run([sys.executable, "-m", "pip", "install", "-q",
                        "--no-build-isolation", "--no-deps", "--target",
                        str(site), str(source)], check=True)
    finally:
        subprocess.run(["git", "-C", str(ROOT), "worktree", "remove",
                        "--force", str(source)], check=False)
    return site


def measure(site: Path | None, repeat: int) -> dict:
    deck = str(ROOT / "data" / "decks" / "thesis_d0250.dat")
    # an editable install's finder comes before sys.path: drop it there
    code = TIMER if site is None else (
        "import sys\n"
        "sys.meta_path = [f for f in sys.meta_path\n"
        "                 if 'editable' not in type(f).__module__]\n"
        f"sys.path.insert(0, {str(site)!r})\n" + TIMER)
    done = subprocess.run([sys.executable, "-c", code, deck, str(repeat)],
                          check=True, capture_output=True, text=True,
                          cwd=tempfile.gettempdir())
    return json.loads(done.stdout)


def missing_build_tools() -> list[str]:
    """The build tools pip --no-build-isolation needs and cannot find."""
    import importlib.util
    import shutil
    missing = [package for package, module in (("meson-python", "mesonpy"),
                                               ("meson", "mesonbuild"))
               if importlib.util.find_spec(module) is None]
    if shutil.which("ninja") is None and \
            importlib.util.find_spec("ninja") is None:
        missing.append("ninja")
    return missing


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", default="2027d9f")
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    missing = missing_build_tools()
    if missing:
        sys.exit(f"bench_lean.py builds a past revision without build "
                 f"isolation and needs: pip install {' '.join(missing)}")
    with tempfile.TemporaryDirectory() as tmp:
        site = build(args.before, Path(tmp))
        before, now = [], []
        for _ in range(args.rounds):
            before.append(measure(site, args.repeat))
            now.append(measure(None, args.repeat))
    assert all(str(site) in b["module"] for b in before)
    best = lambda runs, key: min(r[key] for r in runs)
    b_listing, n_listing = best(before, "listing"), best(now, "listing")
    n_lean = best(now, "lean")
    b_sin, n_sin = best(before, "sin"), best(now, "sin")
    print(f"{'call':<44}{'us':>9}{'/ sin':>8}")
    rows = ((f"solve(ds, 'double') at {args.before}", b_listing, b_sin),
            ("solve(ds, 'double') now", n_listing, n_sin),
            ("solve(ds, 'double', listing=False) now", n_lean, n_sin),
            ("numpy.sin, 1,064 elements", n_sin, n_sin))
    for name, us, sin in rows:
        print(f"{name:<44}{us:>9.1f}{us / sin:>8.1f}")
    print(f"gain: before / lean = {b_listing / n_lean:.1f}x "
          f"(target >= 10x); lean / sin = {n_lean / n_sin:.1f}x "
          f"(target <= 8x); lean / 10 us bound = {n_lean / 10:.1f}x")


if __name__ == "__main__":
    main()
