"""What each study's figure shows, panel by panel: the thesis's one-panel
figures (Figures 5-8 and 23, the convergence study, the preload chart),
the tables' two panels, the conclusion studies' and the chatter study's
panels.  Each draws on axes :mod:`contactsep.studies.plots` made (it
alone imports matplotlib) from the study's columns.
"""

from __future__ import annotations

import textwrap

import numpy as np


def _fig5(ax, c):
    for ys in np.unique(c["ys_in"]):
        rows = c["ys_in"] == ys
        ax.plot(c["d_in"][rows], c["y3_max_in"][rows],
                label=f"y_s = {ys:g} in")
    ax.set_ylim(bottom=0.0)
    ax.set(xlabel="separator thickness d (in)",
           ylabel="max lower-contact displacement y3 (in)")


def _fig6(ax, c):
    length = c["L3_in"][c["curve"] == "I"][0]
    labels = {"I": f"I: L3 = {length:g} in, contact at x3 = r L3",
              "II": f"II: contact at x3 = {length:g} in, L3 = x3/r"}
    for curve in ("I", "II"):
        rows = c["curve"] == curve
        ax.plot(c["r"][rows], c["y3_max_in"][rows], label=labels[curve])
    ax.set(xlabel="contact point ratio r = x3/L3", ylabel="max y3 (in)")


def _fig7(ax, c):
    for r in np.unique(c["r"]):
        rows = c["r"] == r
        ax.plot(c["t_s"][rows], c["y3_in"][rows], label=f"x/L = {r:g}")
    ax.set(xlabel="time after impact t (s)", ylabel="y3 (in)")


def _fig8(ax, c):
    ax.semilogx(c["R"], c["y3_max_in"], "o", ms=3, label="eq. 23")
    ax.semilogx(c["R"], c["law_in"], label="1/(1 + 2R) law")
    ax.set(xlabel="mass ratio R (eq. 24)", ylabel="max y3 (in)")


def _fig23(ax, c):
    ax.plot(c["d_in"], c["y3_max_in"], "o-", label="with L_c (Table III)")
    ax.plot(c["d_in"], c["y3_max_uncorrected_in"], "s--",
            label="without L_c")
    ax.set_ylim(bottom=0.0)
    ax.set(xlabel="separator thickness d (in)", ylabel="max y3 (in)")


def _preload(ax, c):
    # a row without an answer (an event up to the simulation's preload
    # limit): a triangle at the top edge, in its curve's colour
    edge = ax.get_xaxis_transform()
    for ys in np.unique(c["ys_in"]):
        rows = c["ys_in"] == ys
        line, = ax.semilogy(c["d_in"][rows], c["min_preload_lb"][rows],
                            "o-", label=f"y_s = {ys:g} in")
        missing = rows & np.isnan(c["min_preload_lb"])
        if np.any(missing):
            ax.plot(c["d_in"][missing], np.full(missing.sum(), 0.97), "^",
                    color=line.get_color(), transform=edge, clip_on=False,
                    label=f"y_s = {ys:g} in: none below the preload limit")
    # a converged chart (study preload --converge): the rows found again
    # at a higher N ringed, and the N range in the label
    n_low, n_high = int(np.min(c["n_modes"])), int(np.max(c["n_modes"]))
    finer = c["n_modes"] > n_low
    if np.any(finer):
        ax.plot(c["d_in"][finer], c["min_preload_lb"][finer], "s", ms=10,
                mfc="none", color="k", label=f"searched again at N = "
                f"{n_high} (moved > 2 % from N = {n_low})")
    label = f"{c['model'][0]}, N = {n_low}" + (
        f"-{n_high}" if n_high > n_low else "")
    if "converged" in c:
        label += ": each row within 2 % at 2N" if np.all(
            c["converged"][~np.isnan(c["min_preload_lb"])] == 1) else \
            ": checked at 2N"
    ax.set(xlabel="separator thickness d (in)",
           ylabel="smallest preload with no event (lb)")
    ax.text(0.98, 0.95, label, transform=ax.transAxes, fontsize=8,
            ha="right", va="top")


def _convergence(ax, c):
    ax.loglog(c["N"], c["psi_lb_s"] / c["psi_lb_s"][0], "o-",
              label="psi / psi(N=1)")
    ax.loglog(c["N"], c["y3_max_in"] / c["y3_max_in"][0], "s-",
              label="max y3 / max y3(N=1)")
    ax.loglog(c["N"], c["v0_in_s"] / c["v0_in_s"][0], "^-",
              label="v0 / v0(N=1)")
    ax.set(xlabel="modes N", ylabel="relative to N = 1")


#: The tables: x column and label, the value curves (column, label,
#: style), the value axis label, whether it is logarithmic.
TABLES = {
    "table1": ("mode", "mode number", (
        ("model_cps", "model (eq. 23 beam)", "o-"),
        ("printed_theoretical_cps", "printed theory", "s--"),
        ("experimental_upper_cps", "experiment, upper contact", "^:"),
        ("experimental_lower_cps", "experiment, lower contact", "v:")),
        "frequency (cps)", True),
    "table2": ("d_in", "separator thickness d (in)", (
        ("model_cps", "model (eq. 23 beam)", "o-"),
        ("printed_theoretical_cps", "printed theory", "s--"),
        ("experimental_cps", "experiment", "^:")),
        "first frequency (cps)", False),
    "table3": ("d_in", "separator thickness d (in)", (
        ("printed_Lc_in", "printed L_c", "s--"),
        ("Lc_formula_in", "sqrt(1.3e6 d/p), printed p", "o-"),
        ("Lc_model_in", "model separator at the printed p", "^:")),
        "equivalent length L_c (in)", False),
}


