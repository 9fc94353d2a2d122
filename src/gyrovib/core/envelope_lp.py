"""The datasheet envelope's support function (docs/model.md section 11).

The normalised envelope E and its coordinates are defined in
:mod:`gyrovib.core.envelope_basis`. E is compact and symmetric, so its support
function h(d) = max_{y∈E} dᵀy is the worst of any linear functional of the
coefficients; :func:`support` evaluates it for many (envelope, direction)
pairs at once: in closed form for the rms measure, and for the max measure
(a semi-infinite LP) by HiGHS on grids refined until a feasible solution and
an upper bound agree.
"""

from __future__ import annotations

import itertools

import numpy as np

from gyrovib.core import envelope_kkt, highs
from gyrovib.core._types import FloatArray
from gyrovib.core.envelope_basis import (
    FITS,
    MEASURES,
    MINIMAX,
    OFFSET,
    SLOPE,
    basis,
    gram,
    residual_normalised,
    true_max,
)
from gyrovib.progress import advance

__all__ = ["FITS", "MEASURES", "basis", "gram", "minimax_line", "residual_normalised", "support",
           "true_max", "without_idle_cuts"]

#: The grid optimum and the feasible scaled solution agree to this (relative).
TOLERANCE = 1e-7
#: Refinement rounds before giving up (the scaled solution is feasible anyway).
MAX_ROUNDS = 40
#: LPs stacked block-diagonally into one HiGHS call.
CHUNK = 128
#: From this many pairs on, every SPACING-th is solved by the grid LP and the
#: others are polished from a solved neighbour (see _support_max).
SEEDED = 512
SPACING = 8
#: Pairs taken together in those steps (their solutions' contacts are kept
#: for the neighbours only while their window is worked on).
WINDOW = 8192
#: Pairs polished at once from their neighbours (Newton's batched systems).
SEEDED_BATCH = 4096
#: Offsets added around each violating extremum: the extremum moves as the
#: solution does, and a cluster of scales catches it in fewer rounds.
_CLUSTER = np.array([-3e-3, -1e-4, 1e-4, 3e-3])


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
        # per column of the dual: its block, grid point and sign (+1: λ⁺, −1: λ⁻, 0: μ)
        self.col_blk = np.empty(0, dtype=int)
        self.col_u = np.empty(0)
        self.col_s = np.empty(0)
        # the cut's columns μ⁺ (μ⁻ follows after all of them) and their blocks
        self.mu_blk = np.empty(0, dtype=int)
        self.mu_col = np.empty(0, dtype=int)

    def _layout(self, blk: np.ndarray, u: np.ndarray, n_mu: int, reset: bool = False) -> None:
        parts = [] if reset else [(self.col_blk, self.col_u, self.col_s)]
        parts += [(blk, u, np.ones(u.size)), (blk, u, -np.ones(u.size)),
                  (np.full(n_mu, -1), np.zeros(n_mu), np.zeros(n_mu))]
        self.col_blk = np.concatenate([q[0] for q in parts])
        self.col_u = np.concatenate([q[1] for q in parts])
        self.col_s = np.concatenate([q[2] for q in parts])

    def _build(self, options: dict[str, float | str] | None) -> highs.Model:
        k = self.d.shape[0]
        counts = np.array([g.size for g in self.grids])
        u = np.concatenate(self.grids)
        blk = np.repeat(np.arange(k), counts)
        sizes, index, value = _grid_columns(self.fit, blk, u)
        mu = np.flatnonzero(np.isfinite(self.a))
        n_mu = mu.size
        self._layout(blk, u, 2 * n_mu, reset=True)
        self.mu_blk, self.mu_col = mu, 2 * u.size + np.arange(n_mu)
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
        self._layout(blk, u, 0)
        n = sizes.size
        self.model.add_columns(np.ones(n), np.concatenate([[0], np.cumsum(sizes)]), index,
                               value, np.zeros(n), np.full(n, np.inf))

    def solve(self) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """The grid optimum (K,), y (K, 5), line (K, 2) of every block, and the dual's x."""
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
        return np.einsum("ki,ki->k", self.d, y), y, x[:, 5:], res.x

    def cut_weights(self, x: np.ndarray, blocks: np.ndarray) -> FloatArray:
        """μ⁺ − μ⁻ of ``blocks`` in the dual's solution x (0 without a cut)."""
        mu = np.zeros(len(self.grids))
        mu[self.mu_blk] = x[self.mu_col] - x[self.mu_col + self.mu_col.size]
        out: FloatArray = mu[blocks]
        return out

    def contacts(self, x: np.ndarray,
                 blocks: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray, np.ndarray]:
        """The grid optimum's contact points of ``blocks``: u, sign, λ (B, P) and a mask.

        A point's weight is its basic column's value in the dual (x); two
        neighbours on the grid with the same sign straddle one extremum and
        become one point, at their λ-weighted mean, with the sum of their λ.
        """
        n_blocks = len(self.grids)
        row = np.full(n_blocks, -1)
        row[blocks] = np.arange(blocks.size)
        cols = np.flatnonzero((self.col_s != 0) & (x > 0))
        cols = cols[row[self.col_blk[cols]] >= 0]
        total = np.bincount(self.col_blk[cols], weights=x[cols], minlength=n_blocks)
        cols = cols[x[cols] > 1e-10 * total[self.col_blk[cols]]]
        cols = cols[np.lexsort((self.col_u[cols], self.col_blk[cols]))]
        cb, cu, cs, cx = self.col_blk[cols], self.col_u[cols], self.col_s[cols], x[cols]
        first = np.ones(cols.size, dtype=bool)
        first[1:] = cb[1:] != cb[:-1]
        at = np.empty(cols.size, dtype=int)
        edges = np.append(np.flatnonzero(first), cols.size)
        for lo, hi in itertools.pairwise(edges):
            at[lo:hi] = np.searchsorted(self.grids[cb[lo]], cu[lo:hi])
        merge = ~first
        merge[1:] &= (cs[1:] == cs[:-1]) & (at[1:] - at[:-1] == 1)
        gid = np.cumsum(~merge) - 1
        lam = np.bincount(gid, weights=cx)
        u = np.bincount(gid, weights=cx * cu) / np.where(lam > 0, lam, 1.0)
        heads = np.flatnonzero(~merge)
        gb, gs = cb[heads], cs[heads]
        gfirst = np.ones(heads.size, dtype=bool)
        gfirst[1:] = gb[1:] != gb[:-1]
        start_of = np.maximum.accumulate(np.where(gfirst, np.arange(heads.size), 0))
        slot = np.arange(heads.size) - start_of
        p = int(slot.max()) + 1 if slot.size else 1
        shape = (blocks.size, p)
        ou, os_, ol = np.zeros(shape), np.zeros(shape), np.zeros(shape)
        act = np.zeros(shape, dtype=bool)
        r = row[gb]
        ou[r, slot], os_[r, slot], ol[r, slot], act[r, slot] = u, gs, lam, True
        return ou, os_, ol, act


