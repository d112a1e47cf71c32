"""One name per quantity in every output: the model's results under
their snake_case name and unit suffix (docs/names-and-units.md), for every JSON, CSV, Parquet, ``to_dict()`` and DataFrame the
package writes, and the same keys in SI (``--units si``).  The Design's
fields and their names: :mod:`contactsep.model.fields`.

Units are the package's: in, lb, s, psi, lb/in^3.  A key is the
quantity's name followed by its unit's suffix (``_in``, ``_s``,
``_lb``, ``_lb_s``, ``_in_s``, ``_psi``, ``_lb_in3``, ``_rad_s``,
``_cps``, ``_lb_s2_in``); dimensionless names are bare.
"""

from __future__ import annotations

from contextlib import contextmanager
from contextvars import ContextVar

#: The general model's results (:class:`contactsep.model.Evaluation`):
#: (attribute, key with its unit, unit as printed, meaning), in order.
RESULTS = (
    ("t1", "t1_s", "s", "first impact after release"),
    ("v_impact", "v_impact_in_s", "in/s", "impact speed of the upper "
                                          "contact"),
    ("psi", "psi_lb_s", "lb s", "impulse"),
    ("v0", "v0_in_s", "in/s", "separator velocity after the impact"),
    ("R", "R", "-", "mass ratio (eq. 24)"),
    ("y3_max", "y3_max_in", "in", "largest lower-contact separation"),
    ("t_max", "t_max_s", "s", "its time after the impact"),
    ("y3_min", "y3_min_in", "in", "smallest lower-contact displacement"),
    ("t_min", "t_min_s", "s", "its time after the impact"),
    ("M1", "M1_lb_s2_in", "lb s^2/in", "upper contact mass"),
    ("M2", "M2_lb_s2_in", "lb s^2/in", "separator mass"),
    ("M3", "M3_lb_s2_in", "lb s^2/in", "lower contact mass"),
)
#: The model's flags and status: (attribute, key).
FLAGS = (("at_window_end", "at_window_end"), ("t_max_tied", "t_max_tied"),
         ("t_min_tied", "t_min_tied"), ("status", "status"))
#: Per-mode results: (attribute, key with its unit, member index).
PER_MODE = (("p1", "p1_rad_s", 0), ("p2", "p2_rad_s", 1),
            ("p3", "p3_rad_s", 2), ("c3", "c3_in", 2))
#: Every result's attribute -> key.
RESULT_KEYS = {**{a: k for a, k, _, _ in RESULTS}, **dict(FLAGS),
               **{a: k for a, k, _ in PER_MODE}}


#: The Hertz family's energy book in the chatter outputs (issue 28,
#: docs/chatter.md "Energy book"): (key, unit as printed, meaning).
ENERGY_BOOK = (
    ("energy_initial_lbin", "in lb", "energy at the release, the "
     "contacts' included"),
    ("energy_dissipated_contact_lbin", "in lb", "energy the contacts "
     "dissipated (damping's work, plastic work), summed by the stepper"),
    ("energy_member1_lbin", "in lb", "vibration energy left in the upper "
     "contact's modes at the end"),
    ("energy_member2_lbin", "in lb", "vibration energy left in the "
     "separator's modes at the end"),
    ("energy_member3_lbin", "in lb", "vibration energy left in the lower "
     "contact's modes at the end"),
    ("energy_contact_lbin", "in lb", "elastic energy stored in the "
     "contacts at the end"),
)
#: The contact law's settings in the chatter outputs: (key, unit as
#: printed, meaning).
CONTACT_LAW = (
    ("contact", "", "the law's elastic part: hertz or thornton"),
    ("alpha_s_per_in", "s/in", "Hunt-Crossley's material constant"),
    ("yield_pressure_psi", "psi", "Thornton's yield pressure"),
)
#: The columns of ``contactsep study conclusion4`` (a contract).
CONCLUSION4_COLUMNS = ("law", "d_in", "ys_in", "impact_velocity_in_s",
                       "e_apparent")


