"""How ``contactsep study`` runs its studies of three-beam simulations
(preload and conclusion3|5|6|7, conclusion4, buttons, contact-points and
materials): each one's own options refused where they do not apply, its
simulations on local workers or a Dask cluster, a progress bar on
stderr; the command itself and the studies of eq. 23: cli/studies.py.
"""

from __future__ import annotations

import contextlib

from contactsep.cli.cluster import given
from contactsep.cli.design_options import fields_from_file
from contactsep.errors import InputError

#: The studies of three-beam simulations, which --resume can keep.
RESUMABLE = ("preload", "conclusion3", "conclusion5", "conclusion6",
             "conclusion7", "contact-points", "materials", "buttons")


def conclusion4_study(args, overrides: dict):
    """study conclusion4: e_apparent of three contact laws."""
    from contactsep.studies.thesis import restitution
    overrides = dict(overrides)
    n_modes = overrides.pop("n_modes", restitution.MODES)
    if overrides or args.backend:
        raise InputError("study conclusion4 takes no design options but "
                         "--n-modes: it runs the thesis rig over its "
                         "separators and release heights")
    settings = {"alpha": args.alpha, "yield_pressure": args.yield_pressure,
                "reading_time": args.reading_time}
    settings = {k: v for k, v in settings.items() if v is not None}
    try:
        with study_bar(args, 3 * restitution.ROWS) as bar:
            return restitution.conclusion4(n_modes=n_modes, progress=bar,
                                           **settings)
    except ValueError as error:
        name, _, rest = str(error).partition(":")
        raise InputError(f"--{name.replace('_', '-')}:{rest}") from None


def buttons_study(args, overrides: dict, journal=None):
    """study buttons: open time and smallest preload against the
    button's shape and radius."""
    from contactsep.studies.thesis import buttons
    overrides = dict(overrides)
    n_modes = overrides.pop("n_modes", buttons.MODES)
    if overrides or args.backend or args.model:
        raise InputError("study buttons takes no design options but "
                         "--n-modes (and --workers): it runs the thesis "
                         "rig with each button")
    with study_bar(args, None) as bar:
        return buttons.buttons(n_modes=n_modes, workers=study_workers(args),
                               progress=bar, journal=journal)


def refuse_cluster(name: str, args) -> None:
    """A scheduler only for the studies of three-beam simulations."""
    if given(args) and name not in RESUMABLE:
        raise InputError(f"--scheduler and --scheduler-file are options of "
                         f"study {', '.join(RESUMABLE)}, not study "
                         f"{name}'s")


def study_workers(args):
    """What runs a study's simulations: the Dask client of --scheduler
    or --scheduler-file, else --workers (local processes)."""
    client = getattr(args, "cluster", None)
    return args.workers if client is None else client


def search_study(name: str, args, overrides: dict, journal=None):
    """study preload and conclusion3|5|6|7: three-beam simulations with
    the preload search; their own model, N (default 32) and workers."""
    from contactsep.studies.thesis.conclusions import conclusion
    from contactsep.studies.preload.chart import DEFAULT_MODES, preload_chart
    if args.backend:
        raise InputError(f"study {name} runs the chatter simulation (no "
                         f"--backend)")
    overrides = dict(overrides)
    options = {"model": args.model or "hertz",
               "n_modes": overrides.pop("n_modes", DEFAULT_MODES),
               "workers": study_workers(args), "journal": journal}
    from contactsep.studies.preload.search_checks import SearchError
    try:
        with study_bar(args, None) as bar:
            if name == "preload":
                extra = {} if args.alpha is None else {
                    "settings": {"alpha": args.alpha}}
                return preload_chart(**options,
                                     damping=args.damping or "none",
                                     converge=args.converge,
                                     progress=bar, **extra, **overrides)
            return conclusion(name, **options, progress=bar, **overrides)
    except SearchError as error:
        # the study names its arguments; the command, its options
        names, sep, rest = str(error).partition(":")
        if not sep:
            raise
        options = ", ".join("--" + n.strip().replace("_", "-")
                            for n in names.split(","))
        raise InputError(f"{options}:{rest}") from None


def recommendation_study(name: str, args, overrides: dict, journal=None):
    """study contact-points and materials (the thesis's recommendations
    3 and 4): three-beam simulations, Hertz contact; N and workers."""
    from contactsep.studies.thesis.recommendations import STUDIES as ADVICE
    if args.backend or args.model or args.damping:
        raise InputError(f"study {name} runs the chatter simulation with "
                         f"Hertz contact (no --backend, --model or "
                         f"--damping)")
    study, _, fixed = ADVICE[name]
    own = {k: v for k, v in overrides.items() if k not in fields_from_file(
        args) or k not in fixed}
    with study_bar(args, None) as bar:
        return study(workers=study_workers(args), progress=bar,
                     journal=journal, **own)


@contextlib.contextmanager
def study_bar(args, total):
    """A progress bar's update (or None) for a study of simulations:
    --progress auto (on a terminal), always, never; closed after."""
    from contactsep.runs.stops import progress_bar
    enabled = {"auto": None, "always": True,
               "never": False}[getattr(args, "progress", "auto")]
    bar = progress_bar(total, enabled)
    if bar is not None:
        bar.unit, bar.unit_scale = " simulations", False
    try:
        yield None if bar is None else bar.update
    finally:
        if bar is not None:
            bar.close()
