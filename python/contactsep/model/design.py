"""A contact design in the words a designer uses, and its packed form.

Units are the thesis's: inch, pound (force), second; weight densities in
lb/in^3 (the Appendix G decks use lb/ft^3), Young's moduli in psi,
g = 386.4 in/s^2.  Member 1 is the upper contact, 2 the separator, 3 the
lower contact.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from contactsep import beams
from contactsep.beams.member import DEFAULT_NU
from contactsep.constants import LISTING_TAU_S
from contactsep.model import physics
from contactsep.model.contact_points import lower_point_problem
from contactsep.model.design_domain import (
    REAL_COLUMNS,
    SUPPORT_CLEARANCE,
    DesignError,
    _check_number,
    _rules,
    invalid_rows,
)
from contactsep.model.fields import (
    IMPACT_VELOCITIES,
    LC_READINGS,
    LOWER_RESPONSES,
    RELEASES,
)

#: Most modes per member: the sums cost more than N per design (6 s at
#: 1e5, 26 s at 3e5), and modes far beyond L/h are outside Bernoulli-Euler
#: beam theory anyway.
MAX_MODES = 100_000

_ENDS = ("end1", "end2", "end3")
_OPTIONS = {"impact_velocity": IMPACT_VELOCITIES,
            "lower_response": LOWER_RESPONSES,
            "lc_reading": LC_READINGS, "release": RELEASES}


def _largest(array: np.ndarray) -> int:
    return max(int(v) for v in np.ravel(array).tolist())


@dataclass(frozen=True)
class Design:
    """One design, or a columnar batch of designs, of the contact system.

    Any numeric field, the end conditions and ``n_modes`` may hold arrays;
    they broadcast like NumPy and the Design is then a batch.  Defaults are
    the thesis experiment with the 0.25 in separator (Chapters V and VI).
    A scalar design is checked at once (:class:`DesignError`, naming the
    field): its types (numbers, never strings, bools or None where a
    number is needed), ranges, and the model's domain (SIZE_RANGE,
    DENSITY_RANGE, MODULUS_RANGE, DEFLECTION_RANGE, SUPPORT_CLEARANCE;
    docs/model.md, "Domain").  In a batch a value out of range or outside
    the domain gives that design status 2 at evaluation instead.

    Fields (unit; default).  Member 1 is the upper contact, 2 the
    separator, 3 the lower contact; x is measured from each member's
    first-named end.

    L1, L2, L3 : in
        Lengths (19, 2.5, 19).
    b1, b2, b3 : in
        Widths (2, 0.5, 2).
    h1, h2, h3 : in
        Thicknesses (0.125, 0.25, 0.125); h2 is the separator thickness d
        (``--d`` or ``--h2`` on the command line, ``d_in`` in outputs).
    gamma1, gamma2, gamma3 : lb/in^3
        Weight densities (0.100 each; the Appendix G decks use lb/ft^3).
    E1, E2, E3 : psi
        Young's moduli (10.0e6 each).
    end1, end2, end3 : str
        End conditions: "clamped-free" (also "cantilever"),
        "clamped-clamped", "clamped-pinned", "pinned-pinned"
        (clamped-free, clamped-clamped, clamped-free).
    x1, x2, x3 : in or None
        Contact points (None: the tip L1, mid-span L2/2, the tip L3); x2
        is where the upper contact touches the separator.
    x2_lower : in or None
        Where the lower contact touches the separator (None: at x2, as
        in the thesis).  One number shared by a batch; the chatter
        models take it, eq. 23 (``evaluate``) only where it equals x2.
    Lc : in or None
        Separator equivalent length L_c of Table III (None: not used).
    ys : in
        Static deflection of the upper contact before release (0.5).
    e : dimensionless
        Coefficient of restitution, 0 <= e <= 1 (0.375).
    n_modes : int, or a tuple (n1, n2, n3)
        Modes per member (4), at most MAX_MODES.
    tau : s
        Window of the lower-contact response from the impact (0.060).
    gap : in
        Position of the separator surface seen by the upper contact (0).
    impact_velocity : str
        "exact" abs(dy1/dt(x1, t1)) (default) or "listing" (Appendix G's ACT,
        without sin).
    lower_response : str
        "impulse" psi/M3 (default: the momentum psi delivered at x3, whose
        y3_max the release's energy bounds) or "as-printed" eq. 13/23 with
        v0/L3 (the thesis's and the listing's, dimensionally inconsistent;
        the thesis studies use it).
    lc_reading : str
        Reading of Lc: "listing" hybrid (default), "frequencies", "mass".
    release : str
        "tip" (default): the cantilever's tip is deflected by ys;
        "contact": the contact point x1 is.
    beam1, beam2, beam3 : str
        Beam theory: "bernoulli-euler" (default) or "timoshenko".
    nu1, nu2, nu3 : dimensionless
        Poisson's ratio (0.33), for G = E/(2(1 + nu)).
    kappa1, kappa2, kappa3 : dimensionless or None
        Shear coefficient (None: Cowper's 10(1 + nu)/(12 + 11 nu)).
    kr1, kr2, kr3 : lb in/rad or None
        Rotational spring at every clamped end (None: rigid).
    kt1, kt2, kt3 : lb/in or None
        Translational spring at every supported end (None: rigid).
    mass1, mass2, mass3 : lb
        Added point mass, a weight (0: none): a button, a sensor.
    x_mass1, x_mass2, x_mass3 : in or None
        Where it sits (None: the contact point).

    The beam physics fields (contactsep.model.physics) hold one value
    per Design, shared by a batch; eq. 23 (``evaluate``) takes the
    members' modes from contactsep.beams where they are not the thesis's
    (Bernoulli-Euler, rigid ends, no mass; contactsep.model.given).
    """

    #: Upper contact length (in).
    L1: object = 19.0
    #: Upper contact width (in).
    b1: object = 2.0
    #: Upper contact thickness (in).
    h1: object = 0.125
    #: Upper contact weight density (lb/in^3).
    gamma1: object = 0.100
    #: Upper contact Young's modulus (psi).
    E1: object = 10.0e6
    #: Upper contact end conditions (x = 0 first).
    end1: object = "clamped-free"
    #: Contact point on the upper contact (in from x = 0); None: its tip, L1.
    x1: object = None
    #: Separator length (in).
    L2: object = 2.5
    #: Separator width (in).
    b2: object = 0.5
    #: Separator thickness d (in).
    h2: object = 0.25
    #: Separator weight density (lb/in^3).
    gamma2: object = 0.100
    #: Separator Young's modulus (psi).
    E2: object = 10.0e6
    #: Separator end conditions.
    end2: object = "clamped-clamped"
    #: Contact point on the separator (in); None: mid-span, L2/2.
    x2: object = None
    #: Separator equivalent length L_c (in, Table III); None: not used.
    Lc: object = None
    #: Lower contact length (in).
    L3: object = 19.0
    #: Lower contact width (in).
    b3: object = 2.0
    #: Lower contact thickness (in).
    h3: object = 0.125
    #: Lower contact weight density (lb/in^3).
    gamma3: object = 0.100
    #: Lower contact Young's modulus (psi).
    E3: object = 10.0e6
    #: Lower contact end conditions.
    end3: object = "clamped-free"
    #: Contact point on the lower contact (in); None: its tip, L3.
    x3: object = None
    #: Static deflection of the upper contact before release (in).
    ys: object = 0.5
    #: Coefficient of restitution, 0 <= e <= 1.
    e: object = 0.375
    #: Modes per member: an int (shared) or a tuple (n1, n2, n3).
    n_modes: object = 4
    #: Time window of the lower-contact response, from the impact (s).
    tau: object = LISTING_TAU_S
    #: Position of the separator surface seen by the upper contact (in).
    gap: object = 0.0
    #: "exact": abs(dy1/dt(x1, t1)); "listing": Appendix G's ACT (no sin).
    impact_velocity: str = "exact"
    #: "impulse": psi/M3 (eq. 19; default); "as-printed": eq. 13/23 with
    #: v0/L3 (the listing's; the thesis studies pass it).
    lower_response: str = "impulse"
    #: Reading of Lc: "listing" hybrid, "frequencies" only, or "mass" too.
    lc_reading: str = "listing"
    #: "tip": load at the upper contact's tip (cantilever); "contact": at x1.
    release: str = "tip"
    #: Each member's beam physics (contactsep.model.physics).
    beam1: str = "bernoulli-euler"
    beam2: str = "bernoulli-euler"
    beam3: str = "bernoulli-euler"
    nu1: float = DEFAULT_NU
    nu2: float = DEFAULT_NU
    nu3: float = DEFAULT_NU
    kappa1: object = None
    kappa2: object = None
    kappa3: object = None
    kr1: object = None
    kr2: object = None
    kr3: object = None
    kt1: object = None
    kt2: object = None
    kt3: object = None
    mass1: float = 0.0
    mass2: float = 0.0
    mass3: float = 0.0
    x_mass1: object = None
    x_mass2: object = None
    x_mass3: object = None
    #: Where the lower contact touches the separator (in); None: at x2.
    x2_lower: object = None

    def __post_init__(self) -> None:
        for name, allowed in _OPTIONS.items():
            if getattr(self, name) not in allowed:
                raise DesignError(
                    f"{name}: found {getattr(self, name)!r}, expected one "
                    f"of {', '.join(allowed)}")
        for name in _ENDS:
            value = np.asarray(getattr(self, name))
            if value.dtype.kind not in "UO" or not np.all(
                    np.isin(value, beams.END_CONDITIONS)):
                raise DesignError(
                    f"{name}: found {getattr(self, name)!r}, expected "
                    f"one of {', '.join(beams.END_CONDITIONS)}")
        for name in REAL_COLUMNS:
            _check_number(name, getattr(self, name))
        physics_problem = physics.problem(self) or \
            lower_point_problem(self, SUPPORT_CLEARANCE)
        if physics_problem:
            raise DesignError(physics_problem)
        n = self._n_array()
        try:
            self.shape
        except ValueError as error:
            raise DesignError(f"fields do not broadcast together: "
                              f"{error}") from None
        if not np.all(n >= 1):
            raise DesignError(f"n_modes: found {self.n_modes!r}, expected "
                              f"an integer >= 1 (or three of them)")
        if self.shape == ():
            problems = self.problems()
            if problems:
                raise DesignError(problems[0])

    def _n_array(self) -> np.ndarray:
        n = self.n_modes
        if isinstance(n, tuple) and len(n) != 3:
            raise DesignError(f"n_modes: found {n!r}, expected an "
                              f"integer or a tuple (n1, n2, n3)")
        try:
            array = np.stack(np.broadcast_arrays(*map(np.asarray, n)),
                             axis=-1) if isinstance(n, tuple) \
                else np.asarray(n)
        except (TypeError, ValueError, OverflowError):
            array = np.asarray(None)
        # Python ints past 2^64 make an object array: too many modes,
        # not a wrong type
        huge = array.dtype.kind == "O" and all(
            isinstance(v, int) and not isinstance(v, bool)
            for v in array.ravel().tolist())
        whole = array.dtype.kind in "iu" or (
            array.dtype.kind == "f" and np.all(np.isfinite(array))
            and np.all(array == np.round(array)))
        if not (whole or huge):
            raise DesignError(f"n_modes: found {self.n_modes!r}, expected "
                              f"an integer >= 1 (or three of them)")
        if huge or np.any(array > MAX_MODES):
            raise DesignError(f"n_modes: found {_largest(array)}, expected "
                              f"at most {MAX_MODES:,} (cost grows faster "
                              f"than N: 6 s a design at the limit)")
        return array.astype(np.int64)

    @property
    def shape(self) -> tuple:
        """The batch shape (``()`` for one design)."""
        parts = [np.asarray(getattr(self, f)) for f in REAL_COLUMNS
                 if getattr(self, f) is not None]
        parts += [np.asarray(getattr(self, f)) for f in _ENDS]
        n = self._n_array()
        parts.append(n[..., 0] if isinstance(self.n_modes, tuple) else n)
        return np.broadcast_shapes(*(p.shape for p in parts))

    @property
    def size(self) -> int:
        """Number of designs in the batch."""
        return int(np.prod(self.shape, dtype=np.int64))

    def replace(self, **changes) -> "Design":
        """A copy with some fields changed."""
        return dataclasses.replace(self, **changes)

    def to_file(self, path) -> None:
        """Write this design's file (``contactsep.load_design`` and
        ``--design`` read it; contactsep.model.design_file): JSON keys
        with units, ``"units": "us"``, n_modes only where not 4."""
        from contactsep.model import design_file
        design_file.write(self, path)

    def problems(self) -> list[str]:
        """One message per kind of out-of-range value (empty: all good):
        the kernel's own checks, then the model's domain (DOMAIN)."""
        packed = pack(self)
        messages = []
        for name, wrong, expect in _rules(packed.real, packed.ints):
            if np.any(wrong):
                row = int(np.argmax(wrong))
                found = float(packed.real[row, REAL_COLUMNS.index(name)])
                default = " (its default)" if getattr(self, name) is None \
                    else ""
                messages.append(f"{name}: found {found!r}{default}, "
                                f"expected {expect(row)}")
        if not messages and np.any(invalid_rows(packed.real, packed.ints)):
            messages.append("invalid design")
        return messages


@dataclass(frozen=True)
class Packed:
    """A batch flattened for a backend (the compiled kernel's layout).

    ``real`` (M, 23) float64 and ``ints`` (M, 6) int32, both C ordered
    (one design's values contiguous), columns :data:`REAL_COLUMNS` and
    :data:`INT_COLUMNS`;
    ``options`` (4,) int32 codes of impact_velocity, lower_response,
    lc_reading and release; ``shape`` the batch shape; ``modes`` None
    (the backends compute the thesis's modes) or the members' modes of
    other beam physics (:class:`contactsep.model.given.GivenModes`).
    """

    real: np.ndarray
    ints: np.ndarray
    options: np.ndarray
    shape: tuple
    modes: object = None

    @property
    def size(self) -> int:
        """Number of designs M."""
        return self.real.shape[0]


def pack(design: Design) -> Packed:
    """Broadcast and flatten a design for a backend; x defaults resolved."""
    shape = design.shape
    columns = {}
    for name in REAL_COLUMNS:
        value = getattr(design, name)
        if value is None:
            value = {"x1": design.L1, "x3": design.L3, "Lc": 0.0,
                     "x2": np.asarray(design.L2, dtype=np.float64) / 2.0
                     }[name]
        columns[name] = np.broadcast_to(
            np.asarray(value, dtype=np.float64), shape).ravel()
    real = np.ascontiguousarray(np.stack([columns[n] for n in REAL_COLUMNS],
                                         axis=1))
    ends = [np.broadcast_to(np.vectorize(beams.end_code, otypes=[np.int32])(
        np.asarray(getattr(design, name))), shape).ravel() for name in _ENDS]
    n = design._n_array()
    if isinstance(design.n_modes, tuple):
        counts = [np.broadcast_to(n[..., k], shape).ravel() for k in range(3)]
    else:
        counts = [np.broadcast_to(n, shape).ravel()] * 3
    ints = np.ascontiguousarray(
        np.stack(ends + counts, axis=1).astype(np.int32))
    options = np.array([_OPTIONS[name].index(getattr(design, name))
                        for name in _OPTIONS], dtype=np.int32)
    return Packed(real=real, ints=ints, options=options, shape=shape)
