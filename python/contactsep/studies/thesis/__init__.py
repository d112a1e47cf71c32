"""The thesis studies: its figures, conclusions, restitution, contact
points, materials, buttons, separator fit, chatter table and mode share."""
