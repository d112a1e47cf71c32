"""The general uniform beam: Timoshenko or Bernoulli-Euler, rigid or
elastic supports, point masses, in dimensionless form: the beam, its
multiple-shooting system and its frequency equation (the eigenvalues).
On this system, its normal modes are
:mod:`~contactsep.beams.timoshenko_modes` and its static flexibility
:mod:`~contactsep.beams.timoshenko_static`.

Variables (x = xi L; w the deflection, psi the rotation of the section,
M = EI psi' the bending moment, Q = kappa G A (w' - psi) the shear force):

    rho A w_tt = Q',        rho I psi_tt = M' + Q.

At a circular frequency omega the state z = [w/L, psi, M L/EI, Q L^2/EI]
obeys z' = A(b) z (' = d/dxi) with

    A = [[0, 1, 0, s2], [0, 0, 1, 0], [0, -b^2 r2, 0, -1], [-b^2, 0, 0, 0]],

b^2 = rho A omega^2 L^4 / EI (b = (kL)^2 of a Bernoulli-Euler beam),
r2 = I/(A L^2) (rotary inertia) and s2 = EI/(kappa G A L^2) (shear
flexibility); r2 = s2 = 0 is the Bernoulli-Euler beam.  Its exact
transfer matrix over a segment is expm(A Delta).  The beam is cut into
segments short enough (alpha Delta <= 2, alpha <= b^(1/2) the growing
wavenumber) that no transfer matrix grows past e^2; the segments' states
are the unknowns of one banded system (multiple shooting), so no product
of transfer matrices ever subtracts numbers of size e^(kL).  The
frequency equation is det K(b) = 0, an entire function of b: the
eigenvalues are its sign changes, found on a scan finer than the
spectrum's least spacing (both branches of a Timoshenko beam above its
cut-off frequency included) and bisected to adjacent doubles.

Boundary and point conditions (kr = k_r L/EI, kt = k_t L^3/EI, mu = m/(rho
A L); x = 0 left, x = L right):

* clamped end: w = 0 or, elastic, Q = +kt w (left) / -kt w (right);
  psi = 0 or, elastic, M = +kr psi (left) / -kr psi (right);
* pinned end: w as a clamped end's; M = 0;  free end: M = 0, Q = 0;
* point mass at xi_m: Q(xi_m+) - Q(xi_m-) = -mu b^2 w(xi_m).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from contactsep.beams import bernoulli_euler as be
from contactsep.errors import InputError

#: Most modes of a general beam: far past L/h neither beam theory holds,
#: and the segmented system grows with the mode number.
MAX_GENERAL_MODES = 200

#: Frequencies a scan evaluates at once (one batch of determinants).
SCAN_CHUNK = 64

#: Where each end condition's ends are clamped, pinned or free.
ENDS = {"clamped-free": ("clamped", "free"),
        "clamped-clamped": ("clamped", "clamped"),
        "clamped-pinned": ("clamped", "pinned"),
        "pinned-pinned": ("pinned", "pinned")}


@dataclass(frozen=True)
class Beam:
    """A uniform beam in dimensionless form (module docstring).

    end : str
        One of ``contactsep.beams.END_CONDITIONS`` (or an alias).
    r2, s2 : float
        Rotary inertia I/(A L^2) and shear flexibility EI/(kappa G A
        L^2); both 0 for Bernoulli-Euler.
    kr, kt : float or None
        Rotational (k_r L/EI) and translational (k_t L^3/EI) stiffness
        of the supports, the same at every supported end (kr at clamped
        ends only); None: rigid.
    masses : tuple of (xi, mu)
        Point masses m at x = xi L, mu = m/(rho A L).
    """

    end: str = "clamped-clamped"
    r2: float = 0.0
    s2: float = 0.0
    kr: float | None = None
    kt: float | None = None
    masses: tuple = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "end", be._canonical(self.end))
        for name in ("r2", "s2"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value >= 0.0):
                raise ValueError(f"{name} must be finite and >= 0, "
                                 f"got {value!r}")
        for name in ("kr", "kt"):
            value = getattr(self, name)
            if value is not None and not (np.isfinite(value)
                                          and value > 0.0):
                raise ValueError(f"{name} must be None (rigid) or a "
                                 f"finite number > 0, got {value!r}")
        masses = tuple((float(xi), float(mu)) for xi, mu in self.masses
                       if mu != 0.0)
        for xi, mu in masses:
            if not (0.0 <= xi <= 1.0 and np.isfinite(mu) and mu > 0.0):
                raise ValueError(f"a point mass needs 0 <= xi <= 1 and "
                                 f"mu > 0, got ({xi!r}, {mu!r})")
        object.__setattr__(self, "masses", masses)

    @property
    def classical(self) -> bool:
        """Bernoulli-Euler, rigid ends, no mass: the closed-form modes."""
        return (self.r2 == 0.0 and self.s2 == 0.0 and self.kr is None
                and self.kt is None and not self.masses)


# ---------------------------------------------------------------- matrices

def system_matrix(beam: Beam, b, scale):
    """A' = D A D^-1 (..., 4, 4) of the scaled state z_i / scale^i."""
    b = np.asarray(b, dtype=np.float64)
    k = np.asarray(scale, dtype=np.float64)
    a = np.zeros(b.shape + (4, 4))
    a[..., 0, 1] = k
    a[..., 0, 3] = beam.s2 * k**3
    a[..., 1, 2] = k
    a[..., 2, 1] = -b**2 * beam.r2 / k
    a[..., 2, 3] = -k
    a[..., 3, 0] = -b**2 / k**3
    return a


