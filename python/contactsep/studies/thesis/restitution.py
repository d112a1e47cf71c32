"""The thesis's conclusion 4 (``contactsep study conclusion4``): the
coefficient of restitution "was found to be a function of both the
impact velocity and the contact separator thickness" (Chapter VI: it
falls as V and d grow, then levels off).  Today e is an input; here it
emerges from the contact law, in the three-beam Hertz model, for

* ``elastic``: Hertz, energy lost only into the members' vibration;
* ``hunt-crossley``: F = k delta^{3/2} (1 + alpha delta'), one material
  constant alpha for every design (:data:`ALPHA`);
* ``thornton``: elastic-perfectly-plastic with one yield pressure
  (:data:`YIELD_PRESSURE`).

How e_apparent is read (docs/circuit-opening.md, "Conclusion 4"): the thesis
read a velocity transducer on the upper contact (its Figure 19): e =
CD / DB, the rebound velocity over the impact velocity at the contact.
Here the impact velocity DB is the contact point's velocity at the
first impact (every mode of the release flight,
``impact_velocity_in_s``), and the rebound CD is the upper contact's
first mode at its contact point, read ``reading_time`` after the first
impact: e_apparent = sqrt(v_1^2 + p_1^2 q_1^2) / (p_1 |q_1(0)|), the
first mode's velocity amplitude after over before, signed by the way the
mode moves (positive: back toward the release).  The first mode is the
part of the trace the eye reads (the higher modes ring on top of it),
and its amplitude does not change in free flight, so only the
sub-impacts before the reading change e_apparent.  The upper contact
taps the separator many times before its first mode turns back (6-8 ms
on the thesis rig): read before that, e_apparent is negative (the mode
still approaches); the default reading, 20 ms, is after the sequence
and before the mode's return (a quarter period is 23 ms).  A run that
fails its energy check gives NaN.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from contactsep.chatter import simulate
from contactsep.chatter.simulate import UnconvergedWarning
from contactsep.chatter.system import members
from contactsep.studies.study import Study, thesis_study_design

#: The laws compared, their settings for simulate.  The static
#: correction is on for the elastic and Hunt-Crossley laws (the default)
#: and off for Thornton's (which takes none).
LAWS = ("elastic", "hunt-crossley", "thornton")
#: Hunt-Crossley's constant (s/in): e = 0.375 on a rigid stop at
#: 33.9 in/s (the thesis's e at y_s = 0.5 in; tests/chatter/
#: test_contact_laws.py).
ALPHA = 0.0676
#: Thornton's yield pressure (psi), as issue 28 measured.
YIELD_PRESSURE = 45.0e3
#: The separators (in) at y_s = 0.5 in, and the release heights (in) on
#: the d = 0.25 in separator (the thesis varied V on one separator).
THICKNESSES = (0.125, 0.25, 0.375, 0.5, 0.75)
HEIGHTS = (0.25, 0.5, 0.75)
SEPARATOR_OF_HEIGHTS = 0.25
HEIGHT_OF_SEPARATORS = 0.5
#: Modes per member and the reading time after the first impact (s).
MODES = 16
READING_TIME = 0.02
#: Rows per law.
ROWS = len(HEIGHTS) + len(THICKNESSES) - 1
#: Columns (a contract: issue 28).
COLUMNS = ("law", "d_in", "ys_in", "impact_velocity_in_s", "e_apparent")


def law_settings(law: str, alpha: float = ALPHA,
                 yield_pressure: float = YIELD_PRESSURE) -> dict:
    """simulate()'s arguments for one of :data:`LAWS`."""
    if law == "elastic":
        return {}
    if law == "hunt-crossley":
        return {"damping": "hunt-crossley", "alpha": alpha}
    if law == "thornton":
        return {"contact": "thornton", "yield_pressure": yield_pressure,
                "static_correction": False}
    raise ValueError(f"law: found {law!r}, expected one of "
                     f"{', '.join(LAWS)}")


def first_impact(design) -> tuple[float, float]:
    """The release flight's first impact: its time (s) and the contact
    point's speed then (in/s), every mode of the upper contact (the
    flight is free until then: y1 = sum X_j q_j(0) cos p_j t, sampled at
    1/64 of the shortest period, the crossing bisected)."""
    upper = members(design)[0]
    amplitude = upper.x * upper.q0

    def height(t):
        return float(np.sum(amplitude * np.cos(upper.p * t)))

    step = 2.0 * math.pi / float(np.max(upper.p)) / 64.0
    t = 0.0
    while height(t + step) > 0.0:
        t += step
    low, high = t, t + step
    for _ in range(80):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if height(mid) > 0.0 else (low, mid)
    speed = abs(float(np.sum(amplitude * upper.p * np.sin(upper.p
                                                           * high))))
    return high, speed


