"""Named material presets (issue 28, item 5: the thesis's recommendation
4, the materials of the contacts and the separator): steel, brass,
beryllium copper, aluminium and (a relay contact spring's alloy)
phosphor bronze.

A preset fills a member's Young's modulus ``E``, weight density
``gamma`` and Poisson's ratio ``nu`` (``--material2 steel`` on the
command line, ``"material2": "steel"`` in a design file, ``--material``
for all three members; :func:`material_fields`).  Its yield strength
and the contact yield pressure drawn from it are for the contact laws
that take one (Thornton's elastic-perfectly-plastic contact).

Values (docs/model.md, "Material presets", gives them with their
sources): handbook room-temperature values of one common alloy and
temper of each, rounded to three significant digits.
"""

from __future__ import annotations

from dataclasses import dataclass

from contactsep.errors import InputError

#: Peak Hertz pressure at first yield over the yield strength Y, p0 =
#: 1.60 Y (a sphere on a flat, von Mises, nu = 0.3: K. L. Johnson,
#: Contact Mechanics, Cambridge 1985, section 6.2, eq. 6.9).
YIELD_PRESSURE_FACTOR = 1.60


@dataclass(frozen=True)
class Material:
    """One material preset (units of the package: psi, lb/in^3)."""

    #: The preset's name.
    name: str
    #: The alloy and temper the values are of.
    alloy: str
    #: Young's modulus (psi).
    E_psi: float
    #: Weight density (lb/in^3).
    gamma_lb_in3: float
    #: Poisson's ratio.
    nu: float
    #: Tensile yield strength, 0.2 % offset (psi).
    yield_strength_psi: float

    @property
    def yield_pressure_psi(self) -> float:
        """The peak contact pressure at first yield (psi):
        :data:`YIELD_PRESSURE_FACTOR` times the yield strength."""
        return YIELD_PRESSURE_FACTOR * self.yield_strength_psi


#: The presets by name (sources: docs/model.md, "Material presets").
MATERIALS = {
    "steel": Material("steel", "carbon steel AISI 1020, cold drawn",
                      29.7e6, 0.284, 0.29, 51.0e3),
    "brass": Material("brass", "cartridge brass C26000, half hard",
                      16.0e6, 0.308, 0.375, 52.0e3),
    "beryllium-copper": Material(
        "beryllium-copper", "beryllium copper C17200, TH04 "
        "(precipitation hardened)", 18.5e6, 0.298, 0.30, 140.0e3),
    "aluminium": Material("aluminium", "aluminium 6061-T6", 10.0e6, 0.0975,
                          0.33, 40.0e3),
    # the relay contact-spring alloy; Olin Brass's C51000 (ASTM B103)
    # data sheet: E = 16,000,000 psi (110 kN/mm^2), density 0.320 lb/in^3
    # (8.86 g/cm^3) at 68 F, spring hard yield 100 ksi (nominal); the
    # CDA alloy C510 figures suppliers reproduce give the same E (16,000
    # ksi) and density; neither gives Poisson's ratio: 0.34 is
    # MakeItFrom's C51000 entry
    "phosphor-bronze": Material(
        "phosphor-bronze", "phosphor bronze C51000 (5 % Sn), spring "
        "temper H08", 16.0e6, 0.320, 0.34, 100.0e3),
}
#: The presets of the materials study's grid: the four of its committed
#: rows (a preset added later is for designs, not a new study).
STUDY_MATERIALS = ("steel", "brass", "beryllium-copper", "aluminium")
#: Other spellings of a preset's name.
ALIASES = {"aluminum": "aluminium", "becu": "beryllium-copper",
           "beryllium_copper": "beryllium-copper",
           "phosphor_bronze": "phosphor-bronze",
           "c51000": "phosphor-bronze", "c510": "phosphor-bronze"}


class MaterialError(InputError):
    """A material name that is not a preset."""


def material(name: str) -> Material:
    """The preset ``name`` (or an alias: aluminum, becu), or a
    :class:`MaterialError` naming the presets."""
    key = name.strip().lower() if isinstance(name, str) else None
    key = ALIASES.get(key, key)
    if key not in MATERIALS:
        raise MaterialError(f"found {name!r}, expected one of "
                            f"{', '.join(MATERIALS)}")
    return MATERIALS[key]


def material_fields(name: str, members: str = "123") -> dict:
    """The Design fields a preset fills for ``members`` ("1", "2", "3" or
    several): E, gamma and nu of each.

    Examples
    --------
    >>> material_fields("steel", "2")
    {'E2': 29700000.0, 'gamma2': 0.284, 'nu2': 0.29}
    """
    preset = material(name)
    out = {}
    for m in members:
        out.update({f"E{m}": preset.E_psi, f"gamma{m}": preset.gamma_lb_in3,
                    f"nu{m}": preset.nu})
    return out