#: One inch in metres and one pound-force in newtons (exact by
#: definition: the international inch and pound, standard gravity).
INCH_M = 0.0254
LBF_N = 4.4482216152605
#: ``--units si``: each unit suffix of the package -> its SI suffix, the
#: SI unit as printed, and the SI value of one package unit.  A weight
#: density becomes the mass density that weighs it under standard
#: gravity (1 lbf/in^3 is the weight of 1 lb/in^3 of mass); a mass in
#: lb s^2/in becomes kg.
SI_SUFFIXES = {
    "in": ("m", "m", INCH_M),
    "s": ("s", "s", 1.0),
    "lb": ("N", "N", LBF_N),
    "psi": ("Pa", "Pa", LBF_N / INCH_M**2),
    "lb_in3": ("kg_m3", "kg/m^3", 0.45359237 / INCH_M**3),
    "lb_s": ("N_s", "N s", LBF_N),
    "in_s": ("m_s", "m/s", INCH_M),
    "rad_s": ("rad_s", "rad/s", 1.0),
    "cps": ("Hz", "Hz", 1.0),
    "lb_s2_in": ("kg", "kg", LBF_N / INCH_M),
    "lb_in_rad": ("N_m_rad", "N m/rad", LBF_N * INCH_M),
    "lb_per_in": ("N_per_m", "N/m", LBF_N / INCH_M),
    "s_per_in": ("s_per_m", "s/m", 1.0 / INCH_M),
    "lbin": ("J", "J", LBF_N * INCH_M),
    "in_lb": ("J", "J", LBF_N * INCH_M),
}
#: The suffixes longest first, so that 'v0_in_s' is a speed, not a time.
_BY_LENGTH = sorted(SI_SUFFIXES, key=len, reverse=True)


def si_key(key: str) -> tuple[str, float] | None:
    """An output key's SI twin and the factor its values are multiplied
    by ('y3_max_in' -> ('y3_max_m', 0.0254)); None for a key without a
    unit suffix ('e', 'status', 'n_modes')."""
    suffix = _suffix(key)
    if suffix is None:
        return None
    si, _, factor = SI_SUFFIXES[suffix]
    return key[:-len(suffix)] + si, factor


def si_unit(key: str) -> str | None:
    """The SI unit as printed of an output key ('v0_in_s' -> 'm/s')."""
    suffix = _suffix(key)
    return None if suffix is None else SI_SUFFIXES[suffix][1]


def _suffix(key: str) -> str | None:
    for suffix in _BY_LENGTH:
        if key.endswith("_" + suffix) and len(key) > len(suffix) + 1:
            return suffix
    return None


#: The unit system the outputs show their numbers in: "us" (the
#: package's units) unless a caller asked for "si" with
#: :func:`units_shown` (``--units si``): the numbers a sentence, a CSV
#: row, a figure or a page writes as it is made (:func:`shown`,
#: :func:`shown_key`, :func:`shown_columns`, :func:`shown_data`).
_SHOWN: ContextVar[str] = ContextVar("contactsep_units_shown", default="us")


@contextmanager
def units_shown(system: str):
    """Within the block, :func:`shown` and :func:`shown_key` give SI
    values and names where ``system`` is "si"; "us" leaves them as they
    are.

    Examples
    --------
    >>> with units_shown("si"):
    ...     shown(0.5, "lb"), shown_key("preload_lb")
    ((2.22411080763025, 'N'), 'preload_N')
    >>> shown(0.5, "lb")
    (0.5, 'lb')
    """
    if system not in ("us", "si"):
        raise ValueError(f"units_shown: {system!r} is neither 'us' nor 'si'")
    token = _SHOWN.set(system)
    try:
        yield
    finally:
        _SHOWN.reset(token)


def shown(value, suffix: str):
    """A value in the package's unit of ``suffix`` ('lb', 'in', 'lb_s')
    -> (value, unit as printed) in the unit system shown; None and
    non-finite values pass through with the unit's name."""
    _, printed, factor = SI_SUFFIXES[suffix]
    if _SHOWN.get() != "si":
        return value, _PACKAGE_PRINTED.get(suffix, suffix)
    return (value * factor if isinstance(value, (int, float))
            and not isinstance(value, bool) else value), printed


def shown_text(value, suffix: str, digits: int = 6) -> str:
    """A value as a sentence writes it in the unit system shown, with
    ``digits`` significant digits ('0.226 lb', '1.00531 N'); 'none' for
    None or NaN."""
    if value is None or (isinstance(value, float) and value != value):
        return "none"
    number, unit = shown(value, suffix)
    return f"{number:.{digits}g} {unit}"


def shown_key(key: str) -> str:
    """An output key in the unit system shown ('preload_lb' ->
    'preload_N' in SI; unchanged in us or without a unit suffix)."""
    twin = si_key(key) if _SHOWN.get() == "si" else None
    return key if twin is None else twin[0]


#: A suffix -> its unit as printed in the package's own units.
_PACKAGE_PRINTED = {"lb_in3": "lb/in^3", "lb_s": "lb s", "in_s": "in/s",
                    "rad_s": "rad/s", "lb_s2_in": "lb s^2/in",
                    "lb_in_rad": "lb in/rad", "lb_per_in": "lb/in",
                    "s_per_in": "s/in", "lbin": "lb in", "in_lb": "in lb"}