def _new_points(grid: np.ndarray, points: np.ndarray) -> FloatArray:
    """The distinct values of points that are not on the (sorted) grid."""
    p = union(points, np.empty(0))
    pos = np.minimum(np.searchsorted(grid, p), grid.size - 1)
    out: FloatArray = p[grid[pos] != p]
    return out


def _polish(lp: _GridLP, x: np.ndarray, live: np.ndarray, fit: np.ndarray, a: np.ndarray,
            d: np.ndarray, y0: np.ndarray, line0: np.ndarray) -> envelope_kkt.Polished:
    """Newton's polish of the grid optimum of blocks ``live`` (see envelope_kkt)."""
    u, sg, lam, act = lp.contacts(x, live)
    return envelope_kkt.polish(fit, d, y0, line0, u, sg, lam, act, TOLERANCE,
                               cut=a, mu0=lp.cut_weights(x, live))


#: What a certified pair leaves for its neighbours: contact points, signs, weights, cut weight.
Contacts = dict[int, tuple[FloatArray, FloatArray, FloatArray, float]]


def _record(found: Contacts, pairs: np.ndarray, pol: envelope_kkt.Polished) -> None:
    """Keep the contacts of the certified pairs (pol.ok) for their neighbours."""
    for q in np.flatnonzero(pol.ok):
        keep = ~np.isnan(pol.points[q])
        found[int(pairs[q])] = (pol.points[q][keep], pol.signs[q][keep], pol.weights[q][keep],
                                float(pol.mu[q]))


