"""Every output column of a sweep checked against evaluate() of the same
design, built here from the thesis design and the row's inputs (a swapped
or mislabelled column cannot pass), and the inputs against the grid the
command line asked for."""

from __future__ import annotations

import numpy as np
import pytest
from sweep_collect import Collect

from contactsep.model import evaluate, thesis_design
from contactsep.studies.sweep import run as runner
from contactsep.studies.sweep import spec as sweep
RESULTS = {"y3_max_in": "y3_max", "t_max_s": "t_max", "psi_lb_s": "psi",
           "v0_in_s": "v0", "status": "status"}


def test_every_result_column_has_a_check_here():
    assert set(sweep.RESULT_COLUMNS) <= set(RESULTS), \
        set(sweep.RESULT_COLUMNS) - set(RESULTS)


@pytest.mark.parametrize("workers", [1, 2])
def test_every_column_equals_evaluate_of_its_design(workers):
    """A grid over two fields (one of them out of range for some designs:
    gap above the release gives status 1) and two sampled fields."""
    spec = sweep.make_spec(vary=["h2=0.1:0.9:4", "gap=0.0,0.7"],
                           sample=["ys=uniform(0.3,0.6)",
                                   "x3=uniform(14,19)"],
                           samples=6, seed=3, base={"n_modes": 6})
    out = Collect()
    summary = runner.run_sweep(spec, writers=[out], chunk_size=7,
                               workers=workers)
    t = out.table()
    expected = ["d_in", "gap_in", "ys_in", "x3_in"]
    assert list(t) == expected + list(sweep.RESULT_COLUMNS)
    size = 4 * 2 * 6
    assert all(len(v) == size for v in t.values())
    assert summary["n"] + summary["n_failed"] == size
    # the inputs: the grid (last field fastest, each point 6 samples)
    grid_h2 = np.repeat(np.linspace(0.1, 0.9, 4), 2 * 6)
    grid_gap = np.tile(np.repeat([0.0, 0.7], 6), 4)
    np.testing.assert_array_equal(t["d_in"], grid_h2)
    np.testing.assert_array_equal(t["gap_in"], grid_gap)
    assert np.all((t["ys_in"] >= 0.3) & (t["ys_in"] <= 0.6))
    assert np.all((t["x3_in"] >= 14.0) & (t["x3_in"] <= 19.0))
    assert np.unique(t["ys_in"]).size == size
    # the results: evaluate() of the designs the rows name
    ev = evaluate(thesis_design(h2=t["d_in"], gap=t["gap_in"],
                                ys=t["ys_in"], x3=t["x3_in"], n_modes=6))
    assert set(np.unique(ev.status)) == {0, 1}
    for column, field in RESULTS.items():
        np.testing.assert_array_equal(t[column], getattr(ev, field),
                                      err_msg=column)


def test_a_short_separator_sweeps_its_own_thickness():
    """The fixed fields are checked with the swept ones at a value the
    sweep takes: a separator 0.236 in long sampled around 0.0315 in
    thick is a sweep (it was refused for the thesis's d = 0.25 in, which
    no design of it has), and one sampled around 0.3 in is refused."""
    from contactsep.studies.sweep.spec import SweepError, make_spec
    spec = make_spec(sample=["d=normal(0.0315,0.0008)"], samples=3,
                     base={"L2": 0.236}, model="hertz")
    assert spec.size == 3
    spec = make_spec(vary=["d=0.03,0.04"], base={"L2": 0.236})
    assert spec.size == 2
    with pytest.raises(SweepError, match="h2: found 0.3, expected at most "
                                         "L2 = 0.236 in"):
        make_spec(sample=["d=uniform(0.25,0.35)"], samples=3,
                  base={"L2": 0.236})
