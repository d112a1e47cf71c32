"""``contactsep sweep``: a design space on the local pool or a Dask
cluster, as CSV, Parquet or a summary."""

from __future__ import annotations

import argparse
import contextlib
import sys
import warnings

from contactsep import output
from contactsep.cli import cluster
from contactsep.cli import journal as journals
from contactsep.cli.cluster import add_cluster_options, check_cluster
from contactsep.cli.design_options import (
    add_design_options,
    design_overrides,
    fields_from_file,
)
from contactsep.cli.guards import (
    NamedWriter,
    add_backend_option,
    check_targets,
    drop_echoes,
)
from contactsep.cli.help import examples
from contactsep.cli.unit_system import from_si
from contactsep.cli.values import finite, integer
from contactsep.errors import ContactsepWarning, InputError
from contactsep.output.pieces import PIECE_S
from contactsep.studies.sweep.chatter import (
    CHUNK_SIZE as CHATTER_CHUNK_SIZE,
)
from contactsep.model.fields import SETTINGS
from contactsep.runs.pool import WORKERS_PER_CORE, max_workers
from contactsep.studies.sweep.run import kept_note as runner_note
from contactsep.studies.sweep.spec import CHUNK_SIZE, MAX_CHUNK_SIZE
from contactsep.studies.sweep.axes import MAX_DESIGNS
from contactsep.studies.sweep.checks import CHATTER_UNUSED
from contactsep.studies.sweep.checks import MODELS as SWEEP_MODELS


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep sweep``: its options one group a function, in
    the order ``--help`` lists them."""
    sweep = commands.add_parser(
        "sweep", help="sweep or sample design parameters",
        description="Evaluate the thesis design with fields varied "
                    "(--vary; several form a grid) and/or sampled "
                    "(--sample, K samples per grid point), the other "
                    "fields fixed by the design options: one CSV row per "
                    "design (with its status), a summary with the inputs. "
                    "--model eq23 (default) evaluates the general model's "
                    "single impulse (max y3); hertz and newton simulate "
                    "the three beams and report whether and how long the "
                    "circuit opens (p_open: the designs with a "
                    "discontinuity event), and may also fix, vary or "
                    "sample preload, min_open and (hertz) damping, and "
                    "fix or vary the step dt. "
                    "Failed designs are counted (n_failed) and left out of "
                    "the statistics; if every design fails, exit 2.",
        **examples("contactsep sweep --vary d=0.1:1.0:19 "
                   "--vary ys=0.25,0.5,0.75 --csv grid.csv",
                   "contactsep sweep --sample 'd=normal(0.25,0.01)' "
                   "--samples 100000 --threshold 0.11 --json",
                   "contactsep sweep --model hertz --n-modes 16 "
                   "--preload 20 --sample 'd=normal(0.25,0.01)' "
                   "--samples 1000"))
    _add_space_options(sweep)
    _add_chatter_options(sweep)
    _add_output_options(sweep)
    _add_run_options(sweep)
    add_design_options(sweep)
    sweep.set_defaults(handler=run_sweep)


def _add_space_options(sweep: argparse.ArgumentParser) -> None:
    """The model and the design space: --model, --vary, --sample,
    --samples, --seed, --threshold."""
    sweep.add_argument("--model", choices=SWEEP_MODELS,
                       default="eq23",
                       help="eq23: the general model's single impulse "
                            "(default); hertz, newton: the three-beam "
                            "chatter simulation (contactsep chatter)")
    sweep.add_argument("--vary", action="append", default=[],
                       metavar="NAME=START:STOP:COUNT|NAME=V1,V2,...",
                       help="a grid axis (repeatable): any numeric field, "
                            "an end condition or n_modes (values as a "
                            "list)")
    sweep.add_argument("--sample", action="append", default=[],
                       metavar="'NAME=normal(MEAN,SD)'|'NAME=uniform(LO,HI)'",
                       help="a distribution of a numeric field (repeatable;"
                            " quote it for the shell; each number may carry"
                            " a unit: 'd=normal(1mm,0.02mm)')")
    sweep.add_argument("--samples", type=integer(1, MAX_DESIGNS),
                       default=None, metavar="K",
                       help="samples per grid point (default 1000)")
    sweep.add_argument("--seed", type=integer(0, 2**64 - 1), default=0,
                       help="seed of the samples (default 0)")
    sweep.add_argument("--threshold", type=finite("in"), default=None,
                       metavar="T",
                       help="report p_exceed = P(max y3 > T) and its 95 %% "
                            "Wilson interval (T in inches; eq23)")


def _add_chatter_options(sweep: argparse.ArgumentParser) -> None:
    """The chatter settings' group (--model hertz or newton)."""
    chatter = sweep.add_argument_group(
        "chatter settings (--model hertz or newton; each may instead be "
        "varied or sampled)")
    for name, metavar, default in (("preload", "LB", "lb; default 0"),
                                   ("min_open", "S", "s; default 1e-05"),
                                   ("damping",
                                    "{none,flores,hunt-crossley}",
                                    "default none"),
                                   ("alpha", "S_PER_IN", "s/in; with "
                                    "--damping hunt-crossley"),
                                   ("contact", "{hertz,thornton}",
                                    "default hertz"),
                                   ("yield_pressure", "PSI", "psi; with "
                                    "--contact thornton"),
                                   ("dt", "S", "s; default: each "
                                    "design's own; varied, not sampled"),
                                   ("t_end", "S", "s; default: each "
                                    "design's own"),
                                   ("static_correction", "{on,off}",
                                    "default on; fixed, not varied")):
        chatter.add_argument("--" + name.replace("_", "-"),
                             metavar=metavar,
                             help=f"{SETTINGS[name][2]} ({default})")


