"""
Tolerances: the probability that the circuit opens
==================================================

The tutorial's relay with a 0.02 lb preload, its separator thickness
normal (sd 0.02 mm) and its release height uniform within +-10 %: 100
builds, each simulated (Hertz, N = 32, Flores's damping calibrated to
e = 0.5: the numerics of the tutorial's preload answer), by
``contactsep sweep --model hertz``.  That takes minutes, so this example reads
the committed rows, ``docs/studies/tutorial_tolerance.csv`` (the tests
hold them equal to the code), and computes p_open and its 95 % Wilson
interval from them, as the sweep's summary does.
"""

from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from contactsep.studies.stats import wilson_interval

try:
    HERE = Path(__file__).resolve().parent
except NameError:           # a notebook: run it from the checkout's examples/
    HERE = Path.cwd()
CSV = HERE.parent / "docs" / "studies" / "tutorial_tolerance.csv"

builds = pd.read_csv(CSV, comment="#")
ok = builds[builds["status"] == 0]
opens = ok["n_events"] > 0
low, high = wilson_interval(int(opens.sum()), len(ok))
print(f"{len(ok)} builds simulated, {int(opens.sum())} open: p_open = "
      f"{opens.mean():.3g}, 95 % interval [{low:.3g}, {high:.3g}]")
print(builds.columns.tolist())

# %%
# Which builds open: thickness and release height of each, coloured by
# the largest lower gap.
fig, ax = plt.subplots(figsize=(6.5, 4.2))
points = ax.scatter(ok["d_in"] * 25.4, ok["ys_in"] * 25.4,
                    c=ok["max_lower_gap_in"] * 25.4e3, s=18, cmap="viridis")
ax.scatter(ok["d_in"][opens] * 25.4, ok["ys_in"][opens] * 25.4, s=110,
           facecolors="none", edgecolors="C3", label="circuit opens")
fig.colorbar(points, label="max lower gap (um)")
ax.set(xlabel="separator thickness d (mm)", ylabel="release height ys (mm)",
       title=f"p_open = {opens.mean():.2g} [{low:.2g}, {high:.2g}], "
             f"{len(ok)} builds, preload 0.02 lb")
ax.legend(fontsize=8, loc="upper right")
ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()
