"""The tasks of the preload searches: one simulation of a design, or of
one sample of a design's tolerances, at one preload.

A batch of them runs on worker processes or a Dask cluster
(:class:`contactsep.studies.preload.chart.Simulations`), handed out the
costliest first, so that it ends with short runs on every worker rather
than one long run while the others wait.  Their cost is their preload: a
run with none is the cheapest, and while the preload keeps the lower
contact pressed every step is a fixed step of the splitting, so the
larger the preload, the more of the window runs at fixed steps (the
thesis rig at N = 16: 1.3 times a free run's time at 0.1 lb, 41 times
at 20 lb, pressed most of the window; docs/performance.md).

A run is named in a resume journal
(:func:`contactsep.runs.task_keys.task_key`) by
:meth:`PreloadRun.key_tuple`, the tuple the searches handed to the
workers before their tasks had names, so that a journal kept by an
earlier version is still answered from.
"""

from __future__ import annotations

from dataclasses import dataclass

from contactsep.studies.study import StudyRun


@dataclass(frozen=True)
class PreloadRun(StudyRun):
    """One simulation of ``design`` by ``model`` at ``preload_lb``.

    Its cost, the batch's order, is its preload; it is named in a
    journal by ``(design, model, settings, preload_lb)``, its fields in
    order (:class:`~contactsep.studies.study.StudyRun`).

    Parameters
    ----------
    design : Design
        The design simulated.
    model : {"hertz", "newton"}
        The three-beam model (:func:`contactsep.chatter.simulate`).
    settings : dict
        Further keywords of ``simulate()`` (dt, t_end, damping, ...),
        the preload not among them.
    preload_lb : float
        The lower contact's preload (lb).
    """

    design: object
    model: str
    settings: dict
    preload_lb: float


@dataclass(frozen=True)
class SampleRun(PreloadRun):
    """One simulation of a sample of a design's tolerances (the robust
    search, :mod:`contactsep.studies.preload.robust`): ``design`` the
    sample's design fields (a dict), ``settings`` its own ``simulate()``
    keywords, the preload not among them.
    """

    @property
    def sample_settings(self) -> dict:
        """The sample's settings with the preload, as
        :func:`contactsep.studies.sweep.chatter.simulate_design` takes
        them."""
        return {**self.settings, "preload": self.preload_lb}

    def key_tuple(self) -> tuple:
        """``(fields, model, settings with the preload)``: what names
        the run in a journal."""
        return (self.design, self.model, self.sample_settings)


def run_row(search, task: PreloadRun, event) -> tuple:
    """One simulation of a search as a row of the preload CSV
    (:meth:`contactsep.studies.preload.answer.PreloadAnswer.csv_text`):
    ``(search, preload_lb, n_modes, dt_s, event)``; ``search`` the name
    of the search the run belongs to, or a function of the task giving
    it; ``dt_s`` the step the run was given (None: it took its design's
    own at its preload)."""
    name = search(task) if callable(search) else search
    return (name, float(task.preload_lb), task.design.n_modes,
            task.settings.get("dt"), bool(event))
