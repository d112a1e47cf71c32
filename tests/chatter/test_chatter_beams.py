"""The chatter models with any member's beam physics (issue 27): the
modal models come from contactsep.beams, the thesis's stay as they were,
and the release and the impact speed agree with independent paths."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

import contactsep
from contactsep import beams
from contactsep.chatter import system
from contactsep.chatter.single_impulse import modal_impact_speed
from contactsep.model.twin import member_constants

#: The module (contactsep.chatter.simulate is also the function's name).
sim = importlib.import_module("contactsep.chatter.simulate")


def test_thesis_members_are_the_closed_form_modes():
    design = contactsep.thesis_design(n_modes=6)
    upper, separator, lower = system.members(design)
    mass, a = member_constants(2.5, 0.5, 0.25, 0.1, 10.0e6)
    kl = beams.eigenvalues("clamped-clamped", 6)
    assert np.array_equal(separator.p, kl**2 * a / 2.5**2)
    assert np.array_equal(separator.x,
                          beams.mode_shapes("clamped-clamped", 6, [0.5])[:, 0])
    assert separator.mass == mass


def test_timoshenko_separator_member_is_its_modes():
    design = contactsep.thesis_design(d=0.75, beam2="timoshenko",
                                      kr2=3000.0, mass2=0.01, n_modes=5)
    _, separator, _ = system.members(design)
    modes = contactsep.modes(design, 2, 5)
    np.testing.assert_array_equal(separator.p, modes.p_rad_s)
    np.testing.assert_array_equal(separator.x, modes.values[:, 0])
    # generalised mass: the bare beam's, not the beam's plus the sensor's
    assert separator.mass == pytest.approx(0.1 * 0.5 * 0.75 * 2.5 / 386.4,
                                           rel=1e-14)
    # the mid-span mass lowers the symmetric modes (Rayleigh) and leaves
    # the antisymmetric ones, whose node it sits on
    bare = contactsep.modes(design.replace(mass2=0.0), 2, 5)
    symmetric = np.abs(bare.values[:, 0]) > 1e-6
    assert np.all(modes.p_rad_s[symmetric] < bare.p_rad_s[symmetric])
    np.testing.assert_allclose(modes.p_rad_s[~symmetric],
                               bare.p_rad_s[~symmetric], rtol=1e-12)


def test_release_of_an_elastic_timoshenko_contact_converges_to_ys():
    """sum X_j(L) q_j -> y_s as N grows: the modal amplitudes and the
    static flexibility G (with the root's springs) are one physics."""
    errors = []
    for n in (4, 12, 30):
        design = contactsep.thesis_design(beam1="timoshenko", kr1=3000.0,
                                          kt1=2e4, n_modes=n)
        upper = system.members(design)[0]
        errors.append(abs(upper.displacement(upper.q0) - 0.5))
    assert errors[2] < errors[1] < errors[0]
    assert errors[2] < 2e-5 * 0.5


def test_modal_impact_speed_is_eq_23s_for_the_thesis_design():
    """Two paths to the upper contact's impact speed: eq. 23's kernel,
    and the chatter layer's crossing of its own modal model."""
    design = contactsep.thesis_design(d=0.25)
    kernel = float(contactsep.evaluate(design).v_impact)
    assert modal_impact_speed(design) == pytest.approx(kernel,
                                                            rel=1e-9)


def test_chatter_runs_with_a_timoshenko_separator():
    design = contactsep.thesis_design(d=0.75, beam2="timoshenko",
                                      kr2=2.2e4, mass2=0.0155)
    result = sim.simulate(design, "newton")
    assert result.status == 0 and result.first_impact_s > 0.0
    # eq. 23 with the member's physics; its impact speed is the one the
    # chatter layer's own modal model crosses the gap with
    assert result.single_impulse["psi_lb_s"] > 0.0
    assert result.single_impulse["v_impact_in_s"] == pytest.approx(
        modal_impact_speed(design), rel=1e-9)
