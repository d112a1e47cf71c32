"""Figures of the studies (the only module that imports matplotlib; the
``contactsep[plot]`` extra installs it)."""

from __future__ import annotations

import numpy as np

from contactsep.errors import InputError
from contactsep.studies.study import Study


def _pyplot():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise InputError("--png needs matplotlib: pip install "
                         "'contactsep[plot]'") from None
    return plt


def save_png(study: Study, path: str) -> None:
    """Draw the study as the thesis drew it and write a small PNG."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.0, 4.0), dpi=80)
    c = study.columns
    name = study.name
    if name == "fig5":
        for ys in np.unique(c["ys_in"]):
            rows = c["ys_in"] == ys
            ax.plot(c["d_in"][rows], c["y3_max_in"][rows],
                    label=f"y_s = {ys:g} in")
        ax.set(xlabel="separator thickness d (in)",
               ylabel="max lower-contact displacement y3 (in)")
    elif name == "fig6":
        for curve in ("I", "II"):
            rows = c["curve"] == curve
            ax.plot(c["r"][rows], c["y3_max_in"][rows], label=f"curve {curve}")
        ax.set(xlabel="x3/L3", ylabel="max y3 (in)")
    elif name == "fig7":
        for r in np.unique(c["r"]):
            rows = c["r"] == r
            ax.plot(c["t_s"][rows], c["y3_in"][rows], label=f"x/L = {r:g}")
        ax.set(xlabel="time after impact t (s)", ylabel="y3 (in)")
    elif name == "fig8":
        ax.semilogx(c["R"], c["y3_max_in"], "o", ms=3, label="eq. 23")
        ax.semilogx(c["R"], c["law_in"], label="1/(1 + 2R) law")
        ax.set(xlabel="mass ratio R (eq. 24)", ylabel="max y3 (in)")
    elif name == "fig23":
        ax.plot(c["d_in"], c["y3_max_in"], "o-", label="with L_c (Table III)")
        ax.plot(c["d_in"], c["y3_max_uncorrected_in"], "s--",
                label="without L_c")
        ax.set(xlabel="separator thickness d (in)", ylabel="max y3 (in)")
    elif name == "convergence":
        ax.loglog(c["N"], c["psi_lb_s"] / c["psi_lb_s"][0], "o-",
                  label="psi / psi(N=1)")
        ax.loglog(c["N"], c["y3_max_in"] / c["y3_max_in"][0], "s-",
                  label="max y3 / max y3(N=1)")
        ax.loglog(c["N"], c["v0_in_s"] / c["v0_in_s"][0], "^-",
                  label="v0 / v0(N=1)")
        ax.set(xlabel="modes N", ylabel="relative to N = 1")
    elif name.startswith("table"):
        x = np.arange(len(study))
        ax.plot(x, 100 * c["relative_difference"], "o")
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set(xlabel="row", ylabel="model / printed - 1 (%)")
    else:
        plt.close(fig)
        raise InputError(f"no figure for the study {name!r}")
    ax.set_title(study.title, fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def save_chatter_png(result, path, dpi: int = 100) -> None:
    """The two gaps against time, each on its own axis (the lower one,
    which decides opening, is small), the open circuit shaded; written
    to a temporary file beside ``path`` and renamed when finished."""
    import os
    import tempfile

    plt = _pyplot()
    fig, (upper, lower) = plt.subplots(
        2, 1, sharex=True, figsize=(7.0, 5.0), dpi=dpi,
        gridspec_kw={"height_ratios": (1, 1)})
    scale = 1e3
    upper.plot(result.t, result.gap_upper * scale, lw=0.7, color="C0")
    lower.plot(result.t, result.gap_lower * scale, lw=0.7, color="C1")
    for ax in (upper, lower):
        for start, end in result.circuit_open_intervals:
            ax.axvspan(start, end, color="red", alpha=0.12, lw=0)
        ax.axhline(result.open_threshold_in * scale, color="0.5", lw=0.6,
                   ls="--")
        ax.grid(True, lw=0.3)
    upper.set(ylabel="upper gap (0.001 in)",
              title=f"{result.model}, N = {result.n_modes}: circuit open "
                    f"{result.circuit_open_s * 1e3:.3g} ms (shaded), "
                    f"{result.n_events} events >= "
                    f"{result.min_open_s * 1e6:.3g} us")
    lower.set(xlabel="time from release (s)",
              ylabel="lower gap (0.001 in)")
    fig.tight_layout()
    directory = os.path.dirname(os.path.abspath(path))
    fd, temporary = tempfile.mkstemp(suffix=".png", dir=directory)
    try:
        with os.fdopen(fd, "wb") as out:
            fig.savefig(out, format="png")
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise
    finally:
        plt.close(fig)
