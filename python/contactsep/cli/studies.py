"""``contactsep study``: its options, the studies of eq. 23 and the
outputs of every study (the studies of three-beam simulations run in
cli/study_runs.py; ``contactsep sweep``: cli/sweep.py)."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from contactsep import output
from contactsep.cli import journal as journals
from contactsep.cli import sweep
from contactsep.cli.cluster import add_cluster_options, check_cluster, cluster
from contactsep.cli.design_options import (
    add_design_options,
    design_overrides,
    fields_from_file,
)
from contactsep.cli.guards import (
    add_backend_option,
    check_creatable,
    check_targets,
    drop_echoes,
)
from contactsep.cli.help import examples
from contactsep.cli.study_runs import (
    RESUMABLE,
    buttons_study,
    conclusion4_study,
    recommendation_study,
    refuse_cluster,
    search_study,
    study_bar,
)
from contactsep.cli.values import finite, integer
from contactsep.errors import InputError
from contactsep.runs.pool import WORKERS_PER_CORE, max_workers
from contactsep.studies.sweep.checks import CHATTER_UNUSED

#: Resolution of the PNGs (dots per inch of a 6 x 4 in figure).
DEFAULT_DPI = 100


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep study``, then ``contactsep sweep``."""
    from contactsep.studies import STUDIES
    from contactsep.studies.preload.chart import DEFAULT_MODES as PRELOAD_MODES

    study = commands.add_parser(
        "study", help="regenerate a thesis figure or table",
        description="Evaluate one of the thesis's studies on the general "
                    "model and print it as a labelled table. NAME is one "
                    f"of {', '.join(STUDIES)}, chatter, preload, "
                    "conclusion3, conclusion4, conclusion5, conclusion6, "
                    "conclusion7, contact-points, materials, "
                    "or all (every study of eq. 23; with --out). "
                    "Design options change the thesis rig the study starts "
                    "from; a study refuses those it sets itself (fig5 its "
                    "thicknesses, ...); fig5 with --ys draws that one "
                    "curve. preload (three-beam simulations, a minute or "
                    "more) finds the smallest lower-contact preload with "
                    "no discontinuity event, for five separators and "
                    "three release heights; conclusion3, conclusion5, "
                    "conclusion6, conclusion7 re-examine the thesis's "
                    "conclusions (restitution, separator thickness, "
                    "separator mass, contact point) for circuit opening "
                    f"(each: default --model hertz, --n-modes "
                    f"{PRELOAD_MODES}). conclusion4 (10 s) reads the "
                    "apparent coefficient of restitution of three contact "
                    "laws against impact velocity and separator "
                    "thickness (--alpha, --yield-pressure, "
                    "--reading-time). buttons (minutes) finds the open "
                    "time and smallest preload of spherical and "
                    "cylindrical buttons of three radii. separator-fit "
                    "(a minute) fits "
                    "Timoshenko separators with elastic clamps and a "
                    "sensor mass to Table II (no design options). "
                    "contact-points and materials (the thesis's "
                    "recommendations 3 and 4, 50 and 32 simulations, "
                    "N = 32) simulate how the circuit opens against where "
                    "each contact touches the separator (x2, x2_lower) "
                    "and against the material presets of the contacts "
                    "and the separator.",
        **examples("contactsep study fig6 --n-modes 16 --restitution 0.5 "
                   "--csv fig6.csv",
                   "contactsep study all --out figs   # CSV and PNG of "
                   "each",
                   "contactsep study preload --csv preload.csv "
                   "--png preload.png"))
    _add_output_options(study)
    _add_simulation_options(study)
    _add_run_options(study)
    add_design_options(study)
    study.set_defaults(handler=run_study)
    sweep.register(commands)


def _add_output_options(study: argparse.ArgumentParser) -> None:
    """The study's name and its outputs (CSV, PNG, a folder)."""
    study.add_argument("name", metavar="NAME")
    study.add_argument("--csv", metavar="FILE", help="write the CSV here")
    study.add_argument("--png", metavar="FILE",
                       help="draw the figure (needs contactsep[plot])")
    study.add_argument("--out", metavar="DIR",
                       help="write NAME.csv and NAME.png into DIR (for "
                            "all: every study's; needs contactsep[plot])")
    study.add_argument("--dpi", type=integer(10, 1200), default=DEFAULT_DPI,
                       help=f"PNG resolution, dots per inch of the 6 x 4 in "
                            f"figure (default {DEFAULT_DPI})")
    add_backend_option(study)


