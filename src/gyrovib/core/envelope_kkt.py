"""The envelope's worst case to machine precision from a grid optimum (docs/model.md section 11).

The max-measure envelope is a semi-infinite LP in the coordinates of
:mod:`gyrovib.core.envelope_basis`: maximise d̃ᵀỹ subject to |ψ̃(u)ᵀỹ| ≤ 1 for
every u ∈ [−1, 1], with ỹ = (y, α, β) and ψ̃(u) = (ψ(u), −1, −u) for the
minimax fit, ψ̃(u) = (ψ(u), 0, 0) with α = β = 0 otherwise, d̃ = (d, 0, 0).
At its optimum the residual r = ψ̃ᵀỹ touches ±1 at a few points v_j, and

    Σ_j s_j·λ_j·ψ̃(v_j) = d̃        (stationarity, λ_j ≥ 0)
    ψ̃(v_j)ᵀỹ = s_j                 (r = ±1 there, s_j = ±1)
    ψ̃′(v_j)ᵀỹ = 0                  (an extremum, for v_j inside a side)

with v_j fixed where it is an end u = ±1 or the kink u = 0. With an
asymmetry cut |y1| ≤ a that binds, the stationarity gains s_μ·μ·e1 (μ ≥ 0)
and y1 = s_μ·a holds. A grid LP
solved by HiGHS names the points (its basic columns) and gives a starting
point; :func:`polish` solves these equations by Newton's method. The result
carries its own certificate: for any feasible y, dᵀy = Σ s_j·λ_j·r(v_j) + s_μ·μ·y1 ≤
Σ λ_j + a·μ (weak duality), so that sum bounds the continuous optimum from above
while ỹ scaled onto the envelope (its true max |r| from every critical
point) bounds it from below. The grid exchange
(:mod:`gyrovib.core.envelope_lp`) accepts a polished pair only when the two
bounds agree to its tolerance; otherwise it refines the grid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gyrovib.core._types import FloatArray
from gyrovib.core.envelope_basis import MINIMAX, SLOPE, basis, true_max
from gyrovib.frozen import Frozen

#: Newton iterations before a pair is left to the grid exchange.
ITERATIONS = 12


@dataclass(frozen=True, eq=False, repr=False)
class Polished(Frozen):
    """Per pair (K,): ``ok`` where the bounds agree to the tolerance asked for;
    ``h`` the lower bound d·y (y feasible), ``upper`` the dual bound Σ λ_j,
    ``gap`` = 1 − h/upper, ``y`` (K, 5) and ``line`` (K, 2) = (α, β) of the
    feasible solution, ``points`` (K, P) the contact points v_j (NaN pads),
    ``signs`` and ``weights`` (K, P) their s_j and λ_j, ``mu`` (K,) the
    cut's signed weight s_μ·μ (0 where it does not bind): a start for a
    nearby direction."""

    ok: np.ndarray
    h: FloatArray
    upper: FloatArray
    gap: FloatArray
    y: FloatArray
    line: FloatArray
    points: FloatArray
    signs: FloatArray
    weights: FloatArray
    mu: FloatArray


def _psi(fit: np.ndarray, u: np.ndarray) -> FloatArray:
    """ψ̃(u) for fit (K,) at u (K, P): (K, P, 7)."""
    mm = (fit == MINIMAX)[:, None, None]
    extra = np.stack([-np.ones_like(u), -u], axis=-1) * mm
    return np.concatenate([basis(fit[:, None], u), extra], axis=-1)


def _dpsi(fit: np.ndarray, u: np.ndarray) -> FloatArray:
    """ψ̃′(u) (K, P, 7); ½·sign(u) for the kink term (u ≠ 0 where it is used)."""
    mm = (fit == MINIMAX)[:, None, None]
    core = np.stack([0.5 * np.sign(u), 2 * u, 3 * u**2, 4 * u**3, 5 * u**4], axis=-1)
    core = core - SLOPE[fit][:, None, :]
    extra = np.stack([np.zeros_like(u), -np.ones_like(u)], axis=-1) * mm
    return np.concatenate([core, extra], axis=-1)


def _d2psi(u: np.ndarray) -> FloatArray:
    """ψ̃″(u) (K, P, 7) (the line and the kink term are linear on each side)."""
    z = np.zeros_like(u)
    return np.stack([z, 2 + z, 6 * u, 12 * u**2, 20 * u**3, z, z], axis=-1)


def _solve(jac: np.ndarray, rhs: np.ndarray) -> tuple[FloatArray, np.ndarray]:
    """Batched J⁻¹·F; pairs with a singular J get NaN and False."""
    try:
        return np.linalg.solve(jac, rhs[..., None])[..., 0], np.ones(rhs.shape[0], dtype=bool)
    except np.linalg.LinAlgError:
        out = np.full(rhs.shape, np.nan)
        good = np.zeros(rhs.shape[0], dtype=bool)
        for k in range(rhs.shape[0]):
            try:
                out[k] = np.linalg.solve(jac[k], rhs[k])
                good[k] = True
            except np.linalg.LinAlgError:
                pass
        return out, good


def polish(fit: np.ndarray, d: np.ndarray, y0: np.ndarray, line0: np.ndarray,
           u0: np.ndarray, sign: np.ndarray, lam0: np.ndarray, active: np.ndarray,
           tolerance: float, cut: np.ndarray | None = None,
           mu0: np.ndarray | None = None) -> Polished:
    """Newton's method on the optimality conditions of the module docstring.

    fit (K,) FITS indices, d (K, 5) directions, y0 (K, 5) and line0 (K, 2) a
    grid optimum; u0, sign, lam0 (K, P): its contact points, their signs s_j
    and weights λ_j ≥ 0, padded where ``active`` is False. Points at −1, 0
    or 1 stay there; the others move to the extremum of their side (a pair
    whose point would leave its side is not polished). ``tolerance`` is the
    relative gap of the bounds under which a pair is ``ok``. ``cut`` (K,)
    is a (inf: none) and ``mu0`` (K,) the grid optimum's signed weight of the
    cut, μ⁺ − μ⁻ (0 where it does not bind).
    """
    k, p = u0.shape
    n = 8 + 2 * p
    a = np.full(k, np.inf) if cut is None else np.asarray(cut, dtype=float)
    m0 = np.zeros(k) if mu0 is None else np.asarray(mu0, dtype=float)
    total = np.sum(np.where(active, lam0, 0.0), axis=1) + np.abs(m0)
    binds = np.isfinite(a) & (np.abs(m0) > 1e-10 * total)
    s_mu = np.where(binds, np.sign(m0), 0.0)
    a_fin = np.where(np.isfinite(a), a, 0.0)
    mm = fit == MINIMAX
    free = active & (u0 != 0) & (np.abs(u0) != 1)
    pin = np.array(u0, dtype=float)
    dt = np.concatenate([d, np.zeros((k, 2))], axis=1)
    z = np.concatenate([y0, np.where(mm[:, None], line0, 0.0), np.where(active, lam0, 0.0),
                        u0, np.abs(m0)[:, None] * binds[:, None]], axis=1)
    alive = np.ones(k, dtype=bool)
    done = np.zeros(k, dtype=bool)
    ip = np.arange(p)
    lam_i, v_i, m_i = 7 + ip, 7 + p + ip, 7 + 2 * p
    w = np.where(active, sign, 0.0)
    for _ in range(ITERATIONS):
        run = alive & ~done
        if not run.any():
            break
        zz, f_, fr, uu, ww, ac, fe = (z[run], fit[run], mm[run], pin[run], w[run], active[run],
                                      free[run])
        bd, sm = binds[run], s_mu[run]
        y, lam, v, mu = zz[:, :7], zz[:, 7:7 + p], zz[:, 7 + p:m_i], zz[:, m_i]
        ps, dp = _psi(f_, v), _dpsi(f_, v)
        curv = np.einsum("kpi,ki->kp", _d2psi(v), y)
        slope = np.einsum("kpi,ki->kp", dp, y)
        fa = np.einsum("kp,kpi->ki", ww * lam, ps) - dt[run]
        fa[:, 0] += sm * mu
        fa[~fr, 5:] = y[~fr, 5:]
        fb = np.where(ac, np.einsum("kpi,ki->kp", ps, y) - np.where(ac, sign[run], 0.0), lam)
        fc = np.where(fe, slope, v - uu)
        fm = np.where(bd, y[:, 0] - sm * a_fin[run], mu)
        f = np.concatenate([fa, fb, fc, fm[:, None]], axis=1)
        jac = np.zeros((zz.shape[0], n, n))
        jac[:, :7, 7:7 + p] = (ww[:, :, None] * ps).transpose(0, 2, 1)
        jac[:, :7, 7 + p:m_i] = ((ww * lam)[:, :, None] * dp).transpose(0, 2, 1)
        jac[:, 0, m_i] = sm
        jac[~fr, 5:, :] = 0.0
        jac[~fr, 5, 5] = jac[~fr, 6, 6] = 1.0
        jac[:, lam_i, :7] = ac[:, :, None] * ps
        jac[:, lam_i, v_i] = np.where(ac, slope, 0.0)
        jac[:, lam_i, lam_i] += ~ac
        jac[:, v_i, :7] = fe[:, :, None] * dp
        jac[:, v_i, v_i] = np.where(fe, curv, 1.0)
        jac[:, m_i, 0] = bd
        jac[:, m_i, m_i] = ~bd
        step, good = _solve(jac, f)
        znew = zz - np.where(good[:, None], step, 0.0)
        vn = znew[:, 7 + p:m_i]
        # a point that would leave its side stops at the end or the kink it reached
        # and stays there (r′ = 0 is then not asked of it)
        out = fe & ((np.sign(vn) != np.sign(uu)) | (np.abs(vn) >= 1.0))
        stop = np.where(np.abs(vn) >= 1.0, np.sign(uu), 0.0)
        znew[:, 7 + p:m_i] = np.where(out, stop, vn)
        ok = good & np.all(np.isfinite(znew), axis=1)
        scale = 1.0 + np.max(np.abs(zz), axis=1)
        small = np.max(np.abs(step), axis=1) <= 1e-14 * scale
        idx = np.flatnonzero(run)
        z[idx[ok]] = znew[ok]
        free[idx[ok]] = fe[ok] & ~out[ok]
        pin[idx[ok]] = np.where(out[ok], stop[ok], uu[ok])
        alive[idx[~ok]] = False
        done[idx[ok & small]] = True
    y, line, lam, v, mu = z[:, :5], z[:, 5:7], z[:, 7:7 + p], z[:, 7 + p:m_i], z[:, m_i]
    upper = np.sum(np.where(active, lam, 0.0), axis=1) + np.where(binds, a_fin * mu, 0.0)
    # the bound holds for the weights as they are only if they solve the stationarity:
    # its residual e adds at most |eᵀỹ| to it, so it must be negligible, not merely small
    # in Newton's last step
    stat = np.einsum("kp,kpi->ki", w * lam, _psi(fit, v)) - dt
    stat[:, 0] += s_mu * mu
    stat[~mm, 5:] = 0.0
    settled = np.max(np.abs(stat), axis=1) <= 1e-12 * np.maximum(1.0, upper)
    mx, _ = true_max(fit, y, line)
    scale = 1.0 / np.maximum(mx, 1.0)
    y = y * scale[:, None]
    line = line * scale[:, None]
    h = np.einsum("ki,ki->k", d, y)
    with np.errstate(invalid="ignore", divide="ignore"):
        gap = np.where(upper > 0, 1.0 - h / upper, np.inf)
    tiny = 1e-12 * np.abs(upper)
    dual_ok = np.all(~active | (lam >= -tiny[:, None]), axis=1) & (mu >= -tiny)
    within_cut = np.abs(y[:, 0]) <= a * (1.0 + 1e-12)
    ok = (alive & done & settled & dual_ok & within_cut & np.isfinite(gap) & (gap <= tolerance)
          & (gap >= -1e-9) & np.isfinite(h))
    return Polished(ok=ok, h=h, upper=upper, gap=np.maximum(gap, 0.0), y=y, line=line,
                    points=np.where(active, v, np.nan), signs=np.where(active, sign, 0.0),
                    weights=np.where(active, lam, 0.0), mu=s_mu * mu)

