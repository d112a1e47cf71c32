"""
The preload that keeps your relay closed
========================================

A preload presses the lower contact against the separator before the
release.  ``contactsep preload`` searches for the smallest preload with
no discontinuity event in the window and checks it at twice the modes;
for the tutorial's relay (Hertz, N = 32, Flores's damping from e = 0.5)
that search simulates over a hundred preloads (minutes on two cores),
so this example reads its committed file,
``docs/studies/tutorial_preload.csv`` (that command's ``--csv FILE``;
the tests hold it equal to the code), and simulates only the two
preloads it draws.  One row a simulation (``search``, ``preload_lb``,
``event`` 1 or 0, ...), the answers in its comments, so the same lines
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
verdict, = [line for line in comments if line.startswith("verdict: ")]
tested = pd.read_csv(CSV, comment="#")
# the search at the command's N and the design's step (the file also has
# its check at twice the modes, "verify"; with options, the perturbed
# and robust searches)
tested = tested[tested["search"] == "nominal"]
print(f"{len(tested)} preloads simulated, {int(tested['event'].sum())} "
      f"with an event, at N = {tested['n_modes'].iloc[0]}; smallest preload "
      f"with no event above it: {smallest:.4g} lb (the simulation takes up "
      f"to {float(found['ceiling_lb']):.4g} lb)")
print(verdict)

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
# The lower gap without a preload and with 0.02 lb (the tutorial's round
# number above the answer), at the chatter command's N = 64 and with
# Flores's damping calibrated to e, as the tutorial runs them.  A
# negative gap is the Hertz contact's compression: pressed, the contact
# rings on the separator and lifts off only in slivers shorter than the
# 10 us an event needs.
MM, GPA = 1 / 25.4, 1e9 / 6894.757293168    # in, psi
G_CM3 = 1e3 / 27679.9047102                 # lb/in^3 (weight)
relay = contactsep.Design(
    L1=25 * MM, b1=5 * MM, h1=0.2 * MM, E1=110 * GPA, gamma1=8.8 * G_CM3,
    L3=25 * MM, b3=5 * MM, h3=0.2 * MM, E3=110 * GPA, gamma3=8.8 * G_CM3,
    L2=8 * MM, b2=2.5 * MM, h2=1 * MM, E2=200 * GPA, gamma2=7.85 * G_CM3,
    ys=0.4 * MM, e=0.5, n_modes=64)
fig, axes = plt.subplots(2, 1, sharex=True, figsize=(7, 4.6))
for ax, preload in zip(axes, (0.0, 0.02)):
    run = chatter.simulate(relay, model="hertz", damping="flores",
                           preload=preload)
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
