"""benchmarks/scaling_projection.py's simulation of the run machinery
against what can be worked out by hand: equal tasks on W idle workers
take ceil(n / W) task times; a parent slower than its workers makes the
wall n parent costs plus one task; the sweep's chunks cover its designs
once."""

from __future__ import annotations

import importlib.util
import math

import pytest

from conftest import ROOT


@pytest.fixture(scope="module")
def projection():
    spec = importlib.util.spec_from_file_location(
        "scaling_projection", ROOT / "benchmarks" / "scaling_projection.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("tasks, workers", [(10, 3), (256, 16), (7, 64)])
def test_equal_tasks_take_their_waves(projection, tasks, workers):
    wall = projection.simulate([2.0] * tasks, workers, parent_s=0.0)
    assert wall == pytest.approx(2.0 * math.ceil(tasks / workers))


def test_a_slow_parent_decides_the_wall(projection):
    # one task every 1 s from the parent, each 0.1 s on one of 8 workers
    wall = projection.simulate([0.1] * 50, 8, parent_s=1.0)
    assert wall == pytest.approx(50 * 1.0 + 0.1)


def test_the_window_holds_tasks_back(projection):
    # one worker, a window of one task: no overlap of parent and worker
    wall = projection.simulate([1.0] * 5, 1, parent_s=0.5, window=1)
    assert wall == pytest.approx(5 * 1.0 + 0.5 + 4 * 0.5)


def test_the_sweeps_chunks_cover_its_designs(projection):
    chunks = projection.sweep_chunks(100_000, 0.0442, 64, 100_000)
    assert sum(chunks) == pytest.approx(100_000 * 0.0442)
    # after the first (a guess from N: 256 designs), 0.5 s chunks while
    # much is left, 0.2 s at least near the end
    assert chunks[0] == pytest.approx(256 * 0.0442)
    middle = chunks[1:-1]
    assert max(middle) <= 0.5 and min(middle) >= 0.2 - 0.0442


def test_speculative_steps_take_fewer_batches(projection):
    assert projection.search_shape(1)[4:] == [1] * 8
    assert projection.search_shape(3)[4:] == [3] * 4
    assert projection.search_shape(7)[4:] == [7] * 3
