"""The normalised datasheet envelope and its support function (MODEL.md section 11).

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
spec |A1| ≤ a_max gives a = a_max·R/b. E is compact and symmetric, so its
support function h(d) = max_{y∈E} dᵀy is the worst of any linear functional
of the coefficients; :func:`support` evaluates it for many (envelope,
direction) pairs at once.
"""

from __future__ import annotations

import numpy as np

from gyrovib.core import highs
from gyrovib.core.transmissibility import FloatArray

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

#: The grid optimum and the feasible scaled solution agree to this (relative).
TOLERANCE = 1e-7
#: Refinement rounds before giving up (the scaled solution is feasible anyway).
MAX_ROUNDS = 40
#: LPs stacked block-diagonally into one HiGHS call.
CHUNK = 48
#: Offsets added around each violating extremum: the extremum moves as the
#: solution does, and a cluster of scales catches it in fewer rounds.
_CLUSTER = np.array([-3e-3, -1e-4, 1e-4, 3e-3])
#: Pairs solved from the coarse grid alone before the others are seeded.
SEEDS = 16


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


def _support_rms(fit: np.ndarray, a: np.ndarray, d: np.ndarray) -> tuple[FloatArray, FloatArray]:
    """max dᵀy over yᵀGy ≤ 1 (and |y1| ≤ a): closed form.

    Without the cut, h = √(dᵀG⁻¹d) at y = G⁻¹d/h (G is positive definite: the
    ψ_i are independent). When |y1| > a there, the optimum lies on y1 = ±a
    (same sign; a linear objective over a strictly convex set cut by a slab
    that excludes its unconstrained optimum): with G = [[g11, gᵀ], [g, Gz]],
    z = z0 + w, z0 = −y1·Gz⁻¹g, wᵀGz·w ≤ 1 − a²·s (s = g11 − gᵀGz⁻¹g, the
    Schur complement), so h = d1·y1 + d_zᵀz0 + √((1 − a²s)·d_zᵀGz⁻¹d_z).
    """
    k = d.shape[0]
    h = np.zeros(k)
    y = np.zeros((k, 5))
    for f in range(len(FITS)):
        sel = fit == f
        if not sel.any():
            continue
        g = gram(int(f))
        gi = np.linalg.inv(g)
        dd = d[sel]
        t = dd @ gi
        val = np.sqrt(np.einsum("ki,ki->k", t, dd))
        with np.errstate(invalid="ignore", divide="ignore"):
            yy = np.where(val[:, None] > 0, t / val[:, None], 0.0)
        aa = a[sel]
        cut = np.abs(yy[:, 0]) > aa
        if cut.any():
            gz = g[1:, 1:]
            gzi = np.linalg.inv(gz)
            gv = g[1:, 0]
            s = g[0, 0] - gv @ gzi @ gv
            y1 = np.sign(yy[cut, 0]) * aa[cut]
            z0 = -y1[:, None] * (gzi @ gv)[None, :]
            dz = dd[cut, 1:]
            q = np.einsum("ki,ij,kj->k", dz, gzi, dz)
            rem = np.maximum(1.0 - aa[cut] ** 2 * s, 0.0)
            with np.errstate(invalid="ignore", divide="ignore"):
                step = np.where(q > 0, np.sqrt(rem / q), 0.0)
            z = z0 + step[:, None] * (dz @ gzi)
            yy[cut] = np.column_stack([y1, z])
            val[cut] = np.einsum("ki,ki->k", dd[cut], yy[cut])
        h[sel] = val
        y[sel] = yy
    return h, y


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


def union(grid: np.ndarray, points: np.ndarray) -> FloatArray:
    """The sorted distinct values of both (np.unique without numpy.ma, which it imports)."""
    c = np.sort(np.concatenate([grid, points]))
    keep = np.ones(c.size, dtype=bool)
    keep[1:] = c[1:] != c[:-1]
    return c[keep]


def _initial_grid(n: int = 8) -> FloatArray:
    """2n + 1 points on [−1, 1], clustered towards ±1 and 0 (Chebyshev on each half)."""
    t = 0.5 * (1.0 - np.cos(np.pi * np.arange(n + 1) / n))
    return union(-t, t)


