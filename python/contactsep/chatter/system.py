"""The dynamical systems: each member's modes, seen at its contact point.

Model side of the Siconos split.  Member i has modal coordinates q_j with
generalised mass M_i (modes normalised to int X^2 dx = L, so the
generalised mass is the member's mass; with rotary inertia and a point
mass, normalised in the whole mass to the same M_i: contactsep.beams.
member) and frequencies p_j, of the member's beam theory, supports and
masses (contactsep.model.physics):

    M_i (q_j'' + p_j^2 q_j) = X_j(x_i) F_i,      y_i(x_i) = sum X_j(x_i) q_j,

F_i the contact force on member i at its contact point (positive up).
Displacements are positive UP for every member: the upper contact is
released from +y_s above the separator; the lower contact hangs below the
separator, touching it with zero preload (option: a preload, see
:func:`preload_state`); gravity is not applied (the thesis neglects it;
its static sag is a constant offset absorbed by the preload).
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass

import numpy as np

from contactsep import beams
from contactsep.beams import member as member_beams
from contactsep.model import Design, physics
from contactsep.model.contact_points import separator_points
from contactsep.model.twin import member_constants


@dataclass(frozen=True)
class Member:
    """One member's modal model at its contact point."""

    #: Circular frequencies p_j (rad/s).
    p: np.ndarray
    #: Mode values X_j(x_c) at the contact point.
    x: np.ndarray
    #: Generalised (= total) mass (lb s^2/in).
    mass: float
    #: Initial modal displacements q_j (in) and velocities (in/s).
    q0: np.ndarray
    v0: np.ndarray
    #: Residual flexibility (in/lb) of the modes past N at the contact
    #: point: G(x) L^3/(EI) minus the N-mode sum (the static correction's
    #: series spring, docs/chatter.md; :func:`beams.residual_flexibility`).
    residual: float = 0.0
    #: The separator only, where the lower contact touches it elsewhere
    #: than the upper one (Design.x2_lower): X_j there, the residual
    #: flexibility there and the residual cross flexibility between the
    #: two points (in/lb; :func:`beams.residual_cross_flexibility`).
    #: None: one contact point, ``x`` and ``residual`` serve both.
    x_lower: np.ndarray | None = None
    residual_lower: float = 0.0
    residual_cross: float = 0.0

    @property
    def lower_x(self) -> np.ndarray:
        """X_j where the lower contact touches (the separator), else x."""
        return self.x if self.x_lower is None else self.x_lower

    def energy(self, q, v) -> np.ndarray:
        """Kinetic + strain energy (in lb), for states (..., n)."""
        return 0.5 * self.mass * np.sum(v**2 + (self.p * q)**2, axis=-1)

    def displacement(self, q) -> np.ndarray:
        """y(x_c) = sum X_j q_j."""
        return q @ self.x


@functools.lru_cache(maxsize=256)
def _modes(end: str, n: int, xi: float):
    """k_jL and X_j(xi L) of an end condition (cached: a design sweep
    asks for the same few again and again; read-only arrays)."""
    kl = beams.eigenvalues(end, n)
    values = beams.mode_shapes(end, n, [xi])[:, 0]
    kl.flags.writeable = values.flags.writeable = False
    return kl, values


@functools.lru_cache(maxsize=256)
def _residual(end: str, n: int, xi: float) -> float:
    """r_N(xi), in units of L^3 / (EI) (cached as :func:`_modes`)."""
    return float(beams.residual_flexibility(end, n, xi)[0])


def _general(design: Design, i: str):
    """The member's dimensionless beam when its physics is not the
    thesis's (Timoshenko, elastic supports, a point mass), else None."""
    beam = physics.member_beam(design, i).dimensionless()
    classical = beam.classical
    return None if classical else beam


def _member(design: Design, i: str, n: int, q0=None) -> Member:
    member = _member_at(design, i, n, q0)
    if i != "2":
        return member
    x2, x2_lower = separator_points(design)
    if x2_lower == x2:
        return member
    return _two_points(design, member, n, x2, x2_lower)


