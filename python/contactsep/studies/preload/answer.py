"""The answer of ``contactsep preload`` (:class:`PreloadAnswer`, from
:func:`contactsep.studies.preload.command.preload`) and its outputs: the
JSON dictionary, the commented CSV, the converged answer in words."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from contactsep.model.names import shown, shown_key, shown_text
from contactsep.studies.preload.robust import RobustPreload


@dataclass(frozen=True)
class PreloadAnswer:
    """The smallest preload with no discontinuity event for one design
    (:func:`contactsep.studies.preload.command.preload`)."""

    #: The design searched, as given.
    design: object
    model: str
    #: simulate()'s keywords given (dt, damping, min_open, ...).
    settings: dict
    #: The design's step at no preload (s; each run without a given dt
    #: takes its own from its preload: at the answers of the family's
    #: relays 0.5-3 % smaller; the verify runs take half this one), and N.
    dt_s: float
    n_modes: object
    #: The smallest tested preload (lb) above which every tested preload
    #: has no event (NaN: an event up to the simulation's limit).
    min_preload_lb: float
    #: (verify_min_preload_lb - answer) / answer (None: not verified, or
    #: no finite nonzero answer to compare): within 2 % where the check
    #: at half the step and twice the modes held, the whole search's
    #: change where it failed (contactsep.studies.preload.verify).
    min_preload_change: float | None
    #: The answer at half the step and twice the modes (None: not run):
    #: where the check there held (an event at one of the fine grid's
    #: preloads within 2 % either side of the answer, none at one above
    #: the highest such), the smallest of them above that event (the
    #: answer there restricted to the window); else the whole search's.
    verify_min_preload_lb: float | None
    #: (first, last) tested preloads of each run of events (lb).
    event_windows: tuple
    #: (first, last) of each run of closed preloads below the answer.
    closed_windows: tuple
    #: (preload lb, has an event) of every nominal run, by preload.
    tested: tuple
    #: The same for the runs at half the step and twice the modes.
    verify_tested: tuple
    #: The largest preload the simulation takes (lb).
    ceiling_lb: float
    #: The longest opening of the circuit at the answer (s): below
    #: min_open, as the answer has no event; how near it is to one.
    longest_open_at_answer_s: float | None
    #: Simulations run: nominal, verify, checks and perturbed (the
    #: robust ones in robust).
    simulations: int
    #: The robust answer under tolerances (None: none given).
    robust: RobustPreload | None
    notes: tuple
    #: With ``converge``: the answer converged to 2 % (lb), the N and
    #: step (s) it was found at, the N of the check it passed, and
    #: whether it passed one (None: not asked; False: the last check,
    #: at the largest N allowed, failed).  The answer at N when its
    #: change at 2N is within 2 %; else the answer at 2N, checked at 4N
    #: and searched again there if it fails, and so on.
    converged_min_preload_lb: float | None = None
    converged_n_modes: int | None = None
    converged_dt_s: float | None = None
    converged_check_n_modes: int | None = None
    converged: bool | None = None
    #: ((N, answer lb), ...) of every search, coarsest first.
    converge_history: tuple = ()
    #: With ``perturbation`` (a relative change r of y_s; None: not
    #: asked): the answers (lb) of the same search on the design with
    #: y_s (1 + r) and y_s (1 - r), with the same settings, and
    #: the largest abs(perturbed - answer) / answer (None: no finite
    #: nonzero answer to compare).  A spread far above r says the
    #: threshold itself is ill-conditioned: no N or step converges the
    #: answer closer than that (docs/preload-family.md, "How well-posed the
    #: answer is").
    perturbation: float | None = None
    perturbed_min_preload_lb: tuple = ()
    min_preload_spread: float | None = None
    #: (preload lb, has an event) of the two perturbed searches.
    perturbed_tested: tuple = ()
    #: (search, preload lb, N, the step given in s or None, has an
    #: event) of every simulation of :attr:`tested`, :attr:`verify_tested`,
    #: the convergence check and :attr:`perturbed_tested`, in the order
    #: run: the CSV's rows (search "nominal", "verify", "converge",
    #: "perturbed_up", "perturbed_down"; the robust runs in robust).
    runs: tuple = ()
    #: (simulations, wall seconds) of the search at N ("search"), its
    #: repeat at 2N ("verify") and every nominal run ("nominal"): what
    #: the verdict's rerun estimate scales; "ahead": (runs made ahead
    #: for idle workers, those then asked for) (not in the JSON, nor in
    #: comparisons: a resumed search's answer equals an uninterrupted
    #: one's, though its journal's runs took no time).
    timing: dict = dataclasses.field(default_factory=dict, compare=False)

    @property
    def verdict(self):
        """The verdict (contactsep.studies.preload.verdict)."""
        from contactsep.studies.preload.verdict import preload_verdict
        return preload_verdict(self)

    def to_json_dict(self) -> dict:
        """JSON-ready (strict through contactsep.output: NaN -> null)."""
        fields = {name: getattr(self.design, name)
                  for name in type(self.design).__dataclass_fields__}
        return {
            "inputs": {"model": self.model, "n_modes": self.n_modes,
                       "dt_s": self.dt_s,
                       "settings": {k: _plain(v)
                                    for k, v in self.settings.items()},
                       "design": {k: _plain(v) for k, v in fields.items()}},
            "min_preload_lb": self.min_preload_lb,
            "min_preload_change": self.min_preload_change,
            "verify_min_preload_lb": self.verify_min_preload_lb,
            "event_windows_lb": [list(w) for w in self.event_windows],
            "closed_windows_lb": [list(w) for w in self.closed_windows],
            "ceiling_lb": self.ceiling_lb,
            "longest_open_at_answer_s": self.longest_open_at_answer_s,
            "simulations": self.simulations,
            "robust": self.robust.to_json_dict() if self.robust else None,
            "converged_min_preload_lb": self.converged_min_preload_lb,
            "converged_n_modes": self.converged_n_modes,
            "converged_dt_s": self.converged_dt_s,
            "converged_check_n_modes": self.converged_check_n_modes,
            "converged": self.converged,
            "converge_history": [{"n_modes": n, "min_preload_lb": p}
                                 for n, p in self.converge_history],
            "perturbation": self.perturbation,
            "perturbed_min_preload_lb": list(self.perturbed_min_preload_lb),
            "min_preload_spread": self.min_preload_spread,
            "tested": [{"preload_lb": p, "event": bool(e)}
                       for p, e in self.tested],
            "verify_tested": [{"preload_lb": p, "event": bool(e)}
                              for p, e in self.verify_tested],
            "perturbed_tested": [[{"preload_lb": p, "event": bool(e)}
                                  for p, e in tested]
                                 for tested in self.perturbed_tested],
            "notes": list(self.notes),
            "verdict": self.verdict.text}

    def csv_text(self) -> str:
        """The preload CSV (module :data:`CSV_COLUMNS`): '#' comments,
        one line each (the answer, its change, the windows, the robust
        answer, the notes, the verdict), then one row per simulation of
        the search, in the order run, with the search it belongs to
        (:attr:`runs`), then one per preload the robust search tried
        ("robust"; "robust_check": its check at 2N), n the samples run
        (without the n_failed that failed), event 1 where any opened.
        Forces are in lb, or in N (``preload_N``) within
        ``model.names.units_shown("si")``."""
        force = shown(1.0, "lb")[1]
        lines = [f"# contactsep preload: the smallest lower-contact "
                 f"preload with no discontinuity event ({self.model}, "
                 f"N = {self.n_modes}, dt {self.dt_s:g} s)",
                 f"# {shown_key('min_preload_lb')} = "
                 f"{_g(shown(self.min_preload_lb, 'lb')[0])}",
                 f"# {shown_key('ceiling_lb')} = "
                 f"{_g(shown(self.ceiling_lb, 'lb')[0])}",
                 f"# min_preload_change = {_g(self.min_preload_change)} "
                 f"(at half the step and twice the modes: "
                 f"{_force(self.verify_min_preload_lb)})",
                 *self._converged_lines(),
                 *self._perturbed_lines(),
                 f"# event windows ({force}): "
                 + spans_text(self.event_windows),
                 f"# closed windows below the answer ({force}): "
                 + spans_text(self.closed_windows)]
        if self.robust is not None:
            r = self.robust
            ci = r.p_open_ci95
            lines.append(
                f"# robust {shown_key('min_preload_lb')} = "
                f"{_g(shown(r.min_preload_lb, 'lb')[0])}: "
                f"p_open {_g(r.p_open)} (95 % Wilson "
                f"{'-' if ci is None else f'{ci[0]:.4g} to {ci[1]:.4g}'}"
                f"; {r.n_open} of {r.n}, {r.n_failed} failed), its upper "
                f"end <= p_target {r.p_target:g} (samples_needed "
                f"{r.samples_needed}; {r.simulations} simulations, "
                f"{r.simulations_saved} spared by the early stop)")
            if r.check_n_modes is not None:
                lines.append(f"# robust check at N = {r.check_n_modes}: "
                             f"{robust_check_text(r)}")
        lines += [f"# {note}" for note in self.notes]
        lines.append(f"# verdict: {self.verdict.text}")
        # a comment is one line whatever a note holds
        lines = [" ".join(line.splitlines()) for line in lines]
        lines.append(",".join(map(shown_key, CSV_COLUMNS)))
        lines += [run_line(name, p, n, e, dt, 1, int(e), 0)
                  for name, p, n, dt, e in self.runs]
        if self.robust is not None:
            given = self.settings.get("dt")
            lines += [run_line("robust", p, self.n_modes, k > 0, given, n,
                               k, f) for p, n, k, f in self.robust.tested]
            lines += [run_line("robust_check", p, self.robust.check_n_modes,
                               k > 0, self.dt_s / 2, n, k, f)
                      for p, n, k, f in self.robust.checked]
        return "\n".join(lines) + "\n"

    def to_csv(self, path) -> None:
        """Write :meth:`csv_text` to ``path``, replacing it only once
        the file is finished (``contactsep preload --csv``'s file);
        ``contactsep.read(path)`` reads it back."""
        from contactsep import output
        with output.open_output(path) as out:
            output.write_text(out, self.csv_text())

    def converged_text(self) -> str | None:
        """The converged answer in words (None: not asked): its N and
        step, its check, every search's answer."""
        if self.converged is None:
            return None
        steps = ", ".join(f"{_force(p)} at N = {n}"
                          for n, p in self.converge_history)
        return (f"{_force(self.converged_min_preload_lb)} (N = "
                f"{self.converged_n_modes}, dt {_g(self.converged_dt_s)} s;"
                f" {'held' if self.converged else 'NOT held'} at N = "
                f"{self.converged_check_n_modes}; searches: {steps})")

    def perturbed_text(self) -> str | None:
        """The perturbed answers in words (None: not asked)."""
        if self.perturbation is None:
            return None
        up, down = self.perturbed_min_preload_lb
        spread = self.min_preload_spread
        return (f"{'none' if spread is None else f'{spread:.2%}'} (y_s "
                f"(1 + {self.perturbation:g}): {_force(up)}, y_s (1 - "
                f"{self.perturbation:g}): {_force(down)})")

    def _perturbed_lines(self) -> list:
        text = self.perturbed_text()
        return [] if text is None else [f"# min_preload_spread = {text}"]

    def _converged_lines(self) -> list:
        text = self.converged_text()
        return [] if text is None else \
            [f"# {shown_key('converged_min_preload_lb')} = {text}"]


#: The preload CSV's columns: the search a simulation belongs to, its
#: preload, the designs run (1; a robust row: its samples), how many of
#: them opened and failed, its N per member (one number, or one per
#: member joined by ";"), the step it was given (s; empty: its design's
#: own step at its preload) and whether it had an event (1 or 0).
CSV_COLUMNS = ("search", "preload_lb", "n", "n_open", "n_failed", "n_modes",
               "dt_s", "event")


def run_line(search: str, preload_lb: float, n_modes, event, dt_s=None,
             n: int = 1, n_open: int | None = None, n_failed: int = 0
             ) -> str:
    """One row of the preload CSV (:data:`CSV_COLUMNS`), the preload and
    step to the last digit; ``n_open`` defaults to ``event`` (one run)."""
    modes = ";".join(str(int(m)) for m in n_modes) if isinstance(
        n_modes, (tuple, list)) else str(int(n_modes))
    opened = int(bool(event)) if n_open is None else int(n_open)
    # every float as repr writes it: read back, the very number run
    step = "" if dt_s is None else repr(float(dt_s))
    preload = float(shown(float(preload_lb), "lb")[0])
    return (f"{search},{preload!r},{int(n)},{opened},"
            f"{int(n_failed)},{modes},{step},{int(bool(event))}")


def _plain(value):
    if hasattr(value, "item"):
        return value.item()
    return list(value) if isinstance(value, tuple) else value


def _g(value) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "none"
    return f"{value:.6g}"


def robust_check_text(robust) -> str:
    """Whether the robust answer held its check at 2N, in words."""
    if robust.converged is None:
        return "no answer to check"
    return ("held (p_target met from the answer to 2 % above it, "
            "failed within 2 % below)" if robust.converged else
            "NOT held (p_target failed within 2 % above the answer, "
            "or met within 2 % below)")


def spans_text(spans) -> str:
    """Windows (lb) as text in the unit system shown (lb, or N under
    ``--units si``): '0.5; 0.7-0.9' ('none' for none)."""
    spans = [(shown(lo, "lb")[0], shown(hi, "lb")[0]) for lo, hi in spans]
    return "; ".join(f"{lo:.5g}" if lo == hi else f"{lo:.5g}-{hi:.5g}"
                     for lo, hi in spans) or "none"


def _force(value) -> str:
    """A force in lb as text in the unit system shown: '0.226 lb' (or
    '1.00531 N' under ``--units si``), 'none' for none."""
    return shown_text(value, "lb")
