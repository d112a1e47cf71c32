"""The thesis's recommendations (Chapter VII) as studies of three-beam
simulations, by name (``contactsep study contact-points``, ``study
materials``): each entry the study, its figure and the fields it sets
itself."""

from __future__ import annotations

from contactsep.studies.thesis import contact_points

from contactsep.studies.thesis import materials
#: draw(axes, study), the fields it sets: field -> why).
STUDIES = {
    "contact-points": (contact_points.contact_points, contact_points.draw,
                       contact_points.FIXED),
    "materials": (materials.materials, materials.draw, materials.FIXED),
}
