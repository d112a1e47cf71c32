"""The contact laws with their energy books (docs/chatter.md, "Contact
laws" and "Energy book"): Newton's impact law, the Hertz family's force
law (:class:`HertzLaw`) and the contacts' memory under it
(:class:`ContactMemory`: Thornton's unloading curves and plastic work),
and the energy book of a run (:func:`energy_book`).  The checks of
their settings are in :mod:`contactsep.chatter.settings`, the
contact-force solves in :mod:`contactsep.chatter.contacts`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class NewtonImpactLaw:
    """Newton's impact law with restitution e: at a closing contact
    0 <= u+ + e u- complementary to the impulse P >= 0 (velocity level)."""

    e: float


@dataclass(frozen=True)
class HertzLaw:
    """A contact force law of the Hertz family (docs/chatter.md, "Contact
    laws"): F = F_e (1 + chi delta'), F >= 0, with F_e = k delta^{3/2},
    k = (4/3) E* sqrt(R), E* = E / (2 (1 - nu^2)) (two equal materials);
    chi = 0 (elastic), Flores et al. 8 (1 - e) / (5 e V_ref) (calibrated
    to e), or Hunt and Crossley's alpha (a material constant).  With a
    yield pressure p_y > 0, F_e is Thornton's elastic-perfectly-plastic
    law (:class:`ContactMemory`; twin of fortran/chatter/contact_law.f90).
    """

    k: float
    chi: float = 0.0
    #: Thornton: the yield pressure (psi; 0: elastic Hertz), the
    #: effective modulus E* (psi) and the button radius R (in).
    yield_pressure: float = 0.0
    e_star: float = 0.0
    radius: float = 0.0
    #: A line contact (a cylindrical button): F_e = k delta with k =
    #: (pi/4) E* L (lb/in), L the cylinder's length.
    linear: bool = False

    @classmethod
    def for_materials(cls, modulus, nu=0.33, radius=0.125, *, e=None,
                      v_ref=None, alpha=None, yield_pressure=None,
                      button="sphere", length=None):
        """k from the materials; chi from e and V_ref when both given
        (Flores), or alpha (Hunt-Crossley, s/in); Thornton's law with a
        yield pressure (psi); a cylindrical ``button`` of ``length`` (in;
        default its diameter 2R) a line contact."""
        e_star = modulus / (2.0 * (1.0 - nu**2))
        k = 4.0 / 3.0 * e_star * np.sqrt(radius)
        linear = button == "cylinder"
        if linear:
            k = math.pi / 4.0 * e_star * (2.0 * radius if length is None
                                          else length)
        chi = 0.0
        if e is not None and v_ref is not None:
            if not 0.0 < e <= 1.0 or not v_ref > 0.0:
                raise ValueError("Flores damping needs 0 < e <= 1 and "
                                 "V_ref > 0")
            chi = 8.0 * (1.0 - e) / (5.0 * e * v_ref)
        if alpha is not None:
            chi = float(alpha)
        pressure = 0.0 if yield_pressure is None else float(yield_pressure)
        return cls(k=float(k), chi=chi, yield_pressure=pressure,
                   e_star=float(e_star), radius=float(radius),
                   linear=linear)

    @property
    def exponent(self) -> float:
        """n of F_e = k delta^n: 3/2 (sphere), 1 (cylinder)."""
        return 1.0 if self.linear else 1.5

    @property
    def plastic(self) -> bool:
        """Thornton's law (a yield pressure given)."""
        return self.yield_pressure > 0.0

    @property
    def yield_depth(self) -> float:
        """delta_y = (pi p_y / (2 E*))^2 R (in): where the largest Hertz
        pressure reaches p_y (inf for the elastic law)."""
        if not self.plastic:
            return math.inf
        return (math.pi * self.yield_pressure / (2.0 * self.e_star))**2 \
            * self.radius

    def envelope(self, depth: float) -> float:
        """The loading force (lb) at a new largest penetration (in)."""
        if depth <= 0.0:
            return 0.0
        if self.linear:
            return self.k * depth
        yield_depth = self.yield_depth
        if depth <= yield_depth:
            return self.k * depth**1.5
        return self.k * yield_depth**1.5 + math.pi * self.yield_pressure \
            * self.radius * (depth - yield_depth)

    def depth_at(self, force: float) -> float:
        """The penetration (in) at which the loading envelope carries
        ``force`` (lb): the preloaded contact's static depth."""
        if force <= 0.0:
            return 0.0
        if self.linear:
            return force / self.k
        yield_depth = self.yield_depth
        if force <= self.k * yield_depth**1.5:
            return (force / self.k) ** (2.0 / 3.0)
        return yield_depth + (force - self.k * yield_depth**1.5) / (
            math.pi * self.yield_pressure * self.radius)

    def force(self, gap, gap_rate):
        """Contact force (lb) for gaps (in) and their rates (in/s) of the
        elastic law (Thornton's needs its memory: ContactMemory)."""
        delta = np.maximum(-gap, 0.0)
        force = self.k * delta**self.exponent * (1.0 + self.chi
                                                 * (-gap_rate))
        return np.where(delta > 0.0, np.maximum(force, 0.0), 0.0)

    def energy(self, gap):
        """Elastic energy k delta^{n+1} / (n + 1) (in lb) of the elastic
        law ((2/5) k delta^{5/2} for a sphere)."""
        delta = np.maximum(-gap, 0.0)
        if self.linear:
            return 0.5 * self.k * delta**2
        return 0.4 * self.k * delta**2.5


class ContactMemory:
    """The state of k contacts under a :class:`HertzLaw`: each one's
    largest penetration, and Thornton's unloading curve from it (the
    elastic Hertz law with the enlarged radius R_p = 4 E* a_m^3 / (3 F_m),
    a_m^2 = R delta_m, from the plastic offset delta_p = delta_m -
    a_m^2 / R_p) and plastic work (the envelope's work to delta_m less
    the (2/5) F_m (delta_m - delta_p) unloading gives back).  Twin of
    fortran/chatter/contact_law.f90."""

    def __init__(self, law: HertzLaw, k: int):
        self.law = law
        self.depth_max = [0.0] * k
        self.unload_k = [0.0] * k
        self.offset = [0.0] * k
        self.work = [0.0] * k

    def remember(self, c: int, depth: float) -> None:
        """A penetration of contact c (in): a new largest one moves its
        unloading curve and plastic work."""
        law = self.law
        if not law.plastic or not depth > self.depth_max[c]:
            return
        self.depth_max[c] = depth
        yield_depth = law.yield_depth
        if depth <= yield_depth:
            return
        a2 = law.radius * depth
        force = law.envelope(depth)
        r_p = 4.0 * law.e_star * a2 * math.sqrt(a2) / (3.0 * force)
        self.unload_k[c] = 4.0 / 3.0 * law.e_star * math.sqrt(r_p)
        self.offset[c] = depth - a2 / r_p
        over = depth - yield_depth
        f_y = law.k * yield_depth**1.5
        loading = 0.4 * f_y * yield_depth + f_y * over + 0.5 * math.pi \
            * law.yield_pressure * law.radius * over**2
        self.work[c] = loading - 0.4 * force * (depth - self.offset[c])

    def elastic_force(self, c: int, depth: float) -> float:
        """F_e (lb) of contact c at penetration ``depth`` (in)."""
        law = self.law
        if not depth > 0.0:
            return 0.0
        if not law.plastic or depth >= self.depth_max[c] or \
                self.depth_max[c] <= law.yield_depth:
            return law.envelope(depth)
        over = depth - self.offset[c]
        return self.unload_k[c] * over**1.5 if over > 0.0 else 0.0

    def elastic_slope(self, c: int, depth: float) -> float:
        """dF_e/d delta (lb/in) of contact c at ``depth`` (in), on the
        branch :meth:`elastic_force` takes there."""
        law = self.law
        if not depth > 0.0:
            return 0.0
        if not law.plastic or depth >= self.depth_max[c] or \
                self.depth_max[c] <= law.yield_depth:
            if law.linear:
                return law.k
            if depth <= law.yield_depth:
                return 1.5 * law.k * math.sqrt(depth)
            return math.pi * law.yield_pressure * law.radius
        over = depth - self.offset[c]
        return 1.5 * self.unload_k[c] * math.sqrt(over) if over > 0.0 \
            else 0.0

    def force(self, c: int, depth: float, rate: float) -> float:
        """F = max(F_e (1 - chi rate), 0), rate the gap's (in/s)."""
        force = self.elastic_force(c, depth)
        if self.law.chi != 0.0 and force > 0.0:
            force = max(force * (1.0 - self.law.chi * rate), 0.0)
        return force

    def energy(self, c: int, depth: float) -> float:
        """The elastic energy contact c stores (in lb), (2/5) F_e (delta
        - delta_p); past the memory, of the unloading curve from delta."""
        if not depth > 0.0:
            return 0.0
        if not self.law.plastic:
            return float(self.law.energy(-depth))
        law = self.law
        offset = self.offset[c] if self.depth_max[c] > \
            law.yield_depth else 0.0
        if depth > self.depth_max[c] and depth > law.yield_depth:
            # ahead of the memory: the unloading curve from this depth
            a2 = law.radius * depth
            r_p = 4.0 * law.e_star * a2 * math.sqrt(a2) / (
                3.0 * law.envelope(depth))
            offset = depth - a2 / r_p
        return 0.4 * self.elastic_force(c, depth) * max(depth - offset,
                                                         0.0)

    def plastic_work(self) -> float:
        """The plastic work of every contact so far (in lb)."""
        return float(sum(self.work)) if self.law.plastic else 0.0


def energy_book(run, stack, parts) -> dict:
    """The Hertz family's energy book (docs/chatter.md, "Energy book"):
    the energy at the start, the contacts' dissipation (summed by the
    stepper), the vibration energy left in each member's modes and the
    contacts' stored energy at the end (in lb); empty for Newton."""
    if not run.book:
        return {}
    q, v = run.book["q"], run.book["v"]
    modal = 0.5 * stack.m * (v**2 + (stack.p * q)**2)
    ends = np.cumsum([0] + [member.p.size for member in parts])
    return {"energy_initial_lbin": float(run.energy[0]),
            "energy_dissipated_contact_lbin": float(run.book["dissipated"]),
            **{f"energy_member{i + 1}_lbin": float(modal[ends[i]:ends[i + 1]]
                                                   .sum()) for i in range(3)},
            "energy_contact_lbin": float(run.book["stored"])}
