"""One member in the design's units (in, lb, psi, s): its beam theory,
supports and added masses, made dimensionless for
:mod:`~contactsep.beams.timoshenko`, and its modal model (from
:mod:`~contactsep.beams.timoshenko_modes`) and static flexibility (from
:mod:`~contactsep.beams.timoshenko_static`).

Conventions (docs/model.md, "Beam theories, supports and masses"):

* theory "bernoulli-euler" (the thesis's) or "timoshenko" (shear
  flexibility and rotary inertia); nu is Poisson's ratio (G = E/(2(1 +
  nu))), kappa the shear coefficient, by default Cowper's for a
  rectangle, 10(1 + nu)/(12 + 11 nu);
* kr (lb in/rad) and kt (lb/in): the stiffness of every supported end's
  rotational and translational spring (kr at clamped ends only); None is
  rigid;
* mass (lb, a weight) at x_mass (in from x = 0): a point mass (contact
  button, sensor) without rotary inertia;
* modes X_j normalised with the whole mass, int (rho A X_i X_j + rho I
  Psi_i Psi_j) dx + m X_i X_j(x_m) = rho A L delta_ij: the generalised
  mass of every mode is the bare beam's mass rho A L (the package's
  int X^2 dx = L), and p_j the circular frequencies (rad/s).

A member with the thesis's physics (Bernoulli-Euler, rigid ends, no
mass) takes the closed-form modes of
:mod:`~contactsep.beams.bernoulli_euler`, any number of them; any other
takes the exact general solution (at most MAX_GENERAL_MODES modes).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from contactsep.beams import bernoulli_euler as be
from contactsep.beams import timoshenko, timoshenko_modes, timoshenko_static
from contactsep.constants import GRAVITY_IN_PER_S2

#: Beam theories, the default first.
THEORIES = ("bernoulli-euler", "timoshenko")
#: Poisson's ratio when none is given (aluminium, 0.33).
DEFAULT_NU = 0.33


def cowper_kappa(nu):
    """Cowper's (1966) shear coefficient of a rectangle,
    10 (1 + nu)/(12 + 11 nu) (0.8509 for nu = 0.33)."""
    return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)


@dataclass(frozen=True)
class MemberBeam:
    """A uniform member (module docstring for the conventions)."""

    length: float
    width: float
    thickness: float
    gamma: float
    modulus: float
    end: str
    theory: str = "bernoulli-euler"
    nu: float = DEFAULT_NU
    kappa: float | None = None
    kr: float | None = None
    kt: float | None = None
    mass: float = 0.0
    x_mass: float | None = None

    def __post_init__(self) -> None:
        if self.theory not in THEORIES:
            raise ValueError(f"theory must be one of {THEORIES}, got "
                             f"{self.theory!r}")
        be.end_code(self.end)

    @property
    def area(self) -> float:
        return self.width * self.thickness

    @property
    def inertia(self) -> float:
        return self.width * self.thickness**3 / 12.0

    @property
    def beam_mass(self) -> float:
        """rho A L (lb s^2/in)."""
        return self.gamma * self.area * self.length / GRAVITY_IN_PER_S2

    @property
    def frequency_scale(self) -> float:
        """sqrt(EI/(rho A))/L^2 (rad/s): p = b times this."""
        return float(np.sqrt(self.modulus * self.inertia
                             * GRAVITY_IN_PER_S2
                             / (self.area * self.gamma))) / self.length**2

    @property
    def shear_coefficient(self) -> float:
        return cowper_kappa(self.nu) if self.kappa is None else self.kappa

    def dimensionless(self) -> timoshenko.Beam:
        """The :class:`~contactsep.beams.timoshenko.Beam` of this member."""
        ei = self.modulus * self.inertia
        r2 = s2 = 0.0
        if self.theory == "timoshenko":
            r2 = self.inertia / (self.area * self.length**2)
            shear = self.modulus / (2.0 * (1.0 + self.nu))
            s2 = ei / (self.shear_coefficient * shear * self.area
                       * self.length**2)
        kr = None if self.kr is None else self.kr * self.length / ei
        kt = None if self.kt is None else self.kt * self.length**3 / ei
        masses = ()
        if self.mass:
            x = self.length if self.x_mass is None else self.x_mass
            masses = ((x / self.length,
                       self.mass / (self.gamma * self.area * self.length)),)
        return timoshenko.Beam(be._canonical(self.end), r2, s2, kr, kt,
                               masses)


@dataclass(frozen=True)
class ModalModel:
    """A member's first modes, seen at some points."""

    #: Circular frequencies p_j (rad/s), (n,).
    p: np.ndarray
    #: Mode values X_j(x) at the points asked for, (n, points).
    values: np.ndarray
    #: Generalised mass of every mode = the bare beam's mass (lb s^2/in).
    mass: float

    @property
    def f_hz(self) -> np.ndarray:
        """Frequencies in cycles per second."""
        return self.p / (2.0 * np.pi)


@functools.lru_cache(maxsize=256)
def _general_eigenvalues(beam: timoshenko.Beam, n: int):
    """b_j of a general beam (cached: the root search is the costly part
    of its modes, and eq. 23 and the chatter models ask for the same
    member's modes at different points)."""
    b = timoshenko.eigenvalues(beam, n)
    b.flags.writeable = False
    return b


@functools.lru_cache(maxsize=256)
def _dimensionless_modes(beam: timoshenko.Beam, n: int, xi: tuple):
    """b_j and X_j(xi): the closed form for the thesis's physics, the
    general solution otherwise (cached, read-only)."""
    if beam.classical:
        b = be.eigenvalues(beam.end, n)**2
        values = be.mode_shapes(beam.end, n, list(xi))
    else:
        b, values, _ = timoshenko_modes.modes(
            beam, n, list(xi), b=_general_eigenvalues(beam, n))
    b.flags.writeable = values.flags.writeable = False
    return b, values


def dimensionless_modes(beam: timoshenko.Beam, n: int, xi):
    """b_j (n,) and X_j(xi) (n, len(xi)) of a dimensionless beam."""
    xi = tuple(float(v) for v in np.atleast_1d(xi))
    return _dimensionless_modes(beam, int(n), xi)


def modal_model(member: MemberBeam, n: int, x) -> ModalModel:
    """The first n modes of a member, valued at the points x (in)."""
    x = np.atleast_1d(np.asarray(x, dtype=np.float64))
    b, values = dimensionless_modes(member.dimensionless(), n,
                                    x / member.length)
    return ModalModel(p=b * member.frequency_scale, values=values,
                      mass=member.beam_mass)


def static_flexibility(beam: timoshenko.Beam, xi) -> np.ndarray:
    """G(xi) = y(a) EI/(F L^3) of a dimensionless beam (shear and
    supports included), closed form for the thesis's physics."""
    if beam.r2 == 0.0 and beam.s2 == 0.0 and beam.kr is None and \
            beam.kt is None:
        return be.static_flexibility(beam.end, xi)
    return timoshenko_static.static_flexibility(beam, xi)


def static_influence(beam: timoshenko.Beam, xi: float, eta: float) -> float:
    """G(xi, eta) = y(xi) EI/(F L^3) under a load at eta of a
    dimensionless beam (shear and supports included), closed form for
    the thesis's physics."""
    if beam.r2 == 0.0 and beam.s2 == 0.0 and beam.kr is None and \
            beam.kt is None:
        return float(be.static_influence(beam.end, xi, eta))
    return timoshenko_static.static_influence(beam, xi, eta)
