"""contactsep: Appendix G of a 1960s contact-separation thesis, restored,
and the thesis's model as a design tool.

The package is layered, bottom to top (each layer imports only those
below it):

* :mod:`contactsep.restored`: the Appendix G restoration.
  ``replay(deck)`` runs a card deck through the restored Fortran core and
  returns one :class:`Result` per data set; ``solve(data_set)`` runs one
  data set given directly.
* :mod:`contactsep.model`: the general model, eq. (23), in batches
  (``Design``, ``thesis_design``, ``evaluate``), and any member's
  modes (``modes(design, member, count)``: Timoshenko beams, elastic
  supports, point masses).
* :mod:`contactsep.chatter`: repeated impacts and circuit opening.
* :mod:`contactsep.studies`: the thesis's figures and tables, sweeps
  (``sweep(vary=..., sample=...)``: rows and summary, ``to_pandas()``);
  ``preload(design)``, the smallest preload that keeps a design's
  circuit closed (:mod:`contactsep.studies.preload.command`).
* :mod:`contactsep.cli`: the ``contactsep`` command.

Shared by all: :mod:`contactsep.beams`, :mod:`contactsep.constants`,
:mod:`contactsep.errors`, :mod:`contactsep.output`.  The compiled modules
are imported on first use, so the pure-Python parts (cards, beam
functions, the NumPy reference) import without them.
"""

import importlib as _importlib

from contactsep.errors import ContactsepWarning, DeckError, InputError
from contactsep.restored.core import replay, solve
from contactsep.restored.dataset import DataSet, cards_per_set
from contactsep.restored.result import Result

#: The general model's names, imported on first use (``contactsep.model``).
_MODEL_NAMES = ("Design", "thesis_design", "evaluate")
#: Names imported on first use from their modules: the design-file
#: reader's (the model layer's) and the studies layer's.
_LAZY_NAMES = {"read": "contactsep.studies.sweep.frames",
               "load_design": "contactsep.model.design_file_read",
               "preload": "contactsep.studies.preload.command",
               "sweep": "contactsep.studies.sweep.result"}
#: The layers, imported on first use.
_LAYERS = ("restored", "model", "chatter", "studies")

__all__ = ["ContactsepWarning", "DataSet", "DeckError", "InputError",
           "Result", "cards_per_set", "modes", "replay", "solve",
           *_MODEL_NAMES, *_LAZY_NAMES, *_LAYERS]


def __getattr__(name: str):
    if name in _MODEL_NAMES:
        return getattr(_importlib.import_module("contactsep.model"), name)
    if name in _LAZY_NAMES:
        return getattr(_importlib.import_module(_LAZY_NAMES[name]), name)
    if name == "modes":
        return _importlib.import_module("contactsep.model.member_modes").modes
    if name in _LAYERS:
        return _importlib.import_module(f"contactsep.{name}")
    raise AttributeError(f"module 'contactsep' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))


__version__ = "0.1.0"
