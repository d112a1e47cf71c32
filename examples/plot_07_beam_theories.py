"""
Bernoulli-Euler beams, and where they stop being enough
=======================================================

Every member is a Bernoulli-Euler beam (:mod:`contactsep.beams`): slender,
no shear deformation or rotary inertia.  The thesis's separators are not
slender (d/L2 up to 0.3), and its Table II measured their first
frequency.  The beam formula agrees with the thesis's printed theory to
0.22 %, and both run far ahead of the experiment: by a factor of two,
far more than shear and rotary inertia (a Timoshenko beam) take off a
clamped beam at these d/L2; most of it is the clamps' give, which the
thesis folds into an equivalent length L_c (Table III).
"""

import matplotlib.pyplot as plt
import numpy as np

from contactsep import beams, studies

# %%
# The clamped-clamped separator's first modes, and the cantilever's.
xi = np.linspace(0.0, 1.0, 201)
fig, (cc, cf) = plt.subplots(1, 2, figsize=(8, 3.2), sharey=True)
for ax, end in ((cc, "clamped-clamped"), (cf, "clamped-free")):
    shapes = beams.mode_shapes(end, 4, xi)
    values = beams.eigenvalues(end, 4)
    for j in range(4):
        ax.plot(xi, shapes[j], label=f"mode {j + 1}: beta L = "
                f"{values[j]:.4f}")
    ax.set(title=end, xlabel="x / L")
    ax.legend(fontsize=7)
    ax.grid(True, lw=0.3)
cc.set(ylabel="mode shape X_j(x)")
fig.tight_layout()
plt.show()

# %%
# Table II: the separator's first frequency, model against the printed
# theory and the experiment, by thickness (and slenderness d/L2).
table2 = studies.table2().columns
ratio = table2["d_in"] / 2.5
gap = table2["model_cps"] / table2["experimental_cps"] - 1.0
for d, r, model, experiment, g in zip(table2["d_in"], ratio,
                                      table2["model_cps"],
                                      table2["experimental_cps"], gap):
    print(f"d = {d:5.3f} in (d/L2 = {r:4.2f}): Bernoulli-Euler "
          f"{model:7.1f} cps, experiment {experiment:6.0f} cps, "
          f"{100 * g:+5.1f} %")

fig, ax = plt.subplots(figsize=(6, 3.6))
ax.plot(ratio, 100 * gap, "o-")
ax.axhline(0.0, color="0.6", lw=0.8)
ax.set(xlabel="separator slenderness d / L2",
       ylabel="Bernoulli-Euler / experiment - 1 (%)",
       title="Table II: the beam formula against the experiment")
ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()
