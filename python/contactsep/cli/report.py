"""``contactsep report``: one self-contained HTML page for a design: its
inputs, one release's gaps, the preload answer with its verdict and
convergence, the p_open curve under tolerances
(contactsep.studies.report)."""

from __future__ import annotations

import argparse
import shlex

from contactsep import output
from contactsep.cli.design_options import (
    add_design_options,
    damping_law,
    design_overrides,
)
from contactsep.cli.help import examples
from contactsep.cli.preload import (
    add_robust_options,
    parse_p_target,
    tolerances_in_units,
)
from contactsep.cli.values import integer


def register(commands: argparse._SubParsersAction) -> None:
    """Add ``contactsep report``."""
    from contactsep.studies.preload.chart import DEFAULT_MODES
    from contactsep.runs.pool import WORKERS_PER_CORE, max_workers

    parser = commands.add_parser(
        "report", help="a design report: one HTML page",
        description="Run the preload search of `contactsep preload` on "
                    "the design (and the robust search with --tolerance) "
                    "and write one self-contained HTML page: the inputs "
                    "with their units, the gaps of one release with no "
                    "preload and at the answer, the answer's verdict and "
                    "convergence table, the p_open curve under the "
                    "tolerances, the package version and this command. "
                    f"N defaults to {DEFAULT_MODES} modes per member "
                    "(--n-modes). Needs matplotlib "
                    "(pip install 'contactsep[plot]').",
        **examples("contactsep report --design my.json -o my-relay.html",
                   "contactsep report --design my.json --tolerance "
                   "'h2=normal(0.05,0.001)' --samples 100 -o my-relay.html"))
    parser.add_argument("-o", "--output", metavar="FILE", required=True,
                        help="the page (HTML); replaced only when "
                             "finished")
    add_robust_options(parser)
    parser.add_argument("--workers", type=integer(1, max_workers()),
                        default=None,
                        help=f"local processes (default: the usable "
                             f"cores; at most {WORKERS_PER_CORE} a core)")
    add_design_options(parser)
    parser.set_defaults(handler=run)


def run(args: argparse.Namespace) -> int:
    """The page, in the unit system of --units."""
    from contactsep.model.names import units_shown
    with units_shown(args.units):
        return _run(args)


def _run(args: argparse.Namespace) -> int:
    from contactsep import __version__
    from contactsep.model import thesis_design
    from contactsep.studies.preload.command import preload
    from contactsep.studies.plots import require_matplotlib
    from contactsep.studies.preload.chart import DEFAULT_MODES
    from contactsep.studies.report import html_report, releases

    require_matplotlib()            # before any simulation
    p_target = parse_p_target(args.p_target)
    overrides = design_overrides(args)
    args.tolerance = tolerances_in_units(args)
    overrides.setdefault("n_modes", DEFAULT_MODES)
    design = thesis_design(**overrides)
    output.check_targets({"-o": args.output},
                         {"--design": args.design} if args.design else {})
    # as `contactsep preload` runs it: a given e, Flores's law
    law = damping_law(args, overrides, "hertz")
    answer = preload(design, tolerance=args.tolerance, p_target=p_target,
                     samples=args.samples, seed=args.seed,
                     workers=args.workers,
                     **({"damping": law} if law else {}))
    runs = releases(design, answer, answer.model, dict(answer.settings))
    command = shlex.join(["contactsep", *args.argv])
    page = html_report(design, answer, runs, command=command,
                       version=__version__)
    with output.open_output(args.output) as out:
        output.write_text(out, page)
    return 0