def e_apparent(design, law: str, reading_time: float = READING_TIME,
               **constants) -> tuple[float, float]:
    """(impact speed in/s, e_apparent) of one design under one law, read
    ``reading_time`` after the first impact (module docstring)."""
    t1, speed = first_impact(design)
    upper = members(design)[0]
    with warnings.catch_warnings():
        # an unconverged run is a NaN row, not a warning per row
        warnings.simplefilter("ignore", UnconvergedWarning)
        result = simulate(design, t_end=t1 + reading_time, samples=1,
                          single_impulse=False, **law_settings(
                              law, **constants))
    if result.status != 0:
        return speed, math.nan
    q, v = result.end_state["q"][0], result.end_state["v"][0]
    p, before = float(upper.p[0]), float(upper.q0[0])
    # rebounding: the first mode moves back toward the release
    after = math.copysign(math.hypot(v, p * q), v * before)
    return speed, after / (p * abs(before))


def conclusion4(n_modes: int = MODES, reading_time: float = READING_TIME,
                alpha: float = ALPHA,
                yield_pressure: float = YIELD_PRESSURE,
                laws=LAWS, progress=None) -> Study:
    """e_apparent against the impact velocity (y_s on the d = 0.25 in
    separator) and the separator thickness d (at y_s = 0.5 in) for each
    law (module docstring)."""
    for name, value, low, high in (
            ("reading_time", reading_time, 0.0, 0.1),
            ("alpha", alpha, 0.0, 100.0),
            ("yield_pressure", yield_pressure, 0.0, 1e7)):
        if not low < value <= high:
            raise ValueError(f"{name}: found {value!r}, expected more than "
                             f"{low:g} and at most {high:g}")
    for law in laws:
        law_settings(law)
    rows = []
    points = [(SEPARATOR_OF_HEIGHTS, ys) for ys in HEIGHTS] + [
        (d, HEIGHT_OF_SEPARATORS) for d in THICKNESSES
        if d != SEPARATOR_OF_HEIGHTS]
    for law in laws:
        for d, ys in points:
            design = thesis_study_design(d=d, ys=ys, n_modes=n_modes)
            speed, e = e_apparent(design, law, reading_time, alpha=alpha,
                                  yield_pressure=yield_pressure)
            rows.append((law, d, ys, speed, e))
            if progress is not None:
                progress(1)
    columns = {name: np.array([row[i] for row in rows])
               for i, name in enumerate(COLUMNS)}
    notes = (f"e_apparent: the upper contact's first-mode velocity "
             f"amplitude {reading_time:g} s after the first impact over "
             f"the same before it, signed (+: moving back toward the "
             f"release); the thesis's Figure 19 reading CD / DB; NaN: a "
             f"run that failed its energy check",
             "impact_velocity_in_s: the contact point's speed at the first "
             "impact (every mode of the release flight)",
             f"laws: elastic Hertz and Hunt-Crossley with the static "
             f"correction; hunt-crossley alpha = {alpha:g} s/in; thornton "
             f"yield pressure {yield_pressure:g} psi (no static "
             f"correction); N = {n_modes} modes per member, the design's "
             f"own step; no preload",
             f"rows: y_s = {', '.join(f'{h:g}' for h in HEIGHTS)} in on "
             f"d = {SEPARATOR_OF_HEIGHTS:g} in; d = "
             f"{', '.join(f'{d:g}' for d in THICKNESSES)} in at y_s = "
             f"{HEIGHT_OF_SEPARATORS:g} in; the thesis rig otherwise")
    return Study(name="conclusion4",
                 title="Conclusion 4: the apparent coefficient of "
                       "restitution against impact velocity and separator "
                       "thickness, three contact laws",
                 columns=columns, notes=notes)


def draw(axes, study: Study) -> None:
    """e_apparent against V (left) and d (right), one line per law."""
    c = study.columns
    left, right = axes
    for i, law in enumerate(dict.fromkeys(c["law"])):
        mine = c["law"] == law
        on_sep = mine & np.isclose(c["d_in"], SEPARATOR_OF_HEIGHTS)
        at_height = mine & np.isclose(c["ys_in"], HEIGHT_OF_SEPARATORS)
        order = np.argsort(c["impact_velocity_in_s"][on_sep])
        left.plot(c["impact_velocity_in_s"][on_sep][order],
                  c["e_apparent"][on_sep][order], "o-", color=f"C{i}",
                  label=law)
        order = np.argsort(c["d_in"][at_height])
        right.plot(c["d_in"][at_height][order],
                   c["e_apparent"][at_height][order], "s-", color=f"C{i}",
                   label=law)
    left.set(xlabel=f"impact velocity (in/s), d = "
                    f"{SEPARATOR_OF_HEIGHTS:g} in", ylabel="e apparent")
    right.set(xlabel=f"separator thickness d (in), y_s = "
                     f"{HEIGHT_OF_SEPARATORS:g} in")
    for ax in axes:
        ax.set_ylim(bottom=0.0)
