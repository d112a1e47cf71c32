"""Design: validation, batches, replace, pack() layout (the contract with
the compiled backend), thesis_design."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from contactsep.errors import InputError
from contactsep.model import Design, DesignError, evaluate, thesis_design
from contactsep.model.design import pack
from contactsep.model.design_domain import INT_COLUMNS, REAL_COLUMNS

CONTRACT_REAL = ("L1 b1 h1 gamma1 E1 x1 L2 b2 h2 gamma2 E2 x2 Lc "
                 "L3 b3 h3 gamma3 E3 x3 ys e tau gap").split()


def test_contract_columns():
    assert list(REAL_COLUMNS) == CONTRACT_REAL
    assert list(INT_COLUMNS) == "end1 end2 end3 n1 n2 n3".split()


def test_thesis_design_values():
    d = thesis_design()
    assert (d.L1, d.b1, d.h1, d.L2, d.b2, d.h2) == (19.0, 2.0, 0.125, 2.5,
                                                    0.5, 0.25)
    assert (d.E1, d.gamma2, d.ys, d.e, d.n_modes, d.tau) == (
        10.0e6, 0.100, 0.5, 0.375, 4, 0.060)
    assert d.Lc is None and d.x1 is None
    assert dataclasses.is_dataclass(d)
    with pytest.raises(dataclasses.FrozenInstanceError):
        d.L1 = 3.0


def test_pack_resolves_defaults_and_broadcasts():
    d = thesis_design(d=np.array([0.1, 0.2, 0.3]), x3=np.array([[19.0],
                                                                [15.0]]),
                      n_modes=(4, 6, 8), end3="clamped-pinned")
    p = pack(d)
    assert p.shape == (2, 3) and p.real.shape == (6, 23)
    # one design contiguous (the kernel reads a design at a time)
    assert p.real.flags.c_contiguous and p.ints.flags.c_contiguous
    assert p.real.dtype == np.float64 and p.ints.dtype == np.int32
    col = {n: p.real[:, k] for k, n in enumerate(CONTRACT_REAL)}
    np.testing.assert_array_equal(col["x1"], 19.0)
    np.testing.assert_array_equal(col["x2"], 1.25)
    np.testing.assert_array_equal(col["Lc"], 0.0)
    np.testing.assert_array_equal(col["x3"], [19, 19, 19, 15, 15, 15])
    np.testing.assert_array_equal(col["h2"], [.1, .2, .3, .1, .2, .3])
    np.testing.assert_array_equal(p.ints[0], [1, 2, 3, 4, 6, 8])
    # the defaults' codes: lower_response "impulse" is code 1
    np.testing.assert_array_equal(p.options, [0, 1, 0, 0])
    opt = pack(d.replace(impact_velocity="listing",
                         lower_response="as-printed", lc_reading="mass",
                         release="contact")).options
    np.testing.assert_array_equal(opt, [1, 0, 2, 1])


def test_batch_shape_of_results():
    r = evaluate(thesis_design(d=np.array([[0.1, 0.2], [0.3, 0.4]])),
                 backend="numpy")
    assert r.y3_max.shape == (2, 2) and r.p3.shape == (2, 2, 4)
    assert r.y3(np.linspace(0, 0.06, 5)).shape == (2, 2, 5)
    one = evaluate(thesis_design(d=0.3), backend="numpy")
    assert float(r.y3_max[1, 0]) == pytest.approx(float(one.y3_max),
                                                  rel=1e-14)
    assert isinstance(r.to_dict(), dict) and len(repr(r)) < 800


@pytest.mark.parametrize("field,value", [
    ("L1", -1.0), ("b2", 0.0), ("h3", np.nan), ("gamma2", -0.1),
    ("E3", 0.0), ("x1", 25.0), ("x2", 0.0), ("e", -0.1), ("e", 1.5),
    ("tau", 0.0), ("ys", np.inf), ("end1", "free-free"),
    ("n_modes", 0), ("n_modes", 2.5), ("n_modes", (1, 2)),
    ("Lc", -3.0), ("lower_response", "exact"), ("lc_reading", "both")])
def test_validation_one_line_naming_the_field(field, value):
    with pytest.raises(DesignError) as info:
        thesis_design(**{field: value})
    msg = str(info.value)
    assert isinstance(info.value, InputError)
    assert "\n" not in msg and msg.isprintable()
    assert msg.split(":")[0] == field


def test_bad_row_in_batch_is_a_status_not_an_error():
    d = Design(e=np.array([0.3, 1.5, 0.4]))
    r = evaluate(d, backend="numpy")
    np.testing.assert_array_equal(r.status, [0, 2, 0])
    assert np.isnan(r.t1[1]) and np.all(np.isfinite(r.t1[[0, 2]]))
    assert d.problems() and d.problems()[0].startswith("e:")


def test_compiled_backend_error_is_input_error_when_missing():
    try:
        import contactsep.model.compiled  # noqa: F401
    except ImportError:
        with pytest.raises(InputError, match="compiled"):
            evaluate(thesis_design(), backend="compiled")
    with pytest.raises(InputError, match="backend"):
        evaluate(thesis_design(), backend="gpu")


@pytest.mark.parametrize("n_modes", [100_001, 10**9, (4, 4, 200_000)])
def test_more_modes_than_the_limit_are_refused_at_once(n_modes):
    """A billion modes would run for hours (and a huge N ignored SIGTERM
    inside one sum): refused when the design is made, with the limit."""
    with pytest.raises(DesignError, match="at most 100,000"):
        thesis_design(n_modes=n_modes)
    assert thesis_design(n_modes=100_000).n_modes == 100_000


def test_unset_x3_is_the_lower_contacts_tip_not_the_upper_ones():
    """L1 != L3 with x3 unset: the lower contact is touched at its own tip
    L3 (the thesis rig has L1 = L3, which would hide x3 taken from L1)."""
    d = thesis_design(L1=15.0, L3=19.0)
    col = dict(zip(REAL_COLUMNS, pack(d).real[0]))
    assert (col["x1"], col["x3"]) == (15.0, 19.0)
    for backend in ("compiled", "numpy"):
        unset = evaluate(d, backend=backend)
        tip = evaluate(d.replace(x3=19.0), backend=backend)
        wrong = evaluate(d.replace(x3=15.0), backend=backend)
        assert float(unset.y3_max) == float(tip.y3_max)
        assert float(unset.psi) == float(tip.psi)
        # and the other reading would change the answer
        assert abs(float(wrong.y3_max) / float(tip.y3_max) - 1) > 0.1
    # the same for the upper contact, and the separator's mid-span
    d = thesis_design(L1=17.0, L2=3.0, x3=12.0)
    col = dict(zip(REAL_COLUMNS, pack(d).real[0]))
    assert (col["x1"], col["x2"], col["x3"]) == (17.0, 1.5, 12.0)
