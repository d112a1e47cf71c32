"""The performance pages show committed benchmark runs: every part a
benchmark run with ``--save`` wrote to ``benchmarks/results/NAME.md``
(its tables and printed lines) is shown on a page by the
``benchmark-run`` directive (docs/_ext/benchmark_runs.py), its
provenance by the ``benchmark-provenance`` role, and no table row is
retyped; the numbers the prose draws from a run are ``datum`` roles
(resolved by tests/project/test_data_values.py).  What is still read
from the prose here: figures of cells that are not numbers (a time with
its ratio, "0.034 s (0.33x)"), a Wilson interval, and the constants of
the code the pages state in words.  Timings depend on the machine; what
is checked is that the pages show what the committed run measured."""

from __future__ import annotations

import re
import sys

import pytest

from conftest import ROOT

#: The performance pages: the current figures, contact dynamics, and
#: parallel runs and scaling (a quoted figure may be on any of them).
PAGE_FILES = [ROOT / "docs" / name for name in (
    "performance.md", "performance-contact.md", "performance-parallel.md")]


class Pages:
    """The performance pages read as one text."""

    name = "the performance pages"

    def read_text(self) -> str:
        return "\n".join(path.read_text() for path in PAGE_FILES)


PAGE = Pages()
RESULTS = ROOT / "benchmarks" / "results"


def squeezed(line: str) -> str:
    return " ".join(line.split())


def page_lines() -> set[str]:
    return {squeezed(line) for line in PAGE.read_text().splitlines()}


def result_lines(name: str) -> list[str]:
    """The run's lines: its provenance, then what it printed (the
    command, an HTML comment, left out)."""
    lines = (RESULTS / f"{name}.md").read_text().splitlines()
    assert lines[0].startswith("<!-- ") and lines[1].startswith("run ")
    return [squeezed(line) for line in lines[1:] if line.strip()]


def table(name: str) -> dict:
    """label -> (ms, ratio to numpy.sin, work) of a run's table rows."""
    rows = {}
    for line in result_lines(name):
        cells = [c.strip() for c in line.strip("|").split("|")]
        if line.startswith("|") and len(cells) == 4 and \
                re.fullmatch(r"[\d.]+", cells[1]):
            rows[cells[0]] = (float(cells[1]), float(cells[2]), cells[3])
    return rows


#: A use of the directive: ```{benchmark-run} NAME, then :parts: K.
DIRECTIVE = re.compile(r"```\{benchmark-run\}\s+(\w+)\s*\n"
                       r"(?::parts:\s*([\d,\- ]+)\n)?")
RUN_NAMES = sorted(p.stem for p in RESULTS.glob("*.md"))


def shown_parts(text: str) -> dict:
    """{run name: set of part numbers} the directives in ``text`` show
    (None: every part)."""
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    import benchmark_runs

    shown = {}
    for name, parts in DIRECTIVE.findall(text):
        run = benchmark_runs.read_run(RESULTS / f"{name}.md")
        shown.setdefault(name, set()).update(benchmark_runs.selected(
            parts or None, len(run.parts), name))
    return shown


@pytest.mark.parametrize("name", RUN_NAMES)
def test_every_part_of_a_committed_run_is_shown(name):
    """Each part of each committed run is on a performance page, from
    the file (the directive), and its provenance too (the role)."""
    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    import benchmark_runs

    run = benchmark_runs.read_run(RESULTS / f"{name}.md")
    text = PAGE.read_text()
    assert shown_parts(text).get(name) == set(range(1, len(run.parts) + 1))
    assert f"{{benchmark-provenance}}`{name}`" in text


def retyped(lines: set) -> list:
    """The committed runs' table rows among ``lines`` (squeezed)."""
    rows = {line for name in RUN_NAMES for line in result_lines(name)
            if line.startswith("|") and not set(line) <= set("|-: ")}
    return sorted(line for line in lines if line in rows)


def test_no_row_of_a_run_is_retyped():
    """A table row of a committed run typed on a page would go stale."""
    assert retyped(page_lines()) == []


def test_the_scan_sees_what_is_missing():
    """The checks above can fail: a page showing part 1 of a run of two
    parts misses part 2; a retyped row is found, a rule line is not."""
    two = next(name for name in RUN_NAMES
               if len(result_lines(name)) > 2 and shown_parts(
                   f"```{{benchmark-run}} {name}\n```")[name] != {1})
    assert shown_parts(f"```{{benchmark-run}} {two}\n:parts: 1\n```") \
        == {two: {1}}
    row = next(line for line in result_lines("bench_model")
               if line.startswith("| thesis-like"))
    assert retyped({row, "|---|---:|", "prose"}) == [row]


def quoted(pattern: str, page=PAGE) -> tuple[str, ...]:
    found = re.search(pattern, " ".join(page.read_text().split()))
    assert found, f"{page.name} no longer says {pattern!r}"
    return found.groups()


