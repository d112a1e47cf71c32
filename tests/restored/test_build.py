"""The installed binaries are built the way the results depend on."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from contactsep.restored import core, legacy, thesis_decks


def installed_binaries() -> list[Path]:
    import contactsep.restored._core_double as double
    import contactsep.restored._core_single as single

    return [Path(single.__file__), Path(double.__file__),
            legacy.executable("single"), legacy.executable("double")]


@pytest.mark.skipif(shutil.which("nm") is None, reason="needs binutils nm")
@pytest.mark.parametrize("binary", installed_binaries(), ids=lambda p: p.name)
def test_no_simd_libm_variants(binary):
    """-O3 vectorisation would call glibc's _ZGV*sin* SIMD variants, which
    differ from scalar sinf/sin in the last ulp: the Fortran is pinned to
    scalar calls, so listings do not depend on the optimiser."""
    symbols = subprocess.run(["nm", "-D", str(binary)], capture_output=True,
                             text=True, check=True).stdout
    assert not re.search(r"_ZGV\w*(sin|cos|exp)", symbols), symbols
    if binary.name.startswith("appg"):
        assert re.search(r"\b(sinf|sin|cosf|cos)\b", symbols)


def test_double_build_computes_in_double():
    """f2py maps a named kind to C float unless told: the double module must
    return float64 and agree with float64 arithmetic far beyond float32."""
    ds = thesis_decks.thesis_data_set(0.250)
    single, double = core.solve(ds, "single"), core.solve(ds, "double")
    assert single.p.dtype == np.float32 and double.p.dtype == np.float64
    assert double.history_ty3.dtype == np.float64
    # p_j = (k_j L)^2 sqrt(E I g / (A gamma)) / L^2, in float64 here
    area, inertia = ds.b * ds.h, ds.b * ds.h**3 / 12.0
    p = ds.v**2 * np.sqrt(ds.e * inertia * 386.4 / (area * ds.rho / 1728.0)) \
        / ds.xl**2
    np.testing.assert_allclose(double.p, p, rtol=1e-14)
    assert np.max(np.abs(single.p / p - 1)) > 1e-9  # float32 cannot do that
    assert double.listing != single.listing


def test_version_and_typing_marker(capsys):
    import importlib.resources

    import contactsep
    from contactsep.cli import main

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == \
        f"contactsep {contactsep.__version__}"
    assert importlib.resources.files("contactsep").joinpath(
        "py.typed").is_file()
