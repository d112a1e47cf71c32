"""The thesis's general model, eq. (23): any contact points, any orthodox
end conditions, any number of modes, evaluated in batches.

>>> import contactsep
>>> r = contactsep.evaluate(contactsep.thesis_design(d=0.25, x3=0.78 * 19.0))
"""

from contactsep import beams as modes
from contactsep.model import status
from contactsep.model.deck import data_set_from_design, design_from_data_set
from contactsep.model.design import Design, DesignError, pack
from contactsep.model.evaluate import Evaluation, evaluate
from contactsep.model.thesis_rig import thesis_design

__all__ = ["Design", "DesignError", "Evaluation", "data_set_from_design",
           "design_from_data_set", "evaluate", "modes", "pack", "status",
           "thesis_design"]
