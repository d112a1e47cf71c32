"""Repeated impacts and circuit discontinuity: Appendix E (event-driven,
rigid stop), three-beam nonsmooth dynamics (Moreau-Jean, Newton's law) and
Hertz contact; docs/chatter.md.

>>> import contactsep
>>> from contactsep import chatter
>>> r = chatter.simulate(contactsep.thesis_design(n_modes=16), preload=0.2)
>>> r.circuit_open_s, r.first_circuit_open_s, r.max_lower_gap_in
>>> r.status, r.dt_source, r.t_end_source     # 0 ok, 9 unconverged
"""

from contactsep.chatter.result import ChatterResult
from contactsep.chatter.numerics import DEFAULT_MODES
from contactsep.chatter.limits import MODELS
from contactsep.chatter.settings import ChatterError
from contactsep.chatter.simulate import UnconvergedWarning, simulate

__all__ = ["DEFAULT_MODES", "MODELS", "ChatterError", "ChatterResult",
           "UnconvergedWarning", "simulate"]
