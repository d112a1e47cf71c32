"""
The thesis's figures, recomputed
================================

Figures 5, 6 and 8 and Table II of the thesis from the general model
(eq. 23), each a batch of designs in one compiled call
(:mod:`contactsep.studies`; ``contactsep study NAME`` writes the same as
CSV and PNG).
"""

import matplotlib.pyplot as plt
import numpy as np

from contactsep import studies

fig5 = studies.fig5().columns
fig6 = studies.fig6().columns
fig8 = studies.fig8().columns
table2 = studies.table2().columns

fig, axes = plt.subplots(2, 2, figsize=(9, 6.5))
ax = axes[0, 0]
for ys in np.unique(fig5["ys_in"]):
    rows = fig5["ys_in"] == ys
    ax.plot(fig5["d_in"][rows], fig5["y3_max_in"][rows],
            label=f"y_s = {ys:g} in")
ax.set(title="Figure 5", xlabel="separator thickness d (in)",
       ylabel="max y3 (in)", ylim=(0, None))
ax.legend(fontsize=8)

ax = axes[0, 1]
for curve, label in (("I", "I: contact moved along L3"),
                     ("II", "II: L3 = x3 / r")):
    rows = fig6["curve"] == curve
    ax.plot(fig6["r"][rows], fig6["y3_max_in"][rows], label=label)
ax.set(title="Figure 6", xlabel="contact point ratio r = x3/L3",
       ylabel="max y3 (in)")
ax.legend(fontsize=8)

ax = axes[1, 0]
ax.semilogx(fig8["R"], fig8["y3_max_in"], "o", ms=3, label="eq. 23")
ax.semilogx(fig8["R"], fig8["law_in"], label="1/(1 + 2R) law")
ax.set(title="Figure 8", xlabel="mass ratio R (eq. 24)",
       ylabel="max y3 (in)")
ax.legend(fontsize=8)

ax = axes[1, 1]
ax.plot(table2["d_in"], table2["model_cps"], "o-", label="model")
ax.plot(table2["d_in"], table2["printed_theoretical_cps"], "s--",
        label="printed theory")
ax.plot(table2["d_in"], table2["experimental_cps"], "^:", label="experiment")
ax.set(title="Table II: separator first frequency",
       xlabel="separator thickness d (in)", ylabel="frequency (cps)")
ax.legend(fontsize=8)
for ax in axes.flat:
    ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()

# %%
# Figure 5's numbers for the thesis's y_s = 0.5 in: thicker separators
# kick the lower contact less.
rows = fig5["ys_in"] == 0.5
for d, y3 in zip(fig5["d_in"][rows][::4], fig5["y3_max_in"][rows][::4]):
    print(f"d = {d:5.3f} in: max y3 = {y3:.4f} in")