def expm(a):
    """exp of a stack of 4x4 matrices: scaling and squaring, Taylor to
    order 14 on a norm <= 1/4 (truncation < 1e-20)."""
    norm = float(np.max(np.sum(np.abs(a), axis=-1))) if a.size else 0.0
    squarings = max(0, int(np.ceil(np.log2(norm / 0.25)))) if norm > 0.25 \
        else 0
    x = a / 2.0**squarings
    eye = np.broadcast_to(np.eye(4), a.shape)
    result = eye.copy()
    for order in range(14, 0, -1):
        result = eye + (x @ result) / order
    for _ in range(squarings):
        result = result @ result
    return result


def state_scale(b):
    """k = max(|b|, 1)^(1/2): the state's component i is scaled by k^-i
    (:func:`system_matrix`), so that the scaled components are of one
    size."""
    return np.sqrt(np.maximum(np.abs(np.asarray(b, dtype=np.float64)),
                              1.0))


def mesh(beam: Beam, b_max: float, extra=()):
    """Nodes 0 = xi_0 < ... < xi_n = 1 (masses and ``extra`` points among
    them), each segment at most 2 / alpha_max long."""
    growth = np.sqrt(max(b_max, 1.0))
    step = 2.0 / growth
    cuts = sorted({0.0, 1.0, *(xi for xi, _ in beam.masses), *extra})
    nodes = [0.0]
    for lo, hi in zip(cuts[:-1], cuts[1:]):
        count = max(1, int(np.ceil((hi - lo) / step)))
        nodes.extend(lo + (hi - lo) * np.arange(1, count + 1) / count)
        nodes[-1] = hi
    return np.array(nodes)


def _end_rows(beam: Beam, side: str, scale):
    """Two boundary rows (..., 2, 4) on the scaled state at one end."""
    kind = ENDS[beam.end][0 if side == "left" else 1]
    sign = 1.0 if side == "left" else -1.0
    k = np.asarray(scale, dtype=np.float64)
    rows = np.zeros(k.shape + (2, 4))
    powers = np.stack([np.ones_like(k), k, k**2, k**3], axis=-1)
    if kind == "free":
        rows[..., 0, 2] = 1.0
        rows[..., 1, 3] = 1.0
    else:
        if beam.kt is None:
            rows[..., 0, 0] = 1.0
        else:                               # Q = sign kt w
            rows[..., 0, 3] = 1.0
            rows[..., 0, 0] = -sign * beam.kt
        if kind == "pinned":
            rows[..., 1, 2] = 1.0
        elif beam.kr is None:
            rows[..., 1, 1] = 1.0
        else:                               # M = sign kr psi
            rows[..., 1, 2] = 1.0
            rows[..., 1, 1] = -sign * beam.kr
    rows = rows * powers[..., None, :]
    return rows / np.max(np.abs(rows), axis=-1, keepdims=True)


def _jump(mu, b, scale):
    """(I + J): the state past a point mass (scaled)."""
    j = np.broadcast_to(np.eye(4), np.shape(b) + (4, 4)).copy()
    j[..., 3, 0] -= mu * np.asarray(b)**2 / np.asarray(scale)**3
    return j


def assemble(beam: Beam, nodes, b):
    """The multiple-shooting matrix K(b) (..., 4(n+1), 4(n+1))."""
    b = np.atleast_1d(np.asarray(b, dtype=np.float64))
    scale = state_scale(b)
    a = system_matrix(beam, b, scale)
    n = len(nodes) - 1
    size = 4 * (n + 1)
    k = np.zeros(b.shape + (size, size))
    mass_at = dict(beam.masses)
    left = _end_rows(beam, "left", scale)
    if 0.0 in mass_at:                      # rows act on the state before
        left = left @ _jump(-mass_at[0.0], b, scale)
    k[..., 0:2, 0:4] = left
    cache = {}
    for seg in range(n):
        length = nodes[seg + 1] - nodes[seg]
        key = round(length, 15)
        if key not in cache:
            cache[key] = expm(a * length)
        t = cache[key]
        if nodes[seg + 1] in mass_at:
            t = _jump(mass_at[nodes[seg + 1]], b, scale) @ t
        row = 2 + 4 * seg
        k[..., row:row + 4, 4 * seg:4 * seg + 4] = -t
        k[..., row:row + 4, 4 * seg + 4:4 * seg + 8] = np.eye(4)
    k[..., size - 2:size, size - 4:size] = _end_rows(beam, "right", scale)
    return k


