"""The remaining numbers of docs/studies.md and the pages split from
it (issue 30, item 8), beside test_docs_pages.py: the bytes a resumable
sweep keeps a design, the failed-designs message of the page's command,
the Dask chunking's constants, osmium's density, conclusion 8's
convergence, and the Newton band claim's source.  The computed numbers
are ``datum`` roles of committed JSON under docs/studies (each checked
against the command that prints it); the Newton band claim is still
found by the sentence that quotes it (docs/convergence.md's run is not
committed as data)."""

from __future__ import annotations

import re

import pytest
from docs_text import page, quoted, says, script_module

from contactsep.cli import main as cli_main


def test_a_resumable_sweeps_chunks_take_the_quoted_bytes(tmp_path):
    """'~44 bytes a design for an eq23 sweep of one varied field' (a
    ``datum`` role of docs/studies/resume_bytes.json): the chunk files of
    such a sweep, kept, grow by the committed bytes a design and start
    from the committed bytes a chunk, as `python
    docs/studies/make_resume_bytes.py` measures them now (the slope of a
    file's bytes over its designs, docs/studies/make_resume_bytes.py)."""
    import json

    import numpy as np

    from conftest import ROOT
    from docs_text import STUDIES
    says("howto/resume.md", "in binary (~{datum}`studies/resume_bytes.json:"
         "bytes_per_design:.0f` bytes a design for an eq23 sweep of one "
         "varied field: `docs/studies/resume_bytes.json`, printed by "
         "`python docs/studies/make_resume_bytes.py`)")
    committed = json.loads((STUDIES / "resume_bytes.json").read_text())
    module = script_module(STUDIES / "make_resume_bytes.py")
    assert committed["designs"] == module.DESIGNS
    sizes, sizes_bytes = module.chunks(tmp_path)
    assert sum(sizes) == module.DESIGNS and len(set(sizes)) >= 2, sizes
    per_design, header = np.polyfit(sizes, sizes_bytes, 1)
    assert per_design == pytest.approx(committed["bytes_per_design"],
                                       rel=1e-9)
    assert header == pytest.approx(committed["bytes_per_chunk"], rel=1e-9)


def test_the_failed_designs_message_is_the_commands(capsys):
    """The one-line warning the page quotes (its counts ``datum`` roles of
    docs/studies/failed_designs_summary.json, the command's ``--json``
    summary) is what its command prints, and the committed summary is
    the one it prints now (its counts and inputs exactly)."""
    import json

    from docs_text import STUDIES
    name = "studies/failed_designs_summary.json"
    committed = json.loads((STUDIES / "failed_designs_summary.json")
                           .read_text())
    inputs = committed["inputs"]
    (field, law), = inputs["sample"].items()
    assert (field, law["distribution"]) == ("d_in", "normal")
    sample = f"d=normal({law['mean']:g},{law['sd']:g})"
    samples = str(inputs["samples"])
    says("sweeps.md", f"(`--sample '{sample}' --samples {samples}`: "
         f"`contactsep: warning:` {{datum}}`{name}:n_failed:,d` of "
         f"{{datum}}`{name}:inputs.designs:,d` `designs failed (`"
         f"{{datum}}`{name}:n_failed_by_status.2:,d` `invalid input); "
         "...`; its summary with `--json`: "
         "`docs/studies/failed_designs_summary.json`)")
    assert cli_main(["sweep", "--sample", sample, "--samples", samples,
                     "--progress", "never", "--json"]) == 0
    out, err = capsys.readouterr()
    now = json.loads(out)
    for key in ("n", "n_failed", "n_failed_by_status", "inputs"):
        assert now[key] == committed[key], key
    failed, total = committed["n_failed"], inputs["designs"]
    invalid = committed["n_failed_by_status"]["2"]
    assert (f"contactsep: warning: {failed:,} of {total:,} designs failed "
            f"({invalid:,} invalid input); ") in err, err


def test_the_dask_chunking_is_the_codes():
    """The chunks a Dask cluster has in flight, as sweeps.md says them:
    twice its threads plus two (the constants of the sizing rule are
    the page's ``constant`` roles)."""
    from contactsep.runs import backend

    class Threads:
        workers = 8

    says("sweeps.md", "twice as many chunks as the cluster has threads, "
         "plus two, are in flight ({constant}`contactsep.runs.backend."
         "DASK_WINDOW_PER_WORKER:words` times as many when only summaries "
         "come back)")
    assert backend.DaskCluster.chunk_window(Threads(), False) == 2 * 8 + 2
    assert backend.DaskCluster.chunk_window(Threads(), True) == \
        backend.DASK_WINDOW_PER_WORKER * 8 + 2


def test_osmiums_density():
    """'osmium is 0.816' lb/in^3 (docs/studies/model_numbers.json, which
    tests/project/test_docs_model_page.py checks against its command):
    22.59 g/cm^3 (CRC Handbook)."""
    import json

    from conftest import ROOT
    pint = pytest.importorskip("pint")
    says("names-and-units.md", "osmium is {datum}`studies/model_numbers."
         "json:domain.osmium_lb_in3:.3f`)")
    committed = json.loads((ROOT / "docs" / "studies" /
                            "model_numbers.json").read_text())
    value = (22.59 * pint.UnitRegistry()("g/cm^3")).to("lb/in^3").magnitude
    assert committed["domain"]["osmium_lb_in3"] == pytest.approx(
        value, rel=1e-9)


