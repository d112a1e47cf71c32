"""Beam physics shared by every layer: normal modes, frequencies and the
static flexibility of one uniform member.

One module per concern:

* :mod:`~contactsep.beams.bernoulli_euler`: the thesis's beams (rigid
  classical ends, no shear, no rotary inertia, no added mass), closed-form
  mode functions accurate to a few ulps for any mode number.  Its names
  (``eigenvalues``, ``alphas``, ``mode_shapes``, ``tip_values``,
  ``midspan_values``, ``static_flexibility``, ...) are re-exported here,
  unchanged.
* :mod:`~contactsep.beams.timoshenko`: the general beam (Timoshenko or
  Bernoulli-Euler, elastic supports, point masses) in dimensionless form,
  solved exactly by transfer matrices on [w, psi, M, Q]: its
  multiple-shooting system and frequency equation (the eigenvalues).
* :mod:`~contactsep.beams.timoshenko_modes`: the general beam's normal
  modes, normalised with the whole mass.
* :mod:`~contactsep.beams.timoshenko_static`: the general beam's static
  flexibility and influence (deflection under a point load).
* :mod:`~contactsep.beams.member`: a member in the design's units (in,
  lb, psi): its theory, supports and masses made dimensionless, and its
  modal model (frequencies in rad/s, mode values at given points).
"""

from contactsep.beams.bernoulli_euler import (  # noqa: F401
    ALIASES, END_CONDITIONS, SUPPORTS, _alpha_parts, _canonical, _check,
    _sigma_parts, alphas, eigenvalues, end_code, midspan_values,
    mode_shapes, residual_cross_flexibility, residual_flexibility, sigmas,
    static_flexibility, static_influence, tip_values)
