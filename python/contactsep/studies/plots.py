"""Figures of the studies (the only module that imports matplotlib; the
``contactsep[plot]`` extra installs it).

``save_png(study, path, dpi=100)`` draws a study as the thesis drew it: a
figure 6 in wide (4 in tall; the tables, two panels, 5 in; the chatter
study, a column per model, 9 x 5.4 in), written to a
temporary file beside ``path`` and renamed into place when finished.
What each panel shows: :mod:`contactsep.studies.plot_panels`.
"""

from __future__ import annotations

import os
import stat
import sys
import tempfile
import textwrap

from contactsep import output
from contactsep.errors import InputError
from contactsep.model.names import shown
from contactsep.studies.plot_panels import (
    CONCLUSION_AXES,
    ONE_PANEL,
    TABLES,
    chatter_study_figure,
    draw_conclusion,
    draw_conclusion8,
    draw_table,
)
from contactsep.studies.study import Study

#: Default resolution (dots per inch): a 6 x 4 in figure is 600 x 400.
DPI = 100


def _writable_config() -> None:
    """Matplotlib keeps its configuration and font cache in
    $XDG_CONFIG_HOME/matplotlib and $XDG_CACHE_HOME/matplotlib (~/.config,
    ~/.cache); where it cannot create them (an unwritable or missing
    HOME) it prints two warning lines and rebuilds the font cache in a
    new temporary directory every run.  Point it (MPLCONFIGDIR, unless
    set) at a private directory of this user's under the temporary
    directory instead: quiet, and the cache is built once."""
    if "MPLCONFIGDIR" in os.environ or "matplotlib" in sys.modules:
        return
    home = os.path.expanduser("~")
    for variable, default in (("XDG_CONFIG_HOME", ".config"),
                              ("XDG_CACHE_HOME", ".cache")):
        base = os.environ.get(variable) or os.path.join(home, default)
        path = os.path.join(base, "matplotlib")
        try:
            os.makedirs(path, exist_ok=True)
            writable = os.access(path, os.W_OK | os.X_OK)
        except OSError:
            writable = False
        if not writable:
            break
    else:
        return
    private = os.path.join(tempfile.gettempdir(),
                           f"contactsep-matplotlib-{os.getuid()}")
    try:
        os.mkdir(private, 0o700)
    except FileExistsError:
        pass
    except OSError:
        private = None
    if private is not None:
        info = os.lstat(private)
        # another user's directory, or a link planted there: not ours
        if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid():
            private = None
    os.environ["MPLCONFIGDIR"] = private or tempfile.mkdtemp(
        prefix="contactsep-matplotlib-")


def _pyplot():
    _writable_config()
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise InputError("--png needs matplotlib: pip install "
                         "'contactsep[plot]'") from None
    return plt


def require_matplotlib() -> None:
    """Raise the InputError a figure would, before any work is done."""
    _pyplot()


def _recommendations() -> dict:
    from contactsep.studies.thesis.recommendations import STUDIES
    return STUDIES


