"""The robust search keeps many workers busy without runs made ahead:
its batches are a preload's samples in doubling blocks (10, 20, 40, ...)
for every preload still undecided, so most are many times the workers.
Counted on planted samples (an event below 10 lb per inch of separator;
tests/planted_preload.py), with a 2 % tolerance on the separator's
thickness: the runs in flight over the worker slots, round by round."""

from __future__ import annotations

import pytest
from design_family import FAMILY
from test_runs_ahead import busy_share

import planted_preload
from contactsep.chatter.stack import largest_preload
from contactsep.studies.preload import chart
from contactsep.studies.preload import robust
from contactsep.studies.preload.robust_rule import FIRST_BLOCK


def robust_batches(design, samples: int) -> list:
    """The batch sizes of the robust search on ``design`` (W = 1: the
    same batches any W gets, no runs ahead in the robust search)."""
    h2 = float(design.h2)
    spec = robust.parse_tolerances([f"h2=normal({h2},{0.02 * h2})"],
                                   samples, 0)
    with chart.Simulations(1) as sims:
        robust.robust_preload(design, "hertz", {"dt": 1e-8, "t_end": 0.01},
                              spec, 0.01, sims, start=10.0 * h2,
                              ceiling=largest_preload(design))
    return [b for b in sims.batches if b]


@pytest.mark.parametrize("name", ["thesis", "steel_relay", "bronze_offset"])
def test_sixteen_workers_are_over_nine_tenths_busy(name, monkeypatch):
    monkeypatch.setattr(robust, "simulate_design",
                        planted_preload.fake_sample)
    batches = robust_batches(FAMILY[name], 400)
    # the blocks: every batch a whole number of first blocks of the
    # preloads tried together
    assert all(b % FIRST_BLOCK == 0 for b in batches), batches
    assert len(batches) > 20 and sum(batches) > 5000
    assert busy_share(batches, 16) >= 0.9
    assert busy_share(batches, 64) >= 0.8
    # the identity the share rests on: one worker is always busy
    assert busy_share(batches, 1) == 1.0
