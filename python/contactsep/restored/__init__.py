"""The Appendix G restoration: the program of the thesis, restored bit for
bit as a Fortran core (``fortran/restored/``) called through f2py.

* :mod:`~contactsep.restored.core`: ``replay(deck)``, ``solve(data_set)``;
* :mod:`~contactsep.restored.cards`, :mod:`~contactsep.restored.dataset`:
  the card decks and their data sets;
* :mod:`~contactsep.restored.thesis_decks`: the thesis experiment as decks;
* :mod:`~contactsep.restored.legacy`: the transcribed original program;
* :mod:`~contactsep.restored.reference`: the NumPy reference written from
  the equations, and :mod:`~contactsep.restored.compare`, which holds all
  of them against each other;
* :mod:`~contactsep.restored.result`, :mod:`~contactsep.restored.formats`,
  :mod:`~contactsep.restored.listing`: results and their renderings;
* :mod:`~contactsep.restored.checks`: warnings for runs that may not mean
  what they seem; :mod:`~contactsep.restored.status`: the core's status
  codes.
"""

from contactsep.restored.core import iter_replay, replay, solve
from contactsep.restored.dataset import DataSet, cards_per_set
from contactsep.restored.result import Result

__all__ = ["DataSet", "Result", "cards_per_set", "iter_replay", "replay",
           "solve"]
