"""The thesis experiment as a Design (Chapters V and VI)."""

from __future__ import annotations

from contactsep.model.design import Design, DesignError


def thesis_design(d=0.25, **overrides) -> Design:
    """The thesis's experiment as a :class:`Design`.

    19 x 2 x 0.125 in aluminium contacts, a 2.5 x 0.5 x d in separator,
    E = 10.0e6 psi, 0.100 lb/in^3, y_s = 0.5 in, e = 0.375, N = 4,
    contact at the tips and mid-span, tau = 0.060 s, no L_c unless given.

    Parameters
    ----------
    d : float or array_like
        Separator thickness (in); an array makes a batch.
    **overrides
        Any other :class:`Design` field (``h2``, if given, takes the
        place of ``d``).

    Returns
    -------
    Design

    Raises
    ------
    DesignError
        An override that is not a Design field, or a value the Design
        refuses.

    Examples
    --------
    >>> import contactsep
    >>> contactsep.thesis_design(d=0.5, n_modes=16).h2
    0.5
    """
    unknown = sorted(set(overrides) - set(Design.__dataclass_fields__))
    if unknown:
        raise DesignError(f"{unknown[0]}: not a design field (one of "
                          f"{', '.join(Design.__dataclass_fields__)})")
    overrides.setdefault("h2", d)
    return Design(**overrides)
