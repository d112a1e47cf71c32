"""
Your own relay, from scratch
============================

A small relay: two phosphor-bronze contact springs, 25 x 5 x 0.2 mm,
on a steel separator 8 x 2.5 x 1 mm, the upper contact released from
0.4 mm.  The package works in inches, pounds (force) and seconds, so the
dimensions are converted by hand (1 in = 25.4 mm, 1 GPa = 145,038 psi,
1 g/cm^3 = 0.0361273 lb/in^3); these are the numbers of the
:doc:`tutorial </tutorial>`.
"""

import matplotlib.pyplot as plt

import contactsep
from contactsep import chatter

bronze = dict(E=110e9 / 6894.757, gamma=8.8 * 0.0361273)    # psi, lb/in^3
steel = dict(E=200e9 / 6894.757, gamma=7.85 * 0.0361273)
print(f"bronze: E = {bronze['E']:.5g} psi, gamma = {bronze['gamma']:.5g}"
      f" lb/in^3; steel: E = {steel['E']:.6g} psi, "
      f"gamma = {steel['gamma']:.4g} lb/in^3")

# %%
# The design, with the converted values rounded as the tutorial types
# them.  Contact points default to the tips and the separator's mid-span.
relay = contactsep.Design(
    L1=0.98425, b1=0.19685, h1=0.007874, E1=1.5954e7, gamma1=0.31792,
    L2=0.31496, b2=0.098425, h2=0.03937, E2=2.90075e7, gamma2=0.2836,
    L3=0.98425, b3=0.19685, h3=0.007874, E3=1.5954e7, gamma3=0.31792,
    ys=0.015748, e=0.5, n_modes=8)

# %%
# The thesis's answer (eq. 23): one impact, its impulse, and how far the
# lower contact would swing away from the separator.
single = contactsep.evaluate(relay)
print(f"impact at t1 = {single.t1 * 1e3:.3f} ms, impulse psi = "
      f"{single.psi:.4g} lb s, lower contact y3 max = "
      f"{single.y3_max:.4g} in ({single.y3_max * 25.4:.3f} mm)")

# %%
# Repeated impacts: the three beams with Hertz contact.  Does the circuit
# (either contact touching the separator) open, and for how long?
result = chatter.simulate(relay, model="hertz")
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
          title="your relay, Hertz N = 8: circuit open shaded")
lower.set(xlabel="time from release (ms)", ylabel="lower gap (um)")
for ax in (upper, lower):
    ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()
