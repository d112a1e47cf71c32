"""Honest warnings: a data set that runs but may not mean what it seems.

Each check returns one-line messages; :func:`warn` issues them as
:class:`contactsep.errors.ContactsepWarning`.  The listing never changes.

Thresholds and their sources:

* Mode cards.  The deck's mode function differs from the exact one by
  delta_alpha (sinh - sin); A_j moves by about delta_alpha e^v v^3 / 12
  relative (v = k_jL; the derivation is in
  :mod:`contactsep.restored.reference`).
  An ALPHA that is exact at 9 decimals (as the cards carry) has
  delta_alpha up to 5e-10; the check warns where that estimate exceeds
  ``MODE_ERROR`` = 1 % for any mode (the thesis's cantilever: mode 5,
  about 16 %).
* Density.  Decks take weight density in lb/ft^3; solids run from ~30
  (wood) to ~1200 (tungsten) lb/ft^3, while lb/in^3 values of metals are
  0.06-0.7.  Below ``MIN_DENSITY`` = 10 lb/ft^3 the value looks like
  lb/in^3.
* Bernoulli-Euler.  The separator is a thin beam; the thesis's own
  experiment reaches d/L2 = 0.75/2.5 = 0.3 and corrects it with Table III's
  L_c.  Beyond ``MAX_DEPTH_RATIO`` = 0.3 nothing in the thesis validates
  the beam theory (shear and rotary inertia, Timoshenko's correction,
  grow with (d/L)^2).
* Extreme at the end of the window: the largest |TY3| on the last history
  line of T < TAU may lie beyond TAU.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from contactsep.constants import CUBIC_INCHES_PER_CUBIC_FOOT
from contactsep.errors import ContactsepWarning

MODE_ERROR = 0.01
CARD_DECIMALS = 9
MIN_DENSITY = 10.0
MAX_DEPTH_RATIO = 0.3


def mode_card_error(v, alpha) -> np.ndarray:
    """Estimated relative A_j error per mode from ALPHA's precision: the
    rounding of a 9-decimal card if ALPHA is exact at 9 decimals, else of
    a double."""
    v = np.asarray(v, dtype=float)
    alpha = np.asarray(alpha, dtype=float)
    nine = np.all(np.round(alpha, CARD_DECIMALS) == alpha)
    delta = 0.5 * 10.0 ** -CARD_DECIMALS if nine else np.spacing(alpha) / 2
    return delta * np.exp(v) * v ** 3 / 12


def _may_exceed(v, alpha) -> bool:
    """Whether any mode can reach MODE_ERROR at all: the estimate with
    the coarser of the two roundings for the largest |ALPHA| and the
    largest v.  Cheap, so a designer's loop does not pay for the full
    check on every call."""
    top = max((float(x) for x in v), default=0.0)
    size = max((abs(float(x)) for x in alpha), default=0.0)
    if not (math.isfinite(top) and math.isfinite(size)) or top > 700.0:
        return True
    delta = max(0.5 * 10.0 ** -CARD_DECIMALS, size * 2.0 ** -52)
    return delta * math.exp(top) * top ** 3 / 12 > MODE_ERROR


def input_messages(ds) -> list[str]:
    """Messages about a data set's inputs alone."""
    out = []
    for name, v, alpha in (("upper", ds.v, ds.alpha),
                           ("lower", ds.v3, ds.alph3)):
        if not _may_exceed(v, alpha):
            continue
        err = mode_card_error(v, alpha)
        bad = np.nonzero(err > MODE_ERROR)[0]
        if bad.size:
            out.append(
                f"N = {ds.n}: the {name} contact's ALPHA cards carry mode "
                f"{bad[0] + 1} and up only to ~{err[bad[0]]:.0%} in A_j "
                f"(see contactsep.restored.reference); use N <= {bad[0]}")
            break
    for field in ("rho", "rho2", "rho3"):
        value = getattr(ds, field)
        if 0 < value < MIN_DENSITY:
            out.append(
                f"{field.upper()} = {value:g} looks like lb/in^3; decks take "
                f"lb/ft^3 ({value:g} lb/in^3 = "
                f"{value * CUBIC_INCHES_PER_CUBIC_FOOT:g} lb/ft^3)")
    if ds.xl2 > 0 and ds.h2 / ds.xl2 > MAX_DEPTH_RATIO:
        out.append(
            f"separator d/L2 = {ds.h2 / ds.xl2:.3g} is beyond "
            f"{MAX_DEPTH_RATIO} (the thesis's largest): Bernoulli-Euler "
            f"beam theory is not validated there")
    return out


def result_messages(result) -> list[str]:
    """Messages about a result."""
    y = result.history_ty3
    if y.size > 1 and int(np.argmax(np.abs(y))) == y.size - 1:
        return [f"the extreme TY3 = {float(y[-1]):.6g} in is on the last "
                f"history line (T = {float(result.history_t[-1]):.6g} s): "
                f"the true extreme may lie beyond TAU = {result.tau:g} s "
                f"(solve(..., tau=...) extends the window)"]
    return []


def warn(messages, stacklevel: int = 3) -> None:
    for message in messages:
        warnings.warn(message, ContactsepWarning, stacklevel=stacklevel)
