"""contactsep: Appendix G of a 1960s contact-separation thesis, restored.

The compiled Fortran modules are imported on first use, so the pure-Python
parts (deck cards, beam functions, the NumPy reference) import without them.
"""

from contactsep.dataset import DataSet, cards_per_set

__all__ = ["DataSet", "cards_per_set"]
__version__ = "0.1.0"
