"""A deck data set (Appendix G) as a Design, and back where meaningful.

The deck gives weight densities in lb/ft^3 (the listing divides by 1728)
and one Young's modulus for all three members; its members are always a
cantilever touched at the tip, a clamped-clamped separator touched at
mid-span and a cantilever touched at the tip; DELY is the gap; XL2C the
equivalent separator length.  DELT (the listing's time step) has no
counterpart in the model, which finds t1 and the extremes exactly.
"""

from __future__ import annotations

import numpy as np

from contactsep.constants import CUBIC_INCHES_PER_CUBIC_FOOT as IN3_PER_FT3
from contactsep.constants import LISTING_TAU_S
from contactsep.model.design import Design, DesignError
from contactsep.restored.dataset import computed_data_set

#: The listing's time step (s), used when a design becomes a deck.
DECK_TIME_STEP = 0.0005
_ENDS = ("clamped-free", "clamped-clamped", "clamped-free")


# "DataSet" is contactsep.restored.dataset.DataSet, named and not imported:
# the model reaches the restoration through computed_data_set alone
# (tests/project/test_layers.py).
def design_from_data_set(data_set: "DataSet",  # noqa: F821
                         *, listing: bool = True
                         ) -> Design:
    """The design of a deck data set.  ``listing=True`` also takes the
    listing's readings (ACT without sin, the hybrid L_c mass), so the
    model reproduces the listing's EY, TY2DT and TY3.  The lower response
    is eq. 13 as printed either way (the deck is the thesis's program's
    input)."""
    ds = data_set
    options = dict(impact_velocity="listing", lc_reading="listing") \
        if listing else {}
    return Design(
        L1=ds.xl, b1=ds.b, h1=ds.h, gamma1=ds.rho / IN3_PER_FT3, E1=ds.e,
        L2=ds.xl2, b2=ds.b2, h2=ds.h2, gamma2=ds.rho2 / IN3_PER_FT3, E2=ds.e,
        Lc=ds.xl2c, L3=ds.xl3, b3=ds.b3, h3=ds.h3,
        gamma3=ds.rho3 / IN3_PER_FT3, E3=ds.e, ys=ds.ystat, e=ds.er,
        n_modes=ds.n, gap=ds.dely, lower_response="as-printed", **options)


def data_set_from_design(design: Design, *,
                         time_step: float = DECK_TIME_STEP
                         ) -> "DataSet":  # noqa: F821
    """The deck data set of a single design that the listing can run:
    one E, the thesis's end conditions, tip and mid-span contacts, one N,
    tau = 0.060 s.  Mode cards are computed
    (:func:`contactsep.restored.dataset.computed_data_set`)."""
    if design.shape != ():
        raise DesignError("a deck holds one design: this one is a batch")
    d = design
    if not (d.E1 == d.E2 == d.E3):
        raise DesignError("E1, E2, E3: a deck has one Young's modulus")
    if (d.end1, d.end2, d.end3) != _ENDS:
        raise DesignError("end1, end2, end3: a deck's members are "
                          "clamped-free, clamped-clamped, clamped-free")
    for name, default in (("x1", d.L1), ("x2", 0.5 * d.L2), ("x3", d.L3)):
        value = getattr(d, name)
        if value is not None and value != default:
            raise DesignError(f"{name}: a deck's contacts are at the tips "
                              f"and mid-span")
    if d.x2_lower is not None and d.x2_lower != 0.5 * d.L2:
        raise DesignError("x2_lower: a deck's contacts are at the tips "
                          "and mid-span")
    if not isinstance(d.n_modes, (int, np.integer)):
        raise DesignError("n_modes: a deck has one N for all members")
    if d.tau != LISTING_TAU_S:
        raise DesignError("tau: the listing's window is 0.060 s")
    return computed_data_set(
        int(d.n_modes),
        xl=float(d.L1), b=float(d.b1), h=float(d.h1),
        rho=float(d.gamma1) * IN3_PER_FT3, ystat=float(d.ys),
        xl2=float(d.L2), b2=float(d.b2), h2=float(d.h2),
        rho2=float(d.gamma2) * IN3_PER_FT3,
        xl3=float(d.L3), b3=float(d.b3), h3=float(d.h3),
        rho3=float(d.gamma3) * IN3_PER_FT3,
        delt=time_step, er=float(d.e), dely=float(d.gap), e=float(d.E1),
        xl2c=float(d.L2 if d.Lc is None else d.Lc))
