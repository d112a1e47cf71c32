"""A design report: one self-contained HTML page for one design
(``contactsep report``): its inputs with their units, one release's gaps
(with no preload, and at the answer), the preload answer with its
verdict and convergence table, the p_open curve under tolerances when
given, and the package version and command that made it.

The page has no scripts and no outside links: the figures are PNG
images inside it (``data:`` URIs), so it opens the same from a mail, a
disk or a web server.  It carries no date, so that the same command
gives the same bytes; the command line names what made it.
"""

from __future__ import annotations

import base64
import html
import io
import math

from contactsep.model.fields import (
    FIELDS,
    GROUPS,
    OPTIONAL,
    OUTPUT_NAMES,
    PHYSICS_GROUPS,
    SHOWN_WHEN_GIVEN,
)
from contactsep.model.names import shown, shown_key, shown_text
from contactsep.studies.plots import _pyplot, chatter_figure

#: The units the page names (in, lb, s, psi, lb/in^3; or SI).
_UNITS = ("in", "lb", "s", "psi", "lb_in3")
#: Samples of the release's gaps in the figures.
SAMPLES = 4001
#: The page's style: readable on a screen and printed, no outside fonts.
_STYLE = """
body { font-family: sans-serif; max-width: 60em; margin: 2em auto;
       padding: 0 1em; color: #222; line-height: 1.4; }
h1 { font-size: 1.6em; } h2 { font-size: 1.25em; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border-bottom: 1px solid #ccc; padding: 0.2em 0.8em;
         text-align: left; vertical-align: top; }
td.number { text-align: right; font-variant-numeric: tabular-nums; }
.verdict { font-size: 1.15em; padding: 0.6em 1em; border-left: 0.3em
           solid #2a7; background: #f3faf6; }
.verdict.unsettled { border-color: #c60; background: #fdf6ee; }
img { max-width: 100%; } code { font-size: 0.95em; }
footer { margin-top: 3em; font-size: 0.9em; color: #555; }
"""


def _e(value) -> str:
    return html.escape(str(value), quote=True)


def _number(value, digits: int = 5) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "none"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return str(value)


def _table(header, rows, numeric=()) -> str:
    """An HTML table; the columns named in ``numeric`` right-aligned."""
    head = "".join(f"<th>{_e(h)}</th>" for h in header)
    body = []
    for row in rows:
        cells = "".join(
            f'<td class="number">{_e(c)}</td>' if h in numeric
            else f"<td>{_e(c)}</td>" for h, c in zip(header, row))
        body.append(f"<tr>{cells}</tr>")
    return (f"<table><thead><tr>{head}</tr></thead><tbody>"
            + "".join(body) + "</tbody></table>")


def _png(fig, plt) -> str:
    """The figure as an <img> with its PNG inside the page."""
    buffer = io.BytesIO()
    try:
        fig.savefig(buffer, format="png", dpi=100)
    finally:
        plt.close(fig)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return f'<img alt="figure" src="data:image/png;base64,{data}">'


def input_rows(design) -> list:
    """(group, name, value, unit, meaning) of every field of ``design``
    an output shows (the beam-physics groups where one differs from the
    thesis's Bernoulli-Euler beams on rigid clamps); a field left to its
    default reads as the default (``x1``: its tip (L1))."""
    groups = list(GROUPS)
    groups += [(title, names) for title, names in PHYSICS_GROUPS
               if any(getattr(design, name, None) not in (
                   None, 0.0, "bernoulli-euler", 0.33) for name in names)]
    rows = []
    for title, names in groups:
        for name in names:
            value = getattr(design, name, None)
            if value is None and name in SHOWN_WHEN_GIVEN:
                continue
            suffix, unit, meaning = FIELDS[name]
            if value is None:
                value, unit = OPTIONAL.get(name, "none"), ""
            elif isinstance(value, tuple):
                value = ",".join(_number(shown(v, suffix)[0], 12)
                                 if suffix else str(v) for v in value)
                unit = shown(0.0, suffix)[1] if suffix else unit
            elif suffix:
                value, unit = shown(value, suffix)
            rows.append((title, OUTPUT_NAMES.get(name, name),
                         _number(value, 12), unit, meaning))
    return rows


