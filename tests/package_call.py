"""The one place the issue-26 tests (tests/chatter/test_independent.py,
test_identities.py, test_docs_claims.py, test_one_sample.py,
tests/studies/test_cheap_catches.py) call the package's simulation,
with every setting written out, so that a changed default (the step,
the window, a static correction) cannot change what these tests check
without an edit here.  To pin a new option for all of them, add it to
``SETTINGS`` (e.g. ``static_correction=False``)."""

from __future__ import annotations

import warnings

from contactsep import chatter
from contactsep.chatter.stack import CoarseStepWarning

#: Settings every call gets unless the test gives its own.
SETTINGS = dict(model="hertz", damping="none", preload=0.0,
                open_threshold=1e-6, min_open=1e-5, nu=0.33,
                button_radius=0.125, stepper="adaptive", backend="compiled",
                theta=0.5, single_impulse=False, static_correction=False)


def run(design, *, dt, t_end, samples, **settings):
    """contactsep.chatter.simulate with every setting explicit: ``dt``,
    ``t_end`` and ``samples`` always given, the rest from SETTINGS
    unless overridden."""
    unknown = set(settings) - set(SETTINGS)
    if unknown:
        raise TypeError(f"not a pinned setting: {sorted(unknown)}")
    options = {**SETTINGS, **settings}
    if options["model"] == "appE":
        dt = None
    with warnings.catch_warnings():
        # these tests choose dt from the physics they check (a contact
        # duration, a closed form), often coarser than the default
        warnings.simplefilter("ignore", CoarseStepWarning)
        return chatter.simulate(design, dt=dt, t_end=t_end,
                                samples=samples, **options)
