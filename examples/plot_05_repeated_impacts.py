"""
Repeated impacts and the circuit timeline
=========================================

The thesis rig (19-in aluminium contacts, a 0.25-in separator) with the
three beams and Hertz contact, N = 16 modes a member: the upper contact
strikes the separator, bounces, strikes again; the separator kicks the
lower contact away.  The circuit is open while *both* contacts are off
the separator (gap above 1e-6 in); an opening of at least 10 us counts as
a discontinuity event.
"""

import matplotlib.pyplot as plt

import contactsep
from contactsep import chatter

rig = contactsep.thesis_design(d=0.25, n_modes=16)
result = chatter.simulate(rig, model="hertz")
print(result)
print(f"first impact {result.first_impact_s * 1e3:.3f} ms, impulse "
      f"{result.first_impulse_lb_s:.4g} lb s; circuit open "
      f"{result.circuit_open_s * 1e3:.2f} ms in {result.n_events} events, "
      f"the longest {result.longest_open_s * 1e3:.2f} ms")

# %%
# The gaps, and a timeline of when each contact is open and when the
# circuit is.
fig, (upper, lower, timeline) = plt.subplots(
    3, 1, sharex=True, figsize=(7, 6), height_ratios=(2, 2, 1.3))
upper.plot(result.t * 1e3, result.gap_upper, lw=0.7)
upper.set(ylabel="upper gap (in)")
# the lower gap is a hundred times smaller: its own axis
lower.plot(result.t * 1e3, result.gap_lower * 1e3, lw=0.7, color="C1")
lower.set(ylabel="lower gap (0.001 in)")
rows = (("upper open", result.upper_open_intervals, "C0"),
        ("lower open", result.lower_open_intervals, "C1"),
        ("circuit open", result.circuit_open_intervals, "red"))
for row, (label, intervals, colour) in enumerate(rows):
    spans = [(start * 1e3, (end - start) * 1e3) for start, end in intervals]
    timeline.broken_barh(spans, (row - 0.35, 0.7), color=colour)
timeline.set(yticks=range(len(rows)), yticklabels=[r[0] for r in rows],
             xlabel="time from release (ms)", ylim=(-0.6, 2.6))
for ax in (upper, lower, timeline):
    ax.grid(True, lw=0.3)
fig.tight_layout()
plt.show()

# %%
# The events themselves: (start, end) of every circuit opening that
# lasts at least ``min_open_s``.
for start, end in result.events[:8]:
    print(f"open {start * 1e3:8.3f} ms to {end * 1e3:8.3f} ms "
          f"({(end - start) * 1e6:7.1f} us)")
