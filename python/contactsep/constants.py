"""Constants every layer shares, one home each.

fortran/common/constants.f90 holds the same values for the compiled
layers (tests/shared/test_constants.py pins the two together).  Units are
the thesis's: inches, pounds (force), seconds.
"""

#: Acceleration of gravity, in/s^2: a weight becomes a mass, M = W/g
#: (Appendix B, g/(gamma A L) = 1/M; the listing's 386.4).
GRAVITY_IN_PER_S2 = 386.4

#: Cubic inches in a cubic foot: a deck's weight density in lb/ft^3
#: becomes lb/in^3 (the listing's RHOC = RHO/1728).
CUBIC_INCHES_PER_CUBIC_FOOT = 1728.0

#: End of the listing's lower-contact history, s (the listing's
#: TAU = 0.060): the window of every thesis study and simulation.
LISTING_TAU_S = 0.060