def save_png(study: Study, path, dpi: int = DPI) -> None:
    """Draw the study as the thesis drew it and write a PNG (module
    docstring)."""
    plt = _pyplot()
    name = study.name
    if name in ONE_PANEL:
        fig, ax = plt.subplots(figsize=(6.0, 4.0))
        ONE_PANEL[name](ax, study.columns)
        axes = [ax]
    elif name == "chatter":
        fig, grid = chatter_study_figure(plt, study.columns)
        fig.suptitle("\n".join(textwrap.wrap(study.title, 80)), fontsize=9)
        fig.tight_layout(rect=(0.0, 0.05, 1.0, 1.0))
        _write(plt, fig, path, dpi)
        return
    elif name in _recommendations():
        # the thesis's recommendations 3 and 4: two maps (their modules)
        fig, axes = plt.subplots(2, 1, figsize=(6.0, 7.0))
        _recommendations()[name][1](axes, study)
        axes[0].set_title("\n".join(textwrap.wrap(study.title, 64)),
                          fontsize=9)
        fig.tight_layout()
        _write(plt, fig, path, dpi)
        return
    elif name == "buttons":
        from contactsep.studies.thesis.buttons import draw
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(6.0, 5.0))
        draw(axes, study)
    elif name == "conclusion4":
        from contactsep.studies.thesis.restitution import draw
        fig, axes = plt.subplots(1, 2, sharey=True, figsize=(8.0, 4.0))
        draw(axes, study)
    elif name == "separator-fit":
        from contactsep.studies.thesis.separator_fit import draw
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(6.0, 7.0))
        draw(axes, study)
    elif name in TABLES or name in CONCLUSION_AXES or \
            name == "conclusion8":
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(6.0, 5.0),
                                 height_ratios=(2, 1) if name in TABLES
                                 else (1, 1))
        if name == "conclusion8":
            # the study's first note: "...'s node ...: x3/L3 = 0.783445"
            draw_conclusion8(axes, study.columns,
                         float(study.notes[0].rsplit("=", 1)[1]))
        elif name in CONCLUSION_AXES:
            draw_conclusion(axes, study.columns, name)
        else:
            draw_table(axes, study.columns, name)
    else:
        raise InputError(f"no figure for the study {name!r}")
    axes[0].set_title("\n".join(textwrap.wrap(study.title, 64)),
                      fontsize=9)
    for ax in axes:
        if ax.get_legend() is None and ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
        ax.grid(True, lw=0.3)
    fig.tight_layout()
    _write(plt, fig, path, dpi)


def _write(plt, fig, path, dpi: int) -> None:
    try:
        with output.open_output(path, binary=True) as out:
            fig.savefig(out, format="png", dpi=dpi)
    finally:
        plt.close(fig)


def chatter_figure(result, dpi: int = 100):
    """The two gaps against time, each on its own axis (the lower one,
    which decides opening, is small), the open circuit shaded: (pyplot,
    figure); the caller closes the figure."""
    plt = _pyplot()
    fig, (upper, lower) = plt.subplots(
        2, 1, sharex=True, figsize=(7.0, 5.0), dpi=dpi,
        gridspec_kw={"height_ratios": (1, 1)})
    # gaps in thousandths of an inch, or in micrometres where SI is shown
    si = shown(1.0, "in")[1] == "m"
    scale, unit = (shown(1e6, "in")[0], "µm") if si else (1e3, "0.001 in")
    upper.plot(result.t, result.gap_upper * scale, lw=0.7, color="C0")
    lower.plot(result.t, result.gap_lower * scale, lw=0.7, color="C1")
    for ax in (upper, lower):
        for start, end in result.circuit_open_intervals:
            ax.axvspan(start, end, color="red", alpha=0.12, lw=0)
        ax.axhline(result.open_threshold_in * scale, color="0.5", lw=0.6,
                   ls="--")
        ax.grid(True, lw=0.3)
    upper.set(ylabel=f"upper gap ({unit})",
              title=f"{result.model}, N = {result.n_modes}: circuit open "
                    f"{result.circuit_open_s * 1e3:.3g} ms (shaded), "
                    f"{result.n_events} events >= "
                    f"{result.min_open_s * 1e6:.3g} us")
    lower.set(xlabel="time from release (s)",
              ylabel=f"lower gap ({unit})")
    fig.tight_layout()
    return plt, fig


def save_chatter_png(result, path, dpi: int = 100) -> None:
    """:func:`chatter_figure` written to a temporary file beside
    ``path`` and renamed when finished (a device written in place:
    :func:`contactsep.output.open_output`)."""
    plt, fig = chatter_figure(result, dpi)
    try:
        with output.open_output(path, binary=True) as out:
            fig.savefig(out, format="png")
    finally:
        plt.close(fig)
