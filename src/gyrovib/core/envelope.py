"""Datasheet sensors: the worst vibration error over their envelope (docs/model.md section 11).

A spec-form sensor (range R, nonlinearity limit b, fit, measure, optional
asymmetry spec |A1| ≤ a_max, optional VRE spec v) stands for every conversion
function p(ω) = ½A1|ω| + k2ω² + k3ω³ + k4ω⁴ + k5ω⁵ whose residual from its
reference line stays within b on [−R, R]. The vibration enters only through
its multipliers (docs/model.md sections 4 and 10, k1 = 1): with x = (A1, k2…k5),

    Δ_V(Ω) = cᵀx + Σ_jj G_jj⟨a_j²⟩,
    c = (g_A, M2, M3 + 3M2Ω, M4 + 4M3Ω + 6M2Ω², M5 + 5M4Ω + 10M3Ω² + 10M2Ω³)

(g_A = ½E(Ω)), the sum of the eight term functionals of :func:`term_functionals`.
The envelope is symmetric, so worst |Δ_V| = max cᵀx + |v|·S with S = Σ_j⟨a_j²⟩.

Units: rates (R, b, Ω, Δ) in one rate unit; kn in rate^(1−n); A1
dimensionless; M_n in rate^n; S in g²; v in rate/g². In the normalised
coordinates of :mod:`gyrovib.core.envelope_lp` the worst case is
b·h(d) with d_i = c_i/R^(n_i) (n = 1…5), so sensors that share
(fit, measure, a_max·R/b) and R share every programme, and the result scales
with b. Unique (envelope, direction) pairs are solved once.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.coefficients import POLYNOMIAL
from gyrovib.core._types import FloatArray
from gyrovib.core.envelope_lp import FITS, MEASURES, support, without_idle_cuts
from gyrovib.errors import ModelError
from gyrovib.frozen import Frozen

#: The coefficients of the envelope, in the order of x.
COEFFICIENTS = POLYNOMIAL
#: The eight terms of Δ_V: Δ0(1) A1, Δ0 of k2…k5, Δ(1)·Ω, Δ(2)·Ω², Δ(3)·Ω³.
TERMS: tuple[str, ...] = ("A1", "k2", "k3", "k4", "k5", "q1", "q2", "q3")
#: What the nonlinearity value is relative to: % of R, % of 2R, or a rate.
OF: tuple[str, ...] = ("range", "span", "rate")
#: Powers n_i of ω behind each coefficient (A1 multiplies |ω|).
POWERS = np.arange(1, 6)


def term_functionals(g_a: ArrayLike, m2: ArrayLike, m3: ArrayLike, m4: ArrayLike,
                     m5: ArrayLike, omega: ArrayLike) -> FloatArray:
    """The eight terms of Δ_V as linear functionals of x, shape (..., 8, 5).

    Row t, dotted with x = (A1, k2, k3, k4, k5), gives term TERMS[t]
    (docs/model.md sections 4 and 10): ½A1·E(Ω) = A1·g_A, k2·M2, k3·M3, k4·M4,
    k5·M5, Δ(1)·Ω = (3k3M2 + 4k4M3 + 5k5M4)·Ω, Δ(2)·Ω² = (6k4M2 + 10k5M3)·Ω²,
    Δ(3)·Ω³ = 10k5M2·Ω³. Inputs broadcast together (profiles, or profiles ×
    rates); M_n in rate^n, g_A and Ω in rate. Their sum over rows is c.
    """
    g, b2, b3, b4, b5, w = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in
                                                 (g_a, m2, m3, m4, m5, omega)))
    out = np.zeros((*g.shape, 8, 5))
    out[..., 0, 0] = g
    out[..., 1, 1] = b2
    out[..., 2, 2] = b3
    out[..., 3, 3] = b4
    out[..., 4, 4] = b5
    out[..., 5, 2] = 3 * b2 * w
    out[..., 5, 3] = 4 * b3 * w
    out[..., 5, 4] = 5 * b4 * w
    out[..., 6, 3] = 6 * b2 * w**2
    out[..., 6, 4] = 10 * b3 * w**2
    out[..., 7, 4] = 10 * b2 * w**3
    return out


def _codes(name: str, words: str | Sequence[str], allowed: tuple[str, ...],
           n: int) -> NDArray[np.int_]:
    seq = [words] * n if isinstance(words, str) else list(words)
    if len(seq) != n:
        raise ValueError(f"{name} must have one entry per sensor ({n}), not {len(seq)}")
    bad = sorted({w for w in seq if w not in allowed})
    if bad:
        raise ModelError(f"unknown {name} {bad[0]!r}: expected one of {', '.join(allowed)}")
    return np.array([allowed.index(w) for w in seq], dtype=int)


def _check_fit_measure(fit: np.ndarray, measure: np.ndarray) -> None:
    if np.any((fit == FITS.index("minimax")) & (measure == MEASURES.index("rms"))):
        raise ModelError("an rms nonlinearity needs a least-squares or endpoint fit: "
                         "minimax (independent) linearity is defined by the peak deviation")


def _unique_rows(key: np.ndarray) -> tuple[FloatArray, np.ndarray]:
    """The distinct rows of key (sorted) and the index of each row among them.

    np.unique(key, axis=0, return_inverse=True) without importing numpy.ma.
    """
    order = np.lexsort(key.T[::-1])
    s = key[order]
    first = np.ones(s.shape[0], dtype=bool)
    first[1:] = np.any(s[1:] != s[:-1], axis=1)
    inv = np.empty(s.shape[0], dtype=int)
    inv[order] = np.cumsum(first) - 1
    return s[first], inv


def _solve(fit: np.ndarray, measure: np.ndarray, a: np.ndarray,
           d: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """support() over (..., 5) directions, each unique normalised pair solved once.

    fit, measure, a broadcast against d[..., 0]. h is positively homogeneous
    and, as the envelope is symmetric (y → −y) and mirror-symmetric (ω → −ω
    flips the odd coefficients k3, k5 and the line's slope), h(T·d) = h(d)
    and y*(T·d) = T·y*(d) for T = diag(s_e, s_e, s_o, s_e, s_o), s = ±1. So d
    is scaled to ‖d‖∞ = 1 with its first nonzero even entry (A1, k2, k4) and
    its first nonzero odd entry (k3, k5) positive before deduplication.
    """
    shape = d.shape[:-1]
    dd = d.reshape(-1, 5)
    f = np.broadcast_to(fit, shape).reshape(-1)
    ms = np.broadcast_to(measure, shape).reshape(-1)
    aa = without_idle_cuts(f, ms, np.broadcast_to(a, shape).reshape(-1))
    norm = np.max(np.abs(dd), axis=1)
    rows = np.arange(dd.shape[0])

    def first_sign(cols: list[int]) -> FloatArray:
        part = dd[:, cols]
        lead = part[rows, np.argmax(part != 0, axis=1)]
        return np.where(lead < 0, -1.0, 1.0)

    s_e, s_o = first_sign([0, 1, 3]), first_sign([2, 4])
    t = np.column_stack([s_e, s_e, s_o, s_e, s_o])
    with np.errstate(invalid="ignore", divide="ignore"):
        canon = np.where(norm[:, None] > 0, dd * t / norm[:, None], 0.0)
    key = np.column_stack([f, ms, aa, canon])
    uniq, inv = _unique_rows(key)
    # hand the unique pairs over in the caller's order with the last axis (the term)
    # outermost: then neighbours are the same term at neighbouring profiles or rates,
    # whose optima are alike (support() polishes one from the other)
    # (with more sensors than profiles × rates, the sensors are the inner axis instead:
    # worst_case hands them sorted by envelope and range, so that neighbours are the
    # same term and profile at the next range — 3,000 sensors of all-different
    # ranges under 2 profiles were cold programmes, each neighbour another profile)
    rank = np.arange(key.shape[0])
    if len(shape) > 1:
        axes = list(range(len(shape)))
        inner = [*axes[1:-1], 0] if len(shape) == 3 and shape[0] > shape[1] else axes[:-1]
        rank[np.transpose(np.arange(key.shape[0]).reshape(shape), [axes[-1], *inner]).ravel()
             ] = np.arange(key.shape[0])
    first = np.full(uniq.shape[0], key.shape[0])
    np.minimum.at(first, inv, rank)
    order = np.argsort(first, kind="stable")
    where = np.empty_like(order)
    where[order] = np.arange(order.size)
    uniq, inv = uniq[order], where[inv]
    h, y, line, gap = support(uniq[:, 0].astype(int), uniq[:, 1].astype(int), uniq[:, 2],
                              uniq[:, 3:])
    hv = (norm * h[inv]).reshape(shape)
    yv = (t * y[inv]).reshape(*shape, 5)
    lv = (np.column_stack([s_e, s_o]) * line[inv]).reshape(*shape, 2)
    return hv, yv, lv, gap[inv].reshape(shape)


@dataclass(frozen=True, eq=False, repr=False)
class WorstCase(Frozen):
    """The worst vibration error of N spec-form sensors under P profiles (or rates).

    ``total``: worst |Δ_V| = cᵀx* + |v|·S, rate, (N, P); ``nonlinearity``: its
    cᵀx* part and ``g2``: its |v|·S part, rate, (N, P); ``coefficients``: x* =
    (A1, k2…k5) attaining it, (N, P, 5), A1 dimensionless and kn in
    rate^(1−n) — feasible (max |r| ≤ b, or rms r ≤ b) with cᵀx* = ``nonlinearity``;
    ``line``: its reference line (intercept rate, slope 1), (N, P, 2);
    ``terms``: the per-term maxima max|term| over the envelope for TERMS and
    then the g² term, rate, (N, P, 9); ``rms_bound``: √(Σ terms²), rate,
    (N, P) (docs/model.md section 11, eq. (16) per term); ``gap``: relative
    distance between the last grid optimum and ``nonlinearity`` (≤ 1e-7
    when the refinement converged; 0 for rms).
    """

    total: FloatArray
    nonlinearity: FloatArray
    g2: FloatArray
    coefficients: FloatArray
    line: FloatArray
    terms: FloatArray
    rms_bound: FloatArray
    gap: FloatArray


def _sensor_specs(range_: ArrayLike, limit: ArrayLike, asymmetry: ArrayLike | None,
                  vre: ArrayLike | None) -> tuple[FloatArray, ...]:
    """Each sensor's range R, nonlinearity limit b, asymmetry a_max (inf: no spec) and
    VRE (0: no spec) as arrays of one length, checked."""
    r = np.atleast_1d(np.asarray(range_, dtype=float))
    n = r.size
    b = np.broadcast_to(np.asarray(limit, dtype=float), (n,))
    a_max = np.full(n, np.inf) if asymmetry is None else np.broadcast_to(
        np.asarray(asymmetry, dtype=float), (n,))
    v = np.zeros(n) if vre is None else np.broadcast_to(np.asarray(vre, dtype=float), (n,))
    if not (np.all(np.isfinite(r)) and np.all(r > 0)):
        raise ModelError("a sensor's range must be positive and finite")
    if not (np.all(np.isfinite(b)) and np.all(b >= 0)):
        raise ModelError("a nonlinearity limit must be finite and not negative")
    if np.any(np.isnan(a_max)) or np.any(a_max < 0):
        raise ModelError("an asymmetry spec must be a number, not negative")
    if not np.all(np.isfinite(v)):
        raise ModelError("a VRE spec must be a finite number")
    return r, b, a_max, v


def _solve_in_order(f: np.ndarray, ms: np.ndarray, ratio: FloatArray, r: FloatArray,
                    d: FloatArray) -> tuple[FloatArray, ...]:
    """:func:`_solve` with the sensors sorted by envelope (fit, measure, asymmetry
    ratio) and range, so that neighbours in its order polish each other's
    programmes; the results back in the sensors' order."""
    order = np.lexsort((r, ratio, ms, f))
    back = np.empty_like(order)
    back[order] = np.arange(order.size)
    h, y, line, gap = _solve(f[order, None, None], ms[order, None, None],
                             ratio[order, None, None], d[order])
    return h[back], y[back], line[back], gap[back]


def worst_case(terms: ArrayLike, g2: ArrayLike, range_: ArrayLike, limit: ArrayLike,
               fit: str | Sequence[str] = "least-squares",
               measure: str | Sequence[str] = "max",
               asymmetry: ArrayLike | None = None,
               vre: ArrayLike | None = None, *, total: bool = True) -> WorstCase:
    """Worst |Δ_V| over each sensor's datasheet envelope (docs/model.md section 11).

    terms: (P, 8, 5) from :func:`term_functionals` (one row per profile or
    profile-rate); g2: (P,) S = Σ_j⟨a_j²⟩ in g². Per sensor (N,): range_ R
    (rate, > 0), limit b (rate, ≥ 0: the datasheet's nonlinearity as a rate), fit and
    measure (a word or one per sensor), asymmetry a_max = max |A1|
    (dimensionless; inf or None: no spec), vre |v| (rate/g²; 0 or None: no
    spec). The max measure is a semi-infinite LP solved on a grid and refined
    to 1e-7 relative; the rms measure is the closed form b·√(cᵀG⁻¹c).

    ``total`` False: the per-term maxima and ``rms_bound`` only (the
    programme of the whole error, the costly direction, is not solved); the
    fields that need it (``total``, ``nonlinearity``, ``coefficients``,
    ``line``, ``gap``) are NaN, unknown.
    """
    t = np.asarray(terms, dtype=float)
    if t.ndim != 3 or t.shape[1:] != (8, 5):
        raise ValueError(f"terms must have shape (P, 8, 5), not {t.shape}")
    s = np.broadcast_to(np.asarray(g2, dtype=float), t.shape[:1])
    r, b, a_max, v = _sensor_specs(range_, limit, asymmetry, vre)
    n = r.size
    if not np.all(np.isfinite(t)) or not np.all(np.isfinite(s)):
        raise ModelError("the vibration multipliers must be finite")
    f = _codes("fit", fit, FITS, n)
    ms = _codes("measure", measure, MEASURES, n)
    _check_fit_measure(f, ms)

    scale = r[:, None] ** -POWERS[None, :]                        # (N, 5)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(b > 0, a_max * r / np.where(b > 0, b, 1.0), np.inf)
    c = t.sum(axis=1)                                            # (P, 5)
    directions = [c[:, None, :], t] if total else [t]
    d = np.concatenate(directions, axis=1)[None] * scale[:, None, None, :]
    h, y, line, gap = _solve_in_order(f, ms, ratio, r, d)
    if not total:  # the whole error's direction left unsolved: unknown
        h, y, line, gap = (np.concatenate([np.full((*a.shape[:2], 1, *a.shape[3:]), np.nan), a],
                                          axis=2) for a in (h, y, line, gap))
    bb = b[:, None]
    nonlin = bb * h[:, :, 0]
    coef = bb[..., None] * y[:, :, 0, :] * scale[:, None, :]
    ln = np.stack([bb * line[:, :, 0, 0], bb * line[:, :, 0, 1] / r[:, None]], axis=-1)
    g2_part = np.abs(v)[:, None] * s[None, :]
    per_term = np.concatenate([bb[..., None] * h[:, :, 1:], g2_part[..., None]], axis=-1)
    return WorstCase(
        total=nonlin + g2_part,
        nonlinearity=nonlin,
        g2=g2_part,
        coefficients=coef,
        line=ln,
        terms=per_term,
        rms_bound=np.sqrt(np.sum(per_term**2, axis=-1)),
        gap=gap[:, :, 0],
    )


def residual(coefficients: ArrayLike, line: ArrayLike, omega: ArrayLike) -> FloatArray:
    """r(ω) = p(ω) − (l0 + l1·ω) for x (..., 5) and line (..., 2) at ω (..., m)."""
    x = np.asarray(coefficients, dtype=float)
    ln = np.asarray(line, dtype=float)
    w = np.asarray(omega, dtype=float)
    p = (0.5 * x[..., :1] * np.abs(w) + x[..., 1:2] * w**2 + x[..., 2:3] * w**3
         + x[..., 3:4] * w**4 + x[..., 4:5] * w**5)
    return np.asarray(p - ln[..., :1] - ln[..., 1:2] * w, dtype=float)


@dataclass(frozen=True, eq=False, repr=False)
class SpecBounds(Frozen):
    """Allowable datasheet figures for a budget Δ*, per profile (P,).

    ``nonlinearity``: NL_max in %FS of R (``of`` range), of 2R (span) or in
    rate (rate); inf where the profile does not excite the envelope.
    ``vre``: VRE_max in rate/g² (inf without linear vibration). ``w1``: W(1),
    the worst case for b = 1 (rate per rate); ``share_nl``, ``share_vre``:
    the fractions w_NL, w_V of Δ* (they sum to 1 over the excited parts).
    """

    nonlinearity: FloatArray
    vre: FloatArray
    w1: FloatArray
    share_nl: FloatArray
    share_vre: FloatArray


def _split_inputs(budget: float, weights: tuple[float, float], terms: ArrayLike,
                  g2: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The split weights, the terms (P, 8, 5) and S (P,) of :func:`spec_bounds`, checked."""
    if not (np.isfinite(budget) and budget > 0):
        raise ModelError("the budget must be positive and finite")
    w = np.asarray(weights, dtype=float)
    if w.shape != (2,) or not (np.all(np.isfinite(w)) and np.all(w > 0)):
        raise ModelError("the split weights must be two positive numbers")
    t = np.asarray(terms, dtype=float)
    return w, t, np.broadcast_to(np.asarray(g2, dtype=float), t.shape[:1])


def _split(budget: float, w: FloatArray, w1: FloatArray, s: FloatArray
           ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Δ* split between the envelope (W(1) = ``w1``, (P,) or (M, P)) and the g² term
    (S = ``s``, (P,)) in the ratio ``w`` over the parts the profile excites: the shares,
    NL_max = w_NL·Δ*/W(1) and VRE_max = w_V·Δ*/S (inf where a part gets no share)."""
    on_nl = w1 > 0
    on_v = np.broadcast_to(s > 0, w1.shape)
    total = w[0] * on_nl + w[1] * on_v
    with np.errstate(invalid="ignore", divide="ignore"):
        share_nl = np.where(on_nl, w[0] / total, 0.0)
        share_v = np.where(on_v, w[1] / total, 0.0)
        b_max = np.where(on_nl, share_nl * budget / w1, np.inf)
        vre_max = np.where(on_v, share_v * budget / np.broadcast_to(s, w1.shape), np.inf)
    return share_nl, share_v, b_max, vre_max


def spec_bounds(budget: float, terms: ArrayLike, g2: ArrayLike, range_: float,
                fit: str = "least-squares", measure: str = "max", of: str = "range",
                weights: tuple[float, float] = (1.0, 1.0)) -> SpecBounds:
    """NL_max = w_NL·Δ*/W(1) and VRE_max = w_V·Δ*/S (docs/model.md section 11).

    budget Δ* (rate); terms (P, 8, 5) and g2 (P,) as in :func:`worst_case`;
    range_ R (rate). Δ* is split linearly between the envelope and the g²
    term in the ratio ``weights`` over the parts the profile excites (a part
    with W(1) = 0 or S = 0 gets no share). A sensor within both limits meets
    Δ* whatever its polynomial: b·W(1) + |v|·S ≤ (w_NL + w_V)·Δ* = Δ*.
    """
    w, t, s = _split_inputs(budget, weights, terms, g2)
    if of not in OF:
        raise ModelError(f"nonlinearity is relative to one of {', '.join(OF)}, not {of!r}")
    one = worst_case(t, np.zeros_like(s), [range_], [1.0], fit, measure)
    w1 = one.nonlinearity[0]
    share_nl, share_v, b_max, vre_max = _split(budget, w, w1, s)
    per = {"range": 100.0 / range_, "span": 100.0 / (2.0 * range_), "rate": 1.0}[of]
    return SpecBounds(nonlinearity=b_max * per, vre=vre_max, w1=w1,
                      share_nl=share_nl, share_vre=share_v)


def spec_bounds_many(budget: float, terms: ArrayLike, g2: ArrayLike, ranges: ArrayLike,
                     fits: Sequence[str], measures: Sequence[str], ofs: Sequence[str],
                     weights: tuple[float, float] = (1.0, 1.0)
                     ) -> tuple[FloatArray, FloatArray]:
    """:func:`spec_bounds` for M datasheet definitions at once: (NL_max, VRE_max), (M, P).

    One :func:`worst_case` over all M ranges (b = 1), so that the envelope
    programmes of neighbouring ranges polish each other, instead of one call
    per definition (3,000 sensors of all-different ranges: 3,000 calls, each
    solved cold). Same splits and units as :func:`spec_bounds`.
    """
    w, t, s = _split_inputs(budget, weights, terms, g2)
    r = np.asarray(ranges, dtype=float).reshape(-1)
    for of in ofs:
        if of not in OF:
            raise ModelError(f"nonlinearity is relative to one of {', '.join(OF)}, not {of!r}")
    one = worst_case(t, np.zeros_like(s), r, np.ones(r.size), list(fits), list(measures))
    w1 = one.nonlinearity                                          # (M, P)
    _, _, b_max, vre_max = _split(budget, w, w1, s)
    per = np.array([{"range": 100.0 / rk, "span": 100.0 / (2.0 * rk), "rate": 1.0}[of]
                    for rk, of in zip(r.tolist(), ofs, strict=True)])
    return b_max * per[:, None], vre_max
