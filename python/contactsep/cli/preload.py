"""``contactsep preload``: the smallest preload that keeps this design's
circuit closed, its own error estimate, and the robust answer under
tolerances (contactsep.studies.preload.command)."""

from __future__ import annotations

import argparse
import sys

from contactsep import output
from contactsep.cli import journal as journals
from contactsep.cli.cluster import add_cluster_options, check_cluster, cluster
from contactsep.cli.design_options import (
    add_design_options,
    damping_law,
    design_overrides,
    with_sources,
)
from contactsep.cli.help import examples
from contactsep.cli.values import finite, integer
from contactsep.errors import InputError
from contactsep.model.names import shown, shown_text, units_shown
from contactsep.studies.preload.answer import robust_check_text, spans_text

#: simulate()'s keywords that are options of the command.
_OPTIONS = ("dt", "t_end", "open_threshold", "min_open", "damping")


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep preload``."""
    from contactsep.studies.preload.chart import DEFAULT_MODES

    parser = commands.add_parser(
        "preload", help="the smallest preload that keeps the circuit "
                        "closed",
        description="The smallest lower-contact preload with no "
                    "discontinuity event for this design (the thesis rig, "
                    "any design field changed): the search of the "
                    "preload chart (every 0.99 % step from the answer to 2 "
                    "times it simulated, so that windows of events 1 % "
                    "wide are found; from 0.7 times it where the scan is "
                    "not monotone, or with --band-below), its change at "
                    "half the step and twice the modes "
                    "(min_preload_change, checked 2 % either side), the "
                    "windows of "
                    "events and the closed windows below the answer. "
                    "With --tolerance, also the robust answer: the "
                    "smallest preload whose p_open over the tolerances "
                    "is at most --p-target on the upper end of its 95 % "
                    "Wilson interval (0.01 needs 381 samples). The last "
                    "line is the verdict: the answer to use, or what "
                    "moved and the rerun that would settle it. "
                    f"N defaults to {DEFAULT_MODES} modes per member "
                    "(--n-modes). docs/preload.md, \"The preload "
                    "command\".",
        **examples("contactsep preload --n-modes 8 --d 0.75",
                   "contactsep preload --d 0.5 --json",
                   "contactsep preload --tolerance 'd=normal(0.25,0.005)' "
                   "--samples 300 --csv preload.csv --resume"))
    _add_simulation_options(parser)
    _add_output_options(parser)
    add_design_options(parser)
    parser.set_defaults(handler=run)


def _add_simulation_options(parser: argparse.ArgumentParser) -> None:
    """The "simulation" group: the model, its law and the search's
    numerics."""
    from contactsep.chatter.settings import DAMPINGS
    from contactsep.studies.preload.chart import MODELS

    run_group = parser.add_argument_group("simulation")
    run_group.add_argument("--model", choices=MODELS, default="hertz",
                           help="default hertz")
    run_group.add_argument("--damping", choices=DAMPINGS, default=None,
                           help="Hertz damping (default: flores, "
                                "calibrated to e, where e is given; none, "
                                "elastic, otherwise)")
    run_group.add_argument("--dt", type=finite("s"), default=None,
                           metavar="S", help="time step (s; default the "
                                             "simulation's)")
    run_group.add_argument("--t-end", type=finite("s"), default=None,
                           metavar="S", help="window from the release (s;"
                                             " default the simulation's)")
    run_group.add_argument("--min-open", type=finite("s"), default=None,
                           metavar="S",
                           help="shortest opening that counts as a "
                                "discontinuity event (s; default 1e-05): "
                                "the answer depends on it")
    run_group.add_argument("--open-threshold", type=finite("in"),
                           default=None, metavar="IN",
                           help="gap above which a contact is open (in; "
                                "default 1e-06)")
    add_robust_options(parser)
    converging = run_group.add_mutually_exclusive_group()
    converging.add_argument(
        "--converge", nargs="?", const=True, default=None,
        type=integer(2, 1024), metavar="N",
        help="search again where the check of the answer fails, up to "
             "checks at N = 128 (or the N given). By default the answer "
             "is converged to 2 %% as far as one check goes: where it "
             "moves more than 2 %% at 2N, the answer at 2N is checked at "
             "4N and a quarter of the step (or the finest step the work "
             "budget takes)")
    converging.add_argument(
        "--no-converge", dest="converge", action="store_const", const=False,
        help="no check at 4N (the answer and its change at 2N only)")
    run_group.add_argument(
        "--perturbation", default=None, metavar="R",
        help="also search on y_s (1 + R) and y_s (1 - R) with the same "
             "settings (0 < R <= 1e-3; 1e-6: far below a part's "
             "tolerance, 1e-9: round-off's scale): where "
             "the answer moves far more than R, the threshold is "
             "ill-conditioned and no N or step converges it closer "
             "(min_preload_spread; two more searches)")
    run_group.add_argument(
        "--band-below", action="store_true",
        help="the fine band from 0.7 times the answer in every search at N "
             "(default: from just below the answer, from 0.7 only where "
             "the scan saw a closed preload below its last event, or with "
             "--tolerance): the closed windows below the answer; the same "
             "answer")


def _add_output_options(parser: argparse.ArgumentParser) -> None:
    """The "output" group: JSON, CSV, resume, workers, cluster, progress."""
    from contactsep.runs.pool import WORKERS_PER_CORE, max_workers

    out_group = parser.add_argument_group("output")
    out_group.add_argument("--json", action="store_true",
                           help="print the answer as JSON")
    out_group.add_argument("--csv", metavar="FILE",
                           help="write every simulation of the search, one "
                                "row each (comments: the answers); "
                                "replaced only when finished")
    out_group.add_argument("--resume", action="store_true",
                           help="keep every finished simulation beside the "
                                "--csv file, in .FILE.resume/, and continue "
                                "a search an earlier run of the same "
                                "command left there (killed, interrupted): "
                                "the same answer and CSV as an "
                                "uninterrupted run")
    out_group.add_argument("--workers", type=integer(1, max_workers()),
                           default=None,
                           help=f"local processes (default: the usable "
                                f"cores; at most {WORKERS_PER_CORE} a core)")
    add_cluster_options(out_group, "the simulations")
    out_group.add_argument("--progress", choices=("auto", "always",
                                                  "never"),
                           default="auto",
                           help="progress bar on stderr: auto (on a "
                                "terminal), always (needs tqdm), never")


def add_robust_options(parser: argparse.ArgumentParser) -> None:
    """The robust answer's options (--tolerance, --p-target, --samples,
    --seed), shared by ``preload`` and ``report``."""
    from contactsep.studies.preload.robust import (
        DEFAULT_P_TARGET,
        DEFAULT_SAMPLES,
        MAX_SAMPLES,
    )
    robust = parser.add_argument_group("robust answer")
    robust.add_argument("--tolerance", action="append", default=[],
                        metavar="'FIELD=normal(MEAN,SD)'|"
                                "'FIELD=uniform(LO,HI)'",
                        help="a design field's distribution (repeatable; "
                             "the syntax of sweep --sample; quote it)")
    robust.add_argument("--p-target", default=None, metavar="P",
                        help=f"the largest acceptable p_open, met by "
                             f"the upper end of its 95 %% Wilson interval "
                             f"(default {DEFAULT_P_TARGET:g}: needs 381 "
                             f"samples or more)")
    robust.add_argument("--samples", type=integer(1, MAX_SAMPLES),
                        default=None, metavar="K",
                        help=f"draws of the tolerances (default "
                             f"{DEFAULT_SAMPLES}; each preload tried costs "
                             f"up to K runs: 381 show a p_open of 1 %%)")
    robust.add_argument("--seed", type=integer(0, 2**64 - 1), default=0,
                        help="seed of the draws (default 0; the same "
                             "designs as sweep --sample with that seed)")


def tolerances_in_units(args) -> list:
    """--tolerance's texts with their bare numbers in the unit system of
    --units (SI: each given its SI unit, as every option's bare number
    is read in SI)."""
    from contactsep.studies.sweep.axes import sample_in_si
    if getattr(args, "units", "us") != "si":
        return list(args.tolerance)
    return [sample_in_si(text) for text in args.tolerance]


def parse_p_target(text):
    """--p-target's value (DEFAULT_P_TARGET when not given), checked."""
    from contactsep.studies.preload.robust import (
        DEFAULT_P_TARGET,
        check_p_target,
    )
    if text is None:
        return DEFAULT_P_TARGET
    try:
        value = float(text)
    except ValueError:
        value = text
    return check_p_target(value)


