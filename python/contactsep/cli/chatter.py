"""``contactsep chatter``: does the circuit open, when, for how long."""

from __future__ import annotations

import argparse
import contextlib
import importlib.util
import math
import sys
import time
import warnings

from contactsep import output
from contactsep.cli import chatter_options
from contactsep.cli.design_options import (
    add_design_options,
    damping_law,
    design_overrides,
    with_sources,
)
from contactsep.cli.guards import drop_echoes
from contactsep.cli.unit_system import in_units, si_shown
from contactsep.errors import ContactsepWarning, InputError
from contactsep.model.names import shown, shown_key, units_shown

EPILOG = """examples:
  contactsep chatter --preload 0.2
  contactsep chatter --n-modes 16 --d 0.5 --preload 0.2 --json --verify
  contactsep chatter --model newton --n-modes 16 --png gaps.png --csv gaps.csv
"""


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep chatter``."""
    from contactsep.chatter.numerics import DEFAULT_MODES

    parser = commands.add_parser(
        "chatter", help="simulate repeated impacts and circuit opening",
        formatter_class=argparse.RawDescriptionHelpFormatter, epilog=EPILOG,
        description="Simulate the thesis rig, any design field changed, "
                    "from the release:\nAppendix E against a rigid "
                    "separator (appE), the three beams with Newton's\n"
                    "impact law (newton) or with Hertz contact (hertz). "
                    "Prints when and for how\nlong the circuit opens: the "
                    "openings, and the discontinuity events\n(openings of "
                    "at least --min-open).\nThe step and the window come "
                    "from the design and every run checks its\nenergy "
                    f"(docs/chatter.md); N is {DEFAULT_MODES} unless "
                    "--n-modes gives it.")
    run_group = parser.add_argument_group("simulation")
    chatter_options.add_law_options(run_group)
    chatter_options.add_run_options(run_group)
    chatter_options.add_button_options(run_group)
    chatter_options.add_output_options(parser)
    add_design_options(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    from contactsep.chatter import simulate
    from contactsep.model import thesis_design

    if args.png and importlib.util.find_spec("matplotlib") is None:
        raise InputError("--png needs matplotlib (pip install "
                         "'contactsep[plot]')")
    from contactsep.chatter.numerics import DEFAULT_MODES
    from contactsep.studies.preload.verdict import chatter_verdict

    overrides = design_overrides(args)
    overrides.setdefault("n_modes", DEFAULT_MODES)
    design = thesis_design(**overrides)
    args.damping = damping_law(args, overrides, args.model) or "none"
    # a --design file's echo of the rig's e (model --json writes every
    # field) is not the user's choice of e
    if "e" in drop_echoes(args, overrides, ("e",)) and \
            args.model == "hertz" and args.damping != "flores":
        warnings.warn("--e: elastic Hertz contact does not use the "
                      "coefficient of restitution (give --damping flores "
                      "to calibrate its damping to e)", ContactsepWarning)
    output.check_targets({"--csv": args.csv, "--png": args.png},
                         {"--design": args.design} if args.design else {})
    started = time.perf_counter()
    try:
        with elapsed(args.progress) as tick, output.stop_checks(tick):
            result = simulate(
                design, model=args.model, damping=args.damping, dt=args.dt,
                t_end=args.t_end, preload=args.preload,
                open_threshold=args.open_threshold, min_open=args.min_open,
                stepper=args.stepper, nu=args.nu,
                button_radius=args.button_radius,
                static_correction=args.static_correction == "on",
                verify=args.verify, alpha=args.alpha, contact=args.contact,
                yield_pressure=args.yield_pressure, button=args.button,
                button_length=args.button_length)
    except InputError as error:
        # the simulation names its arguments; the command, its options
        name, sep, rest = str(error).partition(":")
        if sep and name in _OPTIONS:
            raise InputError(f"--{name.replace('_', '-')}:{rest}") from None
        raise
    refuse_blown_up(result)
    verdict = chatter_verdict(result, time.perf_counter() - started)
    if args.json:
        data = with_sources(result.to_json_dict(), args)
        if verdict is not None:     # the text without the measured time
            data["verdict"] = verdict.text
        output.write_json(sys.stdout, data)
    else:
        output.write_text(sys.stdout, summary_text(
            result, args.events, si=getattr(args, "units", "us") == "si")
                          + ("" if verdict is None
                             else verdict.line() + "\n"))
    with units_shown(args.units):   # SI where --units si asks for it
        if args.csv:
            write_csv(result, args.csv,
                      in_units(result.to_json_dict(), args)["inputs"])
        if args.png:
            from contactsep.studies.plots import save_chatter_png
            save_chatter_png(result, args.png, dpi=args.dpi)
    if args.preload == 0.0 and args.model != "appE":
        # after the outputs: a failed write's error is the last line
        print("contactsep: note: preload 0: the lower contact rests on the "
              "separator with no force; `contactsep preload` finds the "
              "smallest preload that keeps the circuit closed",
              file=sys.stderr)
    return 0


@contextlib.contextmanager
def elapsed(progress: str):
    """A tick that shows a long run's elapsed time on stderr (tqdm, no
    total: a compiled run reports no steps), for output.stop_checks; a
    no-op without a bar (--progress never, or auto off a terminal)."""
    enabled = {"auto": sys.stderr.isatty(), "always": True,
               "never": False}[progress]
    bar = None
    if enabled:
        try:
            from tqdm import tqdm
        except ImportError:
            bar = None
        else:
            # no monitor thread: a live thread keeps a long run from
            # forking (output.interruptible)
            tqdm.monitor_interval = 0
            bar = tqdm(total=None, desc="simulating", delay=1.0,
                       bar_format="{desc}: {elapsed}", file=sys.stderr,
                       leave=False)
    try:
        yield (lambda: None) if bar is None else (lambda: bar.update(0))
    finally:
        if bar is not None:
            bar.close()


def refuse_blown_up(result) -> None:
    """A run its stepper stopped at the energy bound has no circuit
    figures: refuse it (exit 2) rather than print NaN as an answer."""
    from contactsep.chatter import status

    if result.status == status.ENERGY_BOUND:
        raise InputError(
            f"--dt: the {result.model} run stopped: its energy grew past "
            f"twice the release's (status {status.ENERGY_BOUND}): the step "
            f"{result.dt:g} s is too coarse for the contact; no circuit "
            f"figures (use a smaller --dt, or the default)")


#: simulate()'s arguments that are options of the command.
_OPTIONS = ("dt", "t_end", "preload", "open_threshold", "min_open", "nu",
            "button_radius", "verify", "alpha", "contact", "yield_pressure",
            "static_correction", "button", "button_length")


def _g(value, digits=6) -> str:
    """A number to ``digits`` significant digits ('-' for NaN)."""
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return f"{value:.{digits}g}"


def summary_text(result, listed: int | None = 10, si: bool = False) -> str:
    """The inputs and the summary, with units, 6 significant digits, and
    the circuit's first ``listed`` open intervals (None: all); ``si``:
    every quantity in m, N, s, Pa (--units si)."""
    def q(value, unit):
        """A quantity as shown: its number and unit in the system asked."""
        value, unit = si_shown(value, unit, si)
        return f"{_g(value)} {unit}"

    lines = [f"model {result.model}, N = {result.n_modes}, "
             f"dt = {_g(result.dt)} s ({result.stepper}, "
             f"{result.dt_source}), window 0 to {_g(result.t_end_s)} s "
             f"({result.t_end_source})",
             f"preload {q(result.preload_lb, 'lb')}, damping "
             f"{result.damping}"
             + (f" (alpha {q(result.alpha_s_per_in, 's/in')})"
                if result.alpha_s_per_in is not None else "")
             + (f", contact thornton (yield pressure "
                f"{q(result.yield_pressure_psi, 'psi')})"
                if result.contact == "thornton" else "")
             + f", open above {q(result.open_threshold_in, 'in')}"
             f", events last >= {_g(result.min_open_s)} s"
             + (", static correction" if result.static_correction
                else "")]
    lines.append("design: " + ", ".join(_design_parts(result.design, si)))
    rows = [("first impact", result.first_impact_s, "s"),
            ("first impulse", result.first_impulse_lb_s, "lb s"),
            ("max lower gap", result.max_lower_gap_in, "in"),
            ("first lift (1st swing)", result.first_lift_in, "in"),
            ("energy end / start", result.energy_ratio, ""),
            ("status", f"{result.status} ("
             f"{_STATUS_WORDS.get(result.status, 'see contactsep.chatter.status')})"
             if result.model != "appE" else "0 (ok)", ""),
            ("circuit open, total", result.circuit_open_s, "s"),
            ("first opening", result.first_circuit_open_s, "s"),
            ("longest opening", result.longest_open_s, "s"),
            ("openings", len(result.circuit_open_intervals), ""),
            ("discontinuity events", result.n_events, ""),
            ("chatters", "yes" if result.chatters else "no", "")]
    single = result.single_impulse
    rows += [("eq. 23 y3 max, as printed", single.get("y3_max_in"), "in"),
             ("eq. 23 y3 max, psi/M3", single.get("y3_max_impulse_form_in"),
              "in")]
    for label, value, unit in rows:
        value, unit = si_shown(value, unit, si)
        shown = _g(value) if isinstance(value, float) else str(value)
        lines.append(f"  {label:<28} {shown:>12} {unit}".rstrip())
    for key, value in result.changes.items():
        if key.endswith("_change"):
            rows_label = f"{key} (verify)"
            lines.append(f"  {rows_label:<28} {_g(value, 3):>12}")
    if result.changes:
        lines.append(f"  (verify: N = {result.changes['verify_n_modes']}, "
                     f"dt = {_g(result.changes['verify_dt_s'])} s, status "
                     f"{result.changes['verify_status']})")
    if result.model == "newton":
        lines.append("  (one Newton run's open time is ill-conditioned: "
                     "docs/convergence.md)")
    if result.rigid_stop is not None:
        r = result.rigid_stop
        lines.append(f"  {'impacts, rests':<28} {len(r.impact_t):>12} "
                     f"{len(r.rest_intervals)} (--json lists them)")
    openings = result.circuit_open_intervals
    lines.append("circuit open (s), events marked *:")
    for start, end in openings[:listed]:
        mark = "*" if end - start >= result.min_open_s else " "
        lines.append(f"  {mark} {_g(start):>12} to {_g(end):>12}  "
                     f"({_g((end - start) * 1e6, 4)} us)")
    if not len(openings):
        lines.append("  never")
    elif listed is not None and len(openings) > listed:
        lines.append(f"  ... {len(openings) - listed} more (--events all, "
                     f"or --csv / --json)")
    return "\n".join(lines) + "\n"


def _design_parts(design, si: bool = False) -> list[str]:
    """'L1 19 in', 'd 0.25 in', ...: each given field under its output
    name (model.fields), with its unit (``si``: in SI)."""
    import dataclasses

    from contactsep.model import fields
    parts = []
    for f in dataclasses.fields(design) if design is not None else ():
        value = getattr(design, f.name)
        if value is None:
            continue
        name = fields.OUTPUT_NAMES.get(f.name, f.name)
        value, unit = si_shown(value, fields.unit(f.name), si)
        shown = f"{value:g}" if isinstance(value, float) else str(value)
        parts.append(f"{name} {shown} {unit}".rstrip())
    return parts


def write_csv(result, path, inputs=None) -> None:
    """The sampled gaps, one row a sample, in the unit system shown
    (model.names.units_shown; ``inputs`` the JSON's inputs as they are
    to be written); replaced only when finished."""
    import numpy as np

    threshold = result.open_threshold_in
    is_open = (result.gap_upper > threshold) & (result.gap_lower > threshold)
    if inputs is None:
        inputs = result.to_json_dict()["inputs"]
    factor, unit = shown(1.0, "in")
    with output.open_output(path) as out:
        out.write(f"# contactsep chatter: gap histories ({unit}) at the "
                  f"samples; circuit_open = 1 where both gaps exceed the "
                  f"threshold\n")
        out.write(f"# inputs: {output.json_text(inputs, indent=None)}\n")
        out.write(f"t_s,{shown_key('gap_upper_in')},"
                  f"{shown_key('gap_lower_in')},circuit_open\n")
        # times 1.0 in us: the same bits
        rows = np.column_stack([result.t, result.gap_upper * factor,
                                result.gap_lower * factor])
        for (t, upper, lower), flag in zip(rows, is_open):
            out.write(f"{t:.9g},{upper:.9g},{lower:.9g},{int(flag)}\n")


#: The words of the run's status (contactsep.chatter.status).
_STATUS_WORDS = {0: "ok", 7: "stopped at the energy bound",
                 8: "interrupted", 9: "UNCONVERGED: energy check failed"}
