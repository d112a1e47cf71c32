"""
Timoshenko against Bernoulli-Euler, and where neither is enough
================================================================

Every member is a Bernoulli-Euler beam (:mod:`contactsep.beams`): slender,
no shear deformation or rotary inertia.  The thesis's separators are not
slender (d/L2 up to 0.3), and its Table II measured their first
frequency.  The beam formula agrees with the thesis's printed theory to
0.22 %, and both run far ahead of the experiment: by a factor of two,
far more than shear and rotary inertia (a Timoshenko beam,
``beam2="timoshenko"``) take off a clamped beam at these d/L2; most of it
is the clamps' give, which the thesis folds into an equivalent length L_c
(Table III) and ``contactsep study separator-fit`` explains with elastic
clamps and the sensor's mass.
"""

import matplotlib.pyplot as plt
import numpy as np

import contactsep
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

# %%
# Shear and rotary inertia: the separator's first frequency as a
# Timoshenko beam (Cowper's shear coefficient, nu = 0.33) against the
# Bernoulli-Euler one, for the thesis's five thicknesses
# (``contactsep.modes``; ``contactsep modes --member 2 --beam2
# timoshenko --d 0.75`` on the command line).
thick = np.array([0.125, 0.25, 0.35, 0.5, 0.75])
first = {theory: np.array([
    contactsep.modes(contactsep.thesis_design(d=d, beam2=theory), 2,
                     1).f_hz[0] for d in thick])
    for theory in ("bernoulli-euler", "timoshenko")}
drop = first["timoshenko"] / first["bernoulli-euler"] - 1.0
for d, be, ti, g in zip(thick, first["bernoulli-euler"],
                        first["timoshenko"], drop):
    print(f"d = {d:5.3f} in: Bernoulli-Euler {be:7.0f} Hz, Timoshenko "
          f"{ti:7.0f} Hz ({100 * g:+5.1f} %)")

fig, ax = plt.subplots(figsize=(6, 3.6))
ax.plot(thick / 2.5, 100 * drop, "s-", color="C1")
ax.set(xlabel="separator slenderness d / L2",
       ylabel="Timoshenko / Bernoulli-Euler - 1 (%)",
       title="Shear and rotary inertia lower the separator's frequency")
ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()