def run(args: argparse.Namespace) -> int:
    from contactsep.model import thesis_design
    from contactsep.studies.preload.chart import DEFAULT_MODES
    from contactsep.studies.preload.robust import parse_tolerances

    p_target = parse_p_target(args.p_target)
    overrides = design_overrides(args)
    overrides.setdefault("n_modes", DEFAULT_MODES)
    design = thesis_design(**overrides)
    args.damping = damping_law(args, overrides, args.model)
    args.tolerance = tolerances_in_units(args)
    if args.tolerance:      # refused before any simulation
        parse_tolerances(args.tolerance, args.samples or 1, args.seed)
    elif args.samples is not None:
        raise InputError("--samples: the draws of --tolerance; give a "
                         "tolerance")
    output.check_targets({"--csv": args.csv},
                         {"--design": args.design} if args.design else {})
    resume = journals.Resume(args.resume, args.csv)
    check_cluster(args)
    with cluster(args) as client, units_shown(args.units):
        return _run(args, design, p_target,
                    args.workers if client is None else client, resume)


def _run(args, design, p_target, workers, resume) -> int:
    """The search (on ``workers``: local processes or a Dask client) and
    its outputs."""
    from contactsep.runs.stops import search_progress
    from contactsep.studies.preload.checks import journal_inputs
    from contactsep.studies.preload.command import preload
    from contactsep.studies.preload.verify import expected_runs
    settings = {name: getattr(args, name) for name in _OPTIONS
                if getattr(args, name) is not None}
    enabled = {"auto": None, "always": True, "never": False}[args.progress]
    journal = resume.open_runs(journal_inputs(
        design, args.model, settings, tolerance=args.tolerance,
        p_target=p_target, samples=args.samples, seed=args.seed,
        converge=args.converge, perturbation=args.perturbation,
        band_below=args.band_below))
    bar = search_progress(expected_runs(), enabled)
    finished = False
    try:
        answer = preload(design, model=args.model, tolerance=args.tolerance,
                         p_target=p_target, samples=args.samples,
                         seed=args.seed, workers=workers,
                         converge=args.converge,
                         perturbation=args.perturbation,
                         band_below=args.band_below,
                         progress=bar, journal=journal, **settings)
        finished = True
    except BaseException as error:
        resume.stopped(error)
        if not isinstance(error, InputError):
            raise
        # the simulation names its arguments; the command, its options
        name, sep, rest = str(error).partition(":")
        if sep and (name in _OPTIONS
                    or name in ("converge", "perturbation")):
            raise InputError(f"--{name.replace('_', '-')}:{rest}") from None
        raise
    finally:
        if bar is not None:
            bar.close(finished)
    if args.csv:
        answer.to_csv(args.csv)
        resume.finished()
    if args.json:
        output.write_json(sys.stdout, with_sources(answer.to_json_dict(),
                                                   args))
    else:
        output.write_text(sys.stdout, summary_text(answer))
    return 0