def _inputs_table(rows) -> str:
    """The inputs, a heading row for each group."""
    body, group = [], None
    for title, name, value, unit, meaning in rows:
        if title != group:
            group = title
            body.append(f'<tr><th colspan="4">{_e(title)}</th></tr>')
        body.append(f"<tr><td>{_e(name)}</td><td class=\"number\">"
                    f"{_e(value)}</td><td>{_e(unit)}</td><td>"
                    f"{_e(meaning)}</td></tr>")
    return ("<table><thead><tr><th>name</th><th>value</th><th>unit</th>"
            "<th>meaning</th></tr></thead><tbody>" + "".join(body)
            + "</tbody></table>")


def _p_open_figure(robust):
    """p_open against preload with its 95 % Wilson band, the target and
    the answer marked."""
    from contactsep.studies.stats import wilson_interval
    plt = _pyplot()
    tested = [(shown(p, "lb")[0], n, k) for p, n, k, _ in robust.tested
              if n]
    force = shown(1.0, "lb")[1]
    fig, ax = plt.subplots(figsize=(7.0, 3.8))
    loads = [p for p, _, _ in tested]
    p_open = [k / n for _, n, k in tested]
    bands = [wilson_interval(k, n) for _, n, k in tested]
    ax.fill_between(loads, [b[0] for b in bands], [b[1] for b in bands],
                    color="C0", alpha=0.2, lw=0, label="95 % Wilson")
    ax.plot(loads, p_open, "o-", color="C0", ms=3, lw=0.8,
            label="p_open of the samples")
    ax.axhline(robust.p_target, color="C3", lw=0.8, ls="--",
               label=f"p_target {robust.p_target:g}")
    if math.isfinite(robust.min_preload_lb):
        ax.axvline(shown(robust.min_preload_lb, "lb")[0], color="0.3",
                   lw=0.8, ls=":", label=f"robust answer "
                   f"{shown_text(robust.min_preload_lb, 'lb', 4)}")
    ax.set(xlabel=f"preload ({force})", ylabel="p_open", ylim=(-0.02, 1.02))
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return plt, fig


def _verdict(answer) -> tuple[str, bool]:
    """The answer's verdict line (contactsep.studies.preload.verdict, without
    the measured rerun time: the page's bytes do not depend on the
    machine's speed) and whether it is settled."""
    text = answer.verdict.text
    return text, text.startswith("answer:") and "not checked" not in text


def _force(value, digits: int = 5) -> str:
    """A force (lb) as the page shows it, in the unit system shown."""
    return shown_text(value, "lb", digits)


def _preload_section(answer) -> list:
    parts = ["<h2>The preload that keeps the circuit closed</h2>"]
    force = shown(1.0, "lb")[1]
    rows = [("the answer to use", _force(answer_to_use(answer))),
            ("smallest preload at N = " + _number(answer.n_modes),
             _force(answer.min_preload_lb)),
            ("its change at twice the modes and half the step",
             "none" if answer.min_preload_change is None
             else f"{answer.min_preload_change:+.2%}"),
            ("step at no preload", f"{_number(answer.dt_s)} s"),
            ("largest preload the simulation takes",
             _force(answer.ceiling_lb)),
            ("longest opening at the answer",
             f"{_number(answer.longest_open_at_answer_s)} s"),
            ("simulations", str(answer.simulations))]
    parts.append(_table(("quantity", "value"), rows))
    if answer.converge_history:
        parts.append("<p>Convergence: the answer of each search, "
                     "coarsest first.</p>")
        parts.append(_table(
            ("N", f"answer ({force})"),
            [(n, _number(shown(p, "lb")[0]))
             for n, p in answer.converge_history],
            numeric=("N", f"answer ({force})")))
    windows = [(f"{_number(shown(a, 'lb')[0])}-"
                f"{_number(shown(b, 'lb')[0])}",)
               for a, b in answer.event_windows]
    if windows:
        parts.append(f"<p>Preloads with an event (runs of tested "
                     f"preloads, {force}):</p>")
        parts.append(_table((f"event window ({force})",), windows))
    parts.append("<details><summary>Every preload simulated</summary>"
                 + _table((f"preload ({force})", "event"),
                          [(_number(shown(p, "lb")[0], 6),
                            "yes" if e else "no")
                           for p, e in answer.tested],
                          numeric=(f"preload ({force})",)) + "</details>")
    return parts