def _two_points(design: Design, member: Member, n: int, x2: float,
                x2_lower: float) -> Member:
    """The separator seen at both contact points: the mode values, the
    residual flexibility at x2_lower and the residual cross flexibility
    G(x2, x2_lower) L^3/(EI) less the N-mode sum (the static
    correction's off-diagonal spring)."""
    general = _general(design, "2")
    spec = physics.member_beam(design, "2")
    scale = spec.length**3 / (float(design.E2) * spec.inertia)
    xi, eta = x2 / spec.length, x2_lower / spec.length
    if general is None:
        end = str(design.end2)
        values = _modes(end, n, eta)[1].copy()
        residual = _residual(end, n, eta) * scale
        cross = beams.residual_cross_flexibility(end, n, xi, eta) * scale
    else:
        model = member_beams.modal_model(spec, n, [x2_lower])
        values = model.values[:, 0].copy()
        stiff = model.mass * model.p**2
        residual = max(float(member_beams.static_flexibility(
            general, eta)) * scale - float(np.sum(values**2 / stiff)), 0.0)
        cross = member_beams.static_influence(general, xi, eta) * scale \
            - float(np.sum(member.x * values / stiff))
    return dataclasses.replace(member, x_lower=values,
                               residual_lower=float(residual),
                               residual_cross=float(cross))


def _member_at(design: Design, i: str, n: int, q0=None) -> Member:
    general = _general(design, i)
    if general is not None:
        x = getattr(design, "x" + i)
        spec = physics.member_beam(design, i)
        if x is None:
            x = spec.length / 2.0 if i == "2" else spec.length
        model = member_beams.modal_model(spec, n, [float(x)])
        q = np.zeros(n) if q0 is None else q0
        values = model.values[:, 0].copy()
        # the static correction's series spring: the exact flexibility
        # (shear, supports, masses: G is static, a mass adds none) less
        # the N-mode sum
        flexibility = float(member_beams.static_flexibility(
            general, float(x) / spec.length)) * spec.length**3 / (
            float(getattr(design, "E" + i)) * spec.inertia)
        residual = max(flexibility - float(np.sum(
            values**2 / (model.mass * model.p**2))), 0.0)
        return Member(p=model.p, x=values, mass=model.mass, q0=q,
                      v0=np.zeros(n), residual=residual)
    length = float(getattr(design, "L" + i))
    width = float(getattr(design, "b" + i))
    thick = float(getattr(design, "h" + i))
    gamma = float(getattr(design, "gamma" + i))
    modulus = float(getattr(design, "E" + i))
    end = getattr(design, "end" + i)
    x = getattr(design, "x" + i)
    if x is None:
        x = length / 2.0 if i == "2" else length
    mass, a = member_constants(length, width, thick, gamma, modulus)
    kl, values = _modes(str(end), n, float(x) / length)
    p = kl**2 * a / length**2
    q = np.zeros(n) if q0 is None else q0
    inertia = width * thick**3 / 12.0
    residual = _residual(str(end), n, float(x) / length) * length**3 / (
        modulus * inertia)
    return Member(p=p, x=values, mass=mass, q0=q, v0=np.zeros(n),
                  residual=residual)


def release_state(design: Design, n: int) -> np.ndarray:
    """Modal displacements of the released upper contact (Appendix A):
    the model's exact amplitudes A_j of the static shape."""
    end, length = design.end1, float(design.L1)
    x1 = length if design.x1 is None else float(design.x1)
    xi = 1.0 if (design.release == "tip" and end == "clamped-free") \
        else x1 / length
    general = _general(design, "1")
    if general is not None:
        b, load = member_beams.dimensionless_modes(general, n, [xi])
        return float(design.ys) * load[:, 0] / (
            b**2 * member_beams.static_flexibility(general, xi))
    kl, load = _modes(str(end), n, xi)
    return float(design.ys) * load / (kl**4
                                      * beams.static_flexibility(end, xi))


def members(design: Design) -> tuple[Member, Member, Member]:
    """The three members of a single design (upper, separator, lower)."""
    if design.shape != ():
        raise ValueError("chatter simulates one design at a time")
    n = design.n_modes
    n1, n2, n3 = (n, n, n) if not isinstance(n, tuple) else n
    upper = _member(design, "1", int(n1), release_state(design, int(n1)))
    return upper, _member(design, "2", int(n2)), _member(design, "3",
                                                          int(n3))


def flexibility(member: Member) -> float:
    """Static deflection per unit force at the contact point of the
    member's N-mode model, sum X_j^2 / (M p_j^2) (in/lb): the truncated
    model's own, so that the preloaded state is its exact equilibrium."""
    return float(np.sum(member.x**2 / (member.mass * member.p**2)))


