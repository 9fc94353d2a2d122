"""The normalised datasheet envelope: coordinates, basis and residual (docs/model.md section 11).

On the normalised range u = ω/R ∈ [−1, 1] and with the coefficients in units
of the nonlinearity limit b,

    y = (A1·R, k2·R², k3·R³, k4·R⁴, k5·R⁵) / b                (dimensionless)
    p(u) = ½·y1·|u| + y2·u² + y3·u³ + y4·u⁴ + y5·u⁵

and the residual from the reference line is r(u) = Σ y_i·ψ_i(u) − α − β·u with
ψ_i = φ_i − o_i − s_i·u (φ = (½|u|, u², u³, u⁴, u⁵)):

* least-squares: o, s are the least-squares line of each φ_i over uniform u
  (mean ½|u| = 1/4, mean u² = 1/3, mean u⁴ = 1/5; slope of u³ = (2/5)/(2/3) =
  3/5, of u⁵ = (2/7)/(2/3) = 3/7), α = β = 0;
* endpoint: the chord through u = ±1 (o = φ(1) for even φ, s = φ(1) for odd),
  α = β = 0;
* minimax: o = s = 0 and (α, β) are free variables.

The envelope E is {y : |r(u)| ≤ 1 on [−1, 1]} (measure max) or
{y : mean r² ≤ 1} (measure rms), intersected with |y1| ≤ a when an asymmetry
spec |A1| ≤ a_max gives a = a_max·R/b. Its support function is in
:mod:`gyrovib.core.envelope_lp`.
"""

from __future__ import annotations

import numpy as np

from gyrovib.core._types import FloatArray

FITS: tuple[str, ...] = ("least-squares", "minimax", "endpoint")
MEASURES: tuple[str, ...] = ("max", "rms")

#: o_i and s_i of the module docstring, rows in the order of FITS.
OFFSET = np.array([[0.25, 1.0 / 3.0, 0.0, 0.2, 0.0],
                   [0.0, 0.0, 0.0, 0.0, 0.0],
                   [0.5, 1.0, 0.0, 1.0, 0.0]])
SLOPE = np.array([[0.0, 0.0, 0.6, 0.0, 3.0 / 7.0],
                  [0.0, 0.0, 0.0, 0.0, 0.0],
                  [0.0, 0.0, 1.0, 0.0, 1.0]])
MINIMAX = 1


def basis(fit: np.ndarray, u: np.ndarray) -> FloatArray:
    """ψ(u) of the module docstring, shape (..., 5); fit: FITS index, broadcast with u."""
    u = np.asarray(u, dtype=float)
    a = np.abs(u)
    phi = np.stack([0.5 * a, u * u, u**3, u**4, u**5], axis=-1)
    return np.asarray(phi - OFFSET[fit] - SLOPE[fit] * u[..., None], dtype=float)


def residual_normalised(fit: np.ndarray, y: np.ndarray, line: np.ndarray,
                        u: np.ndarray) -> FloatArray:
    """r(u) for blocks (K,) of y (K, 5) and line (K, 2) = (α, β) at u (K, m)."""
    psi = basis(np.asarray(fit)[:, None], u)
    r = np.einsum("kmi,ki->km", psi, y) - line[:, :1] - line[:, 1:] * u
    return np.asarray(r, dtype=float)


def gram(fit: int) -> FloatArray:
    """Mean of ψ_i·ψ_j over uniform u ∈ [−1, 1], in closed form (5 × 5).

    Every ψ_i is a combination of f = (1, u, u², u³, u⁴, u⁵, |u|); the means
    of their products are ½∫u^(a+b) = 1/(a+b+1) for even a+b (0 for odd),
    ½∫|u|·u^a = 1/(a+2) for even a (0 for odd) and mean u² = 1/3.
    """
    h = np.zeros((7, 7))
    for i in range(6):
        for j in range(6):
            h[i, j] = 1.0 / (i + j + 1) if (i + j) % 2 == 0 else 0.0
        h[i, 6] = h[6, i] = 1.0 / (i + 2) if i % 2 == 0 else 0.0
    h[6, 6] = 1.0 / 3.0
    p = np.zeros((5, 7))
    p[0, 6] = 0.5
    for i in range(1, 5):
        p[i, i + 1] = 1.0
    p[:, 0] -= OFFSET[fit]
    p[:, 1] -= SLOPE[fit]
    return np.asarray(p @ h @ p.T, dtype=float)


def _side_roots(q: np.ndarray) -> FloatArray:
    """Real parts of the roots of the quartics q (K, 5), ascending powers; NaN pads.

    Batched companion-matrix eigenvalues, grouped by effective degree. Complex
    roots contribute their real part too: extra candidate points are harmless.
    """
    k = q.shape[0]
    out = np.full((k, 4), np.nan)
    scale = np.max(np.abs(q), axis=1)
    big = np.abs(q) > 1e-13 * scale[:, None]
    deg = np.where(big.any(axis=1), 4 - np.argmax(big[:, ::-1], axis=1), 0)
    for n in range(1, 5):
        sel = np.flatnonzero(deg == n)
        if sel.size == 0:
            continue
        mon = q[sel, :n] / q[sel, n:n + 1]
        comp = np.zeros((sel.size, n, n))
        comp[:, np.arange(1, n), np.arange(n - 1)] = 1.0
        comp[:, :, n - 1] = -mon
        out[sel, :n] = np.linalg.eigvals(comp).real
    return out


def true_max(fit: np.ndarray, y: np.ndarray, line: np.ndarray) -> tuple[FloatArray, FloatArray]:
    """max |r(u)| over [−1, 1] of each block, from every critical point.

    On each side of the kink r is a quintic; its extrema lie at u = −1, 0, 1
    and the real roots of r' on (−1, 0) and (0, 1). Returns the maxima (K,)
    and the candidate points (K, 11) (NaN where a side has fewer roots).
    """
    lin = -np.einsum("ki,ki->k", y, SLOPE[fit]) - line[:, 1]
    cands = [np.tile([-1.0, 0.0, 1.0], (y.shape[0], 1))]
    for side in (-1.0, 1.0):
        c1 = 0.5 * y[:, 0] * side + lin
        dq = np.column_stack([c1, 2 * y[:, 1], 3 * y[:, 2], 4 * y[:, 3], 5 * y[:, 4]])
        roots = _side_roots(dq)
        lo, hi = (-1.0, 0.0) if side < 0 else (0.0, 1.0)
        roots = np.where((roots >= lo) & (roots <= hi), roots, np.nan)
        cands.append(roots)
    u = np.concatenate(cands, axis=1)
    r = residual_normalised(fit, y, line, np.nan_to_num(u))
    r = np.where(np.isnan(u), 0.0, np.abs(r))
    return np.max(r, axis=1), u