def _refine(fit: np.ndarray, a: np.ndarray, d: np.ndarray, todo: np.ndarray,
            out: tuple[FloatArray, ...], found: Contacts | None = None,
            progress: tuple[int, int, int] | None = None) -> None:
    """Grid LP, polish, continuous check, add the residual's violating extrema; repeat.

    Blocks go CHUNK at a time into one :class:`_GridLP` on the coarse grid,
    re-solved from its last basis after each round adds points. A block is
    done when its polish is certified (:mod:`gyrovib.core.envelope_kkt`) or
    its grid optimum's scaled solution is within TOLERANCE of it. Fills
    ``out`` = (h, y, line, gap) at ``todo``, and ``found`` (if given) with the
    contacts of the certified pairs.
    ``progress``: (offset, scale, total) of the
    "datasheet worst cases" reported after each chunk (offset + scale·done).
    """
    h, y, line, gap = out
    base = _initial_grid()
    for start in range(0, todo.size, CHUNK):
        if progress is not None:
            offset, each, total = progress
            advance("datasheet worst cases", min(offset + each * start, total - 1), total)
        idx = todo[start:start + CHUNK]
        lp = _GridLP(fit[idx], a[idx], d[idx], [base] * idx.size)
        live = np.arange(idx.size)
        for _ in range(MAX_ROUNDS):
            hg, yg, lg, x = lp.solve()
            hg, yg, lg = hg[live], yg[live], lg[live]
            sel = idx[live]
            pol = _polish(lp, x, live, fit[sel], a[sel], d[sel], yg, lg)
            if pol.ok.any():
                done = pol.ok
                h[sel[done]] = pol.h[done]
                y[sel[done]] = pol.y[done]
                line[sel[done]] = pol.line[done]
                gap[sel[done]] = pol.gap[done]
                if found is not None:
                    _record(found, sel, pol)
                live, sel, hg, yg, lg = live[~done], sel[~done], hg[~done], yg[~done], lg[~done]
                if live.size == 0:
                    break
            # HiGHS keeps the grid's y1 within its tolerance of the cut only: clip it onto
            # |y1| ≤ a (its max |r| is measured after), then shrink onto the continuous
            # envelope; never grow (|y1| ≤ a may be what binds)
            yg = yg.copy()
            yg[:, 0] = np.clip(yg[:, 0], -a[sel], a[sel])
            mx, cand = true_max(fit[sel], yg, lg)
            scale = 1.0 / np.maximum(mx, 1.0)
            h[sel] = np.einsum("ki,ki->k", d[sel], yg) * scale
            y[sel] = yg * scale[:, None]
            line[sel] = lg * scale[:, None]
            gap[sel] = np.where(hg > 0, 1.0 - h[sel] / np.where(hg > 0, hg, 1.0), 0.0)
            r = np.abs(residual_normalised(fit[sel], yg, lg, np.nan_to_num(cand)))
            ok = ~np.isnan(cand)
            adds: dict[int, FloatArray] = {}
            for j in range(sel.size):
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


def _seeded(fit: np.ndarray, a: np.ndarray, d: np.ndarray, todo: np.ndarray,
            seed: np.ndarray, found: Contacts, out: tuple[FloatArray, ...]) -> np.ndarray:
    """Polish pairs ``todo`` from the certified solutions of pairs ``seed``; the ones certified.

    The seed's contact points, signs and y start Newton's method for the new
    direction (its weights scaled by the ratio of the directions' norms).
    """
    h, y, line, gap = out
    done = np.zeros(todo.size, dtype=bool)
    for start in range(0, todo.size, SEEDED_BATCH):
        idx, src = todo[start:start + SEEDED_BATCH], seed[start:start + SEEDED_BATCH]
        p = max(found[int(j)][0].size for j in src)
        u0, sg, lam = (np.zeros((idx.size, p)) for _ in range(3))
        act = np.zeros((idx.size, p), dtype=bool)
        mu0 = np.zeros(idx.size)
        ratio = np.linalg.norm(d[idx], axis=1) / np.linalg.norm(d[src], axis=1)
        for j, n in enumerate(src):
            pts, signs, weights, mu = found[int(n)]
            u0[j, :pts.size], sg[j, :pts.size], act[j, :pts.size] = pts, signs, True
            lam[j, :pts.size] = weights * ratio[j]
            mu0[j] = mu * ratio[j]
        pol = envelope_kkt.polish(fit[idx], d[idx], y[src], line[src], u0, sg, lam, act,
                                  TOLERANCE, cut=a[idx], mu0=mu0)
        ok = pol.ok
        h[idx[ok]], y[idx[ok]], line[idx[ok]], gap[idx[ok]] = (pol.h[ok], pol.y[ok],
                                                               pol.line[ok], pol.gap[ok])
        _record(found, idx, pol)
        done[start:start + idx.size] = ok
    return done


