"""The stepper registry: which function runs each (model, stepper,
backend) that :func:`contactsep.chatter.simulate` steps in time.

Every entry takes one :class:`RunRequest` and returns one
:class:`contactsep.chatter.runners.Run`.  A new stepper is one function
here and one row of :data:`REGISTRY` (the way scipy's ``solve_ivp``
keeps its ``METHODS``).  Appendix E (``model="appE"``) is event-driven,
takes no step and is not a stepper: simulate runs it on its own path.
The NumPy backend has no adaptive stepper: an adaptive run there is the
fixed-step reference (and its result says ``stepper="fixed"``).
"""

from __future__ import annotations

from dataclasses import dataclass

from contactsep.chatter import runners
from contactsep.chatter.settings import ChatterError


@dataclass(frozen=True)
class RunRequest:
    """One run's arguments: the model, stepper and backend that choose
    the function, the stacked system and its contact law (None for
    Newton), the design (its e), Moreau-Jean's theta, the step ``dt`` (s)
    over ``steps`` steps sampled every ``stride``, the open threshold
    (in), and ``stop_open`` (s; >= 0: the adaptive stepper stops at its
    first event of that length, :mod:`contactsep.chatter.stop_event`)."""

    model: str
    stepper: str
    backend: str
    stack: object
    law: object
    design: object
    theta: float
    dt: float
    steps: int
    stride: int
    open_threshold: float
    stop_open: float

    @property
    def key(self) -> tuple:
        """The registry's key: (model, stepper, backend)."""
        return self.model, self.stepper, self.backend


def newton_adaptive(r: RunRequest) -> runners.Run:
    """Newton's law, the compiled adaptive exact-flow stepper."""
    return runners.newton_adaptive(r.stack, float(r.design.e), r.dt,
                                   r.steps, r.stride, r.open_threshold,
                                   r.stop_open)


def moreau_jean(r: RunRequest) -> runners.Run:
    """Newton's law, compiled Moreau-Jean time stepping."""
    return runners.moreau_jean(r.stack, float(r.design.e), r.dt, r.theta,
                               r.steps, r.stride, r.open_threshold)


def moreau_jean_numpy(r: RunRequest) -> runners.Run:
    """Newton's law, Moreau-Jean's NumPy twin (tests only)."""
    return runners.moreau_jean_numpy(r.stack, float(r.design.e), r.dt,
                                     r.theta, r.steps, r.stride,
                                     r.open_threshold)


def hertz_adaptive(r: RunRequest) -> runners.Run:
    """Hertz contact, the compiled adaptive stepper."""
    return runners.hertz_adaptive(r.stack, r.law, r.dt, r.steps, r.stride,
                                  r.open_threshold, r.stop_open)


def hertz_fixed(r: RunRequest) -> runners.Run:
    """Hertz contact, the fixed-step splitting on the request's backend."""
    return runners.hertz_fixed(r.stack, r.law, r.dt, r.steps, r.stride,
                               r.open_threshold, r.backend)


#: (model, stepper, backend) -> the function that runs it.
REGISTRY = {
    ("newton", "adaptive", "compiled"): newton_adaptive,
    ("newton", "adaptive", "numpy"): moreau_jean_numpy,
    ("newton", "fixed", "compiled"): moreau_jean,
    ("newton", "fixed", "numpy"): moreau_jean_numpy,
    ("hertz", "adaptive", "compiled"): hertz_adaptive,
    ("hertz", "adaptive", "numpy"): hertz_fixed,
    ("hertz", "fixed", "compiled"): hertz_fixed,
    ("hertz", "fixed", "numpy"): hertz_fixed,
}


def lookup(model: str, stepper: str, backend: str):
    """The registry's function for (model, stepper, backend); one that
    has none is refused in one line (ChatterError)."""
    try:
        return REGISTRY[(model, stepper, backend)]
    except (KeyError, TypeError):
        raise ChatterError(
            f"stepper: found {stepper!r} for model {model!r} on backend "
            f"{backend!r}, expected one of "
            f"{', '.join('/'.join(key) for key in REGISTRY)}") from None
