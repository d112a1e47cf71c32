"""Frequencies against the closed-form frequency equations of the
literature, solved here in 30-digit mpmath (issue 27 item 8).

No published table of Timoshenko (Huang 1961) or elastically restrained
(Rao and Mirza 1989; Grossi and Albarracin 2003) frequencies could be
found in a form to type in; their frequency equations are exact and
stand in for the tables:

* Huang's clamped-clamped Timoshenko beam: W = C1 cosh(a xi) + C2 sinh(a
  xi) + C3 cos(b xi) + C4 sin(b xi) below the cut-off frequency, with
  a^2, b^2 = [-/+ B^2 (r2 + s2) + sqrt(B^4 (r2 - s2)^2 + 4 B^2)] / 2 (B
  the dimensionless frequency), psi from W' - s2 Q;
* Rao and Mirza's Bernoulli-Euler beam elastically restrained against
  rotation (K_r = k_r L/EI) and translation (K_t = k_t L^3/EI) at both
  ends, and the cantilever with a restrained root.

Each root is bracketed by a scan of the determinant's sign (so its rank
is known) and refined by mpmath's bisection (Anderson-Bjorck), then
compared with the package's transfer-matrix eigenvalues b_j.
"""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

import contactsep
from contactsep.beams import timoshenko
from contactsep.model import physics

mp.mp.dps = 30


def _roots(det, top, count, step=0.02):
    """The first ``count`` sign changes of det(x) on (0, top], refined."""
    roots, x0, f0 = [], mp.mpf(step), det(mp.mpf(step))
    x = x0
    while len(roots) < count:
        x = x0 + step
        assert x < top, "fewer roots than asked below the scan's top"
        f = det(x)
        if f0 * f < 0:
            roots.append(mp.findroot(det, (x0, x), solver="anderson",
                                     tol=mp.mpf(10)**-28))
        x0, f0 = x, f
    return [float(r) for r in roots]


def _huang_clamped_clamped(r2, s2):
    """det of the clamped-clamped Timoshenko beam as a function of
    sqrt(B) (B = omega L^2 sqrt(rho A / EI))."""
    r2, s2 = mp.mpf(r2), mp.mpf(s2)

    def det(root_b):
        big = root_b**2
        disc = mp.sqrt(big**4 * (r2 - s2)**2 + 4 * big**2)
        a = mp.sqrt((-big**2 * (r2 + s2) + disc) / 2)
        b = mp.sqrt((big**2 * (r2 + s2) + disc) / 2)
        pa = a + big**2 * s2 / a          # psi of cosh(a xi) is pa sinh
        pb = b - big**2 * s2 / b          # psi of cos(b xi) is -pb sin
        m = mp.matrix([
            [1, 0, 1, 0],
            [0, pa, 0, pb],
            [mp.cosh(a), mp.sinh(a), mp.cos(b), mp.sin(b)],
            [pa * mp.sinh(a), pa * mp.cosh(a), -pb * mp.sin(b),
             pb * mp.cos(b)]])
        return mp.det(m) / mp.cosh(a)
    return det


def _rao_mirza(kr, kt, right="restrained"):
    """det of the Bernoulli-Euler beam W = C1 cosh + C2 sinh + C3 cos +
    C4 sin (k xi), as a function of k = sqrt(B): springs at the left end
    (Q = kt W, M = kr W': the support's force and moment), the right end
    restrained alike (Q = -kt W, M = -kr W') or free; M = W'', Q = -W'''."""
    kr, kt = mp.mpf(kr), mp.mpf(kt)

    def rows(k, x, sign):
        c, s, co, si = mp.cosh(k * x), mp.sinh(k * x), mp.cos(k * x), \
            mp.sin(k * x)
        w = [c, s, co, si]
        w1 = [k * s, k * c, -k * si, k * co]
        w2 = [k**2 * c, k**2 * s, -k**2 * co, -k**2 * si]
        w3 = [k**3 * s, k**3 * c, k**3 * si, -k**3 * co]
        shear = [-w3[i] - sign * kt * w[i] for i in range(4)]
        moment = [w2[i] - sign * kr * w1[i] for i in range(4)]
        return shear, moment, w2, w3

    def det(k):
        left = rows(k, 0, 1)
        if right == "free":
            far = rows(k, 1, 0)
            last = [far[2], far[3]]
        else:
            far = rows(k, 1, -1)
            last = [far[0], far[1]]
        m = mp.matrix([left[0], left[1], last[0], last[1]])
        return mp.det(m) / mp.cosh(k)
    return det


@pytest.mark.parametrize("depth", [0.125, 0.35, 0.75])
def test_timoshenko_clamped_clamped_is_huangs(depth):
    """The thesis's separators (L2 = 2.5 in, aluminium, Cowper's kappa)."""
    design = contactsep.thesis_design(d=depth, beam2="timoshenko")
    beam = physics.member_beam(design, "2").dimensionless()
    b = timoshenko.eigenvalues(beam, 3)
    assert b[-1]**2 * beam.r2 * beam.s2 < 1.0      # below the cut-off
    roots = _roots(_huang_clamped_clamped(beam.r2, beam.s2), 20.0, 3)
    np.testing.assert_allclose(b, np.square(roots), rtol=1e-11)


@pytest.mark.parametrize(("kr", "kt"), [(1.0, 1e9), (10.0, 100.0),
                                        (100.0, 1000.0), (1e9, 50.0)])
def test_elastically_restrained_beam_is_rao_and_mirzas(kr, kt):
    beam = timoshenko.Beam("clamped-clamped", kr=kr, kt=kt)
    b = timoshenko.eigenvalues(beam, 4)
    roots = _roots(_rao_mirza(kr, kt), 20.0, 4)
    np.testing.assert_allclose(b, np.square(roots), rtol=1e-11)


@pytest.mark.parametrize(("kr", "kt"), [(0.5, 1e9), (5.0, 20.0)])
def test_cantilever_with_a_restrained_root_is_rao_and_mirzas(kr, kt):
    beam = timoshenko.Beam("clamped-free", kr=kr, kt=kt)
    b = timoshenko.eigenvalues(beam, 3)
    roots = _roots(_rao_mirza(kr, kt, right="free"), 20.0, 3)
    np.testing.assert_allclose(b, np.square(roots), rtol=1e-11)
