"""The thesis's design studies (Figures 5-8, 21, 23; Tables I-III),
sweeps and tolerance studies, on the general model (contactsep.model).

>>> from contactsep import studies
>>> s = studies.fig5(n_modes=8)        # columnar NumPy data
>>> s["y3_max_in"], s.to_pandas()      # (pandas optional)
"""

from contactsep.studies.thesis import mode_share
from contactsep.studies import tables
from contactsep.studies.thesis import figures
from contactsep.studies.thesis.mode_share import conclusion8
from contactsep.studies.thesis.figures import (
                                        convergence,
                                        fig5,
                                        fig6,
                                        fig7,
                                        fig8,
                                        fig23,
)
from contactsep.studies.study import Study
from contactsep.studies.tables import table1, table2, table3

#: The thesis's studies by name, in the order `study all` writes them.
STUDIES = {"fig5": fig5, "fig6": fig6, "fig7": fig7, "fig8": fig8,
           "fig23": fig23, "convergence": convergence, "table1": table1,
           "table2": table2, "table3": table3, "conclusion8": conclusion8}

#: The fields each study sets itself: a design option for one is refused;
#: from a --design file, the study's own values win (fig5 draws its three
#: y_s curves unless --ys is typed).
OWN_FIELDS = {name: set(fixed) for name, fixed in
              {**figures.FIXED, **tables.FIXED,
               "conclusion8": mode_share.FIXED}.items()}
OWN_FIELDS["fig5"].add("ys")

__all__ = ["OWN_FIELDS", "STUDIES", "Study", "conclusion8", "convergence",
           "fig5", "fig6",
           "fig7", "fig8", "fig23", "table1", "table2", "table3"]
