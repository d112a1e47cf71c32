"""A chunk on a Dask worker gets glibc's own malloc thresholds back
(issue 29, item 1): Dask's nanny starts workers with
MALLOC_TRIM_THRESHOLD_=65536, which makes every array over 128 KiB a
fresh, page-faulted mmap.  Checked by the kernel's own count of page
faults (getrusage), not by timing."""

import os
import subprocess
import sys
import textwrap

import pytest

_PROBE = textwrap.dedent("""
    import resource
    import numpy as np
    from contactsep.runs import dask_run

    def faults():
        before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        for _ in range(50):
            a = np.empty(131072)      # 1 MiB, written: every page touched
            a[:] = 1.0
            del a
        return resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before

    faults()
    plain = faults()
    dask_run.heap_as_glibc_default()
    faults()
    print(plain, faults())
""")


def _faults(env_extra):
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    env.update(env_extra)
    out = subprocess.run([sys.executable, "-c", _PROBE], env=env,
                         capture_output=True, text=True, check=True)
    before, after = map(int, out.stdout.split())
    return before, after


@pytest.mark.skipif(not sys.platform.startswith("linux"),
                    reason="glibc's malloc")
def test_dask_workers_heap_no_longer_faults_every_array():
    before, after = _faults({"MALLOC_TRIM_THRESHOLD_": "65536"})
    # 50 arrays of 256 pages, each a fresh mmap: every page faults
    assert before >= 50 * 256 * 0.9
    # the heap reuses the freed array: (almost) no page touched anew
    assert after < 50 * 256 * 0.05


@pytest.mark.skipif(not sys.platform.startswith("linux"),
                    reason="glibc's malloc")
def test_plain_process_keeps_its_malloc():
    """Without Dask's variable glibc's dynamic threshold already reuses
    the array (the premise: there is nothing to give back)."""
    before, after = _faults({})
    assert before < 50 * 256 * 0.05
    assert after < 50 * 256 * 0.05


def test_only_a_static_heap_is_changed(monkeypatch):
    """mallopt is called only where a MALLOC_*_ variable turned the
    dynamic threshold off, with glibc's own largest thresholds, once."""
    from contactsep.runs import dask_run
    calls = []

    class Libc:
        def mallopt(self, parameter, value):
            calls.append((parameter, value))
            return 1

    monkeypatch.setattr(dask_run.ctypes, "CDLL", lambda name: Libc())
    for name in dask_run._STATIC_HEAP:
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(dask_run, "_heap_set", False)
    dask_run.heap_as_glibc_default()
    assert calls == []
    monkeypatch.setattr(dask_run, "_heap_set", False)
    monkeypatch.setenv("MALLOC_TRIM_THRESHOLD_", "65536")
    dask_run.heap_as_glibc_default()
    dask_run.heap_as_glibc_default()
    assert calls == [(-3, 32 * 1024 * 1024), (-1, 64 * 1024 * 1024)]
