"""A design file: the one JSON object that :meth:`Design.to_file`
writes, ``contactsep model --json`` prints under ``design``, and
``contactsep.load_design`` and ``--design FILE`` read
(:mod:`contactsep.model.design_file_read`).

The object's keys are the fields' output names, each with its unit
(``L1_in``, ``d_in``, ``gamma2_lb_in3``: :mod:`contactsep.model.fields`),
after ``"units": "us"``, the unit system those suffixes are in.  It
holds the geometry, the materials and the physics; a numerics field
(:data:`NUMERICS`) only where it was asked for, so that a simulation
reading the file keeps its own default (a file written for eq. 23's
N = 4 would otherwise run a chatter simulation, whose default is 64, at
N = 4).
"""

from __future__ import annotations

import numpy as np

from contactsep import output
from contactsep.errors import InputError
from contactsep.model import fields

#: The unit system of every key's suffix: in, lb, s (E in psi, weight
#: densities in lb/in^3), as the keys say.
UNITS = "us"
#: The unit systems a design file may name, with what each means.
UNIT_SYSTEMS = {"us": "in, lb, s; E psi, densities lb/in^3",
                "si": "m, N, s; E Pa, densities kg/m^3, as model --units si "
                      "--json writes"}
#: Design fields that set how the model is computed, not what is built:
#: written only where asked for.
NUMERICS = ("n_modes",)


def file_fields(design, numerics=()) -> dict:
    """The design file's object for one Design: ``units`` first, then
    every field under its output key (a field of SHOWN_WHEN_GIVEN only
    when given), the numerics fields only those named in ``numerics``.
    """
    if design.shape != ():
        raise InputError(f"a design file holds one design, not a batch "
                         f"of {design.size}")
    keep = {fields.column_name(name) for name in numerics}
    numeric_keys = {fields.column_name(name) for name in NUMERICS}
    out = {"units": UNITS}
    for key, value in fields.design_keys(design).items():
        if key in numeric_keys and key not in keep:
            continue
        if isinstance(value, list):
            value = [v.item() if isinstance(v, np.generic) else v
                     for v in value]
        elif isinstance(value, np.generic):
            value = value.item()
        out[key] = value
    return out


def write(design, path) -> None:
    """Write ``design``'s file to ``path`` whole (a temporary file beside
    it, renamed into place: :func:`contactsep.output.open_output`); its
    numerics fields only where they differ from the Design's defaults
    (a Design does not know which fields were given)."""
    defaults = {f.name: f.default
                for f in design.__dataclass_fields__.values()}
    given = [name for name in NUMERICS
             if _differs(getattr(design, name), defaults[name])]
    data = file_fields(design, given)
    with output.open_output(path) as stream:
        output.write_json(stream, data)


def _differs(value, default) -> bool:
    if isinstance(value, tuple):
        return True
    try:
        return bool(value != default)
    except (TypeError, ValueError):
        return True
