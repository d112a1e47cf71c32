"""The numbers docs/chatter.md quotes that are cheap to rerun, rerun
(issue 26): each is asserted to the digits the page prints, so that the
page cannot drift from the code.  Every simulate call goes through
package_call.run with its settings explicit (the page's: the thesis rig,
d = 0.25 in, the 0.06 s window, dt 5e-8 s)."""

from __future__ import annotations

import pytest

import contactsep
from package_call import run

DOCS = "docs/chatter.md"


def _printed(value: float, claim: str) -> bool:
    """value printed to the claim's significant digits is the claim."""
    digits = len(claim.split("e")[0].replace(".", "").lstrip("0")) - 1
    return f"{value:.{digits}e}" == f"{float(claim):.{digits}e}"


def _relative(a, b):
    return abs(a / b - 1.0)


def test_the_hertz_n16_convergence_figures():
    """"at the default 5e-8 s against 3.125e-9 s: first impulse 6.8e-7,
    largest lower gap 6.9e-7, open time 4.2e-6 relative" (0.8 s)."""
    design = contactsep.thesis_design(n_modes=16)
    default, fine = (run(design, dt=dt, t_end=0.06, samples=10)
                     for dt in (5e-8, 3.125e-9))
    for name, claim in (("first_impulse_lb_s", "6.8e-7"),
                        ("max_lower_gap_in", "6.9e-7"),
                        ("circuit_open_s", "4.2e-6")):
        measured = _relative(getattr(default, name), getattr(fine, name))
        assert _printed(measured, claim), (name, measured, claim)


# the page's "In N" table, Newton's first impulse (lb s), default dt
NEWTON_FIRST_IMPULSE = {4: "1.999e-3", 8: "9.932e-4", 16: "4.977e-4",
                        32: "2.495e-4", 64: "1.509e-4"}


def test_the_newton_impulse_halves_with_n_up_to_32_only():
    """"the Newton impulse halves each time N doubles up to N = 32
    (... x0.50 per doubling) ...; from N = 32 to 64 the halving stops
    (impulse x0.60 ...)", and the table's first impulses (the window
    cut at 0.0235 s, after the first episode: the same grid, so the same
    impulse)."""
    design = contactsep.thesis_design()
    impulse = {n: run(design.replace(n_modes=n), model="newton", dt=5e-8,
                      t_end=0.0235, samples=10).first_impulse_lb_s
               for n in NEWTON_FIRST_IMPULSE}
    for n, claim in NEWTON_FIRST_IMPULSE.items():
        assert _printed(impulse[n], claim), (n, impulse[n], claim)
    for n in (4, 8, 16):
        assert impulse[2 * n] / impulse[n] == pytest.approx(0.50, abs=0.005)
    assert impulse[64] / impulse[32] == pytest.approx(0.60, abs=0.005)


def test_the_printed_claims_are_on_the_page():
    """The sentences the tests above hold are the page's (an edit of the
    page must come with an edit here)."""
    from pathlib import Path
    text = " ".join((Path(__file__).resolve().parents[2] / DOCS)
                    .read_text().split())
    assert ("first impulse 6.8e-7, largest lower gap 6.9e-7, open time "
            "4.2e-6 relative") in text
    assert "halves each time N doubles up to N = 32" in text
    assert "impulse ×0.60, kick ×0.98" in text
    for claim in NEWTON_FIRST_IMPULSE.values():
        assert claim in text