def _grid_columns(fit: np.ndarray, blk: np.ndarray,
                  u: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The dual's columns λ⁺_j (all j), then λ⁻_j, for points u of blocks blk.

    Column j holds ψ̃(u_j) in the rows of its block (5, or 7 with the minimax
    line); returns the entries per column, their rows and their values.
    Boolean indexing walks the (m, 7) table row-major, so the entries come
    column by column.
    """
    m = u.size
    vals = np.concatenate([basis(fit[blk], u), -np.ones((m, 1)), -u[:, None]], axis=1)
    keep = np.ones((m, 7), dtype=bool)
    keep[:, 5:] = (fit[blk] == MINIMAX)[:, None]
    rows = (7 * blk[:, None] + np.arange(7))[keep]
    v = vals[keep]
    per_col = keep.sum(axis=1)
    return (np.concatenate([per_col, per_col]), np.concatenate([rows, rows]),
            np.concatenate([v, -v]))


class _GridLP:
    """One block-diagonal LP: max Σ_k d_kᵀy_k s.t. |r_k(u)| ≤ 1 on grid k.

    Solved as its LP dual, which has 5 (7 with the minimax line) equality
    rows per block instead of two rows per grid point: with ψ̃(u) = (ψ(u), −1,
    −u) and the line's columns kept only for minimax,

        min Σ_j (λ⁺_j + λ⁻_j) + a·(μ⁺ + μ⁻)
        s.t. Σ_j (λ⁺_j − λ⁻_j)·ψ̃(u_j) + (μ⁺ − μ⁻)·e1 = (d, 0, 0),  λ, μ ≥ 0

    (μ absent when a = inf). Its optimum equals the primal one and the
    multipliers of the equality rows are the primal (y, α, β). A refinement
    round adds grid points, i.e. columns of the dual: HiGHS re-solves from
    the last optimal basis, which stays feasible.
    """

    def __init__(self, fit: np.ndarray, a: np.ndarray, d: np.ndarray,
                 grids: list[FloatArray]) -> None:
        self.fit, self.a, self.d = fit, a, d
        self.grids = list(grids)
        self.model: highs.Model | None = None

    def _build(self, options: dict[str, float | str] | None) -> highs.Model:
        k = self.d.shape[0]
        counts = np.array([g.size for g in self.grids])
        u = np.concatenate(self.grids)
        sizes, index, value = _grid_columns(self.fit, np.repeat(np.arange(k), counts), u)
        mu = np.flatnonzero(np.isfinite(self.a))
        n_mu = mu.size
        sizes = np.concatenate([sizes, np.ones(2 * n_mu, dtype=int)])
        start = np.concatenate([[0], np.cumsum(sizes)])
        index = np.concatenate([index, 7 * mu, 7 * mu])
        value = np.concatenate([value, np.ones(n_mu), -np.ones(n_mu)])
        b_eq = np.concatenate([self.d, np.zeros((k, 2))], axis=1).ravel()
        cost = np.concatenate([np.ones(2 * u.size), self.a[mu], self.a[mu]])
        n = cost.size
        return highs.Model(cost, start, index, value, b_eq, b_eq, np.zeros(n),
                           np.full(n, np.inf), options)

    def add(self, points: dict[int, FloatArray]) -> None:
        """Add grid points to blocks: {block: new points (not yet on its grid)}."""
        for j, p in points.items():
            self.grids[j] = union(self.grids[j], p)
        if self.model is None:
            return
        blk = np.concatenate([np.full(p.size, j) for j, p in points.items()])
        u = np.concatenate(list(points.values()))
        sizes, index, value = _grid_columns(self.fit, blk, u)
        n = sizes.size
        self.model.add_columns(np.ones(n), np.concatenate([[0], np.cumsum(sizes)]), index,
                               value, np.zeros(n), np.full(n, np.inf))

    def solve(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The grid optimum (K,), y (K, 5) and line (K, 2) of every block."""
        if self.model is None:
            self.model = self._build(highs.TIGHT)
        res = self.model.run()
        if not res.ok:
            # HiGHS can stall at the tight tolerances on a badly scaled block (a tight
            # asymmetry cut with the minimax line); its defaults solve it, and the
            # refinement checks feasibility on the continuous range either way. The
            # next round starts again from a fresh model at the tight tolerances.
            self.model = None
            res = self._build(None).run()
        if not res.ok:  # pragma: no cover - the envelope is compact, its dual feasible
            raise ArithmeticError(f"envelope LP failed: {res.status}")
        x = res.row_dual.reshape(-1, 7)
        y = x[:, :5]
        return np.einsum("ki,ki->k", self.d, y), y, x[:, 5:]


def _new_points(grid: np.ndarray, points: np.ndarray) -> FloatArray:
    """The distinct values of points that are not on the (sorted) grid."""
    p = union(points, np.empty(0))
    pos = np.minimum(np.searchsorted(grid, p), grid.size - 1)
    out: FloatArray = p[grid[pos] != p]
    return out


def _refine(fit: np.ndarray, a: np.ndarray, d: np.ndarray, grids: list[FloatArray],
            todo: np.ndarray, out: tuple[FloatArray, ...]) -> list[FloatArray]:
    """Grid LP, continuous check, add the residual's violating extrema; repeat.

    Blocks go CHUNK at a time into one :class:`_GridLP`, re-solved from its
    last basis after each round adds points. Fills ``out`` = (h, y, line,
    gap) at ``todo`` with the feasible scaled solution; returns each block's
    final extrema (|r| ≥ 0.99), for seeding.
    """
    h, y, line, gap = out
    extrema: list[FloatArray] = [np.empty(0)] * d.shape[0]
    for start in range(0, todo.size, CHUNK):
        idx = todo[start:start + CHUNK]
        lp = _GridLP(fit[idx], a[idx], d[idx], [grids[i] for i in idx])
        live = np.arange(idx.size)
        for _ in range(MAX_ROUNDS):
            hg, yg, lg = (v[live] for v in lp.solve())
            sel = idx[live]
            mx, cand = true_max(fit[sel], yg, lg)
            # shrink onto the continuous envelope; never grow (|y1| ≤ a may be what binds)
            scale = 1.0 / np.maximum(mx, 1.0)
            h[sel] = hg * scale
            y[sel] = yg * scale[:, None]
            line[sel] = lg * scale[:, None]
            gap[sel] = 1.0 - scale
            r = np.abs(residual_normalised(fit[sel], yg, lg, np.nan_to_num(cand)))
            ok = ~np.isnan(cand)
            adds: dict[int, FloatArray] = {}
            for j, i in enumerate(sel):
                extrema[i] = cand[j][ok[j] & (r[j] >= 0.99 * mx[j])]
                if mx[j] > 1.0 + TOLERANCE:
                    new = cand[j][ok[j] & (r[j] > 1.0)]
                    near = (new[:, None] + _CLUSTER[None, :]).ravel()
                    near = near[np.abs(near) <= 1.0]
                    pts = _new_points(lp.grids[live[j]], np.concatenate([new, near]))
                    if pts.size:
                        adds[int(live[j])] = pts
            if not adds:
                break
            lp.add(adds)
            live = np.fromiter(adds, dtype=int)
        for j, i in enumerate(idx):
            grids[i] = lp.grids[j]
    return extrema


def _support_max(fit: np.ndarray, a: np.ndarray,
                 d: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Semi-infinite LP by grid refinement (exchange): see :func:`support`.

    Nearby directions have nearby extrema, so the pairs are solved in waves
    (SEEDS, then 8× as many, then the rest): each grid of a later wave starts
    from the coarse grid plus the final extrema of the most similar solved
    pair (same fit; largest |cos| of the directions, then closest cut). This
    only changes how many refinement rounds are needed, not the answer.
    """
    k = d.shape[0]
    out = (np.zeros(k), np.zeros((k, 5)), np.zeros((k, 2)), np.zeros(k))
    live = np.flatnonzero(np.any(d != 0, axis=1))
    unit = d / np.maximum(np.linalg.norm(d, axis=1), 1e-300)[:, None]
    cut = a / (1.0 + np.where(np.isfinite(a), a, 0.0))
    cut = np.where(np.isfinite(a), cut, 1.0)
    base = _initial_grid()
    grids = [base for _ in range(k)]
    # a fixed spread-out order (golden-ratio scrambling), so the seeds are not
    # all neighbours in the caller's order
    order = live[np.argsort((np.arange(live.size) * 0.6180339887498949) % 1.0, kind="stable")]
    solved = np.empty(0, dtype=int)
    extrema: list[FloatArray] = [np.empty(0)] * k
    size = SEEDS
    while order.size:
        wave, order = order[:size], order[size:]
        size *= 8
        if solved.size:
            sim = np.abs(unit[wave] @ unit[solved].T) - np.abs(
                cut[wave][:, None] - cut[solved][None, :])
            sim = np.where(fit[wave][:, None] == fit[solved][None, :], sim, -np.inf)
            near = solved[np.argmax(sim, axis=1)]
            for i, n in zip(wave, near, strict=True):
                if fit[n] == fit[i]:
                    grids[i] = union(base, extrema[n])
        found = _refine(fit, a, d, grids, wave, out)
        for i in wave:
            extrema[i] = found[i]
        solved = np.concatenate([solved, wave])
    return out


def without_idle_cuts(fit: np.ndarray, measure: np.ndarray, a: np.ndarray) -> FloatArray:
    """a with inf wherever the cut |y1| ≤ a is at or above the envelope's own max |y1|.

    Such a cut changes nothing, and without it the pair shares its programme
    with the uncut envelope. One programme per (fit, measure) present.
    """
    fit = np.asarray(fit, dtype=int)
    measure = np.asarray(measure, dtype=int)
    a = np.asarray(a, dtype=float)
    finite = np.flatnonzero(np.isfinite(a))
    if finite.size == 0:
        return a
    pairs = np.array(sorted(set(zip(fit[finite].tolist(), measure[finite].tolist(), strict=True))))
    e1 = np.tile([1.0, 0.0, 0.0, 0.0, 0.0], (pairs.shape[0], 1))
    free, *_ = support(pairs[:, 0], pairs[:, 1], np.full(pairs.shape[0], np.inf), e1)
    for (f, ms), top in zip(pairs, free, strict=True):
        # top is within 1e-7 below the true maximum
        a = np.where((fit == f) & (measure == ms) & (a >= top * (1.0 + 1e-6)), np.inf, a)
    return a


def support(fit: np.ndarray, measure: np.ndarray, a: np.ndarray,
            d: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """h(d) = max dᵀy over the normalised envelope, for K pairs at once.

    fit, measure: (K,) indices into FITS and MEASURES; a: (K,) the asymmetry
    cut |y1| ≤ a (inf: none); d: (K, 5) directions. Returns h (K,), the
    maximiser y (K, 5) — feasible: its true max |r| is 1 (max measure) or its
    mean r² is 1 (rms) — its reference line (α, β) (K, 2), r = p − α − β·u
    (the fitted line of p for least-squares and endpoint), and the
    relative gap (K,) between the last grid optimum and h (≤ 1e-7 once
    converged; 0 for rms). For the max measure h is within that gap of the
    continuous optimum and never above it (y is feasible).
    """
    fit = np.asarray(fit, dtype=int)
    measure = np.asarray(measure, dtype=int)
    a = np.asarray(a, dtype=float)
    d = np.asarray(d, dtype=float)
    k = d.shape[0]
    h = np.zeros(k)
    y = np.zeros((k, 5))
    line = np.zeros((k, 2))
    gap = np.zeros(k)
    rms = measure == 1
    if rms.any():
        h[rms], y[rms] = _support_rms(fit[rms], a[rms], d[rms])
    mx = ~rms
    if mx.any():
        h[mx], y[mx], line[mx], gap[mx] = _support_max(fit[mx], a[mx], d[mx])
    line[:, 0] += np.einsum("ki,ki->k", y, OFFSET[fit])
    line[:, 1] += np.einsum("ki,ki->k", y, SLOPE[fit])
    return h, y, line, gap


def minimax_line(w: np.ndarray, p: np.ndarray) -> FloatArray:
    """The line c0 + c1·w of least max deviation from p on the grid w, evaluated on w.

    A 3-variable LP (c0, c1, t): min t s.t. p ≤ c0 + c1·w + t and
    c0 + c1·w − t ≤ p at every point.
    """
    w = np.asarray(w, dtype=float)
    p = np.asarray(p, dtype=float)
    n = w.size
    start = np.array([0, 2 * n, 4 * n, 6 * n])
    index = np.tile(np.arange(2 * n), 3)
    value = np.concatenate([np.ones(2 * n), w, w, np.ones(n), -np.ones(n)])
    lower = np.concatenate([p, np.full(n, -np.inf)])
    upper = np.concatenate([np.full(n, np.inf), p])
    res = highs.solve(np.array([0.0, 0.0, 1.0]), start, index, value, lower, upper,
                      np.full(3, -np.inf), np.full(3, np.inf))
    if not res.ok:  # pragma: no cover - always feasible and bounded below by 0
        raise ArithmeticError(f"minimax line LP failed: {res.status}")
    return np.asarray(res.x[0] + res.x[1] * w, dtype=float)
