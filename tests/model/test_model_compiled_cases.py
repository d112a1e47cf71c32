"""The compiled general model (fortran/model/, contactsep.model._model) held
against independent paths: published beam constants, mpmath, analytic
identities, and the NumPy twin (written from the equations separately).

Error models (why each tolerance is what it is)
- Mode values X_j(xi) at N <= 50: the argument k_jL xi carries a rounding
  error of a few ulp of k_jL (<= 160); X is O(1) with dX/du = O(1), so
  the absolute error is ~ a few eps k_jL.  We allow 32 eps max(k_jL, 1).
- Compiled vs twin: both evaluate the same closed forms in double with
  different operation orders; sums of <= 30 terms of O(1) mode values
  lose at most ~30 eps relative to the sum of magnitudes.  The first
  impact is polished to 1e-12 s in both, i.e. ~1e-12/t1 relative in t1
  and, through the velocity, ~p1 * 1e-12 relative in V.  Hence 1e-10
  relative for t1, V, psi, v0, R, masses, frequencies and c3.
- y3 extremes are sums sum c_j sin(p_j t): their rounding floor is
  ~ eps * S with S = sum |c_j|; y3_max can be exactly 0 (no positive
  excursion), so the floor used is 1e-10 * S absolute.
- The time of an extremum is ill-conditioned: y3(t* + dt) - y3(t*) =
  y3''(t*) dt^2 / 2, so a value error dy allows dt = sqrt(2 dy / |y3''|).
  With dy = 1e-10 S the times are compared within that bound; where the
  two backends pick different, equally high peaks (a tie within dy), the
  value at the compiled time must still reach the twin's extreme.
"""

import numpy as np
import pytest

from contactsep.model import compiled, status, twin
from contactsep.model.design import Packed

mpmath = pytest.importorskip("mpmath")

EPS = np.finfo(float).eps
ENDS = {1: "clamped-free", 2: "clamped-clamped", 3: "clamped-pinned",
        4: "pinned-pinned"}

# --------------------------------------------------------------- statuses


# ------------------------------------------------------------ beam modes

PUBLISHED = {  # tests/data/beam-constants.md (8-9 digits)
    1: [1.87510407, 4.69409113, 7.85475744, 10.99554073, 14.13716839,
        17.27875953],
    2: [4.73004074, 7.85320462, 10.9956078, 14.1371655, 17.2787597],
    3: [3.92660231, 7.06858275, 10.21017612, 13.35176878, 16.49336143],
}


@pytest.mark.parametrize("end", [1, 2, 3])
def test_eigenvalues_match_published(end):
    want = np.array(PUBLISHED[end])
    kl, _ = compiled.mode_values(end, len(want), [0.5])
    # published to 8 decimals or 9 significant digits
    np.testing.assert_allclose(kl, want, rtol=0, atol=6e-8)


def test_pinned_pinned_eigenvalues_are_j_pi():
    kl, x = compiled.mode_values(4, 50, [0.3])
    j = np.arange(1, 51)
    np.testing.assert_allclose(kl, j * np.pi, rtol=4 * EPS)
    np.testing.assert_allclose(x[:, 0], np.sqrt(2) * np.sin(j * np.pi * 0.3),
                               atol=32 * EPS * 160)


def _mp_modes(end, n, xi):
    """k_jL and X_j(xi) with 120-digit arithmetic (independent root solve
    from asymptotic guesses; the classical sigma and mode form)."""
    mp = mpmath.mp
    mp.dps = 120
    funcs = {1: lambda x: mp.cos(x) + 1 / mp.cosh(x),
             2: lambda x: mp.cos(x) - 1 / mp.cosh(x),
             3: lambda x: mp.sin(x) - mp.cos(x) * mp.tanh(x)}
    guesses = {1: lambda j: (2 * j - 1) * mp.pi / 2 + (0.3 if j == 1 else 0),
               2: lambda j: (2 * j + 1) * mp.pi / 2,
               3: lambda j: (4 * j + 1) * mp.pi / 4}
    kls, values = [], []
    for j in range(1, n + 1):
        if end == 4:
            k = j * mp.pi
            kls.append(k)
            values.append([mp.sqrt(2) * mp.sin(k * mp.mpf(x)) for x in xi])
            continue
        k = mp.findroot(funcs[end], guesses[end](j))
        if end == 1:
            sigma = (mp.cosh(k) + mp.cos(k)) / (mp.sinh(k) + mp.sin(k))
        else:
            sigma = (mp.cosh(k) - mp.cos(k)) / (mp.sinh(k) - mp.sin(k))
        row = []
        for x in xi:
            u = k * mp.mpf(x)
            row.append(mp.cosh(u) - mp.cos(u)
                       - sigma * (mp.sinh(u) - mp.sin(u)))
        kls.append(k)
        values.append(row)
    return (np.array([float(k) for k in kls]),
            np.array([[float(v) for v in r] for r in values]))


XI = [0.0, 0.1, 0.25, 0.5, 0.63, 0.78, 0.9, 0.999, 1.0]


