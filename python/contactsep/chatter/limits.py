"""The chatter layer's limits: models, modes, steps, work, window,
samples (their checks: :mod:`contactsep.chatter.settings`)."""

from __future__ import annotations

#: The models simulate() runs.
MODELS = ("appE", "newton", "hertz")
#: Most modes per member, and most time steps, a run may take.
MAX_MODES = 1024
MAX_STEPS = 1e9
#: Most steps x modes (all three members) a newton or hertz run may take:
#: the default run at N = 1024 is 3.7e9 (about a minute).
MAX_WORK = 1e10
#: Most modes appE takes: its event search grows steeply with N (0.7 s
#: at N = 64, 1.9 s at 96, 25 s at 128; N = 1024 ran for 9 minutes).
APPE_MAX_MODES = 128
#: Longest window (s): 170 times the listing's TAU.
MAX_T_END = 10.0
#: Most sample intervals of the gaps (each sample holds t, two gaps and
#: the energy, and more on their way out: about 200 MB at the limit;
#: 10^9 asked for gigabytes).
MAX_SAMPLES = 4_000_000
#: A run of at least this many steps x modes (or appE with more modes
#: than FORKED_APPE_MODES) runs in a child process, so that Ctrl-C and
#: SIGTERM stop it at once instead of after the compiled call returns.
FORKED_WORK = 3e8
FORKED_APPE_MODES = 48
STEPPERS = ("adaptive", "fixed")