def _add_output_options(sweep: argparse.ArgumentParser) -> None:
    """Where the rows and the summary go: --csv, --parquet, --resume,
    --json."""
    sweep.add_argument("--csv", metavar="FILE",
                       help="one row per design, written as the sweep goes "
                            "to a temporary file beside FILE that replaces "
                            "it at the end")
    sweep.add_argument("--parquet", metavar="FILE",
                       help="also write Parquet (needs pyarrow)")
    sweep.add_argument("--resume", action="store_true",
                       help="continue a sweep an earlier run of the same "
                            "command left unfinished (killed, interrupted) "
                            "from the chunks it kept beside the --csv "
                            "(else --parquet) file, in .FILE.resume/ (a "
                            "sweep into a file always keeps them until "
                            "its outputs are in place): the same outputs "
                            "as an uninterrupted run")
    sweep.add_argument("--json", action="store_true",
                       help="print the summary as JSON")


def _add_run_options(sweep: argparse.ArgumentParser) -> None:
    """How the chunks run: --chunk-size, --workers, the cluster,
    --progress, --backend."""
    sweep.add_argument("--chunk-size", type=integer(1, MAX_CHUNK_SIZE),
                       default=None,
                       help=f"most designs per chunk (default {CHUNK_SIZE}, "
                            f"chatter models {CHATTER_CHUNK_SIZE}; "
                            f"chunks are sized to about "
                            f"{PIECE_S:g} s of work below it)")
    sweep.add_argument("--workers", type=integer(1, max_workers()),
                       default=None,
                       help=f"local processes (default: the usable cores; "
                            f"at most {WORKERS_PER_CORE} a core)")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="run the chunks on this Dask scheduler")
    add_cluster_options(sweep, "the chunks", address=False)
    sweep.add_argument("--progress", choices=("auto", "always", "never"),
                       default="auto",
                       help="progress bar on stderr: auto (on a terminal),"
                            " always (needs tqdm), never")
    add_backend_option(sweep)


def _failures(summary: dict, model: str) -> str:
    """'1,567 of 10,000 designs failed (1,567 invalid input)'."""
    if model == "eq23":
        from contactsep.model.status import MESSAGES
    else:
        from contactsep.studies.sweep.chatter import MESSAGES
    total = summary["n"] + summary["n_failed"]
    reasons = ", ".join(f"{count:,} {MESSAGES[code].split(':')[0]}"
                        for code, count in sorted(
                            summary["n_failed_by_status"].items()))
    return (f"{summary['n_failed']:,} of {total:,} designs failed "
            f"({reasons})")


def _print_summary(summary: dict, spec) -> None:
    width = max([14] + [len(key) for key in summary])
    for key, value in summary.items():
        if key in ("inputs", "n_failed_by_status"):
            continue
        if value is None:
            value = "-"
        elif isinstance(value, float):
            value = f"{value:.6g}"
        elif isinstance(value, list):
            value = ", ".join(f"{v:.6g}" for v in value)
        print(f"{key:>{width}} = {value}")
    for line in spec.describe():
        print(f"{'':>{width}}   {line}")


def _settings(args: argparse.Namespace, si: bool = False) -> dict:
    """The chatter settings typed as options (setting -> value; a bare
    number read in SI where ``si``)."""
    from contactsep.chatter.settings import parse_value
    typed = {"preload": (args.preload, "--preload"),
             "min_open": (args.min_open, "--min-open"),
             "damping": (args.damping, "--damping"),
             "alpha": (args.alpha, "--alpha"),
             "contact": (args.contact, "--contact"),
             "yield_pressure": (args.yield_pressure, "--yield-pressure"),
             "dt": (args.dt, "--dt"),
             "t_end": (args.t_end, "--t-end"),
             "static_correction": (args.static_correction,
                                   "--static-correction")}
    values = {name: parse_value(name, text, option)
              for name, (text, option) in typed.items() if text is not None}
    if si:
        values = {name: from_si(SETTINGS[name][0], typed[name][0], value)
                  for name, value in values.items()}
    return values


def _unfinished(writers, store):
    """What a sweep stopped by SIGTERM left (it otherwise prints
    nothing), for one line on stderr: how far it got, its outputs
    unchanged, where its finished chunks are (None: nothing to say)."""
    def note():
        partial = next((getattr(w, "partial", None) for w in writers
                        if getattr(w, "partial", None)), None)
        if partial:
            return partial + runner_note(store, writers)
        return None
    return note


