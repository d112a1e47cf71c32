"""Repeated impacts and circuit discontinuity: Appendix E (event-driven,
rigid stop), three-beam nonsmooth dynamics (Moreau-Jean, Newton's law) and
Hertz contact; docs/chatter.md.

>>> import contactsep
>>> from contactsep import chatter
>>> r = chatter.simulate(contactsep.thesis_design(n_modes=16), model="hertz")
>>> r.circuit_open_s, r.first_circuit_open_s, r.max_lower_gap_in
"""

from contactsep.chatter.result import ChatterResult
from contactsep.chatter.simulate import MODELS, ChatterError, simulate

__all__ = ["MODELS", "ChatterError", "ChatterResult", "simulate"]