def _robust_section(robust) -> list:
    ci = robust.p_open_ci95
    rows = [("robust answer", _force(robust.min_preload_lb)),
            ("p_open there", f"{_number(robust.p_open)} ({robust.n_open} "
                             f"of {robust.n} open, {robust.n_failed} "
                             f"failed)"),
            ("95 % Wilson interval", "-" if ci is None else
             f"{ci[0]:.3g} - {ci[1]:.3g}"),
            ("p_target", f"{robust.p_target:g}"),
            ("samples, seed", f"{robust.samples}, {robust.seed}")]
    tolerances = []
    for name, kind, a, b in robust.tolerances:
        suffix = FIELDS[name][0] if name in FIELDS else ""
        unit = shown(0.0, suffix)[1] if suffix else ""
        a, b = ((shown(a, suffix)[0], shown(b, suffix)[0]) if suffix
                else (a, b))
        tolerances.append((shown_key(f"{OUTPUT_NAMES.get(name, name)}_"
                                     f"{suffix}") if suffix else name,
                           kind, _number(a), _number(b), unit))
    parts = ["<h2>Under tolerances: the robust preload</h2>",
             _table(("field", "distribution", "a", "b", "unit"),
                    tolerances)]
    if not robust.shown:    # no preload tried: no curve to draw
        return parts + [f"<p>Not searched: {robust.samples} samples cannot "
                        f"show p_open &lt;= {robust.p_target:g} on its 95 % "
                        f"upper bound; it needs {robust.samples_needed} or "
                        f"more (--samples).</p>"]
    plt, fig = _p_open_figure(robust)
    return parts + [_table(("quantity", "value"), rows), _png(fig, plt)]


def html_report(design, answer, releases, *, command: str,
                version: str) -> str:
    """The page (a str) for ``design``: ``answer`` its
    :class:`~contactsep.studies.preload.answer.PreloadAnswer`,
    ``releases`` ((title, ChatterResult), ...) the runs whose gaps it
    shows, ``command`` and ``version`` what made it."""
    verdict, settled = _verdict(answer)
    parts = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset='
             '"utf-8">', "<title>contactsep design report</title>",
             f"<style>{_STYLE}</style></head><body>",
             "<h1>Design report</h1>",
             f'<p class="verdict{"" if settled else " unsettled"}">'
             f"{_e(verdict)}</p>",
             f"<p>Model {_e(answer.model)}; units: "
             f"{_e(', '.join(shown(1.0, s)[1] for s in _UNITS))}.</p>",
             "<h2>Inputs</h2>",
             _inputs_table(input_rows(design))]
    for title, result in releases:
        plt, fig = chatter_figure(result)
        parts += [f"<h2>{_e(title)}</h2>", _png(fig, plt)]
    parts += _preload_section(answer)
    if answer.robust is not None:
        parts += _robust_section(answer.robust)
    if answer.notes:
        parts.append("<h2>Notes</h2><ul>" + "".join(
            f"<li>{_e(note)}</li>" for note in answer.notes) + "</ul>")
    parts.append(f"<footer>contactsep {_e(version)}; made by "
                 f"<code>{_e(command)}</code></footer></body></html>")
    return "\n".join(parts) + "\n"


def answer_to_use(answer) -> float:
    """The preload a designer takes from ``answer`` (lb): the converged
    one where a check ran (its N may be above the design's), else the
    answer at the design's N."""
    if answer.converged is not None and \
            answer.converged_min_preload_lb is not None:
        return answer.converged_min_preload_lb
    return answer.min_preload_lb


def releases(design, answer, model: str, settings: dict) -> list:
    """The runs a report shows, at the design's N: the release with no
    preload, and at the answer to use where it is a finite preload
    above 0."""
    from contactsep.chatter import simulate
    runs = [(0.0, "One release, no preload")]
    load = answer_to_use(answer)
    if math.isfinite(load) and load > 0:
        runs.append((load, f"The release at the answer, "
                           f"{shown_text(load, 'lb', 4)}"))
    return [(title, simulate(design, model=model, preload=load,
                             samples=SAMPLES, single_impulse=False,
                             **settings)) for load, title in runs]
