"""The members' modes for eq. 23 when their beam physics is not the
thesis's (issue 27): a Timoshenko beam, elastic supports, point masses.

Eq. 23 needs of each member only its eigenvalues b_j = omega_j L^2
sqrt(rho A/EI) (= (k_jL)^2 of a Bernoulli-Euler beam), its mode values at
the contact point, normalised to the generalised mass of the bare member
rho A L (:mod:`contactsep.beams.member`), and of the upper contact the
mode values and static flexibility G(a) at its load point.  With those
the backends (the compiled ``evaluate_batch_given`` and the twin) run the
same arithmetic as for the thesis's beams: p_j = b_j a/L^2, A_j = y_s
X_j(a)/(b_j^2 G(a)), the impulse of eqs. 20 and 23, v0, y3 and its
extremes.

Batching: a member's dimensionless beam (theory, supports, masses made
dimensionless, and its contact point) depends only on a few of the
design's columns, so the batch's rows are grouped by the unique values of
those columns (``np.unique`` over the packed columns) and the modes are
computed once per group, not once per design (a sweep of the lower
contact's length computes the separator's Timoshenko modes once); the
groups' results are cached by :func:`contactsep.beams.member.
dimensionless_modes`.  A member whose physics is the thesis's takes the
closed-form modes through the same function.

A group whose modes cannot be computed (more than MAX_GENERAL_MODES
modes of a general member, a point mass outside the member, roots the
scan cannot separate) marks its designs ``failed``: status 2 (invalid
input) and NaN results, like any other design the model cannot take.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactsep import beams
from contactsep.beams import member as member_beams
from contactsep.beams.member import THEORIES
from contactsep.errors import InputError
from contactsep.model.design import Packed
from contactsep.model.design_domain import (
    REAL_COLUMNS,
    invalid_rows,
    outside_domain,
)

#: The packed real columns a member's modes depend on, by member.
_MEMBER_COLUMNS = {m: tuple(f"{name}{m}" for name in
                            ("L", "b", "h", "gamma", "E", "x"))
                   for m in "123"}


@dataclass(frozen=True)
class GivenModes:
    """Each design's member modes, for the backends (module docstring).

    ``b`` (M, 3, n_max): b_j of members 1, 2, 3, NaN past a member's
    count; ``values`` (M, 4, n_max): X1j(x1), X2j(x2), X3j(x3) and X1j at
    the upper contact's load point, 0 past a count; ``flex`` (M,): the
    upper contact's G(a); ``flex3`` (M,): the lower contact's G(x3) (for
    the energy bound, :mod:`contactsep.model.energy`); ``failed`` (M,):
    no modes (status 2).
    """

    b: np.ndarray
    values: np.ndarray
    flex: np.ndarray
    flex3: np.ndarray
    failed: np.ndarray

    def rows(self, first: int, last: int, n_max: int) -> GivenModes:
        """Designs first..last-1, modes 1..n_max."""
        return GivenModes(b=self.b[first:last, :, :n_max],
                          values=self.values[first:last, :, :n_max],
                          flex=self.flex[first:last],
                          flex3=self.flex3[first:last],
                          failed=self.failed[first:last])


def _member(design, m: str, row: dict) -> member_beams.MemberBeam:
    """Member m of one group (its packed columns in ``row``) with the
    design's (scalar) beam physics; the point mass at the contact point
    unless x_mass says otherwise."""
    def get(name):
        return getattr(design, name + m)

    mass = float(get("mass"))
    x_mass = get("x_mass")
    if x_mass is None and mass:
        x_mass = row["x" + m]
    return member_beams.MemberBeam(
        length=row["L" + m], width=row["b" + m], thickness=row["h" + m],
        gamma=row["gamma" + m], modulus=row["E" + m],
        end=beams.END_CONDITIONS[int(row["end"]) - 1], theory=get("beam"),
        nu=float(get("nu")),
        kappa=None if get("kappa") is None else float(get("kappa")),
        kr=None if get("kr") is None else float(get("kr")),
        kt=None if get("kt") is None else float(get("kt")),
        mass=mass, x_mass=None if x_mass is None else float(x_mass))


def _classical(design, member: str) -> bool:
    """Member ``member`` has the thesis's beam physics."""
    return (getattr(design, "beam" + member) == THEORIES[0]
            and getattr(design, "kr" + member) is None
            and getattr(design, "kt" + member) is None
            and not getattr(design, "mass" + member))


def given_modes(design, packed: Packed) -> GivenModes:
    """The members' modes of every design of ``packed`` (the batch of
    ``design``, whose beam physics fields are scalars)."""
    m = packed.size
    counts = packed.ints[:, 3:].astype(np.int64)
    n_max = int(counts.max()) if m else 1
    b = np.full((m, 3, n_max), np.nan)
    values = np.zeros((m, 4, n_max))
    flex = np.full(m, np.nan)
    flex3 = np.full(m, np.nan)
    failed = invalid_rows(packed.real, packed.ints) | outside_domain(
        packed.real, packed.ints)
    tip_release = (packed.options[3] == 0) & (packed.ints[:, 0] == 1)
    for k, member in enumerate("123"):
        real = {name: packed.real[:, REAL_COLUMNS.index(name)]
                for name in _MEMBER_COLUMNS[member]}
        if _classical(design, member):
            # the thesis's physics: the modes depend on the end, N and
            # the contact point's xi only
            columns = [real["x" + member] / real["L" + member]]
        else:
            columns = list(real.values())
        columns += [packed.ints[:, k], counts[:, k]]
        if member == "1":
            columns.append(tip_release)
        table = np.stack([np.asarray(c, dtype=np.float64)
                          for c in columns], axis=1)
        live = np.flatnonzero(~failed)
        if live.size == 0:
            continue
        groups, inverse = np.unique(table[live], axis=0,
                                    return_inverse=True)
        inverse = np.ravel(inverse)
        # the rows of each group, without a pass over the batch a group
        order = np.argsort(inverse, kind="stable")
        sizes = np.bincount(inverse, minlength=len(groups))
        stops = np.cumsum(sizes)
        for g in range(len(groups)):
            rows = live[order[stops[g] - sizes[g]:stops[g]]]
            first = rows[0]
            row = {name: float(value[first])
                   for name, value in real.items()}
            row["end"] = int(packed.ints[first, k])
            n = int(counts[first, k])
            length = row["L" + member]
            xi = [row["x" + member] / length]
            if member == "1":
                xi.append(1.0 if tip_release[first] else xi[0])
            try:
                spec = _member(design, member, row)
                beam = spec.dimensionless()
                # one point a call: the chatter models' keys, so that
                # the cache serves both layers
                at = [member_beams.dimensionless_modes(beam, n, [point])
                      for point in xi]
                bj = at[0][0]
                at = np.concatenate([v for _, v in at], axis=1)
                if member != "2":
                    # G at the upper's load point, the lower's contact
                    shape = float(member_beams.static_flexibility(
                        beam, np.array(xi[-1])))
            except (InputError, ValueError):
                failed[rows] = True
                continue
            b[rows, k, :n] = bj
            values[rows, k, :n] = at[:, 0]
            if member == "1":
                values[rows, 3, :n] = at[:, 1]
                flex[rows] = shape
            elif member == "3":
                flex3[rows] = shape
    b[failed] = np.nan
    values[failed] = 0.0
    flex[failed] = flex3[failed] = np.nan
    return GivenModes(b=b, values=values, flex=flex, flex3=flex3,
                      failed=failed)
