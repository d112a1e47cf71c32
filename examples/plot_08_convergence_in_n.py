"""
Convergence of an answer in N
=============================

Every number the model gives depends on N, the modes kept per member.
Before quoting one, show that it has settled (or that it does not):
here the single impact of eq. 23 on the thesis rig (d = 0.25 in) for
N = 1 to 512, and the three-beam Hertz simulation's largest lower gap
for N = 4 to 32.  ``docs/model.md`` and ``docs/convergence.md``
carry the full studies.
"""

import matplotlib.pyplot as plt
import numpy as np

import contactsep
from contactsep import chatter

modes = 2 ** np.arange(10)          # 1, 2, 4, ..., 512
single = [contactsep.evaluate(contactsep.thesis_design(d=0.25, n_modes=int(n)))
          for n in modes]
psi = np.array([float(r.psi) for r in single])
v0 = np.array([float(r.v0) for r in single])
y3 = np.array([float(r.y3_max) for r in single])
for n, p, v, y in zip(modes, psi, v0, y3):
    print(f"N = {n:3d}: psi = {p:.5g} lb s (psi N = {p * n:.5g}), "
          f"v0 = {v:.5g} in/s, max y3 = {y:.6g} in")

# %%
# The impulse psi does not converge: a point impact on a Bernoulli-Euler
# beam meets a vanishing effective mass, and psi falls like 1/N (psi N
# settles instead).  The separator's velocity v0 and the lower contact's
# swing max y3 converge, their changes halving as N doubles.
fig, (left, right) = plt.subplots(1, 2, figsize=(9, 3.8))
left.loglog(modes, psi / psi[0], "o-", label="psi / psi(N=1)")
left.loglog(modes, psi * modes / psi[0], "s-", label="psi N / psi(1)")
left.set(xlabel="modes N", ylabel="relative to N = 1",
         title="eq. 23: the impulse")
left.legend(fontsize=8)
right.loglog(modes[1:], np.abs(np.diff(v0)) / v0[1:], "o-", label="v0")
right.loglog(modes[1:], np.abs(np.diff(y3)) / y3[1:], "s-", label="max y3")
right.set(xlabel="modes N", ylabel="|change from N/2| / value",
          title="eq. 23: v0 and max y3 settle")
right.legend(fontsize=8)
for ax in (left, right):
    ax.set_xticks(modes[::2], [str(n) for n in modes[::2]])
    ax.minorticks_off()
    ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()

# %%
# The three-beam simulation is costlier (each run a fraction of a
# second at these N); its largest lower gap is still falling at N = 32,
# so a number from it is quoted with its N.
sim_modes = (4, 8, 16, 32)
gaps = [chatter.simulate(contactsep.thesis_design(d=0.25, n_modes=n),
                         model="hertz", samples=1).max_lower_gap_in
        for n in sim_modes]
for n, g in zip(sim_modes, gaps):
    print(f"Hertz, N = {n:2d}: max lower gap = {g:.5g} in")

fig, ax = plt.subplots(figsize=(5, 3.4))
ax.plot(sim_modes, gaps, "o-")
ax.set(xscale="log", xlabel="modes N", ylabel="max lower gap (in)",
       title="three beams, Hertz contact", ylim=(0, None))
ax.set_xticks(sim_modes, [str(n) for n in sim_modes])
ax.minorticks_off()
ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()