def checks_table() -> dict:
    """design -> cells of the bench_checks run's rows."""
    rows = {}
    for line in result_lines("bench_checks"):
        cells = [c.strip() for c in line.strip("|").split("|")]
        if line.startswith("|") and len(cells) == 5 and \
                cells[2].endswith("(1x)"):
            rows[cells[0]] = cells
    return rows


def test_the_checks_prose_is_the_run():
    rows = checks_table()

    def ratio(cell):                  # "0.034 s (0.33x)" -> 0.33
        return float(re.search(r"\(([\d.]+)x\)", cell).group(1))

    def numerics(design):             # dt (s), window (s)
        dt, window, _ = rows[design][4].split(", ")
        return float(dt), float(window)

    step, thesis = quoted(r"on the thesis rig 0.295 s instead of 0.06 s, "
                          r"at a step ([\d.]+)x the old one, ([\d.]+)x the "
                          r"time of the old settings")
    assert numerics("thesis") == (pytest.approx(float(step) * 5e-8,
                                                rel=0.01), 0.295)
    assert f"{numerics('thesis')[0] / 5e-8:.2f}" == step
    assert f"{1 / ratio(rows['thesis'][1]):.1f}" == thesis
    low, high, finer_low, finer_high, cost_low, cost_high = quoted(
        r"on the relays the window is short \((\d+)-(\d+) ms\) and the step "
        r"([\d.]+)-([\d.]+)x finer, ([\d.]+)x to ([\d.]+)x the old cost")
    relays = ("steel_relay", "becu_light")
    windows = sorted(1e3 * numerics(r)[1] for r in relays)
    assert [f"{w:.0f}" for w in windows] == [low, high]
    finer = sorted(5e-8 / numerics(r)[0] for r in relays)
    assert [f"{f:.1f}" for f in finer] == [finer_low, finer_high]
    costs = sorted(1 / ratio(rows[r][1]) for r in relays)
    assert [f"{c:.1f}" for c in costs] == [cost_low, cost_high]
    steps, preloaded = quoted(r"window / step \(([\d.]+)x the old steps on "
                              r"the steel relay\): the default is "
                              r"([\d.]+)x the old settings' time there")
    dt, window = numerics("steel_relay, preload 0.35 lb")
    assert f"{(window / dt) / (0.06 / 5e-8):.1f}" == steps
    assert f"{1 / ratio(rows['steel_relay, preload 0.35 lb'][1]):.1f}" \
        == preloaded
    low, high = quoted(r"`--verify` costs a run at 2N and half the step: "
                       r"([\d.]+)-([\d.]+)x the run")
    verify = [ratio(cells[3]) for cells in rows.values()]
    assert (f"{min(verify):.1f}", f"{max(verify):.1f}") == (low, high)


def test_the_memory_target_is_the_run():
    ratios = dict(re.findall(r"\| `contactsep (\w+)` \| \d+ MB \| "
                             r"([\d.]+)x \| exit 0", "\n".join(
                                 result_lines("bench_memory"))))
    replay, legacy = quoted(r"Target <= 3x: met \(`replay` ([\d.]+)x and "
                            r"`legacy` ([\d.]+)x\)")
    assert (replay, legacy) == (ratios["replay"], ratios["legacy"])
    assert max(float(replay), float(legacy)) <= 3


def test_the_constants_the_page_states_are_the_codes():
    """What follows from the chunk sizing's constants (the first chunk,
    the chunks to the cap), Dask's window, the model's build flags and
    its search chunk (Fortran's): what the page says in words is what
    the code does.  The Python constants themselves are ``constant`` roles
    on the page (a changed constant changes the page)."""
    import inspect

    from contactsep.output import pieces
    from contactsep.runs import backend
    from contactsep.studies.sweep import spec as sweep
    # the constants are the code's own on the page (``constant`` roles:
    # tests/project/test_code_constants.py); what follows from them is
    # checked here
    (first,) = quoted(r"s of work each, the first ([\d,]+) designs at "
                      r"N = 4, growing at most \{constant\}`contactsep\.output"
                      r"\.pieces\.GROWTH`-fold a chunk\)")
    # one rule for both: contactsep.output.pieces
    assert int(first.replace(",", "")) == pieces.FIRST_PIECE_COST // 4
    assert "GROWTH * self.next" in inspect.getsource(pieces.PieceSizes)
    (after,) = quoted(r"spec\.CHUNK_SIZE:,` cap after (\w+)\.")
    size, count = pieces.FIRST_PIECE_COST // 4, 0
    while size < sweep.CHUNK_SIZE:    # each chunk at most GROWTH x the last
        size = min(pieces.GROWTH * size, sweep.CHUNK_SIZE)
        count += 1
    assert {"two": 2, "three": 3, "four": 4}[after] == count
    # the window the page describes: DASK_WINDOW_PER_WORKER chunks a
    # worker thread when only summaries come back, twice the threads
    # otherwise, plus 2
    quoted(r"then twice the cluster's threads plus 2, now \{constant\}"
           r"`contactsep\.runs\.backend\.DASK_WINDOW_PER_WORKER:words` "
           r"times when only summaries come back")
    assert backend.DaskCluster.chunk_window(
        _Threads(8), summaries=True) == 8 * backend.DASK_WINDOW_PER_WORKER + 2
    assert backend.DaskCluster.chunk_window(
        _Threads(8), summaries=False) == 2 * 8 + 2
    (flags,) = quoted(r"The model is built with ([-\w, ]+ and -flto)")
    meson = (ROOT / "fortran" / "model" / "meson.build").read_text()
    args = re.search(r"model_fortran_args = \[([^\]]+)\]", meson).group(1)
    assert re.split(r", | and ", flags) == re.findall(r"'([^']+)'", args)
    (chunk,) = quoted(r"the extremes' search works on chunks of ([\d,]+) "
                      r"designs")
    api = (ROOT / "fortran" / "model" / "model_api.f90").read_text()
    assert f"integer, parameter :: chunk = {chunk.replace(',', '')}" in api