def lower_flexibility(member: Member) -> float:
    """:func:`flexibility` where the lower contact touches the separator
    (x2_lower; the same as flexibility at one contact point)."""
    if member.x_lower is None:
        return flexibility(member)
    return float(np.sum(member.x_lower**2 / (member.mass * member.p**2)))


def series_matrix(upper: Member, separator: Member,
                  lower: Member) -> np.ndarray:
    """C = [[c1 + c2, -c2x], [-c2x, c2l + c3]] (in/lb): the gaps' quasi-
    static change per unit contact force from the members' residual
    flexibilities (the upper force pushes member 1 up and the separator
    down at x2, the lower one the separator up at x2_lower and member 3
    down).  c2 and c2l are the separator's residual flexibilities at x2
    and x2_lower, c2x its residual cross flexibility between them; at
    one contact point all three are c2."""
    c1, c2, c3 = upper.residual, separator.residual, lower.residual
    if separator.x_lower is None:
        return np.array([[c1 + c2, -c2], [-c2, c2 + c3]])
    c2l, c2x = separator.residual_lower, separator.residual_cross
    return np.array([[c1 + c2, -c2x], [-c2x, c2l + c3]])


def preload_state(separator: Member, lower: Member, force: float,
                  penetration: float = 0.0, static_correction=False):
    """Initial modal displacements and gap offsets with the lower contact
    pressed up against the separator by ``force`` (lb, >= 0).

    Static equilibrium of the N-mode models: the separator is pushed up,
    q_j = F X_j / (M p_j^2), the lower contact down by the same law.
    The lower gap's offset makes the contact exactly closed (Newton) or
    closed by ``penetration`` (Hertz: (F/k)^(2/3)); the upper gap's
    offset keeps the release height y_s measured from the separator as
    preloaded (the assembled rig), not from its unloaded position.
    With ``static_correction`` the contact points' deflections add the
    residual springs' F c_i: the exact F G(x) L^3/(EI) of a point load,
    and the offsets make the series law's force exactly F (the Hertz
    element's own penetration, docs/chatter.md).
    Where the lower contact touches the separator at x2_lower, the
    force acts there and the upper gap's offset is the separator's
    deflection at x2 (the cross flexibility: modes + residual spring).
    Returns (q_separator, q_lower, g0)."""
    if separator.x_lower is not None:
        return _preload_two_points(separator, lower, force, penetration,
                                   static_correction)
    q_sep = force * separator.x / (separator.mass * separator.p**2)
    q_low = -force * lower.x / (lower.mass * lower.p**2)
    lift = force * flexibility(separator)     # = sum X_j q_j, separator
    drop = -force * flexibility(lower)        # = sum X_j q_j, lower
    if static_correction:
        # the contact points' whole deflections: modes + residual springs
        lift = force * (flexibility(separator) + separator.residual)
        drop = -force * (flexibility(lower) + lower.residual)
    # closed beyond the round-off of h q + g0 (a gap of +1e-19 would leave
    # a rigid contact open for a step and start a rattle at rest)
    slack = 8.0 * np.finfo(float).eps * (abs(lift) + abs(drop))
    g0 = np.array([lift, -max(penetration, slack) - (lift - drop)])
    return q_sep, q_low, g0


def _preload_two_points(separator: Member, lower: Member, force: float,
                        penetration: float, static_correction: bool):
    """:func:`preload_state` with the lower contact at x2_lower: the
    separator's deflection there (``lift``) sets the lower gap, its
    deflection at x2 (``upper``) the upper gap's offset."""
    stiff = separator.mass * separator.p**2
    q_sep = force * separator.x_lower / stiff
    q_low = -force * lower.x / (lower.mass * lower.p**2)
    upper = force * float(np.sum(separator.x * separator.x_lower / stiff))
    lift = force * lower_flexibility(separator)
    drop = -force * flexibility(lower)
    if static_correction:
        upper += force * separator.residual_cross
        lift += force * separator.residual_lower
        drop -= force * lower.residual
    slack = 8.0 * np.finfo(float).eps * (abs(lift) + abs(drop))
    g0 = np.array([upper, -max(penetration, slack) - (lift - drop)])
    return q_sep, q_low, g0
