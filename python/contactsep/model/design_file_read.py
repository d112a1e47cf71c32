"""Reading a design file: :func:`load_design` (``contactsep.load_design``)
and the command line's ``--design FILE`` read it here, the same way
(the format and its writer: :mod:`contactsep.model.design_file`).

The format is :mod:`contactsep.model.design_file`'s: one JSON object of
design fields (output names with units such as ``d_in``, names as in
``--set`` such as ``h2``, aliases ``d`` and ``restitution``, material
presets ``"material2": "steel"``), optionally ``"units": "us"`` (or
``"si"``: keys such as ``d_m`` and bare numbers in SI, as ``model
--units si --json`` writes them); or the output of ``contactsep model
--json``, whose ``design`` object it reads.  A file without ``units`` is
in the package's units (every file written before the key existed).  Each value is read by
:func:`contactsep.model.fields.parse_value`, so a file accepts what
the command line accepts and refuses it with the same one line, naming
the file and the key.
"""

from __future__ import annotations

import json
import os

from contactsep import output
from contactsep.errors import InputError
from contactsep.model import fields as F
from contactsep.model.design_file import UNIT_SYSTEMS
from contactsep.model.names import si_key

#: The largest design file read (a design is a few hundred bytes; the
#: output of model --json with N = 100,000 modes about 10 MB).
MAX_DESIGN_BYTES = 16 << 20
#: Material presets in a file -> the members whose E, gamma and nu they
#: fill (the command line's --material, --material1, ...).
FILE_PRESETS = {"material": "123", "material1": "1", "material2": "2",
                "material3": "3"}


def load_design(path):
    """The design in a design file.

    Parameters
    ----------
    path : str or os.PathLike
        A file :meth:`contactsep.Design.to_file` wrote, the output of
        ``contactsep model --json``, or a JSON object of design fields
        written by hand (module docstring).

    Returns
    -------
    contactsep.Design
        The thesis design with the file's fields; a field the file does
        not give (n_modes, unless it was asked for) keeps the Design's
        default.

    Raises
    ------
    InputError
        One line naming the file and the key: not JSON, not a design
        field, a value of the wrong type or range, another unit system.

    Examples
    --------
    >>> import contactsep, os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "my.json")
    >>> contactsep.thesis_design(d=0.5).to_file(path)
    >>> contactsep.load_design(path).h2
    0.5
    """
    name = os.fspath(path)
    values, labels = read_fields(name, name)
    return make_design(values, labels)


def read_fields(path: str, label: str) -> tuple[dict, dict]:
    """(values, labels) of a design file: Design field -> value, and
    field -> how an error names it ('my.json: d_in'); ``label`` names
    the file in errors about the whole file ('--design my.json')."""
    data = read_object(path, label)
    values, labels = {}, {}
    for key, value in data.items():
        if key in FILE_PRESETS:
            # the file's own fields win over its presets
            for field, number in preset_fields(
                    value, FILE_PRESETS[key], f"{path}: {key}").items():
                values[field] = number
                labels[field] = f"{path}: {key}"
    presets = {f"{path}: {k}" for k in FILE_PRESETS}
    for key, value in data.items():
        if key in FILE_PRESETS:
            continue
        where = f"{path}: {key}"
        field = F.field_name(key, where)
        if field in labels and labels[field] not in presets:
            # two names of one field ("d_in" and "h2"), refused as on
            # the command line (issue 31: the last one won)
            raise InputError(f"{where}: the {F.FIELDS[field][2]} is "
                             f"already given by {labels[field]}")
        values[field] = F.parse_value(field, value, where)
        labels[field] = where
    return values, labels


