"""contactsep: Appendix G of a 1960s contact-separation thesis, restored.

``replay(deck)`` runs a card deck through the restored Fortran core and
returns one :class:`Result` per data set; ``solve(data_set)`` runs one data
set given directly.  The compiled modules are imported on first use, so the
pure-Python parts (cards, beam functions, the NumPy reference) import
without them.
"""

from contactsep.core import replay, solve
from contactsep.dataset import DataSet, cards_per_set
from contactsep.errors import DeckError
from contactsep.result import Result

__all__ = ["DataSet", "DeckError", "Result", "cards_per_set", "replay",
           "solve"]
__version__ = "0.1.0"