def _g(value, unit="") -> str:
    import math
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "none"
    return f"{value:.5g}{unit}"


def _force(value) -> str:
    """A force (lb) in the unit system shown, 5 significant digits."""
    return shown_text(value, "lb", 5)


def _answer_line(answer) -> list:
    """The answer to use first, where a check says which: the converged
    one where it held (its N), none otherwise."""
    if answer.converged is None:
        return []
    if answer.converged:
        return [f"  answer (converged to 2 %) "
                f"{_force(answer.converged_min_preload_lb)} (N = "
                f"{answer.converged_n_modes}, held at N = "
                f"{answer.converged_check_n_modes})"]
    return [f"  answer                   not converged to 2 % by N = "
            f"{answer.converged_check_n_modes} (below)"]


def _law(answer) -> str:
    """', damping flores' where a damping law was named or chosen from
    e (the answer depends on it); nothing for elastic Hertz contact by
    default, whose line is as it was."""
    law = answer.settings.get("damping")
    return f", damping {law}" if law is not None else ""


def summary_text(answer) -> str:
    """The answer, its change, the windows and the robust answer, its
    forces in the unit system shown (lb; N under ``--units si``)."""
    force = shown(1.0, "lb")[1]
    change = answer.min_preload_change
    at_n = f"min preload at N = {answer.n_modes}"
    lines = [f"model {answer.model}, N = {answer.n_modes}, dt = "
             f"{answer.dt_s:g} s; {answer.simulations} simulations"
             + _law(answer),
             *_answer_line(answer),
             f"  {at_n:<24} {_force(answer.min_preload_lb)}",
             f"  at dt/2 and 2N           "
             f"{_force(answer.verify_min_preload_lb)} (change "
             f"{'none' if change is None else f'{change:+.2%}'})",
             *([] if answer.converged is None else
               [f"  converged to 2 %         {answer.converged_text()}"]),
             *([] if answer.perturbation is None else
               [f"  spread, y_s (1 +- r)     {answer.perturbed_text()}"]),
             f"  longest opening there    "
             f"{_g(answer.longest_open_at_answer_s, ' s')} (events: "
             f"openings >= min_open)",
             f"  {f'event windows ({force})':<24} "
             f"{spans_text(answer.event_windows)}",
             f"  {f'closed below it ({force})':<24} "
             f"{spans_text(answer.closed_windows)}"]
    r = answer.robust
    if r is not None and not r.shown:
        lines.append(f"  robust min preload       not searched: "
                     f"{r.samples} samples cannot show p_open <= "
                     f"{r.p_target:g} on its 95 % upper bound (needs "
                     f">= {r.samples_needed})")
    elif r is not None:
        ci = r.p_open_ci95
        lines.append(f"  robust min preload       "
                     f"{_force(r.min_preload_lb)}: p_open {_g(r.p_open)}"
                     f" (95 % Wilson "
                     f"{'-' if ci is None else f'{ci[0]:.3g}-{ci[1]:.3g}'};"
                     f" {r.n_open} of {r.n} open, {r.n_failed} failed), "
                     f"upper end <= {r.p_target:g}")
        lines.append(f"  robust runs              {r.simulations} "
                     f"({r.simulations_saved} spared: a preload's samples "
                     f"stop once its decision is settled)")
        if r.check_n_modes is not None:
            lines.append(f"  robust, at N = {r.check_n_modes:<10} "
                         f"{robust_check_text(r)}")
    lines += [f"note: {note}" for note in answer.notes]
    # last: the one line to read (its rerun's time measured on this run)
    lines.append(answer.verdict.line())
    return "\n".join(lines) + "\n"
