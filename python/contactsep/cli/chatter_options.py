"""The options of ``contactsep chatter`` (:mod:`contactsep.cli.chatter`),
group by group, in the order ``--help`` lists them."""

from __future__ import annotations

from contactsep.cli.values import finite, integer


def event_count(text: str):
    """--events: 'all' (None) or a count >= 0."""
    if text.strip() == "all":
        return None
    return integer(0, 10**9)(text)


def add_law_options(run_group) -> None:
    """The model and its contact law, in the "simulation" group."""
    run_group.add_argument("--model", choices=("appE", "newton", "hertz"),
                           default="hertz", help="default hertz")
    run_group.add_argument("--damping",
                           choices=("none", "flores", "hunt-crossley"),
                           default=None,
                           help="Hertz damping (default: flores where e is "
                                "given, none otherwise; none: elastic, e "
                                "unused; flores: calibrated to --e; "
                                "hunt-crossley: the material constant "
                                "--alpha)")
    run_group.add_argument("--alpha", type=finite("s/in"), default=None,
                           metavar="S_PER_IN",
                           help="Hunt-Crossley's constant (s/in): F = k "
                                "delta^1.5 (1 + alpha delta'), never "
                                "calibrated to the design")
    run_group.add_argument("--contact", choices=("hertz", "thornton"),
                           default="hertz",
                           help="the law's elastic part: hertz (default) "
                                "or thornton (elastic-perfectly-plastic; "
                                "with --yield-pressure)")
    run_group.add_argument("--yield-pressure", type=finite("psi"),
                           default=None, metavar="PSI",
                           help="Thornton's yield pressure (psi)")


def add_run_options(run_group) -> None:
    """The step, the window, the preload and the circuit's thresholds."""
    from contactsep.chatter import circuit

    run_group.add_argument(
        "--dt", type=finite("s"), default=None, metavar="S",
        help="time step (s; default: the design's own, from its stiffest "
             "contact and highest mode, halved until the energy check "
             "passes; docs/chatter.md)")
    run_group.add_argument("--t-end", type=finite("s"), default=None,
                           metavar="S", help="window from the release (s; "
                           "default: the first impact and "
                           "several periods of the slowest member's first "
                           "mode)")
    run_group.add_argument("--verify", action="store_true",
                           help="rerun at half the step and twice the "
                                "modes and report the relative change of "
                                "each headline quantity (*_change)")
    run_group.add_argument("--preload", type=finite("lb"), default=0.0,
                           metavar="LB",
                           help="force pressing the lower contact against "
                                "the separator at the start (lb; default 0)")
    run_group.add_argument("--open-threshold", type=finite("in"),
                           default=circuit.OPEN_THRESHOLD, metavar="IN",
                           help="gap above which a contact is open (in; "
                                f"default {circuit.OPEN_THRESHOLD:g})")
    run_group.add_argument("--min-open", type=finite("s"),
                           default=circuit.MIN_OPEN, metavar="S",
                           help="shortest circuit opening that counts as a "
                                "discontinuity event (s; default "
                                f"{circuit.MIN_OPEN:g}; 0: every opening)")
    run_group.add_argument("--stepper", choices=("adaptive", "fixed"),
                           default="adaptive",
                           help="adaptive (default) or the fixed-step "
                                "reference (Moreau-Jean, Hertz splitting)")
    run_group.add_argument("--static-correction", choices=("on", "off"),
                           default="on",
                           help="hertz: the truncated modes' residual "
                                "flexibility in series with each contact "
                                "(default on; off: the plain N-mode "
                                "truncation; docs/static-correction.md)")


def add_button_options(run_group) -> None:
    """The contact button and its Hertz constant."""
    from contactsep.chatter.simulate import (
        DEFAULT_BUTTON_RADIUS,
        DEFAULT_NU,
    )

    run_group.add_argument("--nu", type=finite(), default=DEFAULT_NU,
                           help="Poisson's ratio of the Hertz constant "
                                f"(default {DEFAULT_NU:g})")
    run_group.add_argument("--button-radius", type=finite("in"),
                           default=DEFAULT_BUTTON_RADIUS, metavar="IN",
                           help="contact button radius of the Hertz "
                                f"constant (in; default "
                                f"{DEFAULT_BUTTON_RADIUS:g})")
    run_group.add_argument("--button", choices=("sphere", "cylinder"),
                           default="sphere",
                           help="contact button: sphere on a flat (Hertz, "
                                "default) or cylinder across it (line "
                                "contact, force proportional to the "
                                "penetration; docs/chatter.md)")
    run_group.add_argument("--button-length", type=finite("in"),
                           default=None, metavar="IN",
                           help="cylinder button's length (in; default "
                                "its diameter)")


def add_output_options(parser) -> None:
    """The "output" group: progress, events, JSON, CSV and PNG."""
    out_group = parser.add_argument_group("output")
    out_group.add_argument("--progress", choices=("auto", "always",
                                                  "never"), default="auto",
                           help="the elapsed time of a long run on stderr: "
                                "auto (on a terminal, after a second), "
                                "always, never")
    out_group.add_argument("--events", type=event_count, default=10,
                           metavar="N|all",
                           help="circuit openings listed after the "
                                "summary (default 10; all: every one; "
                                "--csv and --json have them all)")
    out_group.add_argument("--json", action="store_true",
                           help="print the inputs and the summary as JSON")
    out_group.add_argument("--csv", metavar="FILE",
                           help="write the gap histories: t_s, "
                                "gap_upper_in, gap_lower_in, circuit_open")
    out_group.add_argument("--png", metavar="FILE",
                           help="plot both gaps, each on its own axis, "
                                "the open circuit shaded")
    out_group.add_argument("--dpi", type=integer(10, 1200), default=100,
                           help="resolution of --png (default 100)")