def _add_simulation_options(study: argparse.ArgumentParser) -> None:
    """The simulating studies' model, law and checks."""
    from contactsep.chatter.settings import DAMPINGS
    from contactsep.studies.preload.chart import MODELS as PRELOAD_MODELS

    study.add_argument("--model", choices=PRELOAD_MODELS, default=None,
                       help="preload and conclusionN only: the contact "
                            "model (default hertz)")
    study.add_argument("--damping", choices=DAMPINGS, default=None,
                       help="preload only: the Hertz contact's damping "
                            "(default none: elastic; flores: calibrated "
                            "to e)")
    study.add_argument("--converge", action="store_true",
                       help="preload only: check each row at twice its N "
                            "and half its step, and search again there "
                            "where it moves by more than 2 %% (up to checks "
                            "at N = 128; docs/chatter.md)")
    study.add_argument("--alpha", type=finite("s/in"), default=None,
                       metavar="S_PER_IN",
                       help="conclusion4 (default 0.0676 s/in) and "
                            "preload with --damping hunt-crossley: "
                            "Hunt-Crossley's constant")
    study.add_argument("--yield-pressure", type=finite("psi"), default=None,
                       metavar="PSI",
                       help="conclusion4 only: Thornton's yield pressure "
                            "(default 45000 psi)")
    study.add_argument("--reading-time", type=finite("s"), default=None,
                       metavar="S",
                       help="conclusion4 only: when e_apparent is read "
                            "after the first impact (default 0.02 s)")


def _add_run_options(study: argparse.ArgumentParser) -> None:
    """Where the simulations run, resume and progress."""
    study.add_argument("--workers", type=integer(1, max_workers()),
                       default=None,
                       help=f"preload, conclusionN, contact-points and "
                            f"materials only: local "
                            f"processes for the simulations (default: the "
                            f"usable cores; at most {WORKERS_PER_CORE} a "
                            f"core)")
    add_cluster_options(study, "the simulations (the studies that take "
                               "--workers)")
    study.add_argument("--resume", action="store_true",
                       help=f"{', '.join(RESUMABLE)} only: keep every "
                            f"finished simulation beside the CSV (--csv "
                            f"FILE, or DIR/NAME.csv of --out) in "
                            f".FILE.resume/, and continue a study an "
                            f"earlier run of the same command left there "
                            f"(killed, interrupted): the same CSV as an "
                            f"uninterrupted run")
    study.add_argument("--progress", choices=("auto", "always", "never"),
                       default="auto",
                       help="chatter, preload and conclusionN: a progress "
                            "bar of the simulations on stderr: auto (on a "
                            "terminal, after a second), always, never")


def _write_csv(path, study) -> None:
    with output.open_output(path) as out:
        output.write_text(out, study.csv_text())


def _need_matplotlib() -> None:
    from contactsep.studies.plots import require_matplotlib
    require_matplotlib()


def _compute(name: str, args, overrides: dict, journal=None):
    from contactsep.studies import OWN_FIELDS, STUDIES
    from contactsep.studies.thesis.conclusions import STUDIES as CONCLUSIONS
    from contactsep.studies.preload.chart import FIXED as PRELOAD_FIXED

    # a --design file's value of a study's own field gives way to it (a
    # file from model --json lists every field: issue 31)
    own = {**OWN_FIELDS, "preload": set(PRELOAD_FIXED),
           **{n: {field} for n, (field, _, _) in CONCLUSIONS.items()}}
    overrides = {k: v for k, v in overrides.items() if not (
        k in fields_from_file(args) and k in own.get(name, ()))}
    if name == "preload":
        overrides = drop_echoes(args, overrides, CHATTER_UNUSED)
    from contactsep.studies.thesis.recommendations import STUDIES as ADVICE
    if name in ADVICE:
        return recommendation_study(name, args, overrides, journal)
    searches = ("preload", *CONCLUSIONS)
    refuse_cluster(name, args)
    if name not in (*searches, "buttons") and (args.model or args.workers):
        raise InputError(f"--model and --workers are options of study "
                         f"{', '.join(searches)}, not study {name}'s")
    if name != "preload" and args.converge:
        raise InputError(f"--converge is study preload's option, not "
                         f"study {name}'s")
    if name != "preload" and args.damping:
        raise InputError(f"--damping is study preload's option, not "
                         f"study {name}'s (conclusion3 uses flores)")
    own_options = {"--alpha": args.alpha,
                   "--yield-pressure": args.yield_pressure,
                   "--reading-time": args.reading_time}
    if name == "preload":
        # the preload chart takes Hunt-Crossley's constant with its
        # --damping hunt-crossley
        own_options.pop("--alpha")
    if name != "conclusion4" and any(v is not None
                                     for v in own_options.values()):
        given = ", ".join(k for k, v in own_options.items()
                          if v is not None)
        raise InputError(f"{given}: options of study conclusion4, not "
                         f"study {name}'s")
    if name == "conclusion4":
        return conclusion4_study(args, overrides)
    if name == "buttons":
        return buttons_study(args, overrides, journal)
    if name in searches:
        return search_study(name, args, overrides, journal)
    if name == "separator-fit":
        if args.backend:
            raise InputError("study separator-fit computes the beams' "
                             "modes itself (no --backend)")
        from contactsep.studies.thesis.separator_fit import separator_fit
        return separator_fit(**overrides)
    if name == "chatter":
        if overrides or args.backend:
            raise InputError("study chatter takes no design options: it "
                             "runs the thesis rig for its five separators "
                             "and N = 4, 16, 32 (contactsep chatter runs "
                             "any design)")
        from contactsep.studies.thesis.chatter_table import (
            MODES,
            THICKNESSES,
            chatter_table,
        )
        with study_bar(args, 3 * len(THICKNESSES) * len(MODES)) as bar:
            return chatter_table(progress=bar)
    return STUDIES[name](backend=args.backend or "compiled", **overrides)