def run_sweep(args: argparse.Namespace) -> int:
    """The sweep, its outputs in the unit system of --units (its bare
    numbers read in it)."""
    from contactsep.model.names import units_shown
    with units_shown(getattr(args, "units", "us")):
        return _run_sweep(args)


def _run_sweep(args: argparse.Namespace) -> int:
    from contactsep.model.names import shown_data
    from contactsep.studies.sweep import run as runner

    spec = _checked_spec(args, runner)
    resume = journals.Resume(args.resume, args.csv or args.parquet,
                             kept="chunks", give="--csv or --parquet")
    # every option checked: only now the scheduler and the files
    check_cluster(args, workers=False)
    summary = _run_into_files(args, spec, runner, resume)
    resume.finished()
    if args.json:
        output.write_json(sys.stdout, shown_data(summary))
    else:
        _print_summary(shown_data(summary), spec)
    if summary["n_failed"]:
        if not summary["n"]:
            sys.stdout.flush()
            raise InputError(f"{_failures(summary, args.model)}: every "
                             f"one; nothing to summarise"
                             f"{_first_refusal(args, spec, summary)}")
        warnings.warn(f"{_failures(summary, args.model)}; the statistics "
                      f"are over the other {summary['n']:,}",
                      ContactsepWarning)
    return 0


def _checked_spec(args: argparse.Namespace, runner):
    """The sweep's spec from the options (its bare numbers in --units),
    every option that needs no file or scheduler checked."""
    from contactsep.studies.sweep.spec import make_spec
    from contactsep.studies.sweep.writers import require_pyarrow
    from contactsep.studies.sweep.axes import (
        parse_sample,
        parse_vary,
        sample_in_si,
        vary_in_si,
    )

    si = getattr(args, "units", "us") == "si"
    vary = [parse_vary(vary_in_si(text) if si else text)
            for text in args.vary]
    sample = [parse_sample(sample_in_si(text) if si else text)
              for text in args.sample]
    swept = {name for name, _ in vary} | {s[0] for s in sample}
    # a --design file's value of a swept field gives way to the sweep;
    # its echo of a default the chatter models do not read is dropped
    base = {k: v for k, v in design_overrides(args).items()
            if not (k in swept and k in fields_from_file(args))}
    if args.model != "eq23":
        base = drop_echoes(args, base, CHATTER_UNUSED)
    spec = make_spec(vary=vary, sample=sample, samples=args.samples,
                     seed=args.seed, base=base,
                     backend=args.backend or "compiled", model=args.model,
                     settings=_settings(args, si))
    runner.check_run(chunk_size=args.chunk_size, workers=args.workers,
                     threshold=args.threshold)
    runner.check_threshold(spec, args.threshold)
    if args.parquet:
        require_pyarrow()
    check_targets(args, {"--csv": args.csv, "--parquet": args.parquet})
    return spec


def _run_into_files(args: argparse.Namespace, spec, runner,
                    resume) -> dict:
    """The sweep's summary, its rows written to --csv and --parquet; a
    sweep that does not finish leaves the old outputs and its chunks."""
    from contactsep.studies.sweep.writers import CsvWriter, ParquetWriter

    progress = {"auto": None, "always": True, "never": False}[args.progress]
    scheduler = cluster.connect(args)
    writers, store = [], None
    try:
        if args.parquet:
            writers.append(NamedWriter(
                ParquetWriter(args.parquet, spec,
                              design=args.design), "--parquet",
                args.parquet))
        if args.csv:
            writers.append(NamedWriter(
                CsvWriter(args.csv, spec, design=args.design),
                "--csv", args.csv))
        # the writers hold the outputs' locks: the chunks are this run's.
        # Every sweep into a file keeps its finished chunks beside it
        # until the outputs are in place: one that does not finish leaves
        # its old outputs as they were and its chunks for --resume (a
        # sweep started afresh drops an earlier one's)
        store = resume.open_chunks(spec)
        return runner.run_sweep(
            spec, writers=writers, threshold=args.threshold,
            chunk_size=args.chunk_size, workers=args.workers,
            scheduler=scheduler, progress=progress, store=store)
    except BaseException as error:
        for writer in writers:
            writer.abort()      # a no-op for a writer run_sweep closed
        resume.stopped(error, _unfinished(writers, store))
        raise
    finally:
        if scheduler is not None:
            with contextlib.suppress(Exception):
                scheduler.close()


def _first_refusal(args: argparse.Namespace, spec, summary: dict) -> str:
    """'; the first design: ...' when every chatter design was refused
    (status 2), else ''."""
    if args.model == "eq23" or 2 not in summary["n_failed_by_status"]:
        return ""
    from contactsep.studies.sweep.chatter import first_refusal
    first = first_refusal(spec)
    return f"; the first design: {first}" if first else ""
