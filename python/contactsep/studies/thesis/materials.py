"""The thesis's recommendation 4 (``contactsep study materials``): the
materials of the contacts and the separator (modulus, density and, for
a contact law that yields, the yield pressure).

Every row is one simulation of the thesis rig's geometry (y_s = 0.5 in)
with the contacts (members 1 and 3, which carry the buttons) of one
material preset and the separator of another (contactsep.model.
materials: steel, brass, beryllium copper, aluminium; E, density and
Poisson's ratio of each member): Hertz contact (elastic, the static
correction; its constant from the buttons' E1 and nu, the package's
two-equal-materials convention, docs/chatter.md), N = :data:`MODES`
per member, each design's own step (its stiffness changes with the
material), window 0-0.06 s from the release, events = openings of at
least 1e-05 s; the lower contact touching the separator with no preload
and pressed against it by :data:`PRELOAD` lb.

Where :func:`contactsep.chatter.simulate` takes Thornton's
elastic-perfectly-plastic law (``contact="thornton"``,
``yield_pressure=``), every design is also run with it at the lower of
the two materials' yield pressures (:attr:`~contactsep.model.materials.
Material.yield_pressure_psi`), and the columns ``law`` and
``yield_pressure_psi`` say which rows are which; without it the study
has only the Hertz rows.

The smallest preload without events costs about 130 simulations a
design; ``min_preload=True`` adds it (``min_preload_lb``).
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass

import numpy as np

from contactsep.chatter import simulate
from contactsep.constants import LISTING_TAU_S
from contactsep.model.materials import (
    STUDY_MATERIALS,
    material,
    material_fields,
)
from contactsep.model.fields import design_lines
from contactsep.studies.preload.chart import Simulations, limit_notes, min_preloads
from contactsep.studies.study import Study, StudyRun, refuse_fixed, thesis_study_design

#: Modes per member (as study contact-points).
MODES = 32
#: The preload (lb) of the second set of rows (as study contact-points).
PRELOAD = 6.0
#: The fields the study sets itself.
FIXED = {f"{kind}{m}": "the material presets of its rows"
         for kind in ("E", "gamma", "nu") for m in "123"}


def thornton_available() -> bool:
    """Whether the chatter simulation takes Thornton's law
    (``contact="thornton"`` and ``yield_pressure=``)."""
    parameters = inspect.signature(simulate).parameters
    return "contact" in parameters and "yield_pressure" in parameters


@dataclass(frozen=True)
class MaterialsRun(StudyRun):
    """One simulation of the study: ``design`` under ``preload_lb`` (lb)
    by the contact ``law`` (keywords of ``simulate()``: the law, its
    yield pressure, the buttons' Poisson ratio), ``settings`` the
    study's own; its cost (the batch's order) its preload."""

    design: object
    preload_lb: float
    law: dict
    settings: dict


def _run(task: MaterialsRun):
    """One simulation (runs in a worker)."""
    r = simulate(task.design, preload=task.preload_lb, samples=1,
                 single_impulse=False, **task.law, **task.settings)
    return r.circuit_open_s, r.n_events, r.max_lower_gap_in


def materials(*, n_modes: int = MODES, contacts=STUDY_MATERIALS,
              separators=STUDY_MATERIALS, preloads=(0.0, PRELOAD),
              min_preload: bool = False, workers=None, progress=None,
              journal=None, **overrides) -> Study:
    """Opening of the circuit against the materials of the contacts
    (their buttons) and of the separator (module docstring): one row per
    law, preload, contact material and separator material; any other
    design field overridden by keyword; ``progress(k)`` is called as k
    more simulations finish (a bar);
    ``journal``: a :class:`~contactsep.runs.journal.RunJournal`
    that keeps every finished simulation and answers those it holds
    (``study NAME --resume``), or None.

    Returns
    -------
    Study
        Columns (law, yield_pressure_psi: with Thornton's law),
        contact_material, separator_material, E1_psi, gamma1_lb_in3,
        E2_psi, gamma2_lb_in3, preload_lb, circuit_open_s, n_events,
        max_lower_gap_in (and min_preload_lb).
    """
    from contactsep.studies.preload.search_checks import (
        check_modes,
        check_values,
        check_workers,
    )
    check_modes(n_modes)
    check_workers(workers)
    preloads = check_values("preloads", preloads, "lb")
    refuse_fixed("materials", overrides, FIXED)
    pairs = [(material(c), material(s)) for c in contacts
             for s in separators]
    designs = [thesis_study_design(n_modes=n_modes, **overrides,
                             **material_fields(c.name, "13"),
                             **material_fields(s.name, "2"))
               for c, s in pairs]
    laws = [("hertz", lambda c, s: {})]
    if thornton_available():
        laws.append(("thornton", lambda c, s: {
            "contact": "thornton", "static_correction": False,
            "yield_pressure": min(c.yield_pressure_psi,
                                  s.yield_pressure_psi)}))
    settings = {"t_end": LISTING_TAU_S}
    tasks, rows = _tasks(laws, preloads, pairs, designs, settings)
    with Simulations(workers, progress=progress,
                     journal=journal) as sims:
        # the preloaded runs first (their cost)
        answers = sims.map(_run, tasks)
        found = min_preloads(designs, "hertz", settings, simulations=sims) \
            if min_preload else []
    columns = _columns(answers, rows, len(laws) > 1)
    if min_preload:
        columns["min_preload_lb"] = np.tile(
            [r.min_preload_lb for r in found], len(rows) // len(designs))
    notes = _notes(pairs, designs, found, n_modes, len(laws) > 1,
                   sims.runs)
    return Study("materials", f"Recommendation 4: circuit opening against "
                 f"the materials of the contacts and the separator "
                 f"(N = {n_modes})", columns, tuple(notes))


def _tasks(laws, preloads, pairs, designs, settings):
    """The simulations (:class:`MaterialsRun`) and their rows
    (law, preload, contact material, separator material): each law, then
    each preload, then each pair of materials."""
    tasks, rows = [], []
    for law, extra in laws:
        for preload in preloads:
            for (c, s), design in zip(pairs, designs):
                tasks.append(MaterialsRun(
                    design, preload, {**extra(c, s), "nu": c.nu}, settings))
                rows.append((law, preload, c, s))
    return tasks, rows


def _columns(answers, rows, with_law: bool) -> dict:
    """The study's columns from each simulation's (open time, events,
    largest lower gap) and its row; ``with_law``: the law's columns
    first (Thornton's rows beside Hertz's)."""
    open_s, events, gap = (np.array(v, dtype=float) for v in zip(*answers))
    columns = {}
    if with_law:
        columns["law"] = np.array([law for law, _, _, _ in rows])
        columns["yield_pressure_psi"] = np.array(
            [min(c.yield_pressure_psi, s.yield_pressure_psi)
             for _, _, c, s in rows])
    columns.update({
        "contact_material": np.array([c.name for _, _, c, _ in rows]),
        "separator_material": np.array([s.name for _, _, _, s in rows]),
        "E1_psi": np.array([c.E_psi for _, _, c, _ in rows]),
        "gamma1_lb_in3": np.array([c.gamma_lb_in3 for _, _, c, _ in rows]),
        "E2_psi": np.array([s.E_psi for _, _, _, s in rows]),
        "gamma2_lb_in3": np.array([s.gamma_lb_in3 for _, _, _, s in rows]),
        "preload_lb": np.array([p for _, p, _, _ in rows]),
        "circuit_open_s": open_s, "n_events": events.astype(np.int64),
        "max_lower_gap_in": gap})
    return columns


def _notes(pairs, designs, found, n_modes, with_law, runs) -> list:
    """The study's notes: the thesis's recommendation, the presets, the
    simulations, Thornton's rows, each pair's limits and the design."""
    presets = "; ".join(f"{m.name}: {m.alloy}, E {m.E_psi:.3g} psi, "
                        f"{m.gamma_lb_in3:g} lb/in^3, nu {m.nu:g}, yield "
                        f"{m.yield_strength_psi:.3g} psi"
                        for m in {c.name: c for pair in pairs
                                  for c in pair}.values())
    notes = ["the thesis (recommendation 4): study the materials' modulus, "
             "density and hardness; contact_material: the upper and lower "
             "contacts (E1 = E3, gamma1 = gamma3, their buttons), "
             "separator_material: the separator",
             f"presets (contactsep.model.materials; docs/model.md): "
             f"{presets}",
             f"three beams, Hertz contact (elastic, static correction; k "
             f"from E1 and the contacts' nu), N = {n_modes}, each design's "
             f"own step, window 0-{LISTING_TAU_S:g} s from the release; an "
             f"event is an opening >= 1e-05 s; preload_lb: the lower "
             f"contact pressed against the separator at the start",
             "Thornton's law (law, yield_pressure_psi: the lower of the two "
             "materials' 1.60 x yield strength) "
             + ("included, without the static correction (the law's "
                "memory is not in the series solve)" if with_law else
                "not in this build of the chatter layer: Hertz rows only"),
             f"{runs} simulations",
             *(note for (c, s), r in zip(pairs, found)
               for note in limit_notes(f"{c.name} on {s.name}", r)),
             *design_lines(designs[0], per_row=tuple(FIXED))]
    return notes


def draw(axes, study: Study) -> None:
    """Two maps over (contact material, separator material), the Hertz
    rows: the largest lower gap with no preload and the total open time
    at the largest preload."""
    c = study.columns
    hertz = np.ones(len(study), dtype=bool) if "law" not in c else \
        np.asarray(c["law"]) == "hertz"
    preload = np.asarray(c["preload_lb"])
    names_c = list(dict.fromkeys(c["contact_material"]))
    names_s = list(dict.fromkeys(c["separator_material"]))
    panels = ((axes[0], preload == preload.min(), "max_lower_gap_in",
               f"max lower gap (0.001 in), {preload.min():g} lb"),
              (axes[1], preload == preload.max(), "circuit_open_s",
               f"circuit open (ms), {preload.max():g} lb"))
    for ax, rows, key, label in panels:
        rows = rows & hertz
        values = np.asarray(c[key][rows], dtype=float).reshape(
            len(names_c), len(names_s)) * 1e3
        image = ax.imshow(values.T, origin="lower", aspect="auto",
                          cmap="viridis")
        for i in range(len(names_c)):
            for j in range(len(names_s)):
                ax.text(i, j, f"{values[i, j]:.3g}", ha="center",
                        va="center", fontsize=7, color="w")
        ax.figure.colorbar(image, ax=ax, label=label)
        ax.set_yticks(range(len(names_s)), names_s, fontsize=7)
        ax.set_xticks(range(len(names_c)), names_c, fontsize=7)
        ax.set(ylabel="separator")
        ax.grid(False)
    axes[1].set(xlabel="contacts (upper and lower, their buttons)")
