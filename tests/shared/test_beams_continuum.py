"""Perfect clamps on a 2-D continuum against the Timoshenko beam (issue 27:
"perfect clamps on an exact 2-D continuum stay within 1.4 % of
Timoshenko, so perfect clamps cannot explain the table").

The thesis's separators (aluminium, L2 = 2.5 in, d = 0.125 ... 0.75 in)
as plane-stress strips with both end faces fixed, by the tests' own
finite elements (tests/shared/plane_fe.py: biquadratic quadrilaterals,
consistent mass).  A conforming model with a consistent mass bounds each
eigenvalue from above, and refining the mesh lowers it; the change from
ny = 4 to 8 elements through the depth is 3 times the change from 8 to 16
(measured: 1.2e-3 then 3.9e-4 at d = 0.75 in; the clamped corners'
singularity keeps the rate below h^4), so the continuum's frequency lies
in [f8 - (f4 - f8), f8] (a rate of at least 2 assumed).  Measured with
ny = 16: the continuum is 0.14 % (d = 0.125) to 0.88 % (d = 0.75) above
the Timoshenko beam with Cowper's shear coefficient, about 1.4 % above it
with kappa = 5/6 at d = 0.75.
"""

from __future__ import annotations

import numpy as np
import plane_fe
import pytest

import contactsep

E, NU, GAMMA, GRAVITY = 10.0e6, 0.33, 0.100, 386.4
LENGTH = 2.5
THICKNESSES = (0.125, 0.25, 0.35, 0.5, 0.75)


def _continuum(depth, ny):
    nx = int(np.ceil(ny * LENGTH / depth))
    return plane_fe.clamped_strip_frequencies(
        LENGTH, depth, E, NU, GAMMA / GRAVITY, nx, ny)[0]


@pytest.mark.parametrize("depth", THICKNESSES)
def test_perfect_clamps_on_a_continuum_are_within_1_4_pct_of_timoshenko(
        depth):
    coarse, fine = _continuum(depth, 4), _continuum(depth, 8)
    assert fine < coarse                    # refining lowers the bound
    low, high = fine - (coarse - fine), fine
    design = contactsep.thesis_design(d=depth, beam2="timoshenko", nu2=NU)
    timoshenko = contactsep.modes(design, 2, 1).p_rad_s[0]
    for value in (low, high):
        assert abs(value / timoshenko - 1.0) < 0.014, (depth, value)
    # and the continuum tells the beam theories apart: Bernoulli-Euler
    # is 1.6 % (d = 0.125) to 48 % (d = 0.75) above it
    bernoulli = contactsep.modes(design.replace(beam2="bernoulli-euler"),
                                 2, 1).p_rad_s[0]
    assert bernoulli / high - 1.0 > 0.01


def test_a_slender_strip_is_the_published_clamped_beam():
    """The element itself: a strip 100 times longer than deep is a
    Bernoulli-Euler clamped-clamped beam, k1 L = 4.73004074 (Blevins
    1979, Table 8-1), less its small shear correction (-4e-4)."""
    depth = LENGTH / 100.0
    rho = GAMMA / GRAVITY
    beam = 4.73004074**2 * np.sqrt(E * depth**2 / 12.0 / rho) / LENGTH**2
    strip = plane_fe.clamped_strip_frequencies(LENGTH, depth, E, NU, rho,
                                               400, 2)[0]
    assert -1e-3 < strip / beam - 1.0 < 0.0