def test_the_newton_band_claim_is_the_convergence_pages():
    """studies.md quotes docs/convergence.md's tolerance-band convergence
    (whose table is benchmarks/chatter_convergence.py band's run): the
    same 1 % at the default step and the same ±0.5 % band."""
    within, band = quoted("sweeps.md", r"converged to (\d+) % at the "
                          r"default step for L2 within ±([\d.]+) %: "
                          r"docs/convergence.md, \"The Newton open time "
                          r"over a tolerance band\"")
    convergence = page("convergence.md")
    assert re.search(rf"The default 5e-8 s is within {within} % for every "
                     rf"thesis separator", convergence)
    assert re.search(rf"uniform within ±{re.escape(band)} %", convergence)


C8 = "studies/conclusion8_convergence.json"


def _make_conclusion8_convergence():
    from docs_text import STUDIES
    return script_module(STUDIES / "make_conclusion8_convergence.py")


def _conclusion8_convergence() -> dict:
    import json

    from docs_text import STUDIES
    return json.loads((STUDIES / "conclusion8_convergence.json")
                      .read_text())


def test_conclusion_8s_convergence_is_what_its_command_prints():
    """docs/studies/conclusion8_convergence.json is what `python
    docs/studies/make_conclusion8_convergence.py` prints now: the
    counts exactly, the share's departures to 1e-8 relative (each a
    difference of two near shares)."""
    committed = _conclusion8_convergence()
    now = _make_conclusion8_convergence().main()
    assert committed["counts"] == now["counts"]
    share, fresh = committed["share"], now["share"]
    assert share["departure"].keys() == fresh["departure"].keys()
    for n, off in fresh["departure"].items():
        assert share["departure"][n] == pytest.approx(off, rel=1e-8), n
    for key in ("reference_n", "tolerance", "converged_from_n"):
        assert share[key] == fresh[key], key


def _first_mode_share(n_modes):
    """Conclusion 8's first-mode share over its x3/L3 grid, from eq. 23's
    c3_j (the study's formula, without its costly maxima count)."""
    import numpy as np

    from contactsep.model import evaluate, thesis_design
    from contactsep.studies.thesis import mode_share
    base = thesis_design(n_modes=n_modes)
    c3 = np.nan_to_num(evaluate(base.replace(
        x3=mode_share.RATIOS * float(base.L3))).c3)
    return c3[:, 0] ** 2 / np.sum(c3 ** 2, axis=1)


def test_conclusion_8s_share_converges_from_the_quoted_n():
    """'converged to 1e-4 from N = 16 on' (the committed file's N):
    against N = 256, relative, and not yet at half that N."""
    import numpy as np
    says("studies.md", "The share is converged to 1e-4 from N = "
         f"{{datum}}`{C8}:share.converged_from_n` on (N = 32 against 64)")
    share = _conclusion8_convergence()["share"]
    assert (share["tolerance"], share["reference_n"]) == (1e-4, 256)
    first = share["converged_from_n"]
    limit = _first_mode_share(256)

    def off(n):
        return float(np.max(np.abs(_first_mode_share(n) / limit - 1)))

    assert all(off(n) < 1e-4 for n in (first, 2 * first, 64))
    assert off(first // 2) > 1e-4


def test_conclusion_8s_counts_at_one_and_twenty_percent():
    """'at 1 % prominence the count at x3/L3 = 0.5 grows 56, 153, 290,
    361 at N = 8, 16, 32, 64'; at 20 %, x3/L3 = 0.67: 1 and 2 at N = 32
    and 64: the committed file's counts (which the test above reruns),
    of the rows and prominences the page names."""
    from contactsep.studies.thesis import mode_share
    counts = _conclusion8_convergence()["counts"]
    low, study = counts["one_percent"], counts["study_prominence"]
    assert (low["prominence"], low["r"]) == (0.01, 0.5)
    assert (study["prominence"], study["r"]) == (mode_share.PROMINENCE,
                                                  0.67)
    assert mode_share.PROMINENCE == 0.2              # "at 20 %"

    def shown(key, n):
        return f"{{datum}}`{C8}:counts.{key}.n_maxima.{n}`"

    says("studies.md", "at 1 % prominence the count at x3/L3 = 0.5 grows "
         + ", ".join(shown("one_percent", n) for n in (8, 16, 32, 64))
         + " at N = 8, 16, 32, 64); at 20 % prominence")
    says("studies.md", "between N = 32 and 64 (x3/L3 = 0.67: "
         f"{shown('study_prominence', 32)} and "
         f"{shown('study_prominence', 64)};")
    assert list(low["n_maxima"]) == ["8", "16", "32", "64"]
    assert list(study["n_maxima"]) == ["32", "64"]
