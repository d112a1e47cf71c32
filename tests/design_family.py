"""The family of designs every claim about designs is tested on (not the
thesis rig alone): from the thesis's 19-in aluminium rig to 1-in steel
and bronze relays, thick and thin separators, light and heavy contacts,
contact points off mid-span and off the tip.

Units: in, lb, s; weight densities lb/in^3; moduli psi.  Material
values: aluminium E = 10.0e6 psi, 0.100 lb/in^3 (the thesis); carbon
steel E = 30e6 psi, 0.283 lb/in^3; phosphor bronze E = 16e6 psi,
0.320 lb/in^3; beryllium copper E = 18.5e6 psi, 0.298 lb/in^3
(handbook values, e.g. MatWeb / ASM, rounded).

``FAMILY`` maps a short name to a :class:`contactsep.Design` (N = 4; use
``design.replace(n_modes=...)``).  ``UNSEEN`` holds designs kept out of
every default-setting study, for "designs the tests never saw" checks.
"""

from __future__ import annotations

from contactsep.model import Design, thesis_design

STEEL = dict(E=30.0e6, gamma=0.283)
BRONZE = dict(E=16.0e6, gamma=0.320)
BERYLLIUM_COPPER = dict(E=18.5e6, gamma=0.298)


def _materials(upper: dict, separator: dict, lower: dict) -> dict:
    return {"E1": upper["E"], "gamma1": upper["gamma"],
            "E2": separator["E"], "gamma2": separator["gamma"],
            "E3": lower["E"], "gamma3": lower["gamma"]}


def relay(length, width, thick, sep_length, sep_width, sep_thick, ys, *,
          contacts=STEEL, separator=STEEL, e=0.5, **fields) -> Design:
    """A relay of two equal cantilever contacts on a clamped-clamped
    separator (contact points at the tips and mid-span unless given)."""
    return Design(L1=length, b1=width, h1=thick, L3=length, b3=width,
                  h3=thick, L2=sep_length, b2=sep_width, h2=sep_thick,
                  ys=ys, e=e, **_materials(contacts, separator, contacts),
                  **fields)


FAMILY = {
    # the thesis rig: 19 x 2 x 0.125 in aluminium, separator d = 0.25 in
    "thesis": thesis_design(d=0.25),
    # the thesis rig's thinnest and thickest separators
    "thesis_thin": thesis_design(d=0.125),
    "thesis_thick": thesis_design(d=0.75),
    # issue 25's small steel relay
    "steel_relay": relay(1.2, 0.25, 0.01, 0.3, 0.1, 0.05, 0.02),
    # a bronze relay, thin separator, contacts off the tip and the
    # separator's contact point off mid-span
    "bronze_offset": relay(1.0, 0.2, 0.008, 0.25, 0.08, 0.02, 0.015,
                           contacts=BRONZE, separator=BRONZE,
                           x1=0.95, x2=0.1, x3=0.9),
    # a steel relay with a thick (stubby) separator, heavy contacts
    "steel_thick": relay(1.0, 0.3, 0.02, 0.3, 0.1, 0.09, 0.02, e=0.4),
    # light beryllium-copper contacts on a thin bronze separator, lower
    # contact touching off the tip
    "becu_light": relay(1.5, 0.15, 0.006, 0.4, 0.1, 0.03, 0.03,
                        contacts=BERYLLIUM_COPPER, separator=BRONZE,
                        x3=1.2),
}

#: Kept out of every study that sets a default (see the module doc).
UNSEEN = {
    "brass_mid": relay(0.8, 0.2, 0.012, 0.35, 0.12, 0.06, 0.025,
                       contacts=dict(E=15.0e6, gamma=0.307),
                       separator=STEEL, x2=0.14, x3=0.72),
    "thesis_offset": thesis_design(d=0.35, x2=0.8, x3=0.78 * 19.0),
}
