"""
The preload that keeps your relay closed
========================================

A preload presses the lower contact against the separator before the
release.  :func:`contactsep.studies.preload.min_preloads` searches for the
smallest preload with no discontinuity event in the window; for the
tutorial's relay (Hertz, N = 8) that search simulates dozens of preloads
(a minute or so on one core), so this example reads its committed
result, ``docs/studies/tutorial_preload.csv`` (the tests hold it equal to
the code), and simulates only the two preloads it draws.  The file has
the columns of ``contactsep preload --csv FILE`` (one row a simulation:
``search``, ``preload_lb``, ``event`` 1 or 0, ...), so the same lines
read and draw a file that command wrote for your design.
"""

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import contactsep
from contactsep import chatter

try:
    HERE = Path(__file__).resolve().parent
except NameError:           # a notebook: run it from the checkout's examples/
    HERE = Path.cwd()
CSV = HERE.parent / "docs" / "studies" / "tutorial_preload.csv"

comments = [line[2:] for line in CSV.read_text().splitlines()
            if line.startswith("#")]
found = dict(line.split(" = ") for line in comments
             if line.startswith(("min_preload_lb", "ceiling_lb")))
smallest = float(found["min_preload_lb"])
tested = pd.read_csv(CSV, comment="#")
# the search at the design's own N and step (a command's file also has
# its checks: at twice the modes, perturbed, robust)
tested = tested[tested["search"] == "nominal"]
print(f"{len(tested)} preloads simulated, {int(tested['event'].sum())} "
      f"with an event; smallest preload with no event above it: "
      f"{smallest:.4g} lb (the simulation takes up to "
      f"{float(found['ceiling_lb']):.4g} lb)")

# %%
# Events against preload: they thin out and stop; near the threshold
# they come and go (an event at one preload, none at the next), which is
# why the search scans a bracket rather than bisecting once.
fig, ax = plt.subplots(figsize=(7, 2.6))
event = tested["event"].to_numpy(dtype=bool)
ax.plot(tested["preload_lb"][event], np.ones(event.sum()), "o", ms=4,
        color="C3", label="discontinuity event")
ax.plot(tested["preload_lb"][~event], np.zeros((~event).sum()), "o", ms=4,
        color="C2", label="no event")
ax.axvline(smallest, color="k", lw=0.8, ls="--",
           label=f"smallest with none above: {smallest:.3g} lb")
ax.set(xlabel="preload (lb)", yticks=(0, 1), yticklabels=("closed", "opens"),
       ylim=(-0.5, 1.5))
ax.legend(fontsize=7, loc="center left")
ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()

# %%
# The lower gap without a preload and with 0.3 lb (the tutorial's round
# number above the threshold).  A negative gap is the Hertz contact's
# compression: pressed, the contact rings on the separator and lifts off
# only in slivers shorter than the 10 us an event needs.
relay = contactsep.Design(
    L1=0.98425, b1=0.19685, h1=0.007874, E1=1.5954e7, gamma1=0.31792,
    L3=0.98425, b3=0.19685, h3=0.007874, E3=1.5954e7, gamma3=0.31792,
    L2=0.31496, b2=0.098425, h2=0.03937, E2=2.90075e7, gamma2=0.2836,
    ys=0.015748, e=0.5, n_modes=8)
fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 4.6))
for ax, preload in zip(axes, (0.0, 0.3)):
    run = chatter.simulate(relay, model="hertz", preload=preload)
    print(f"preload {preload:g} lb: {run.n_events} events, max lower gap "
          f"{run.max_lower_gap_in:.3g} in")
    ax.plot(run.t * 1e3, run.gap_lower * 25.4e3, lw=0.4,
            color="C1" if preload else "C0")
    ax.axhline(run.open_threshold_in * 25.4e3, color="0.4", lw=0.6,
               ls="--")
    ax.set(ylabel="lower gap (um)",
           title=f"preload {preload:g} lb: {run.n_events} discontinuity "
                 f"events")
    ax.grid(True, lw=0.3)
axes[-1].set(xlabel="time from release (ms)")
fig.tight_layout()
plt.show()
