"""The members' beam physics in a Design (issue 27): beam theory,
Poisson's ratio, shear coefficient, elastic supports and point masses,
checked, and made into each member's :class:`~contactsep.beams.member.
MemberBeam`.  Functions take a Design (duck-typed: this module sits below
design.py)."""

from __future__ import annotations

import numpy as np

from contactsep.beams.member import DEFAULT_NU, THEORIES, MemberBeam

#: The beam physics fields of each member, and their defaults.
PHYSICS_FIELDS = ("beam", "nu", "kappa", "kr", "kt", "mass", "x_mass")
PHYSICS_DEFAULTS = {"beam": THEORIES[0], "nu": DEFAULT_NU, "kappa": None,
                    "kr": None, "kt": None, "mass": 0.0, "x_mass": None}


def problem(design) -> str | None:
    """The first wrong beam physics field (one scalar value per Design),
    as one line; None when all are good."""
    for m in "123":
        end = np.asarray(getattr(design, f"end{m}"))
        for kind in PHYSICS_FIELDS:
            name = f"{kind}{m}"
            value = getattr(design, name)
            if kind == "beam":
                if not isinstance(value, str) or value not in THEORIES:
                    return (f"{name}: found {value!r}, expected one of "
                            f"{', '.join(THEORIES)}")
                continue
            if value is None and PHYSICS_DEFAULTS[kind] is None:
                continue
            if isinstance(value, (bool, str)) or np.ndim(value) != 0 or \
                    np.asarray(value).dtype.kind not in "iuf":
                return (f"{name}: found {value!r}, expected one number "
                        f"(shared by a batch)")
            value = float(value)
            expected = {
                "nu": ("-1 < nu < 0.5", -1.0 < value < 0.5),
                "kappa": ("a finite number > 0 (or None: Cowper's)",
                          np.isfinite(value) and value > 0.0),
                "kr": ("a finite stiffness > 0 lb in/rad (or None: rigid)",
                       np.isfinite(value) and value > 0.0),
                "kt": ("a finite stiffness > 0 lb/in (or None: rigid)",
                       np.isfinite(value) and value > 0.0),
                "mass": ("a finite weight >= 0 lb",
                         np.isfinite(value) and value >= 0.0),
                "x_mass": ("a finite position in the member (or None: "
                           "the contact point)",
                           np.isfinite(value) and value >= 0.0)}[kind]
            if not expected[1]:
                return f"{name}: found {value!r}, expected {expected[0]}"
            if kind == "kr" and np.all(end == "pinned-pinned"):
                return (f"{name}: found {value!r}, but end{m} is "
                        f"pinned-pinned (no clamped end to make elastic)")
            if kind == "x_mass" and end.ndim == 0:
                length = np.asarray(getattr(design, f"L{m}"))
                if length.ndim == 0 and value > float(length):
                    return (f"{name}: found {value!r}, expected 0 <= "
                            f"{name} <= L{m} = {float(length):.6g} in")
    return None


def physics_changes(design) -> list[tuple[str, object]]:
    """The beam physics fields that differ from the thesis's
    (Bernoulli-Euler, rigid ends, no mass), as (field, value)."""
    changed = []
    for m in "123":
        if getattr(design, f"beam{m}") != THEORIES[0]:
            changed.append((f"beam{m}", getattr(design, f"beam{m}")))
        for kind in ("kr", "kt"):
            if getattr(design, f"{kind}{m}") is not None:
                changed.append((f"{kind}{m}", getattr(design, kind + m)))
        if getattr(design, f"mass{m}"):
            changed.append((f"mass{m}", getattr(design, f"mass{m}")))
    return changed


def member_beam(design, member: str) -> MemberBeam:
    """Member ``member`` ("1", "2" or "3") of a single design as a
    :class:`~contactsep.beams.member.MemberBeam`; the point mass sits at
    the contact point unless x_mass says otherwise."""
    m = str(member)

    def get(name):
        return getattr(design, name + m)

    x_mass = get("x_mass")
    if x_mass is None and get("mass"):
        x = get("x")
        length = float(get("L"))
        x_mass = (length / 2.0 if m == "2" else length) if x is None \
            else float(x)
    return MemberBeam(
        length=float(get("L")), width=float(get("b")),
        thickness=float(get("h")), gamma=float(get("gamma")),
        modulus=float(get("E")), end=str(get("end")), theory=get("beam"),
        nu=float(get("nu")),
        kappa=None if get("kappa") is None else float(get("kappa")),
        kr=None if get("kr") is None else float(get("kr")),
        kt=None if get("kt") is None else float(get("kt")),
        mass=float(get("mass")),
        x_mass=None if x_mass is None else float(x_mass))
