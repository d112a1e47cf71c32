"""
A sweep on a Dask cluster
=========================

``contactsep sweep --scheduler ADDRESS`` (or ``run_sweep(spec,
scheduler=client)``) sends the sweep's chunks to a Dask cluster instead
of local processes.  Here a small local cluster (two threads, no
dashboard) evaluates Figure 5's sweep of the separator thickness with a
tolerance on the release height, and is closed afterwards.
"""

import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd
from dask.distributed import Client, LocalCluster

from contactsep.studies.sweep import run as runner

from contactsep.studies.sweep import spec as sweep
from contactsep.studies.sweep.writers import CsvWriter
spec = sweep.make_spec(vary=["d=0.125:0.75:11"],
                       sample=["ys=uniform(0.45,0.55)"], samples=40,
                       seed=0, base={"n_modes": 8})

with tempfile.TemporaryDirectory() as scratch:
    rows_csv = Path(scratch) / "sweep.csv"
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False,
                      dashboard_address=None) as cluster, \
            Client(cluster) as client:
        summary = runner.run_sweep(
            spec, scheduler=client, threshold=0.115,
            writers=[CsvWriter(str(rows_csv), spec)])
    # every CSV the package writes starts with '#' comment lines
    rows = pd.read_csv(rows_csv, comment="#")

print(f"{summary['n']} designs, {summary['n_failed']} failed; "
      f"P(max y3 > 0.115 in) = {summary['p_exceed']:.3f}, 95 % interval "
      f"[{summary['p_exceed_ci95'][0]:.3f}, "
      f"{summary['p_exceed_ci95'][1]:.3f}]")
print(rows.head())

# %%
# Each thickness's 40 builds: the spread the release height gives.
fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(rows["d_in"], rows["y3_max_in"], ".", ms=3, alpha=0.5)
means = rows.groupby("d_in")["y3_max_in"].mean()
ax.plot(means.index, means.values, "k-", label="mean of 40 builds")
ax.axhline(0.115, color="C3", lw=0.8, ls="--", label="threshold 0.115 in")
ax.set(xlabel="separator thickness d (in)", ylabel="max y3 (in)",
       title="y_s ~ uniform(0.45, 0.55) in, N = 8")
ax.legend(fontsize=8)
ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()