#: Keys whose numbers carry the unit of the key that holds them: a
#: sweep's grids and distributions ({"d_in": {"start": 0.1, ...}}).
_SCALED_WITHIN = ("start", "stop", "values", "mean", "sd", "low", "high")


def si_data(data, bare: dict | None = None):
    """JSON-ready ``data`` in SI: every key with a unit suffix renamed to
    its SI twin ('y3_max_in' -> 'y3_max_m') and its numbers converted,
    at any depth (the numbers of a grid or distribution under such a key
    with it), and a design's "units" "us" -> "si".  ``bare``: objects
    whose keys are bare names of quantities ({"design": {"L1": "L1_in"}}),
    converted as their suffixed names are."""
    def convert(value, factor):
        if isinstance(value, list):
            return [convert(v, factor) for v in value]
        if isinstance(value, float) or (isinstance(value, int) and
                                        not isinstance(value, bool)):
            return si_number(value, factor) if factor != 1.0 else value
        return value

    def walk(value, names=None, factor=1.0):
        if isinstance(value, list):
            return [walk(v) for v in value]
        if not isinstance(value, dict):
            return value
        out = {}
        for key, item in value.items():
            twin = si_key(key) if isinstance(key, str) else None
            if twin is None and names and key in names:
                twin = si_key(names[key])
            if key == "units" and item == "us":
                out[key] = "si"
            elif twin is not None and isinstance(item, dict):
                out[twin[0]] = walk(item, None, twin[1])
            elif twin is not None:
                out[twin[0]] = convert(item, twin[1])
            elif key in _SCALED_WITHIN and factor != 1.0:
                out[key] = convert(item, factor)
            else:
                out[key] = walk(item, (bare or {}).get(key))
        return out
    return walk(data)


def shown_data(data):
    """``data`` in the unit system shown (:func:`units_shown`):
    :func:`si_data` of it in SI, itself otherwise."""
    return si_data(data) if _SHOWN.get() == "si" else data


#: A unit suffix -> its name in a units note, in the package's units.
_UNIT_NAMES = {"in": "inch", "s": "second", "lb_s": "lb s", "in_s": "in/s",
               "lb_in3": "lb/in^3", "psi": "psi", "lb": "lb"}


def units_note(suffixes) -> str:
    """How a table's column names give their units, in the unit system
    shown: "units in each column's name: _in inch, _s second" (SI:
    "_m m, _s s")."""
    names = []
    for suffix in suffixes:
        key = shown_key("x_" + suffix)[2:]
        names.append(f"_{key} " + (_UNIT_NAMES.get(suffix, suffix)
                                   if key == suffix
                                   else shown(1.0, suffix)[1]))
    return "units in each column's name: " + ", ".join(names)


def from_si_number(value: float, suffix: str) -> float:
    """A bare SI number -> the package's unit of ``suffix`` ('0.025' m
    for 'in': 0.984... in), rounded to 15 digits as contactsep.units
    rounds a value typed with its unit."""
    return float(f"{value / SI_SUFFIXES[suffix][2]:.15g}")


def shown_columns(columns: dict) -> dict:
    """A table's columns ({name: array}) in the unit system shown: in SI
    each column with a unit suffix renamed to its SI twin and its
    numbers converted ('y3_max_in' -> 'y3_max_m', times 0.0254)."""
    if _SHOWN.get() != "si":
        return columns
    import numpy as np
    out = {}
    for key, values in columns.items():
        twin = si_key(key)
        array = np.asarray(values)
        if twin is None or array.dtype.kind != "f":
            out[key] = values
        else:
            out[twin[0]] = array * twin[1] if twin[1] != 1.0 else values
    return out


def si_number(value: float, factor: float) -> float:
    """``value`` (in the package's units) times ``factor``, written with
    the fewest significant digits that a design file's
    reader (divide by ``factor``, round to 15 digits, as contactsep.units
    rounds) turns back into ``value`` exactly: 5 mm typed is written
    0.005, not 0.00499999999999999.  A value with more digits than the
    reader keeps is written as the plain product, as before."""
    product = value * factor

    def reads_back(digits: int) -> float | None:
        written = float(f"{product:.{digits}g}")
        return written if float(f"{written / factor:.15g}") == value \
            else None

    if reads_back(15) is None:
        # a computed value (a result, not a typed one): the plain
        # product unless 16 or 17 digits read back
        return reads_back(16) or reads_back(17) or product
    return next(written for written in map(reads_back, range(1, 16))
                if written is not None)
