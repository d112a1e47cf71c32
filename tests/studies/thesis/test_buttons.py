"""``contactsep study buttons`` (issue 28 item 3): open time and the
smallest preload against the contact button's shape and radius."""

from __future__ import annotations

import numpy as np
import pytest

from contactsep.cli import main
from contactsep.studies.thesis import buttons
@pytest.mark.slow
def test_the_study_has_a_row_per_shape_and_radius():
    study = buttons.buttons(n_modes=4, radii=(0.125,), workers=1)
    assert list(study["button"]) == ["sphere", "cylinder"]
    assert np.all(study["button_radius_in"] == 0.125)
    assert np.all(study["min_preload_lb"] > 0.0)
    assert np.all(study["circuit_open_s"] > 0.0)


def test_a_shape_it_does_not_know_is_refused():
    with pytest.raises(ValueError, match="shapes"):
        buttons.buttons(shapes=("cone",))


@pytest.mark.parametrize("argv", [
    ["study", "buttons", "--d", "0.5"],
    ["study", "buttons", "--model", "newton"],
])
def test_bad_options_are_refused_in_one_line(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("contactsep: error:")
