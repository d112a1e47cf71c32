"""docs/model.md's computed numbers, printed as one JSON object.

Run from the repository root::

    python docs/studies/make_model_numbers.py > docs/studies/model_numbers.json

``domain``: the design domain's limits (contactsep.model.design_domain)
in other units and against published materials (osmium 22.59 g/cm³,
aluminium 2.70 g/cm³: CRC Handbook; diamond's Young's modulus, the top
of the literature's 1050-1220 GPa).  ``clamp_roundoff``: the largest
relative error of the compiled mode values at SUPPORT_CLEARANCE from
each clamped end (every end condition with a clamp, N = 32) against
120-digit mpmath.  ``deck_alpha``: how much the restored reference's
closed-form A_3 moves, relative, on the first thesis deck when its
alpha_3 moves by ``change``.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import mpmath
import numpy as np

import contactsep
from contactsep.model import compiled
from contactsep.model import design_domain as domain

ROOT = Path(__file__).resolve().parents[2]
INCH_CM = 2.54
POUND_G = 453.59237
PSI_PA = POUND_G / 1000 * 9.80665 / (INCH_CM / 100) ** 2
G_CM3_LB_IN3 = INCH_CM ** 3 / POUND_G
OSMIUM, ALUMINIUM, DIAMOND_GPA = 22.59, 2.70, 1220.0
ALPHA_CHANGE = 5e-10


def domain_numbers() -> dict:
    return {
        "size_min_um": domain.SIZE_RANGE[0] * INCH_CM * 1e4,
        "size_max_ft": domain.SIZE_RANGE[1] / 12,
        "osmium_lb_in3": OSMIUM * G_CM3_LB_IN3,
        "density_max_over_osmium":
            domain.DENSITY_RANGE[1] / (OSMIUM * G_CM3_LB_IN3),
        "aluminium_lb_ft3": ALUMINIUM * G_CM3_LB_IN3 * 1728,
        "modulus_max_over_diamond":
            domain.MODULUS_RANGE[1] * PSI_PA / 1e9 / DIAMOND_GPA,
    }


def _clamped_mode(end: int, n: int, x: float) -> list[float]:
    """X_j(x), j = 1..n, of a beam clamped at 0 (end 1: free, 2: clamped,
    3: pinned at 1), in 120-digit mpmath."""
    mp = mpmath.mp
    mp.dps = 120
    equation = {1: lambda k: mp.cos(k) * mp.cosh(k) + 1,
                2: lambda k: mp.cos(k) * mp.cosh(k) - 1,
                3: lambda k: mp.tan(k) - mp.tanh(k)}[end]
    start = {1: lambda j: (2 * j - 1) * mp.pi / 2,
             2: lambda j: (2 * j + 1) * mp.pi / 2,
             3: lambda j: (4 * j + 1) * mp.pi / 4}[end]
    values = []
    for j in range(1, n + 1):
        k = mp.findroot(equation, start(j) + (mp.mpf("0.3") if
                                              (end, j) == (1, 1) else 0))
        plus = end == 1
        sigma = (mp.cosh(k) + mp.cos(k) if plus else mp.cosh(k) - mp.cos(k)) \
            / (mp.sinh(k) + mp.sin(k) if plus else mp.sinh(k) - mp.sin(k))
        u = k * mp.mpf(x)
        values.append(float(mp.cosh(u) - mp.cos(u)
                            - sigma * (mp.sinh(u) - mp.sin(u))))
    return values


def clamp_roundoff(n: int = 32) -> float:
    clear = domain.SUPPORT_CLEARANCE
    worst = 0.0
    for end in (1, 2, 3):
        # a clamped-clamped beam's far end is the near one mirrored
        points = [clear, 1.0 - clear] if end == 2 else [clear]
        _, got = compiled.mode_values(end, n, points)
        want = np.array(_clamped_mode(end, n, clear))
        for column in range(len(points)):
            mirror = (-1.0) ** np.arange(n) if column else 1.0
            worst = max(worst, float(np.max(np.abs(
                got[:, column] - mirror * want) / np.abs(want))))
    return worst


def deck_alpha() -> dict:
    from contactsep.restored import reference
    deck = sorted((ROOT / "data" / "decks").glob("*.dat"))[0]
    ds = contactsep.replay(deck, precision="double")[0].inputs
    before = reference.initial_amplitudes(ds, "closed-form")[2]
    alpha = np.array(ds.alpha, dtype=np.float64)
    alpha[2] += ALPHA_CHANGE
    moved = type(ds.alpha)(alpha) if isinstance(ds.alpha, tuple) else alpha
    after = reference.initial_amplitudes(
        dataclasses.replace(ds, alpha=moved), "closed-form")[2]
    return {"deck": deck.name, "change": ALPHA_CHANGE,
            "a3_relative_move": abs(after / before - 1)}


def main() -> dict:
    return {"domain": domain_numbers(), "clamp_roundoff": clamp_roundoff(),
            "deck_alpha": deck_alpha()}


if __name__ == "__main__":
    print(json.dumps(main(), indent=2))
