"""``evaluate(design)``: the general model on one design or a batch."""

from __future__ import annotations

import dataclasses
import importlib
import time
from dataclasses import dataclass

import numpy as np

from contactsep import output
from contactsep.errors import InputError
from contactsep.model import energy, given, physics
from contactsep.model import status as status_codes
from contactsep.model.contact_points import lower_point_differs
from contactsep.model.design import Design, Packed, pack
from contactsep.model.design_domain import (
    REAL_COLUMNS,
    DesignError,
    outside_domain,
)
from contactsep.model.names import RESULT_KEYS
from contactsep.output import pieces

BACKENDS = ("compiled", "numpy")

_SCALARS = ("t1", "v_impact", "psi", "v0", "R", "y3_max", "t_max",
            "y3_min", "t_min", "at_window_end", "t_max_tied", "t_min_tied",
            "status", "M1", "M2", "M3")
_PER_MODE = ("p1", "p2", "p3", "c3")


@dataclass(frozen=True, repr=False)
class Evaluation:
    """Results of the general model, NumPy arrays of the batch's shape
    (0-d for one design); per-mode arrays add a trailing mode axis.

    Times: ``t1`` from the release; ``t_max``, ``t_min`` and the argument
    of :meth:`y3` from the impact.  Designs whose ``status`` is not 0 have
    NaN results (:data:`contactsep.model.status.MESSAGES` says why).
    """

    t1: np.ndarray
    """First impact time after release (s)."""
    v_impact: np.ndarray
    """Impact speed of the upper contact at x1 (in/s, >= 0)."""
    psi: np.ndarray
    """Impulse of the impact (lb s, >= 0), eqs. 20 and 23."""
    v0: np.ndarray
    """Separator velocity at x2 just after the impact (in/s), eq. 12."""
    R: np.ndarray
    """Mass ratio of eq. 24, (M2/sum X2j^2)/(M3/sum X3j^2)."""
    y3_max: np.ndarray
    """Largest lower-contact displacement away from the separator over
    0 <= t <= tau (in): the maximum of the N-mode y3, true to 1e-12 of
    sum abs(c3_j) (not a grid value)."""
    t_max: np.ndarray
    """Time of y3_max after the impact (s); of several peaks within
    1e-12 sum abs(c3_j) of each other, the earliest."""
    y3_min: np.ndarray
    """Smallest lower-contact displacement (in; negative: through the
    separator's original position), true to 1e-12 of sum abs(c3_j)."""
    t_min: np.ndarray
    """Time of y3_min after the impact (s); the earliest of ties."""
    at_window_end: np.ndarray
    """True where y3_max sits at t = tau: the window cuts the maximum."""
    t_max_tied: np.ndarray
    """True where another point, more than half the shortest period
    (pi / max p3_j) after t_max, comes within 1e-12 sum abs(c3_j) of y3_max:
    t_max is the earliest of peaks the search cannot rank."""
    t_min_tied: np.ndarray
    """The same for y3_min and t_min."""
    status: np.ndarray
    """Per-design status code (0 = ok; see contactsep.model.status)."""
    M1: np.ndarray
    """Upper contact mass (lb s^2/in)."""
    M2: np.ndarray
    """Separator mass used in the impulse (lb s^2/in)."""
    M3: np.ndarray
    """Lower contact mass (lb s^2/in)."""
    p1: np.ndarray
    """Upper contact frequencies (rad/s), trailing mode axis."""
    p2: np.ndarray
    """Separator frequencies (rad/s), trailing mode axis."""
    p3: np.ndarray
    """Lower contact frequencies (rad/s), trailing mode axis."""
    c3: np.ndarray
    """Modal coefficients of y3(x3, t) = sum c3_j sin(p3_j t) (in)."""

    def y3(self, t) -> np.ndarray:
        """Lower-contact displacement at x3 (in) at times ``t`` after the
        impact (s); the result has the batch shape followed by t's shape."""
        t = np.asarray(t, dtype=np.float64)
        c = np.nan_to_num(self.c3)
        p = np.nan_to_num(self.p3)
        phase = p[(..., ) + (None,) * t.ndim] * t
        return np.sum(c[(..., ) + (None,) * t.ndim] * np.sin(phase),
                      axis=-1 - t.ndim)

    def messages(self) -> np.ndarray:
        """The meaning of each design's status, as strings."""
        lookup = np.vectorize(lambda code: status_codes.MESSAGES[int(code)],
                              otypes=[object])
        return lookup(self.status)

    def to_dict(self) -> dict:
        """Plain Python values (lists for batches) under the names every
        output uses (``psi_lb_s``, ``y3_max_in``, ``p1_rad_s``, ...:
        :mod:`contactsep.model.names`); NaN stays NaN (``json.dumps``
        of a failed design needs ``contactsep.output.write_json``)."""
        return {RESULT_KEYS[f.name]: getattr(self, f.name).tolist()
                for f in dataclasses.fields(self)}

    def to_pandas(self, modes: bool = False):
        """A pandas DataFrame, one row per design (index ``design``, the
        batch flattened in C order) with a column per scalar result
        under its output name; ``modes=True``: one row per design and
        mode (index ``design``, ``mode`` from 1) with the per-mode
        results (``p1_rad_s``, ``p2_rad_s``, ``p3_rad_s``, ``c3_in``;
        NaN past a member's own N).  Needs pandas
        (``pip install 'contactsep[tables]'``).

        Examples
        --------
        >>> import numpy as np, contactsep
        >>> batch = contactsep.evaluate(
        ...     contactsep.thesis_design(d=np.linspace(0.1, 1.0, 4)))
        >>> batch.to_pandas()[["psi_lb_s", "y3_max_in"]].shape
        (4, 2)
        """
        pandas = output.require_pandas()
        count = int(np.prod(self.status.shape, dtype=np.int64))
        if not modes:
            columns = {RESULT_KEYS[name]: np.reshape(
                getattr(self, name), count) for name in _SCALARS}
            return pandas.DataFrame(columns, index=pandas.RangeIndex(
                count, name="design"))
        n = self.p1.shape[-1]
        columns = {RESULT_KEYS[name]: np.reshape(getattr(self, name),
                                                 count * n)
                   for name in _PER_MODE}
        index = pandas.MultiIndex.from_product(
            [range(count), range(1, n + 1)], names=["design", "mode"])
        return pandas.DataFrame(columns, index=index)

    def __repr__(self) -> str:
        shape = self.status.shape
        if shape == ():
            return (f"Evaluation(status={int(self.status)}, "
                    f"psi={float(self.psi):.6g} lb s, "
                    f"v0={float(self.v0):.6g} in/s, "
                    f"y3_max={float(self.y3_max):.6g} in)")
        ok = int(np.sum(self.status == 0))
        return f"Evaluation(shape={shape}, ok={ok}/{self.status.size})"


