"""A member's normal modes for a design: ``contactsep.modes(design,
member, count)`` and ``contactsep modes``.

The member's beam theory, supports and added mass are the design's
(:mod:`contactsep.model.physics`); the frequencies are p_j (rad/s) and
f_j = p_j / 2 pi (cps), the mode values X_j those at the member's contact
point (the upper contact's x1, the separator's x2, which both contacts
strike, and its x2_lower where the lower contact touches elsewhere, the
lower contact's x3), normalised as every mode of the package
(:mod:`contactsep.beams.member`: generalised mass = the bare member's
mass).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactsep.beams import member as member_beams
from contactsep.beams.timoshenko import MAX_GENERAL_MODES
from contactsep.errors import InputError
from contactsep.model import physics
from contactsep.model.contact_points import lower_point_differs
from contactsep.model.design import MAX_MODES, Design

#: The members by number.
MEMBERS = {1: "upper contact", 2: "separator", 3: "lower contact"}


@dataclass(frozen=True)
class Modes:
    """The first modes of one member of one design."""

    #: 1, 2 or 3.
    member: int
    #: "bernoulli-euler" or "timoshenko".
    theory: str
    #: The contact point(s) (in from the member's x = 0).
    x_in: tuple
    #: Circular frequencies p_j (rad/s), (count,).
    p_rad_s: np.ndarray
    #: Frequencies f_j (cps), (count,).
    f_hz: np.ndarray
    #: X_j at the contact point(s), (count, len(x_in)): the separator's
    #: upper contact point x2, then x2_lower where the lower contact
    #: touches elsewhere.
    values: np.ndarray
    #: Generalised mass of each mode, the bare member's (lb s^2/in).
    mass_lb_s2_in: float

    def to_json_dict(self) -> dict:
        """Plain types, keys with their units."""
        return {"member": self.member, "member_name": MEMBERS[self.member],
                "theory": self.theory, "x_in": list(self.x_in),
                "mass_lb_s2_in": self.mass_lb_s2_in,
                "p_rad_s": self.p_rad_s.tolist(),
                "f_hz": self.f_hz.tolist(),
                "X_contact": self.values.tolist()}


class ModesError(InputError):
    """A member number or a count modes cannot take."""


def modes(design: Design, member: int, count: int | None = None) -> Modes:
    """The first ``count`` modes of member 1, 2 or 3 of a single design
    (count default: the design's n_modes for that member)."""
    if not isinstance(design, Design):
        raise ModesError(f"design: expected a contactsep.Design, found "
                         f"{type(design).__name__}")
    if design.shape != ():
        raise ModesError("modes takes one design, not a batch")
    if isinstance(member, bool) or member not in MEMBERS:
        raise ModesError(f"member: found {member!r}, expected 1, 2 or 3")
    m = str(member)
    spec = physics.member_beam(design, m)
    classical = spec.dimensionless().classical
    if count is None:
        n = design.n_modes
        count = int(n[member - 1] if isinstance(n, tuple) else n)
    limit = MAX_MODES if classical else MAX_GENERAL_MODES
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) \
            or not 1 <= count <= limit:
        raise ModesError(f"count: found {count!r}, expected an integer "
                         f"from 1 to {limit:,}"
                         + ("" if classical else " (a Timoshenko beam, "
                            "elastic supports or a point mass)"))
    x = getattr(design, "x" + m)
    if x is None:
        x = spec.length / 2.0 if m == "2" else spec.length
    points = [float(x)]
    if m == "2" and lower_point_differs(design):
        points.append(float(design.x2_lower))
    model = member_beams.modal_model(spec, int(count), points)
    return Modes(member=int(member), theory=spec.theory,
                 x_in=tuple(points), p_rad_s=np.array(model.p),
                 f_hz=np.array(model.f_hz), values=np.array(model.values),
                 mass_lb_s2_in=float(model.mass))