@pytest.mark.parametrize("end", [1, 2, 3, 4])
def test_modes_match_mpmath_to_n50(end):
    want_kl, want_x = _mp_modes(end, 50, XI)
    kl, x = compiled.mode_values(end, 50, XI)
    np.testing.assert_allclose(kl, want_kl, rtol=4 * EPS)
    tol = 32 * EPS * np.maximum(want_kl, 1.0)[:, None]
    assert np.all(np.abs(x - want_x) <= tol), np.max(np.abs(x - want_x))
    # integral X^2 dxi = 1 (normalised to L), checked by Gauss-Legendre
    nodes, weights = np.polynomial.legendre.leggauss(200)
    _, xq = compiled.mode_values(end, 50, (nodes + 1) / 2)
    np.testing.assert_allclose(xq ** 2 @ weights / 2, 1.0, atol=1e-12)


def test_cantilever_identities():
    kl, x = compiled.mode_values(1, 50, [1.0])
    j = np.arange(1, 51)
    np.testing.assert_allclose(x[:, 0], 2.0 * (-1.0) ** (j + 1),
                               atol=32 * EPS * 160)
    # sum 1/(kL)^4 = 1/12; tail past j = 50 is < sum_{j>50} (pi(j-1/2))^-4
    tail = np.sum(1 / (np.pi * (np.arange(51, 100000) - 0.5)) ** 4)
    assert abs(np.sum(kl ** -4.0) + tail - 1 / 12) < 1e-14


def test_clamped_clamped_midspan_flexibility():
    kl, x = compiled.mode_values(2, 50, [0.5])
    assert np.all(np.abs(x[1::2, 0]) < 1e-13)  # antisymmetric modes
    s = np.sum(x[:, 0] ** 2 / kl ** 4)
    # tail bound: X^2 <= ~2.6 (|X| <= 1.61 at mid-span), kL > (j+1/2) pi
    tail = np.sum(2.6 / (np.pi * (np.arange(51, 100000) + 0.5)) ** 4)
    assert abs(s - 1 / 192) <= tail + 1e-15


# ------------------------------------------------------------ batches

COLUMNS = ("L1 b1 h1 gamma1 E1 x1 L2 b2 h2 gamma2 E2 x2 Lc "
           "L3 b3 h3 gamma3 E3 x3 ys e tau gap").split()


def random_packed(m, seed, n_range=(1, 30), options=(0, 0, 0, 0)):
    rng = np.random.default_rng(seed)
    col = {}
    for i, (lo, hi) in zip("123", [(5, 25), (1, 5), (5, 25)]):
        col["L" + i] = rng.uniform(lo, hi, m)
        col["b" + i] = rng.uniform(0.2, 2.0, m)
        col["h" + i] = rng.uniform(0.05, 0.5, m)
        col["gamma" + i] = rng.uniform(0.05, 0.35, m)
        col["E" + i] = rng.uniform(5e6, 30e6, m)
    ends = rng.integers(1, 5, size=(m, 3))
    for k, i in enumerate("123"):
        frac = rng.uniform(0.5, 1.0, m)
        # a cantilever may touch at its very tip; other ends are supported
        # at x = L, where every mode vanishes
        tip = (ends[:, k] == 1) & (rng.random(m) < 0.3)
        frac[tip] = 1.0
        col["x" + i] = frac * col["L" + i]
    col["Lc"] = np.where(rng.random(m) < 0.3,
                         rng.uniform(0.6, 1.0, m) * col["L2"], 0.0)
    col["ys"] = rng.uniform(0.05, 1.0, m)
    col["e"] = rng.uniform(0.0, 1.0, m)
    col["tau"] = rng.uniform(0.01, 0.1, m)
    col["gap"] = np.zeros(m)
    real = np.asfortranarray(np.stack([col[c] for c in COLUMNS], axis=1))
    n = rng.integers(n_range[0], n_range[1] + 1, size=(m, 3))
    ints = np.asfortranarray(np.concatenate([ends, n], axis=1)
                             .astype(np.int32))
    return Packed(real=real, ints=ints,
                  options=np.array(options, dtype=np.int32), shape=(m,))


RELATIVE = ("t1", "v_impact", "psi", "v0", "R", "M1", "M2", "M3",
            "p1", "p2", "p3", "c3")


def _y3(c, p, t):
    return np.nansum(c * np.sin(p * t[:, None]), axis=1)


