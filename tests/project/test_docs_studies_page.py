"""The remaining numbers of docs/studies.md and the pages split from
it (issue 30, item 8), beside test_docs_pages.py: the bytes a resumable
sweep keeps a design, the failed-designs message of the page's command,
the Dask chunking's constants, osmium's density, and the Newton band
claim's source.  Each number is found by the sentence that quotes it; a
reworded sentence fails."""

from __future__ import annotations

import re

import pytest
from docs_text import page, printed, quoted, says

from contactsep.cli import main as cli_main


def test_a_resumable_sweeps_chunks_take_the_quoted_bytes(tmp_path,
                                                         monkeypatch):
    """'~44 bytes a design for an eq23 sweep of one varied field': the
    chunk files of such a sweep, kept (the store's removal at the end
    switched off), grow by that much a design.  The slope of a file's
    bytes over its designs, not the total over the designs: a file's own
    header (~1.4 kB) adds to the total once a chunk, and the chunks are
    sized by the measured time, so a loaded machine cuts more of them."""
    import numpy as np

    from contactsep.runs import journal as resume
    (claim,) = quoted("howto/resume.md", r"in binary \(~(\d+) bytes a design "
                      r"for an eq23 sweep of one varied field\)")
    monkeypatch.setattr(resume.ChunkStore, "remove", lambda self: None)
    out = tmp_path / "out.csv"
    designs = 50_000
    assert cli_main(["sweep", "--vary", f"d=0.1:1:{designs}", "--csv",
                     str(out), "--resume", "--progress", "never"]) == 0
    chunks = list((tmp_path / ".out.csv.resume").glob("*.npz"))
    # a chunk's file is named by its first and last design
    sizes = [int(c.stem.split("-")[1]) - int(c.stem.split("-")[0])
             for c in chunks]
    assert sum(sizes) == designs and len(set(sizes)) >= 2, sizes
    per_design, _ = np.polyfit(sizes, [c.stat().st_size for c in chunks], 1)
    assert printed(per_design, claim), per_design


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
    """'converged to 1e-4 from N = 16 on': against N = 256, relative, and
    not yet at half that N."""
    import numpy as np
    (first,) = quoted("studies.md", r"The share is converged to 1e-4 from "
                      r"N = (\d+) on \(N = 32 against 64\)")
    limit = _first_mode_share(256)

    def off(n):
        return float(np.max(np.abs(_first_mode_share(n) / limit - 1)))

    assert all(off(n) < 1e-4 for n in (int(first), 2 * int(first), 64))
    assert off(int(first) // 2) > 1e-4


@pytest.mark.slow
def test_conclusion_8s_counts_at_one_and_twenty_percent(monkeypatch):
    """'at 1 % prominence the count at x3/L3 = 0.5 grows 56, 153, 290,
    361 at N = 8, 16, 32, 64'; at 20 %, x3/L3 = 0.67: 1 and 2 at N = 32
    and 64 (the study itself at each N, on those two of its rows: a
    row's count is its own history's, on the time grid of the first
    row's period, and the first row stays x3/L3 = 0.5)."""
    import numpy as np

    from contactsep.studies.thesis import mode_share
    claims = quoted("studies.md", r"at 1 % prominence the count at x3/L3 = "
                    r"0.5 grows (\d+), (\d+), (\d+), (\d+) at N = 8, 16, 32, "
                    r"64\); at 20 % prominence")
    steps = quoted("studies.md", r"between N = 32 and 64 \(x3/L3 = 0.67: "
                   r"(\d+) and (\d+)\)")
    at = {r: int(np.argmin(np.abs(mode_share.RATIOS - r)))
          for r in (0.5, 0.67)}
    assert mode_share.PROMINENCE == 0.2
    assert at[0.5] == 0
    monkeypatch.setattr(mode_share, "RATIOS",
                        mode_share.RATIOS[[at[0.5], at[0.67]]])
    at = {0.5: 0, 0.67: 1}
    counts = {}
    for prominence in (0.01, 0.2):
        monkeypatch.setattr(mode_share, "PROMINENCE", prominence)
        for n in (8, 16, 32, 64) if prominence == 0.01 else (32, 64):
            counts[prominence, n] = mode_share.conclusion8(
                n_modes=n)["n_maxima"]
    assert [str(counts[0.01, n][at[0.5]]) for n in (8, 16, 32, 64)] == \
        list(claims)
    assert [str(counts[0.2, n][at[0.67]]) for n in (32, 64)] == list(steps)