def _support_max(fit: np.ndarray, a: np.ndarray,
                 d: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Semi-infinite LP by grid refinement (exchange) and polish: see :func:`support`.

    Many pairs (a sweep: the same terms at neighbouring rates, given in
    order) are solved in steps: every SPACING-th by :func:`_refine`; then,
    pass after pass, each unsolved pair is polished from the more similar of
    the nearest solved pairs before and after it in the given order (same fit
    and cut kind), as long as passes certify new pairs; what is left goes to
    :func:`_refine` too. The answer is certified either way; the order only
    decides how much of it the grid LP has to do.
    """
    k = d.shape[0]
    out = (np.zeros(k), np.zeros((k, 5)), np.zeros((k, 2)), np.zeros(k))
    live = np.flatnonzero(np.any(d != 0, axis=1))
    if live.size < SEEDED:
        _refine(fit, a, d, live, out, progress=(0, 1, live.size))
        advance("datasheet worst cases", live.size, live.size)
        return out
    for start in range(0, live.size, WINDOW):
        _seeded_window(fit, a, d, live[start:start + WINDOW], out, (start, live.size))
    advance("datasheet worst cases", live.size, live.size)
    return out


def _seeded_window(fit: np.ndarray, a: np.ndarray, d: np.ndarray, live: np.ndarray,
                   out: tuple[FloatArray, ...], where: tuple[int, int] = (0, 0)) -> None:
    """The steps of :func:`_support_max` for the pairs ``live`` (consecutive in order);
    ``where``: the window's first pair and the pairs in all (for the progress, reported
    as the spaced refinement goes, each of its pairs standing for SPACING)."""
    found: Contacts = {}
    _refine(fit, a, d, live[::SPACING], out, found, progress=(where[0], SPACING, where[1]))
    unit = d[live] / np.maximum(np.linalg.norm(d[live], axis=1), 1e-300)[:, None]
    pos = np.arange(live.size)
    tried = np.full(live.size, -1)
    while True:
        solved = np.array([int(i) in found for i in live], dtype=bool)
        left = np.maximum.accumulate(np.where(solved, pos, -1))
        right = np.minimum.accumulate(np.where(solved, pos, live.size)[::-1])[::-1]
        best = np.full(live.size, -1)
        score = np.full(live.size, -1.0)
        for side in (left, right):
            ok = (side >= 0) & (side < live.size) & ~solved
            at = np.clip(side, 0, live.size - 1)
            n = live[at]
            same = ok & (fit[n] == fit[live]) & (np.isfinite(a[n]) == np.isfinite(a[live]))
            sim = np.where(same, np.abs(np.einsum("ki,ki->k", unit, unit[at])), -1.0)
            better = sim > score
            best, score = np.where(better, side, best), np.where(better, sim, score)
        todo = np.flatnonzero((best >= 0) & (best != tried))
        if todo.size == 0:
            break
        tried[todo] = best[todo]
        if not _seeded(fit, a, d, live[todo], live[best[todo]], found, out).any():
            break
    _refine(fit, a, d, live[~np.array([int(i) in found for i in live], dtype=bool)], out)


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
    relative gap (K,) between an upper bound of the continuous optimum and h
    (≤ 1e-7 once converged; 0 for rms). The bound is the dual one, Σλ (+ a·μ),
    where the polish is certified (usually ~1e-15), else the last grid
    optimum. For the max measure h is within that gap of the continuous
    optimum and never above it (y is feasible).
    """
    fit = np.asarray(fit, dtype=int)
    measure = np.asarray(measure, dtype=int)
    a = np.asarray(a, dtype=float)
    d = np.asarray(d, dtype=float)
    k = d.shape[0]
    # a cut at 0 fixes y1 = 0: d1 adds nothing, and left in it would set the scale below
    d = np.where((a == 0)[:, None] & (np.arange(5) == 0), 0.0, d)
    # h is positively homogeneous: solve for d/max|d_i| (HiGHS's tolerances are absolute,
    # and dᵀG⁻¹d under- or overflows far from 1) and scale h back
    norm = np.max(np.abs(d), axis=1) if k else np.zeros(0)
    d = np.where(norm[:, None] > 0, d / np.where(norm > 0, norm, 1.0)[:, None], 0.0)
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
    return h * norm, y, line, gap


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
