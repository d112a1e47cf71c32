"""The inputs of one Appendix G data set (6 + 3N cards).

Field names are the listing's variable names, lower-cased, so that the code
can be read beside the thesis.  Units are the listing's: inches, seconds,
pounds; ``rho`` is a weight density in lb/ft^3 (the listing divides it by
1728 to get lb/in^3 and by g = 386.4 in/s^2 to get a mass density), ``e`` is
Young's modulus in psi.

Card layout (FORMAT 10 is 7F15.9, FORMAT 15 is E15.9,I2):

======  ==========================  ========================================
card    FORMAT, columns             fields
======  ==========================  ========================================
1       10: 1-15,16-30,...,61-75    xl, b, h, rho, ystat   (upper contact)
2       10                          xl2, b2, h2, rho2      (separator)
3       10                          xl3, b3, h3, rho3      (lower contact)
4       10                          delt, er, dely
5       15: 1-15, 16-17             e, n
6       10                          xl2c  (equivalent separator length)
7..     10, N cards                 v, c, alpha    (upper: k_jL, X_j(L), alpha_j)
..      10, N cards                 v2, c2, alph2  (separator: k_jL, X_j(L/2), alpha_j)
..      10, N cards                 v3, c3, alph3  (lower: k_jL, X_j(L), alpha_j)
======  ==========================  ========================================
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from contactsep import beams

#: Scalar fields in card order, as (card number, field names).
SCALAR_CARDS: tuple[tuple[int, tuple[str, ...]], ...] = (
    (1, ("xl", "b", "h", "rho", "ystat")),
    (2, ("xl2", "b2", "h2", "rho2")),
    (3, ("xl3", "b3", "h3", "rho3")),
    (4, ("delt", "er", "dely")),
    (5, ("e", "n")),
    (6, ("xl2c",)),
)

#: The three groups of N mode cards, in deck order.
MODE_GROUPS: tuple[tuple[str, str, str], ...] = (
    ("v", "c", "alpha"),
    ("v2", "c2", "alph2"),
    ("v3", "c3", "alph3"),
)

#: Cards in a data set before the mode cards.
FIXED_CARDS = 6


def cards_per_set(n: int) -> int:
    """Number of cards in a data set with ``n`` modes: 6 + 3N."""
    return FIXED_CARDS + 3 * n


def _frozen_array(values) -> np.ndarray:
    arr = np.array(values, dtype=np.float64, copy=True).reshape(-1)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class DataSet:
    """One data set: the contact, separator and mode constants of a run."""

    # card 1: upper contact
    xl: float
    b: float
    h: float
    rho: float
    ystat: float
    # card 2: separator (clamped-clamped)
    xl2: float
    b2: float
    h2: float
    rho2: float
    # card 3: lower contact
    xl3: float
    b3: float
    h3: float
    rho3: float
    # card 4: time step, coefficient of restitution, separator position
    delt: float
    er: float
    dely: float
    # card 5: modulus, number of modes
    e: float
    n: int
    # card 6: equivalent separator length (Table III)
    xl2c: float
    # mode cards, N values each
    v: np.ndarray
    c: np.ndarray
    alpha: np.ndarray
    v2: np.ndarray
    c2: np.ndarray
    alph2: np.ndarray
    v3: np.ndarray
    c3: np.ndarray
    alph3: np.ndarray

    def __post_init__(self) -> None:
        for group in MODE_GROUPS:
            for name in group:
                arr = _frozen_array(getattr(self, name))
                if arr.shape != (self.n,):
                    raise ValueError(
                        f"{name} has {arr.size} values, N = {self.n}")
                object.__setattr__(self, name, arr)
        object.__setattr__(self, "n", int(self.n))

    def replace(self, **changes) -> "DataSet":
        """A copy with some fields changed (mode arrays may change N).

        To change N with the mode constants recomputed, use
        :meth:`with_modes`."""
        if "n" in changes and int(changes["n"]) != self.n and not any(
                name in changes for group in MODE_GROUPS for name in group):
            raise ValueError(
                f"replace(n={changes['n']}) keeps the {self.n} mode cards; "
                f"use ds.with_modes({changes['n']}) to recompute them")
        return dataclasses.replace(self, **changes)

    def with_modes(self, n: int) -> "DataSet":
        """A copy with ``n`` modes and the mode cards recomputed for the
        program's members (cantilever contacts, clamped-clamped separator)
        by :func:`mode_constants`."""
        return dataclasses.replace(self, **mode_constants(int(n)))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, DataSet):
            return NotImplemented
        for field in dataclasses.fields(self):
            a, b = getattr(self, field.name), getattr(other, field.name)
            if isinstance(a, np.ndarray):
                if not np.array_equal(a, b):
                    return False
            elif a != b:
                return False
        return True

    __hash__ = None  # type: ignore[assignment]


def mode_constants(n: int) -> dict:
    """N and the mode cards of the program's members, computed by
    :mod:`contactsep.beams`: cantilever contacts (k_jL, X_j(L), alpha_j)
    and a clamped-clamped separator (k_jL, X_j(L/2), alpha_j)."""
    kl_free = beams.eigenvalues("cantilever", n)
    alpha_free = beams.alphas("cantilever", n)
    tip = beams.tip_values(n)
    return dict(
        n=n, v=kl_free, c=tip, alpha=alpha_free,
        v2=beams.eigenvalues("clamped-clamped", n),
        c2=beams.midspan_values(n),
        alph2=beams.alphas("clamped-clamped", n),
        v3=kl_free, c3=tip, alph3=alpha_free)


def computed_data_set(n: int, **card_fields) -> DataSet:
    """A data set of ``n`` modes from its scalar card fields, the mode cards
    computed by :func:`mode_constants` (the one door from the general model
    into the restoration: :func:`contactsep.model.data_set_from_design`)."""
    return DataSet(**card_fields, **mode_constants(int(n)))