def draw_table(axes, c, name):
    x_name, x_label, curves, y_label, log = TABLES[name]
    top, bottom = axes
    x = c[x_name]
    for column, label, style in curves:
        top.plot(x, c[column], style, label=label)
    if log:
        top.set_yscale("log")
    top.set(ylabel=y_label)
    residual = 100 * np.asarray(c["relative_difference"], dtype=float)
    bottom.plot(x, residual, "o-")
    # the zero line only where the residuals reach it: drawn always, it
    # stretched the axis to 0 and left Table I's 3.2-3.7 % points
    # between two ticks (0 and 2)
    low, high = np.nanmin(residual), np.nanmax(residual)
    if low <= 0.0 <= high:
        bottom.axhline(0.0, color="0.6", lw=0.8)
    else:
        pad = max(0.2 * (high - low), 0.02 * max(abs(low), abs(high)))
        bottom.set_ylim(low - pad, high + pad)
    which = "formula" if name == "table3" else "model"
    bottom.set(xlabel=x_label, ylabel=f"{which} / printed - 1 (%)")
    if name == "table1":
        bottom.set_xticks(x)


#: The chatter study's figure (in): a column per model, 9 x 5.4 in.
CHATTER_FIGSIZE = (9.0, 5.4)
#: The chatter study's models, as a reader knows them (docs/chatter.md).
CHATTER_MODEL_LABELS = {
    "appE": "Appendix E (rigid separator)",
    "newton": "three beams, Newton's law (restitution e)",
    "hertz": "three beams, Hertz contact",
}


def chatter_study_figure(plt, c):
    """One column per model (its nine curves no longer overlap): circuit
    open time above, the largest lower gap below, N told apart by marker
    and line style, one legend for the figure."""
    models = list(dict.fromkeys(c["model"]))
    fig, axes = plt.subplots(2, len(models), sharex=True, sharey="row",
                             figsize=CHATTER_FIGSIZE,
                             squeeze=False)
    styles = ("o-", "s--", "^:")
    n_values = np.unique(c["N"])
    for column, model in enumerate(models):
        top, bottom = axes[0, column], axes[1, column]
        for style, n in zip(styles, n_values):
            rows = (c["model"] == model) & (c["N"] == n)
            top.plot(c["d_in"][rows], 1e3 * c["circuit_open_s"][rows],
                     style, color="k", ms=3.5, lw=1.0, label=f"N = {n}")
            bottom.plot(c["d_in"][rows], c["max_lower_gap_in"][rows],
                        style, color="k", ms=3.5, lw=1.0)
        top.set_title("\n".join(textwrap.wrap(
            CHATTER_MODEL_LABELS.get(model, model), 26)), fontsize=9)
        if model == "appE":
            top.text(0.5, 0.5, "the lower contact never moves:\n"
                     "the circuit never opens", transform=top.transAxes,
                     ha="center", va="center", fontsize=7, color="0.3")
        bottom.set(xlabel="separator thickness d (in)")
        for ax in (top, bottom):
            ax.grid(True, lw=0.3)
    axes[0, 0].set(ylabel="circuit open (ms)")
    axes[0, 0].set_ylim(bottom=0.0)
    axes[1, 0].set(ylabel="max lower gap (in)")
    axes[1, 0].set_ylim(bottom=0.0)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels),
               fontsize=8, frameon=False)
    return fig, axes


#: The conclusion studies' x axis: column and label.
CONCLUSION_AXES = {
    "conclusion3": ("e", "coefficient of restitution e"),
    "conclusion5": ("d_in", "separator thickness d (in)"),
    "conclusion6": ("R", "mass ratio R (eq. 24), through gamma2"),
    "conclusion7": ("r", "lower contact point x3/L3"),
}


def draw_conclusion(axes, c, name):
    top, bottom = axes
    column, label = CONCLUSION_AXES[name]
    x = c[column]
    top.semilogy(x, c["y3_max_in"], "s--", label="eq. 23 max y3 (thesis)")
    top.semilogy(x, c["max_lower_gap_in"], "o-",
                 label="three beams: max lower gap, no preload")
    top.set(ylabel="lower contact (in)")
    preloads = c["min_preload_lb"]
    bottom.plot(x, preloads, "o-", color="C2",
                label="smallest preload with no event")
    if np.nanmax(preloads) > 10 * np.nanmin(preloads) > 0:
        bottom.set_yscale("log")
    else:
        bottom.set_ylim(bottom=0.0)
    bottom.set(xlabel=label, ylabel="preload (lb)")
    if name == "conclusion6":
        top.set_xscale("log")


def draw_conclusion8(axes, c, node):
    top, bottom = axes
    top.plot(c["r"], c["first_mode_share"], "o-", ms=3,
             label="first mode's share of y3's mean square")
    top.set(ylabel="first-mode share", ylim=(0.0, 1.05))
    bottom.step(c["r"], c["n_maxima"], where="mid", color="C1",
                label="swings (maxima) in the first period")
    bottom.set(xlabel="contact point x3/L3", ylabel="maxima",
               ylim=(0, max(2, int(np.max(c["n_maxima"]))) + 1))
    for ax in axes:
        ax.axvline(node, color="0.4", lw=0.8, ls=":",
                   label=f"second mode's node, {node:.4f}")


ONE_PANEL = {"fig5": _fig5, "fig6": _fig6, "fig7": _fig7, "fig8": _fig8,
              "fig23": _fig23, "convergence": _convergence,
              "preload": _preload}
