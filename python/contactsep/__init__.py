"""contactsep: Appendix G of a 1960s contact-separation thesis, restored.

``replay(deck)`` runs a card deck through the restored Fortran core and
returns one :class:`Result` per data set; ``solve(data_set)`` runs one data
set given directly.  The compiled modules are imported on first use, so the
pure-Python parts (cards, beam functions, the NumPy reference) import
without them.
"""

import importlib

from contactsep.core import replay, solve
from contactsep.dataset import DataSet, cards_per_set
from contactsep.errors import ContactsepWarning, DeckError, InputError
from contactsep.result import Result

#: The general model's names, imported on first use (``contactsep.model``).
_MODEL_NAMES = ("Design", "thesis_design", "evaluate")

__all__ = ["ContactsepWarning", "DataSet", "DeckError", "InputError", "Result", "cards_per_set",
           "replay", "solve", *_MODEL_NAMES]


def __getattr__(name: str):
    if name in _MODEL_NAMES:
        return getattr(importlib.import_module("contactsep.model"), name)
    raise AttributeError(f"module 'contactsep' has no attribute {name!r}")
__version__ = "0.1.0"