# ------------------------------------------------------------ frequencies

def _upper_bound(beam: Beam, n: int) -> float:
    """b_n of the rigid Bernoulli-Euler beam: every added flexibility
    (shear, supports) and inertia (rotary, masses) lowers each eigenvalue
    (Rayleigh's min-max), so b_n of ``beam`` is below it."""
    return float(be.eigenvalues(beam.end, n)[-1]) ** 2


def _sign(beam: Beam, nodes, b):
    """(sign, log |det K(b)|) for each b: the frequency function, kept
    in two parts so that no determinant overflows."""
    sign, logabs = np.linalg.slogdet(assemble(beam, nodes, b))
    return sign, logabs


def _scan_points(beam: Beam, top: float, refine: int):
    """b values finer than the spectrum's spacing: Delta kappa = pi/8 in
    kappa = b^(1/2) (Bernoulli-Euler roots are pi apart), and the second
    branch's pi/(2 kappa max(r, s)) above the cut-off, over 8."""
    width = max(np.sqrt(beam.r2), np.sqrt(beam.s2))
    kappa = [0.0]
    while kappa[-1] < top:
        spacing = np.pi / (1.0 + 2.0 * kappa[-1] * width)
        kappa.append(kappa[-1] + spacing / (8.0 * 2**refine))
    return np.array(kappa)**2


def eigenvalues(beam: Beam, n: int) -> np.ndarray:
    """b_j = omega_j L^2 sqrt(rho A/EI), j = 1..n (= (k_jL)^2 for a
    Bernoulli-Euler beam), to adjacent doubles."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or \
            not 1 <= n <= MAX_GENERAL_MODES:
        raise ValueError(f"n must be an integer from 1 to "
                         f"{MAX_GENERAL_MODES}, got {n!r}")
    top = np.sqrt(_upper_bound(beam, n)) + 0.5
    nodes = mesh(beam, top**2)
    for refine in range(4):
        points = _scan_points(beam, top, refine)
        # in chunks from b = 0, until n sign changes are seen: the bound
        # is far above the n-th root of a stubby Timoshenko beam
        sign = np.empty(0)
        for start in range(0, len(points), SCAN_CHUNK):
            fresh = _sign(beam, nodes, points[start:start + SCAN_CHUNK])[0]
            sign = np.concatenate([sign, fresh])
            change = np.flatnonzero(sign[:-1] * sign[1:] < 0.0)
            if change.size >= n:
                break
        if change.size >= n:
            break
    else:
        # an InputError (one line from the CLI), not a traceback: the
        # scan could not separate two roots of this beam
        raise InputError(f"found {change.size} of {n} eigenvalues of "
                         f"{beam} (two roots closer than the scan "
                         f"resolves; ask for fewer modes)")
    lo, hi = points[change[:n]], points[change[:n] + 1]
    return _refine(beam, nodes, lo, hi)


def _refine(beam: Beam, nodes, lo, hi):
    """Roots bracketed by [lo, hi], to adjacent doubles: regula falsi
    with the Illinois modification (superlinear) on det K, kept as (sign,
    log |det|) so that no determinant overflows; bisection where a step
    would not move."""
    s_lo, l_lo = _sign(beam, nodes, lo)
    s_hi, l_hi = _sign(beam, nodes, hi)
    last = np.zeros(lo.shape)              # -1: lo kept last, +1: hi
    for _ in range(400):
        done = (hi - lo) <= 2.0 * np.spacing(hi)
        if np.all(done):
            break
        # |f_lo| / (|f_lo| + |f_hi|), from the logs
        t = 1.0 / (1.0 + np.exp(np.clip(l_hi - l_lo, -700.0, 700.0)))
        x = lo + t * (hi - lo)
        stuck = ~((x > lo) & (x < hi))
        x = np.where(stuck, 0.5 * (lo + hi), x)
        x = np.where(done, lo, x)
        s_x, l_x = _sign(beam, nodes, x)
        same = (s_x == s_lo) & ~done
        other = ~same & ~done
        # Illinois: an end kept twice in a row has its |f| halved
        l_hi = np.where(same & (last == 1.0), l_hi - np.log(2.0), l_hi)
        l_lo = np.where(other & (last == -1.0), l_lo - np.log(2.0), l_lo)
        lo = np.where(same, x, lo)
        l_lo = np.where(same, l_x, l_lo)
        hi = np.where(other, x, hi)
        l_hi = np.where(other, l_x, l_hi)
        s_hi = np.where(other, s_x, s_hi)
        last = np.where(same, 1.0, np.where(other, -1.0, last))
    at_lo = _sign(beam, nodes, lo)[1]
    at_hi = _sign(beam, nodes, hi)[1]
    return np.where(at_lo <= at_hi, lo, hi)