def _save(study, out: Path, dpi: int) -> None:
    from contactsep.studies.plots import save_png
    _write_csv(out / f"{study.name}.csv", study)
    save_png(study, out / f"{study.name}.png", dpi=dpi)
    print(f"{study.name}: {out / study.name}.csv, {out / study.name}.png")


def _study_targets(args, names) -> dict:
    targets = {"--csv": args.csv, "--png": args.png}
    if args.out:
        out = Path(args.out)
        if out.exists() and not out.is_dir():
            raise InputError(f"--out {args.out}: not a directory")
        if not out.exists():
            # made at the end: the nearest existing folder must take it
            check_creatable(args.out)
            return targets
        for name in names:
            targets[f"--out ({name}.csv)"] = out / f"{name}.csv"
            targets[f"--out ({name}.png)"] = out / f"{name}.png"
    return targets


def run_study(args: argparse.Namespace) -> int:
    from contactsep.studies import STUDIES
    from contactsep.studies.thesis.conclusions import STUDIES as CONCLUSIONS
    from contactsep.studies.thesis.recommendations import STUDIES as ADVICE

    names = list(STUDIES) if args.name == "all" else [args.name]
    searches = ("preload", *CONCLUSIONS, *ADVICE)
    if args.name not in (*STUDIES, "chatter", "separator-fit", *searches,
                         "conclusion4", "buttons", "all"):
        raise InputError(f"study {args.name!r}: expected one of "
                         f"{', '.join(STUDIES)}, chatter, separator-fit, "
                         f"{', '.join(searches)}, conclusion4, buttons or "
                         f"all")
    if args.name == "all" and (not args.out or args.csv or args.png):
        raise InputError("study all writes with --out DIR (not --csv "
                         "or --png)")
    overrides = design_overrides(args)
    check_targets(args, _study_targets(args, names))
    resume = _study_resume(args)
    if args.png or args.out:
        _need_matplotlib()          # before anything is computed
    if args.name == "all":
        # every study first: a refused option stops before any file
        done = [_compute(name, args, overrides) for name in STUDIES]
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        for study in done:
            _save(study, out, args.dpi)
        print("preload, conclusion3, conclusion5, conclusion6, "
              "conclusion7: skipped (hundreds of three-beam simulations, "
              "a minute or more each; contactsep study NAME --out DIR "
              "writes one)")
        print("chatter: skipped (45 three-beam simulations, 20 s or more;"
              " contactsep study chatter --out DIR writes it)")
        return 0
    if args.resume and not args.csv:
        # the journal lies beside DIR/NAME.csv: DIR is made now
        Path(args.out).mkdir(parents=True, exist_ok=True)
    check_cluster(args)
    refuse_cluster(args.name, args)
    with cluster(args) as args.cluster:
        journal = resume.open_runs(_journal_inputs(args, overrides))
        try:
            study = _compute(args.name, args, overrides, journal)
        except BaseException as error:
            resume.stopped(error)
            raise
    sys.stdout.write(study.table_text())
    if args.csv:
        _write_csv(args.csv, study)
    if args.png:
        from contactsep.studies.plots import save_png
        save_png(study, args.png, dpi=args.dpi)
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        _save(study, out, args.dpi)
    resume.finished()
    return 0


def _study_resume(args) -> journals.Resume:
    """The resume life cycle of a study of simulations: its journal
    beside the CSV (--csv, else --out's NAME.csv); none for a study of
    eq. 23, or without a CSV.  --resume is refused where it has nothing
    to keep."""
    csv = args.csv or (os.path.join(args.out, f"{args.name}.csv")
                       if args.out else None)
    if args.name not in RESUMABLE:
        if args.resume:
            raise InputError(f"--resume: study {args.name} runs no "
                             f"three-beam simulations to keep (it is for "
                             f"{', '.join(RESUMABLE)})")
        return journals.Resume(False, None)
    return journals.Resume(args.resume, csv, give="--csv or --out")


def _journal_inputs(args, overrides: dict) -> dict:
    """What makes a study's simulations, for its journal's manifest (the
    journal keys every simulation by its whole task too)."""
    return {"study": args.name, "model": args.model,
            "damping": args.damping, "converge": args.converge,
            "alpha": args.alpha, "design": overrides}
