"""``ChatterResult``: one simulation's inputs, its sampled gaps and the
summary a designer reads (docs/chatter.md)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from contactsep import output
from contactsep.chatter import circuit, laws, numerics, stop_event
from contactsep.model import fields


def plain(value):
    """A JSON-ready copy: NumPy scalars and arrays to Python, NaN and
    infinities to None (strict JSON)."""
    if isinstance(value, dict):
        return {k: plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [plain(v) for v in np.asarray(value, dtype=object).tolist()]
    if isinstance(value, (np.generic,)):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def design_dict(design) -> dict:
    """Every field of a single Design under its output name (``L3_in``,
    ``d_in``: :mod:`contactsep.model.fields`), JSON-ready."""
    return plain(fields.design_keys(design))


@dataclass(frozen=True, repr=False)
class ChatterResult:
    """A simulation of the contact system over 0 <= t <= t_end_s from the
    release.  Gaps are positive when open (in); times in s; impulses in
    lb s; energies in in lb.  ``repr`` is a one-line summary."""

    model: str
    n_modes: int
    #: Time step (s; 0 for appE, event-driven).
    dt: float
    #: Sample times (s) and both gaps (in) at them.
    t: np.ndarray
    gap_upper: np.ndarray
    gap_lower: np.ndarray
    #: Total mechanical energy at the samples (in lb).
    energy: np.ndarray
    #: Open intervals ((k, 2), s) of each contact and of the circuit,
    #: with exact open and close instants (circuit.py).
    upper_open_intervals: np.ndarray
    lower_open_intervals: np.ndarray
    circuit_open_intervals: np.ndarray
    #: Total time the circuit is open, its first opening (NaN: never)
    #: and its longest (0: never); every opening counts.
    circuit_open_s: float
    first_circuit_open_s: float
    longest_open_s: float
    #: The discontinuity events: openings of at least min_open_s
    #: ((k, 2) start, end), their number, and whether there is one.
    events: np.ndarray
    n_events: int
    chatters: bool
    #: Largest lower gap (in): how far the lower contact separates.
    max_lower_gap_in: float
    #: The first impact of the upper contact: time and impulse (the
    #: impulse of its first contact episode).
    first_impact_s: float
    first_impulse_lb_s: float
    #: Energy at the end over energy at the release.
    energy_ratio: float
    #: The thesis's single-impulse predictions for the same design.
    single_impulse: dict = field(default_factory=dict)
    #: The lower contact's largest gap (in) in its first swing: from the
    #: first impact to half a period of its first mode after it, at the
    #: samples (NaN: no impact, or fewer than 100 samples in the swing;
    #: circuit.first_lift).  Converges in N and dt where
    #: max_lower_gap_in, over the whole window, does not.
    first_lift_in: float = math.nan
    #: Force pressing the lower contact on the separator at the start (lb);
    #: the energies then include the preload's strain energy.
    preload_lb: float = 0.0
    #: The settings: window (s), open threshold (in), detection time of
    #: an event (s), Hertz damping, stepper ("adaptive" or "fixed").
    t_end_s: float = 0.060
    open_threshold_in: float = circuit.OPEN_THRESHOLD
    min_open_s: float = circuit.MIN_OPEN
    damping: str = "none"
    stepper: str = "fixed"
    #: Whether the Hertz law had the static correction (the truncated
    #: modes' residual flexibility in series; always False for Newton and
    #: appE, which take no compliance).
    static_correction: bool = False
    #: The simulated design (a contactsep.Design).
    design: object = None
    #: Work done: flight steps, fixed steps and flow evaluations of the
    #: adaptive stepper; steps of a fixed-step one.
    work: dict = field(default_factory=dict)
    #: appE only: every event (impact times, impulses, velocities before
    #: and after, energy after each; resting intervals), see
    #: :class:`contactsep.chatter.rigid_stop.RigidStopResult`.
    rigid_stop: object = None
    #: How the run ended (contactsep.chatter.status): 0 ok; 7 stopped at
    #: the energy bound (no circuit figures); 8 interrupted; 9 finished
    #: but unconverged (its energy check failed); 10 stopped at its first
    #: discontinuity event, as asked (see stopped_s).
    status: int = 0
    #: How dt and t_end_s were chosen: "design" (from the design,
    #: contactsep.chatter.numerics) or "given" (by the caller).
    dt_source: str = "given"
    t_end_source: str = "given"
    #: What set the design's step: its step (s), the bound on the highest
    #: frequency with the contacts closed (rad/s), the highest mode
    #: (rad/s), the contact force (lb) and stiffness (lb/in) it assumed,
    #: how often the step was halved, the energy check's tolerance.
    numerics: dict = field(default_factory=dict)
    #: verify=True: the relative change of each headline quantity at half
    #: the step and twice the modes (first_impact_change,
    #: first_impulse_change, max_lower_gap_change, first_lift_change,
    #: circuit_open_change,
    #: longest_open_change, n_events_change) and the rerun's dt, N and
    #: status (verify_dt_s, verify_n_modes, verify_status); empty without.
    changes: dict = field(default_factory=dict)
    #: The contact law (docs/chatter.md, "Contact laws"): its elastic
    #: part ("hertz" or "thornton"), Hunt-Crossley's constant (s/in) and
    #: Thornton's yield pressure (psi), None where not used.
    contact: str = "hertz"
    alpha_s_per_in: float | None = None
    yield_pressure_psi: float | None = None
    #: The contact button ("sphere" or "cylinder") and its radius (in).
    button: str = "sphere"
    button_radius_in: float = 0.125
    #: The Hertz family's energy book (in lb; empty for Newton and
    #: appE): ``energy_initial_lbin``, ``energy_dissipated_contact_lbin``,
    #: ``energy_member1_lbin`` .. ``energy_member3_lbin`` (the vibration
    #: energy left in each member's modes) and ``energy_contact_lbin``
    #: (the contacts' stored energy at the end); ``energy_ratio`` +
    #: dissipated / initial = 1 to the stepper's energy error.
    energy_book: dict = field(default_factory=dict)
    #: Hertz runs: the stacked modal state at the window's end, ``q``
    #: and ``v`` (upper contact's modes, separator's, lower contact's;
    #: not in the JSON).
    end_state: dict = field(default_factory=dict)
    #: Status 10 (``simulate(..., stop_at_event=True)``): the instant (s)
    #: its first discontinuity event was established (its start +
    #: min_open_s); NaN for a run of the whole window.  The stepper ran
    #: on to the end of the step that holds it, and every figure covers
    #: the run up to there only: ``chatters`` and ``first_circuit_open_s``
    #: are the whole window's, ``n_events`` (1 or more: "at least"),
    #: ``events`` (the last cut there), the open intervals and times,
    #: ``max_lower_gap_in``, ``first_lift_in``, ``energy_ratio`` and the
    #: energy book (at the stop) are partial, the samples after it NaN.
    stopped_s: float = math.nan

    def __repr__(self) -> str:
        first = ("never" if math.isnan(self.first_circuit_open_s)
                 else f"{self.first_circuit_open_s:.6g} s")
        return (f"ChatterResult(model={self.model!r}, "
                f"n_modes={self.n_modes}, dt={self.dt:.3g}, "
                f"circuit_open_s={self.circuit_open_s:.6g}, "
                f"first_open={first}, n_events={self.n_events}, "
                f"max_lower_gap_in={self.max_lower_gap_in:.6g}, "
                f"{len(self.t)} samples)")

    def inputs(self) -> dict:
        """What was simulated: the design and the settings."""
        return {"design": design_dict(self.design)
                if self.design is not None else None,
                "model": self.model, "n_modes": self.n_modes,
                "dt_s": self.dt, "t_end_s": self.t_end_s,
                "dt_source": self.dt_source,
                "t_end_source": self.t_end_source,
                "preload_lb": self.preload_lb, "damping": self.damping,
                "contact": self.contact,
                "alpha_s_per_in": self.alpha_s_per_in,
                "yield_pressure_psi": self.yield_pressure_psi,
                "button": self.button,
                "button_radius_in": self.button_radius_in,
                "stepper": self.stepper,
                "static_correction": self.static_correction,
                "open_threshold_in": self.open_threshold_in,
                "min_open_s": self.min_open_s}

    def to_json_dict(self) -> dict:
        """Inputs and summary (no sampled arrays), strict-JSON-ready."""
        return plain({
            "inputs": self.inputs(),
            "first_impact_s": self.first_impact_s,
            "first_impulse_lb_s": self.first_impulse_lb_s,
            "energy_ratio": self.energy_ratio,
            **self.energy_book,
            "status": self.status,
            **self.changes,
            "max_lower_gap_in": self.max_lower_gap_in,
            "first_lift_in": self.first_lift_in,
            "chatters": self.chatters,
            "n_events": self.n_events,
            "events": self.events,
            "circuit_open_s": self.circuit_open_s,
            "first_circuit_open_s": self.first_circuit_open_s,
            "longest_open_s": self.longest_open_s,
            "circuit_open_intervals": self.circuit_open_intervals,
            "upper_open_s": circuit.total(self.upper_open_intervals),
            "lower_open_s": circuit.total(self.lower_open_intervals),
            "single_impulse": self.single_impulse,
            "work": self.work,
            "numerics": self.numerics,
            **self._rigid_stop_events(),
        })

    def to_pandas(self, what: str = "summary"):
        """A pandas DataFrame of the run (needs pandas, ``pip install
        'contactsep[tables]'``), columns under the names of every output:

        * ``"summary"``: one row, the inputs (``model``, ``n_modes``,
          ``dt_s``, ..., the design's fields as ``L1_in``, ``d_in``, ...)
          and every scalar of :meth:`to_json_dict` (``first_impact_s``,
          ``max_lower_gap_in``, ``circuit_open_s``, ``n_events``, ...);
        * ``"events"``: one row per discontinuity event (``start_s``,
          ``end_s``, ``duration_s``);
        * ``"openings"``: one row per circuit opening, events or not
          (the same columns and ``event``: at least ``min_open_s``);
        * ``"gaps"``: one row per sample (``t_s``, ``gap_upper_in``,
          ``gap_lower_in``, ``circuit_open``), as ``chatter --csv``.

        Examples
        --------
        >>> import contactsep
        >>> from contactsep.chatter import simulate
        >>> r = simulate(contactsep.thesis_design(n_modes=4),
        ...              model="hertz", t_end=0.005)
        >>> r.to_pandas("gaps").columns.tolist()
        ['t_s', 'gap_upper_in', 'gap_lower_in', 'circuit_open']
        """
        pandas = output.require_pandas()
        if what == "summary":
            data = self.to_json_dict()
            inputs = data.pop("inputs")
            row = {k: v for k, v in inputs.items() if k != "design"}
            row.update(inputs["design"] or {})
            row.update({k: v for k, v in data.items()
                        if v is None or isinstance(v, (bool, int, float,
                                                       str))})
            row.update({f"single_impulse_{k}": v
                        for k, v in data["single_impulse"].items()})
            return pandas.DataFrame([row])
        if what in ("events", "openings"):
            spans = np.asarray(self.events if what == "events"
                               else self.circuit_open_intervals,
                               dtype=float).reshape(-1, 2)
            frame = pandas.DataFrame({"start_s": spans[:, 0],
                                      "end_s": spans[:, 1],
                                      "duration_s": spans[:, 1]
                                      - spans[:, 0]})
            if what == "openings":
                frame["event"] = frame["duration_s"] >= self.min_open_s
            return frame
        if what == "gaps":
            threshold = self.open_threshold_in
            return pandas.DataFrame({
                "t_s": self.t, "gap_upper_in": self.gap_upper,
                "gap_lower_in": self.gap_lower,
                "circuit_open": ((self.gap_upper > threshold)
                                 & (self.gap_lower > threshold))
                .astype(int)})
        raise ValueError(f"what: found {what!r}, expected summary, events, "
                         f"openings or gaps")

    def _rigid_stop_events(self) -> dict:
        """appE: its impacts and rests (times s, impulses lb s, contact
        velocities in/s, energy after each impact in lb)."""
        r = self.rigid_stop
        if r is None:
            return {}
        return {"impacts": [
            {"t_s": float(t), "impulse_lb_s": float(psi),
             "v_before_in_s": float(a), "v_after_in_s": float(b),
             "energy_after_in_lb": float(w)}
            for t, psi, a, b, w in zip(r.impact_t, r.impulse, r.v_before,
                                       r.v_after, r.energy_after)],
            "rest_intervals": r.rest_intervals.tolist()}


def blown_up(run, model, design, dt, preload, damping, stepper,
             settings) -> ChatterResult:
    """A run its stepper stopped at the energy bound (status
    ENERGY_BOUND): the samples it reached, and no circuit figures (NaN;
    n_events -1, as a failed design's row in a chatter sweep)."""
    nan, none = math.nan, np.empty((0, 2))
    return ChatterResult(
        model=model, n_modes=int(design.n_modes), dt=dt, t=run.t,
        gap_upper=run.gaps[:, 0], gap_lower=run.gaps[:, 1],
        energy=run.energy, upper_open_intervals=none,
        lower_open_intervals=none, circuit_open_intervals=none,
        circuit_open_s=nan, first_circuit_open_s=nan, longest_open_s=nan,
        events=none, n_events=-1, chatters=False, max_lower_gap_in=nan,
        first_impact_s=nan, first_impulse_lb_s=nan, energy_ratio=nan,
        preload_lb=float(preload), damping=damping, stepper=stepper,
        work=run.work, status=run.status, **settings)


def from_run(checked, stack, parts, choice, status, *, model, design,
             preload, damping, stepper, dt_source, min_open,
             settings) -> ChatterResult:
    """A stepped run that reached its end or its first event
    (``checked``: :func:`numerics.checked_run`'s answer; ``stack`` and
    ``parts`` its system, ``choice`` the design's step choice,
    ``status`` the run's, UNCONVERGED where its energy check failed)."""
    run = checked.run
    found = circuit.discontinuity(run.upper_open, run.lower_open, min_open)
    return ChatterResult(
        model=model, n_modes=int(design.n_modes), dt=checked.dt, t=run.t,
        gap_upper=run.gaps[:, 0], gap_lower=run.gaps[:, 1],
        energy=run.energy, **found,
        max_lower_gap_in=run.max_lower_gap_in,
        first_lift_in=circuit.first_lift(
            run.t, run.gaps[:, 1], run.first[0],
            math.pi / float(parts[2].p[0])),
        first_impact_s=run.first[0], first_impulse_lb_s=run.first[1],
        energy_ratio=checked.ratio, preload_lb=float(preload),
        damping=damping, stepper=stepper, work=run.work, status=status,
        dt_source=dt_source,
        energy_book=laws.energy_book(run, stack, parts),
        stopped_s=stop_event.stopped_s(status, found["events"], min_open),
        end_state={"q": run.book["q"], "v": run.book["v"]}
        if run.book else {},
        numerics={"design_dt_s": choice.dt, "omega_bound_rad_s":
                  choice.omega, "p_max_rad_s": choice.p_max,
                  "contact_force_bound_lb": choice.force_lb,
                  "contact_stiffness_lb_per_in": choice.stiffness_lb_in,
                  "contact_dt_s": choice.contact_dt,
                  "alias_share": choice.alias_share,
                  "dt_halvings": checked.halvings,
                  "energy_tolerance": numerics.ENERGY_TOLERANCE},
        **settings)