def test_the_status_4_limits_are_model_mds():
    """'N = 10⁴ and τ = 10⁸ s give status 4': docs/model.md's limits
    (tests/project/test_docs_pages.py runs them, slow)."""
    n, tau = quoted(r"N = (10\S+) and τ = (10\S+) s give status 4")
    model = " ".join((ROOT / "docs" / "model.md").read_text().split())
    assert f"τ = {tau} s gives status 4, and so does N = {n}" in model


def test_the_chatter_sweep_p_open_is_the_run():
    """'every one of the 40 preloaded designs opens (p_open 1; 95 % Wilson
    interval [0.912, 1]': the run's design count (its table's header) and
    the Wilson interval of 40 of 40 (the statistics module's)."""
    from contactsep.studies.stats import wilson_interval
    designs = None
    for line in result_lines("bench_chatter_sweep"):
        found = re.match(r"\| run \(([\d,]+) designs", line)
        if found:
            designs = int(found.group(1).replace(",", ""))
    count, low, high = quoted(r"every one of the (\d+) preloaded designs "
                              r"opens \(p_open 1; 95 % Wilson interval "
                              r"\[([\d.]+), (\d)\]")
    assert int(count) == designs
    assert "preload 20 lb: sweep, 1 worker(s), progress bar (p_open 1)" in \
        " ".join(result_lines("bench_chatter_sweep"))
    interval = wilson_interval(designs, designs)
    assert (f"{interval[0]:.3f}", f"{interval[1]:g}") == (low, high)
    # the closed form for k = n: n / (n + z^2), z = 1.96
    assert abs(interval[0] - designs / (designs + 1.959964 ** 2)) < 1e-4


def test_the_contact_dynamics_counts_are_the_codes():
    """'one fused loop over the 48 modes' (three members of N = 16),
    '-fopenmp-simd', '64 steps kept': the chatter build and the stepper's
    parameter."""
    (modes,) = quoted(r"Each step is one fused loop over the (\d+) modes")
    assert int(modes) == 3 * 16
    (kept,) = quoted(r"the largest-gap searches wait for the end of the "
                     r"run \((\d+) steps kept\)")
    state = (ROOT / "fortran" / "chatter" / "adaptive_state.f90").read_text()
    assert f"integer, parameter :: max_waiting = {kept}" in state
    quoted(r"compiled with `-fopenmp-simd`")
    build = (ROOT / "fortran" / "chatter" / "meson.build").read_text()
    assert "'-fopenmp-simd'" in build


def test_the_samples_cost_a_flight_step_each():
    """'The 60,000 samples cost one flight step each (the default row
    against the summary-only one)': simulate's default samples (the
    page's ``constant`` role), and the two rows' flight steps differ by
    that many, to within 5 %."""
    import importlib
    simulate_module = importlib.import_module("contactsep.chatter.simulate")
    rows = table("bench_chatter")
    quoted(r"The \{constant\}`contactsep\.chatter\.simulate\."
           r"DEFAULT_SAMPLES:,` samples cost one flight step each")
    samples = simulate_module.DEFAULT_SAMPLES

    def flight(row):
        return int(re.search(r"flight_steps (\d+)", row[2]).group(1))

    extra = flight(rows["hertz N=16 (default)"]) - \
        flight(rows["hertz N=16, summary only"])
    assert abs(extra / samples - 1) < 0.05


class _Threads:
    """A Dask backend's workers alone (its window's one input)."""

    def __init__(self, workers: int) -> None:
        self.workers = workers
