"""
Your own relay, from scratch
============================

A small relay: two phosphor-bronze contact springs, 25 x 5 x 0.2 mm,
on a steel separator 8 x 2.5 x 1 mm, the upper contact released from
0.4 mm: the relay of the :doc:`tutorial </tutorial>`, which types it
with units (``--L1 25mm``).  In Python a ``Design`` takes the package's
units, inches, pounds (force) and seconds, so the dimensions are
converted here (1 in = 25.4 mm, 1 psi = 6894.757 Pa, 1 lb/in^3 =
27679.9 kg/m^3 under standard gravity).
"""

import matplotlib.pyplot as plt

import contactsep
from contactsep import chatter

MM, PA, KG_M3 = 1 / 25.4, 1 / 6894.757293168, 1 / 27679.9047102
bronze = dict(E=110e9 * PA, gamma=8800 * KG_M3)    # psi, lb/in^3
steel = dict(E=200e9 * PA, gamma=7850 * KG_M3)
print(f"bronze: E = {bronze['E']:.5g} psi, gamma = {bronze['gamma']:.5g}"
      f" lb/in^3; steel: E = {steel['E']:.6g} psi, "
      f"gamma = {steel['gamma']:.4g} lb/in^3")

# %%
# The design.  Contact points default to the tips and the separator's
# mid-span; N = 64 modes a member, the chatter command's default.
relay = contactsep.Design(
    L1=25 * MM, b1=5 * MM, h1=0.2 * MM, E1=bronze["E"], gamma1=bronze["gamma"],
    L2=8 * MM, b2=2.5 * MM, h2=1 * MM, E2=steel["E"], gamma2=steel["gamma"],
    L3=25 * MM, b3=5 * MM, h3=0.2 * MM, E3=bronze["E"], gamma3=bronze["gamma"],
    ys=0.4 * MM, e=0.5, n_modes=64)

# %%
# The thesis's answer (eq. 23): one impact, its impulse, and how far the
# lower contact would swing away from the separator.
single = contactsep.evaluate(relay)
print(f"impact at t1 = {single.t1 * 1e3:.3f} ms, impulse psi = "
      f"{single.psi:.4g} lb s, lower contact y3 max = "
      f"{single.y3_max:.4g} in ({single.y3_max * 25.4:.3f} mm)")

# %%
# Repeated impacts: the three beams with Hertz contact, damped by Flores's
# law calibrated to e (as ``contactsep chatter`` does where the design
# gives e).  Does the circuit (either contact touching the separator)
# open, and for how long?
result = chatter.simulate(relay, model="hertz", damping="flores")
print(result)
print(f"circuit open {result.circuit_open_s * 1e3:.2f} ms of "
      f"{result.t_end_s * 1e3:.0f} ms; first opening at "
      f"{result.first_circuit_open_s * 1e3:.3f} ms; "
      f"{result.n_events} discontinuity events")

# %%
# The two gaps (positive when open), in micrometres.  Without a preload
# the lower contact rests on the separator with no force, and the
# separator's vibration lifts it off almost at once.
fig, (upper, lower) = plt.subplots(2, 1, sharex=True, figsize=(7, 4.5))
upper.plot(result.t * 1e3, result.gap_upper * 25.4e3, lw=0.7)
lower.plot(result.t * 1e3, result.gap_lower * 25.4e3, lw=0.7, color="C1")
for start, end in result.circuit_open_intervals:
    for ax in (upper, lower):
        ax.axvspan(start * 1e3, end * 1e3, color="red", alpha=0.12, lw=0)
upper.set(ylabel="upper gap (um)",
          title="your relay, Hertz N = 64: circuit open shaded")
lower.set(xlabel="time from release (ms)", ylabel="lower gap (um)")
for ax in (upper, lower):
    ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()
