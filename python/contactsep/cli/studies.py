"""``contactsep study`` and ``contactsep sweep``."""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
from pathlib import Path

from contactsep.errors import InputError

_OVERRIDES = (("--n-modes", "n_modes", int), ("--e", "e", float),
              ("--ys", "ys", float), ("--tau", "tau", float))


def _overrides(parser: argparse.ArgumentParser) -> None:
    for option, dest, kind in _OVERRIDES:
        parser.add_argument(option, dest=dest, type=kind, default=None)
    parser.add_argument("--backend", choices=("compiled", "numpy"),
                        default="compiled")


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep study`` and ``contactsep sweep``."""
    from contactsep.studies import STUDIES

    study = commands.add_parser(
        "study", help="regenerate a thesis figure or table",
        description="Evaluate one of the thesis's studies on the general "
                    "model and print it as a labelled table. NAME is one "
                    f"of {', '.join(STUDIES)}, chatter, or all (with --out).")
    study.add_argument("name", metavar="NAME")
    study.add_argument("--csv", metavar="FILE", help="write the CSV here")
    study.add_argument("--png", metavar="FILE",
                       help="draw the figure (needs contactsep[plot])")
    study.add_argument("--out", metavar="DIR",
                       help="with NAME all: write every study's CSV and PNG")
    study.add_argument("--lc-reading", choices=("listing", "frequencies",
                                                "mass"), default=None,
                       help="fig23: reading of the equivalent length")
    _overrides(study)
    study.set_defaults(handler=run_study)

    sweep = commands.add_parser(
        "sweep", help="sweep or sample design parameters",
        description="Evaluate the thesis design with fields varied "
                    "(--vary; several form a grid) and/or sampled "
                    "(--sample, K samples per grid point): one CSV row per "
                    "design, a JSON summary.")
    sweep.add_argument("--vary", action="append", default=[],
                       metavar="NAME=START:STOP:COUNT|NAME=V1,V2,...")
    sweep.add_argument("--sample", action="append", default=[],
                       metavar="NAME=normal(MEAN,SD)|NAME=uniform(LO,HI)")
    sweep.add_argument("--samples", type=int, default=None, metavar="K",
                       help="samples per grid point (default 1000)")
    sweep.add_argument("--seed", type=int, default=0)
    sweep.add_argument("--threshold", type=float, default=None, metavar="T",
                       help="report p_exceed = P(max y3 > T) (in)")
    sweep.add_argument("--csv", metavar="FILE")
    sweep.add_argument("--parquet", metavar="FILE",
                       help="also write Parquet (needs pyarrow)")
    sweep.add_argument("--json", action="store_true",
                       help="print the summary as JSON")
    sweep.add_argument("--chunk-size", type=int, default=None)
    sweep.add_argument("--workers", type=int, default=None,
                       help="local processes (default: all cores)")
    sweep.add_argument("--scheduler", metavar="ADDRESS",
                       help="run the chunks on this Dask scheduler")
    sweep.add_argument("--progress", choices=("auto", "always", "never"),
                       default="auto")
    _overrides(sweep)
    sweep.set_defaults(handler=run_sweep)


def _design_overrides(args) -> dict:
    return {dest: getattr(args, dest) for _, dest, _ in _OVERRIDES
            if getattr(args, dest) is not None}


def _write_text(path: str, text: str) -> None:
    Path(path).write_text(text, encoding="ascii")


def _run_one(name: str, args) -> "object":
    from contactsep.studies import STUDIES

    kwargs = _design_overrides(args)
    kwargs["backend"] = args.backend
    if name == "fig23" and args.lc_reading:
        kwargs["lc_reading"] = args.lc_reading
    return STUDIES[name](**kwargs)


def run_study(args: argparse.Namespace) -> int:
    from contactsep.studies import STUDIES

    if args.name == "chatter":
        try:
            from contactsep.studies.chatter import chatter_table
        except ImportError:
            raise InputError("the chatter layer is not installed") from None
        study = chatter_table()
    elif args.name == "all":
        if not args.out:
            raise InputError("study all needs --out DIR")
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        from contactsep.studies.plots import save_png
        for name in STUDIES:
            study = _run_one(name, args)
            _write_text(out / f"{name}.csv", study.csv_text())
            save_png(study, out / f"{name}.png")
            print(f"{name}: {out / name}.csv, {out / name}.png")
        return 0
    elif args.name in STUDIES:
        study = _run_one(args.name, args)
    else:
        raise InputError(f"study {args.name!r}: expected one of "
                         f"{', '.join(STUDIES)}, chatter or all")
    sys.stdout.write(study.table_text())
    if args.csv:
        _write_text(args.csv, study.csv_text())
    if args.png:
        from contactsep.studies.plots import save_png
        save_png(study, args.png)
    return 0


def run_sweep(args: argparse.Namespace) -> int:
    from contactsep.studies.runner import CsvWriter, ParquetWriter
    from contactsep.studies.runner import run_sweep as run
    from contactsep.studies.sweep import CHUNK_SIZE, make_spec

    spec = make_spec(vary=args.vary, sample=args.sample,
                     samples=args.samples, seed=args.seed,
                     base=_design_overrides(args), backend=args.backend)
    writers = []
    if args.csv:
        writers.append(CsvWriter(args.csv, spec))
    if args.parquet:
        writers.append(ParquetWriter(args.parquet))
    progress = {"auto": None, "always": True, "never": False}[args.progress]
    summary = run(spec, writers=writers, threshold=args.threshold,
                  chunk_size=args.chunk_size or CHUNK_SIZE,
                  workers=args.workers, scheduler=args.scheduler,
                  progress=progress)
    if args.json:
        clean = {k: (None if isinstance(v, float) and math.isnan(v) else v)
                 for k, v in summary.items()}
        json.dump(clean, sys.stdout, indent=2)
        sys.stdout.write("\n")
    else:
        for key, value in summary.items():
            print(f"{key:>12} = {value}")
    return 0