def _backend(name: str):
    if name not in BACKENDS:
        raise InputError(f"backend: found {name!r}, expected one of "
                         f"{', '.join(BACKENDS)}")
    if name == "numpy":
        return importlib.import_module("contactsep.model.twin")
    try:
        return importlib.import_module("contactsep.model.compiled")
    except ImportError as error:
        raise InputError(f"backend 'compiled': the compiled model is not "
                         f"available ({error}); use backend='numpy'") from None


def evaluate(design: Design, *, backend: str = "compiled") -> Evaluation:
    """Evaluate the general model (eq. 23) on a design or a batch.

    Parameters
    ----------
    design : Design
        One design, or a batch (any field an array; they broadcast).
        Inches, pounds, seconds; weight densities in lb/in^3, moduli in
        psi.
    backend : {"compiled", "numpy"}
        ``"compiled"`` runs the Fortran kernel (one call for the whole
        batch, or pieces of about ``contactsep.output.pieces.PIECE_S``
        seconds of a batch that takes longer: a signal is seen between
        them); ``"numpy"`` the
        NumPy twin.

    Returns
    -------
    Evaluation
        The single impact and the lower contact's response, shaped like
        the batch: ``t1`` (s), ``psi`` (lb s), ``v0`` (in/s), ``y3_max``
        (in), ``t_max`` (s), per-mode frequencies (rad/s), and
        ``status`` (0: evaluated; per-design failures are statuses, not
        exceptions).

    Raises
    ------
    InputError
        ``design`` is not a :class:`Design`, or ``backend`` is unknown.

    Examples
    --------
    >>> import contactsep
    >>> r = contactsep.evaluate(contactsep.thesis_design(d=0.25))
    >>> round(float(r.y3_max), 4)     # in, N = 4
    0.1107
    """
    if not isinstance(design, Design):
        raise InputError(f"design: expected a contactsep.Design, found "
                         f"{type(design).__name__}")
    if lower_point_differs(design):
        raise DesignError(
            f"x2_lower: found {design.x2_lower!r}, but eq. 23 (evaluate, "
            f"sweep) takes both contacts at the separator's one point x2 "
            f"(its impulse passes through it); contactsep chatter takes "
            f"this design")
    packed = pack(design)
    if physics.physics_changes(design):
        # other beam physics than the thesis's: the members' modes from
        # contactsep.beams, the same eq. 23 arithmetic (model/given.py)
        packed = dataclasses.replace(
            packed, modes=given.given_modes(design, packed))
    out = _refuse_outside_domain(packed, _in_pieces(_backend(backend),
                                                    packed))
    shape = packed.shape
    fields = {}
    for key in _SCALARS:
        fields[key] = np.asarray(out[key]).reshape(shape)
    for key in _PER_MODE:
        value = np.asarray(out[key])
        fields[key] = value.reshape(shape + value.shape[1:])
    shapes = None if packed.modes is None else tuple(
        np.reshape(g, shape) for g in (packed.modes.flex,
                                       packed.modes.flex3))
    energy.warn_if_beyond(design, fields["y3_max"], fields["status"],
                          shapes=shapes)
    return Evaluation(**fields)