def compare(got, want):
    """Assert the error model of the module docstring; return tie count."""
    np.testing.assert_array_equal(got["status"], want["status"])
    ok = want["status"] == status.OK
    assert ok.mean() > 0.5  # the comparison is not vacuous
    for key in RELATIVE:
        g, w = got[key][ok], want[key][ok]
        np.testing.assert_array_equal(np.isnan(g), np.isnan(w), err_msg=key)
        fin = ~np.isnan(w)
        np.testing.assert_allclose(g[fin], w[fin], rtol=1e-10, atol=0,
                                   err_msg=key)
    for key in RELATIVE + ("y3_max", "y3_min", "t_max", "t_min"):
        assert np.all(np.isnan(got[key][~ok][..., 0] if got[key].ndim > 1
                               else got[key][~ok])), key
    c, p = want["c3"][ok], want["p3"][ok]
    scale = np.nansum(np.abs(c), axis=1)
    floor = 1e-10 * scale
    ties = 0
    for name, tname, sign in (("y3_max", "t_max", 1), ("y3_min", "t_min", -1)):
        g, w = got[name][ok], want[name][ok]
        assert np.all(np.abs(g - w) <= floor), (name, np.max(
            np.abs(g - w) / scale))
        tg, tw = got[tname][ok], want[tname][ok]
        y2 = np.abs(np.nansum(c * p ** 2 * np.sin(p * tw[:, None]), axis=1))
        dt = np.sqrt(2 * floor / np.maximum(y2, 1e-300)) + 1e-12
        close = np.abs(tg - tw) <= dt
        # a tie: the compiled time reaches the twin's extreme all the same
        tie = ~close & (sign * (_y3(c, p, tg) - w) >= -2 * floor)
        assert np.all(close | tie), tname
        ties += int(tie.sum())
    end_g, end_w = got["at_window_end"][ok], want["at_window_end"][ok]
    tau = want["t_max"][ok]  # only used where flags differ
    differ = end_g != end_w
    if differ.any():  # allowed only for a tie between y3(tau) and y3_max
        taus = np.where(end_g, got["t_max"][ok], tau)[differ]
        at_tau = _y3(c[differ], p[differ], taus)
        assert np.all(np.abs(at_tau - want["y3_max"][ok][differ])
                      <= 2 * floor[differ])
    return ties


@pytest.mark.parametrize("options", [(0, 0, 0, 0), (1, 1, 1, 1),
                                     (0, 1, 2, 1)])
def test_compiled_matches_twin_small(options):
    packed = random_packed(150, seed=sum(options) + 11, n_range=(1, 12),
                           options=options)
    ties = compare(compiled.evaluate_packed(packed),
                   twin.evaluate_packed(packed))
    assert ties <= 3


def test_compiled_matches_twin_1000_designs_n_to_30():
    packed = random_packed(1200, seed=2026)
    ties = compare(compiled.evaluate_packed(packed),
                   twin.evaluate_packed(packed))
    assert ties <= 12


def test_invalid_designs_mid_batch_keep_the_others():
    packed = random_packed(40, seed=5, n_range=(1, 6))
    clean = compiled.evaluate_packed(packed)
    real, ints = packed.real.copy(order="F"), packed.ints.copy(order="F")
    bad = {10: ("h2", -1.0), 11: ("E1", np.nan), 12: ("x3", np.inf),
           13: ("e", 1.5), 14: ("tau", 0.0), 15: ("L2", -np.inf),
           16: ("ys", np.nan), 17: ("x1", 0.0)}
    for row, (name, value) in bad.items():
        real[row, COLUMNS.index(name)] = value
    ints[20, 0] = 7      # unknown end code
    ints[21, 4] = 0      # n2 < 1
    mixed = compiled.evaluate_packed(
        Packed(real=real, ints=ints, options=packed.options, shape=(40,)))
    broken = sorted(list(bad) + [20, 21])
    assert np.all(mixed["status"][broken] == status.INVALID_INPUT)
    for key in RELATIVE[:8] + ("y3_max", "t_max", "y3_min", "t_min"):
        assert np.all(np.isnan(mixed[key][broken])), key
    for key in ("at_window_end", "t_max_tied", "t_min_tied"):
        assert not np.any(mixed[key][broken]), key
    keep = np.setdiff1d(np.arange(40), broken)
    for key, value in clean.items():
        if key in ("p1", "p2", "p3", "c3"):
            continue  # nmax may differ; rows compared below
        np.testing.assert_array_equal(mixed[key][keep], value[keep],
                                      err_msg=key)
    n = clean["c3"].shape[1]
    np.testing.assert_array_equal(mixed["c3"][keep, :n], clean["c3"][keep])


def test_nan_and_inf_in_every_column_give_status_2():
    base = random_packed(1, seed=3, n_range=(4, 4))
    for value in (np.nan, np.inf, -np.inf):
        real = np.asfortranarray(np.repeat(base.real, len(COLUMNS), axis=0))
        real[np.arange(len(COLUMNS)), np.arange(len(COLUMNS))] = value
        ints = np.asfortranarray(np.repeat(base.ints, len(COLUMNS), axis=0))
        got = compiled.evaluate_packed(Packed(real=real, ints=ints,
                                              options=base.options,
                                              shape=(len(COLUMNS),)))
        assert np.all(got["status"] == status.INVALID_INPUT), value


def test_empty_batch():
    packed = random_packed(0, seed=1)
    got = compiled.evaluate_packed(packed)
    assert got["status"].shape == (0,)