def read_object(path: str, label: str) -> dict:
    """The file's JSON object of design fields (a ``model --json``
    output's ``design``), its ``units`` checked and removed."""
    with open(path, "rb") as handle:
        raw = handle.read(MAX_DESIGN_BYTES + 1)
    if len(raw) > MAX_DESIGN_BYTES:
        raise InputError(f"{label}: larger than {MAX_DESIGN_BYTES >> 20} "
                         f"MB, not a design")
    try:
        data = json.loads(raw.decode("utf-8"),
                          object_pairs_hook=_no_duplicates)
    except _DuplicateKey as error:
        raise InputError(f"{label}: {error.args[0]}: given twice (JSON "
                         f"keeps only the last; give it once)") from None
    except (UnicodeDecodeError, json.JSONDecodeError) as error:
        raise InputError(f"{label}: not a JSON file "
                         f"({output.one_line(error)})") from None
    except RecursionError:
        raise InputError(f"{label}: not a design (JSON nested too "
                         f"deeply)") from None
    if isinstance(data, dict) and isinstance(data.get("design"), dict):
        data = data["design"]
    if not isinstance(data, dict):
        raise InputError(f"{label}: expected a JSON object of design "
                         f"fields")
    data = dict(data)
    units = data.pop("units", "us")
    if not isinstance(units, str) or units not in UNIT_SYSTEMS:
        accepted = "; ".join(f"{k} ({v})" for k, v in UNIT_SYSTEMS.items())
        raise InputError(f"{path}: units: found {units!r}, expected "
                         f"{accepted}")
    return _from_si_file(data, path) if units == "si" else data


def _si_columns() -> dict:
    """SI key ('d_m', 'E1_Pa') -> (field, factor) of each field with a
    unit (model.names.SI_SUFFIXES)."""
    out = {}
    for field in F.FIELDS:
        twin = si_key(F.column_name(field)) if F.FIELDS[field][0] else None
        if twin is not None:
            out[twin[0]] = (field, twin[1])
    return out


def _from_si_file(data: dict, path: str) -> dict:
    """A file of ``"units": "si"`` in the package's units: its SI keys
    ('L1_m') as field names, its bare numbers (under an SI key or a
    field's name) divided by the SI value of the field's unit, rounded as
    contactsep.units rounds; a value with its unit ('25 mm') as typed; an
    inch-pound key ('L1_in') refused in one line."""
    from contactsep import units
    columns = _si_columns()
    by_field = {field: factor for field, factor in columns.values()}
    inch_pound = {F.column_name(f): key for key, (f, _) in columns.items()
                  if F.column_name(f) != key}
    out = {}
    for key, value in data.items():
        if key in inch_pound:
            raise InputError(f"{path}: {key}: an inch-pound key in a file "
                             f"whose units are si (give {inch_pound[key]})")
        field, factor = columns.get(key, (key, by_field.get(key)))
        if factor is not None and not isinstance(value, bool) and (
                isinstance(value, (int, float)) or (
                    isinstance(value, str) and units.split(value) is None
                    and _number(value))):
            value = float(f"{float(value) / factor:.15g}")
        out[field] = value
    return out


def _number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def make_design(values: dict, labels: dict):
    """The thesis design with ``values``, its own checks reported under
    the name the user gave the field (``labels``: field -> name)."""
    from contactsep.model.thesis_rig import thesis_design
    try:
        return thesis_design(**values)
    except InputError as error:
        message = str(error)
        field, sep, rest = message.partition(":")
        if sep and field in labels:
            message = f"{labels[field]}:{rest}"
        raise InputError(message) from None


def preset_fields(name, members: str, label: str) -> dict:
    """The fields a material preset fills, or an InputError naming the
    option (or file key) as given."""
    from contactsep.model.materials import material_fields
    try:
        return material_fields(name, members)
    except InputError as error:
        raise InputError(f"{label}: {error}") from None


class _DuplicateKey(Exception):
    """A JSON object with a key twice (args[0] the key)."""


def _no_duplicates(pairs) -> dict:
    """json's object_pairs_hook: a dict, or _DuplicateKey."""
    out = {}
    for key, value in pairs:
        if key in out:
            raise _DuplicateKey(key)
        out[key] = value
    return out