#: From this many modes, or this window (s), one design may take a
#: second or more (the extremum search's budget allows ~20 s; the thesis
#: design takes 1.4 s at tau = 1e4 s, 0.7 s at N = 800: docs/model.md):
#: such a batch starts with a piece of one design, and each piece runs
#: in a child process, which a signal ends at once (output.interruptible).
COSTLY_MODES = 200
COSTLY_TAU_S = 1.0


def costly(n_max: int, tau_max: float) -> bool:
    """True when a design of up to ``n_max`` modes and a window up to
    ``tau_max`` (s) may take seconds (COSTLY_MODES, COSTLY_TAU_S)."""
    return n_max >= COSTLY_MODES or not tau_max < COSTLY_TAU_S


def _in_pieces(backend, packed: Packed) -> dict:
    """backend.evaluate_packed(packed), in pieces sized by the time the
    ones before took (the results do not depend on the pieces)."""
    m = packed.size
    n_max = int(packed.ints[:, 3:].max()) if m else 1
    tau = packed.real[:, REAL_COLUMNS.index("tau")]
    forked = m > 0 and costly(n_max, float(np.max(tau)))
    # pieces of about pieces.PIECE_S of compiled work: Python sees Ctrl-C
    # and SIGTERM only between compiled calls (a study of 57 designs at
    # N = 100,000 was one call, deaf for minutes)
    sizes = pieces.PieceSizes(1 if forked else pieces.first_size(n_max))
    if sizes.next >= m and not forked:
        return backend.evaluate_packed(packed)
    out, first = {}, 0
    while first < m:
        last = min(m, first + sizes.next)
        start = time.perf_counter()
        piece = packed.ints[first:last, 3:]
        modes = None if packed.modes is None else packed.modes.rows(
            first, last, int(piece.max()))
        part = output.interruptible(
            forked, backend.evaluate_packed, Packed(
                real=packed.real[first:last], ints=packed.ints[first:last],
                options=packed.options, shape=(last - first,),
                modes=modes))
        # each piece copied into the batch's arrays as it comes: keeping
        # the pieces to concatenate at the end held the results twice
        # (1e6 designs: 710 MB peak against 470 MB)
        for key, value in part.items():
            value = np.asarray(value)
            per_mode = value.ndim == 2
            if key not in out:
                # per mode: padded with NaN to the batch's N
                out[key] = np.full((m, n_max), np.nan, dtype=value.dtype) \
                    if per_mode else np.empty((m,) + value.shape[1:],
                                              dtype=value.dtype)
            if per_mode:
                out[key][first:last, :value.shape[1]] = value
            else:
                out[key][first:last] = value
        del part
        sizes.record(last - first, time.perf_counter() - start)
        first = last
    return out


def _refuse_outside_domain(packed, out: dict) -> dict:
    """Designs outside the model's domain (the kernel computes them, but
    not to true digits) get status 2 and NaN results, as the kernel gives
    any other invalid design."""
    bad = outside_domain(packed.real, packed.ints) & (
        np.asarray(out["status"]) == status_codes.OK)
    if not np.any(bad):
        return out
    out = dict(out)
    for key, value in out.items():
        value = np.array(value)
        if key == "status":
            value[bad] = status_codes.INVALID_INPUT
        elif value.dtype.kind == "f":
            value[bad] = np.nan
        elif value.dtype.kind == "b":
            value[bad] = False
        out[key] = value
    return out
