"""Locked groups mixed with other components (docs/model.md section 10): two groups
alone (:func:`two_groups_excess`), and one or two groups with independent tones on
a Gaussian part (:func:`locked_mixture_excess`, the tones' and the Gaussian part's
excess tabulated once). The groups themselves are :mod:`gyrovib.core.harmonics`."""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import partial

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import ComplexArray, FloatArray
from gyrovib.core.harmonics import (
    LockedGroup,
    _x3_at,
    _x3_coefficients,
    locked_abs_excess,
    locked_peak,
    monotone_roots,
    stationary_points,
    waveform_mean,
)
from gyrovib.core.statistics import rectified_excess, stretched_rule
from gyrovib.errors import ModelError
from gyrovib.progress import advance

#: Most pieces per rate of :func:`two_groups_excess` (the second group's period split
#: where the first group's excess has a kink); beyond, the mean is taken on a grid.
MAX_PAIR_PIECES = 512


def two_groups_excess(omega: ArrayLike, first: LockedGroup, second: LockedGroup) -> FloatArray:
    """``E(Ω) = <|Ω + x3(θ1) + y3(θ2)|> − |Ω|`` for two independent locked groups alone.

    ``omega``: any shape (rate); returns the same shape. With E1 and E2 each
    group's excess alone (:func:`locked_abs_excess`),

        E(Ω) = <E1(Ω + y3(θ2))>_θ2 + E2(Ω)

    (the mean of |Ω + y3| − |Ω| over θ2 is E2), both terms ≥ 0, so E keeps
    its relative precision. E1(s) is smooth except where s = 0 (the kink of
    −|s|) and where s = −x3(θ*) at a stationary point θ* of x3 (a (·)^{3/2}
    edge); the second group's period is split where Ω + y3(θ2) reaches one of
    those values (:func:`monotone_roots`) and on a uniform grid of 8·n_max
    points, and each piece gets the stretched
    Gauss-Legendre rule of :func:`gyrovib.core.statistics.stretched_rule`, which
    converges geometrically across such end-point singularities (a uniform grid
    over θ2 converges only algebraically: 256 nodes left 6e-6 relative).
    Falls back to a 4096-node grid over θ2 when the pieces would exceed
    :data:`MAX_PAIR_PIECES` per rate (high orders).
    """
    w = np.asarray(omega, dtype=float)
    flat = w.ravel()
    n1, p1 = _x3_coefficients(first)
    n2, p2 = _x3_coefficients(second)
    if n1.size == 0 or n2.size == 0:
        n, p = (n2, p2) if n1.size == 0 else (n1, p1)
        return locked_abs_excess(w, n, p) if n.size else np.zeros(w.shape)
    t1 = stationary_points(n1, p1)
    t2 = stationary_points(n2, p2)
    values = _x3_at(n1.astype(float), p1, t1)[0]
    targets = np.concatenate([[0.0], values])
    second_alone = locked_abs_excess(flat, n2, p2)
    if targets.size * t2.size > MAX_PAIR_PIECES:
        m = 4096
        theta = 2.0 * math.pi * (np.arange(m) + 0.5) / m
        y3 = _x3_at(n2.astype(float), p2, theta)[0]
        out = np.empty(flat.size)
        step = max(1, (1 << 20) // m)
        for lo in range(0, flat.size, step):
            s = flat[lo:lo + step, None] + y3[None, :]
            out[lo:lo + step] = locked_abs_excess(s, n1, p1).mean(axis=1)
        return (out + second_alone).reshape(w.shape)
    stretch, stretch_weight = stretched_rule()
    # pieces no longer than 2π/(8·n_max): between the kinks the integrand is
    # analytic but oscillates with y3, and one 24-node rule over a long piece
    # left 3e-7; with these cuts the rule is converged to rounding
    uniform = 2.0 * math.pi * np.arange(8 * int(n2.max()) + 1) / (8 * int(n2.max()))
    out = np.empty(flat.size)
    per_rate = (targets.size * t2.size + uniform.size) * stretch.size
    step = max(1, (1 << 18) // per_rate)
    for lo in range(0, flat.size, step):
        advance("E(Ω) of locked harmonics", lo, flat.size)
        part = flat[lo:lo + step]
        offsets = (part[:, None] + targets[None, :]).ravel()
        roots = monotone_roots(n2, p2, offsets, t2).reshape(part.size, -1)
        cuts = np.concatenate([np.broadcast_to(uniform, (part.size, uniform.size)),
                               np.where(np.isnan(roots), 2.0 * math.pi, roots)], axis=1)
        cuts.sort(axis=1)
        length = np.diff(cuts, axis=1)[..., None]  # (W, B, 1)
        theta = cuts[:, :-1, None] + length * stretch  # (W, B, G)
        weight = length * stretch_weight / (2.0 * math.pi)
        s = part[:, None, None] + _x3_at(n2.astype(float), p2, theta)[0]
        e1 = locked_abs_excess(s, n1, p1)
        out[lo:lo + step] = np.sum(e1 * weight, axis=(1, 2))
    advance("E(Ω) of locked harmonics", flat.size, flat.size)
    result: FloatArray = (out + second_alone).reshape(w.shape)
    return result


#: Most grid nodes × rates :func:`locked_mixture_excess` evaluates (about 0.3 µs
#: each: a few seconds); beyond, the profile is refused with the reason.
MAX_MIXTURE_NODES = 1 << 24
#: Table steps per σ and the points of the local Lagrange interpolation of
#: :func:`_excess_table` (error ~(1/16)^8 of log E's scale: below 1e-12).
_TABLE_PER_SIGMA = 16
_STENCIL = 8


#: Most values of E_Y in the table of :func:`_excess_table` ((Σa + 40σ)·16/σ): a
#: Gaussian part narrow against the tones needs more (up to ~0.25 ms each).
MAX_SHIFT_TABLE = 1 << 15


def table_size(amplitudes: ArrayLike, sigma: float) -> float:
    """Values :func:`_excess_table` computes for tones ``amplitudes`` on σ > 0 (a float:
    it may be huge)."""
    a = np.asarray(amplitudes, dtype=float).reshape(-1)
    return (math.fsum(a[a > 0].tolist()) + 40.0 * sigma) * _TABLE_PER_SIGMA / sigma + _STENCIL


def _excess_table(amplitudes: FloatArray, sigma: float) -> tuple[float, float, FloatArray]:
    """``log E_Y(c)`` on c = 0, h, 2h, … for Y = Σ a_k·sin φ_k + σZ (σ > 0), with h and
    the reach beyond which E_Y underflows (Σa + 40σ).

    E_Y(c) = <|c + Y|> − |c| is even, smooth on c ≥ 0 at the scale σ (the Gaussian
    part smooths the tones' kinks) and decays like a Gaussian past Σa: its
    logarithm is tabulated, so that interpolation keeps relative precision in
    the tail.
    """
    reach = math.fsum(amplitudes.tolist()) + 40.0 * sigma
    h = sigma / _TABLE_PER_SIGMA
    c = h * np.arange(math.ceil(reach / h) + _STENCIL + 1)
    e = rectified_excess(c, amplitudes, sigma)
    log: FloatArray = np.log(np.maximum(e, 1e-300))
    return h, reach, log


def _cached_table(amplitudes: FloatArray, sigma: float) -> tuple[float, float, FloatArray]:
    """:func:`_excess_table` as per-interval polynomials, kept for the last few
    (tones, σ): a phase search evaluates E(Ω) hundreds of times on one table."""
    key = (amplitudes.tobytes(), float(sigma))
    hit = _TABLES.get(key)
    if hit is None:
        h, reach, log = _excess_table(amplitudes, sigma)
        hit = (h, reach, _interval_polynomials(log))
        if len(_TABLES) >= 8:
            _TABLES.pop(next(iter(_TABLES)))
        _TABLES[key] = hit
    return hit


_TABLES: dict[tuple[bytes, float], tuple[float, float, FloatArray]] = {}


def _lagrange_to_power(offset: int) -> FloatArray:
    """(8, 8) M with M[p, j] the coefficient of u^p in the Lagrange basis polynomial
    L_j(u + offset) on the nodes 0…7: the interpolant on one table interval as a
    polynomial in its local coordinate u ∈ [0, 1). Computed once per offset."""
    hit = _POWER.get(offset)
    if hit is not None:
        return hit
    out = np.zeros((_STENCIL, _STENCIL))
    for j in range(_STENCIL):
        poly = np.array([1.0])  # ascending powers of u
        for k in range(_STENCIL):
            if k != j:
                poly = np.convolve(poly, np.array([offset - k, 1.0])) / (j - k)
        out[:, j] = poly
    _POWER[offset] = out
    return out


_POWER: dict[int, FloatArray] = {}


def _interval_polynomials(log: FloatArray) -> FloatArray:
    """(8, L − 1) power coefficients in u of the 8-point Lagrange interpolant of ``log``
    on each interval [i, i + 1) (nodes i − 3 … i + 4, shifted inwards at the ends):
    the same interpolant as evaluating the Lagrange basis at every point, computed once
    per table so that each point costs a gather and a Horner step."""
    intervals = log.size - 1
    base = np.clip(np.arange(intervals) - (_STENCIL // 2 - 1), 0, log.size - _STENCIL)
    offset = np.arange(intervals) - base
    windows = log[base[:, None] + np.arange(_STENCIL)[None, :]]
    coef = np.empty((intervals, _STENCIL))
    for d in np.unique(offset).tolist():
        rows = offset == d
        coef[rows] = windows[rows] @ _lagrange_to_power(int(d)).T
    # one contiguous row per power: each point gathers 8 scalars from short rows
    out: FloatArray = np.ascontiguousarray(coef.T)
    return out


def _horner(x: FloatArray, coef: FloatArray) -> FloatArray:
    """The table's interpolant at positions ``x`` (in table steps, ≥ 0)."""
    i = np.minimum(x.astype(np.int64), coef.shape[1] - 1)
    u = x - i
    total = coef[_STENCIL - 1].take(i)
    for p in range(_STENCIL - 2, -1, -1):
        total *= u
        total += coef[p].take(i)
    out: FloatArray = total
    return out


def _interpolate(c: FloatArray, h: float, reach: float, coef: FloatArray) -> FloatArray:
    """E_Y(|c|) from :func:`_excess_table` by Lagrange interpolation on 8 table points
    (its per-interval polynomials, :func:`_interval_polynomials`)."""
    a = np.abs(c)
    inside = a < reach
    out = np.zeros(a.shape)
    out[inside] = np.exp(_horner(a[inside] / h, coef))
    return out


#: Locked groups kept on the midpoint grid of :func:`locked_mixture_excess`; the
#: further groups are folded into the table of E_Y (:func:`_folded_table`): the grid
#: of one group costs its nodes per rate, a fold the table's length times its nodes
#: once (and once per phase of the folded group in a ``phase: worst`` search, whose
#: moves change one group at a time), where a grid of two would cost their product
#: per rate.
GRID_GROUPS = 1
#: Most interpolations :func:`_folded_table` may make (about 1 µs each).
MAX_FOLD_INTERPOLATIONS = 1 << 26


def _folded_table(amplitudes: FloatArray, sigma: float,
                  folded: Sequence[tuple[NDArray[np.int64], ComplexArray, int]]
                  ) -> tuple[float, float, FloatArray]:
    """``log E_Y'(c)`` on c = −R, −R + h, …, R for Y' = Y + x3 of the ``folded`` groups
    (Y the tones and the Gaussian part of :func:`_excess_table`), with h = σ/16 and
    the reach R = Σa + 40σ + Σ peaks.

    Each group g (its orders, phasors and midpoint nodes m) is independent of Y, so
    with F(c) = E(c) + |c| = <|c + Y|>, F_{Y+g}(c) = <F_Y(c + g(θ))>_θ: the mean
    over g's period, a midpoint rule on m nodes (geometric convergence: F_Y is
    analytic at the scale σ, as in :func:`mixture_nodes`). Where |c| exceeds the
    group's peak, c + g keeps its sign and E_{Y+g}(c) = <E_Y(c + g)> (no
    cancellation). A folded group makes E_Y' odd-asymmetric (odd moments), so the
    table is signed.
    """
    peaks = [_peak(n, p) for n, p, _ in folded]
    reach = math.fsum(amplitudes.tolist()) + 40.0 * sigma + math.fsum(peaks)
    h = sigma / _TABLE_PER_SIGMA
    half = math.ceil(reach / h) + _STENCIL
    c = np.arange(-half, half + 1, dtype=np.float64) * h
    key = (amplitudes.tobytes(), float(sigma), half)
    coef = _BASES.get(key)
    if coef is None:
        e = rectified_excess(np.abs(c[half:]), amplitudes, sigma)
        coef = _signed_polynomials(
            np.log(np.maximum(np.concatenate([e[:0:-1], e]), 1e-300)))
        _BASES.clear()
        _BASES[key] = coef
    for (n, p, m), peak in zip(folded, peaks, strict=True):
        theta = 2.0 * math.pi * (np.arange(m) + 0.5) / m
        x3 = _x3_at(n.astype(float), p, theta)[0]
        new = waveform_mean(c, x3, peak, partial(_interpolate_signed, h=h, reach=reach,
                                                 coef=coef), label=None)
        coef = _signed_polynomials(np.log(np.maximum(new, 1e-300)))
    return h, reach, coef


def _signed_polynomials(log: FloatArray) -> FloatArray:
    """:func:`_interval_polynomials` of a signed table (c = 0 in the middle), each half
    on its own: E(c) = F(c) − |c| has a kink at c = 0 (F is smooth), so no stencil
    may straddle it."""
    half = (log.size - 1) // 2
    out: FloatArray = np.concatenate([_interval_polynomials(log[:half + 1]),
                                      _interval_polynomials(log[half:])], axis=1)
    return out


def _cached_fold(amplitudes: FloatArray, sigma: float,
                 folded: Sequence[tuple[NDArray[np.int64], ComplexArray, int]]
                 ) -> tuple[float, float, FloatArray]:
    """:func:`_folded_table`, kept for the last few (tones, σ, folded groups)."""
    key = (amplitudes.tobytes(), float(sigma),
           tuple((n.tobytes(), p.tobytes(), m) for n, p, m in folded))
    hit = _FOLDS.get(key)
    if hit is None:
        hit = _folded_table(amplitudes, sigma, folded)
        if len(_FOLDS) >= 16:
            _FOLDS.pop(next(iter(_FOLDS)))
        _FOLDS[key] = hit
    return hit


_FOLDS: dict[tuple[object, ...], tuple[float, float, FloatArray]] = {}
_BASES: dict[tuple[bytes, float, int], FloatArray] = {}
_PEAKS: dict[tuple[bytes, bytes], float] = {}


def _peak(n: NDArray[np.int64], p: ComplexArray) -> float:
    """:func:`~gyrovib.core.harmonics.locked_peak`, kept for the last few groups (a
    phase search asks for the same group's peak at every evaluation)."""
    key = (n.tobytes(), p.tobytes())
    hit = _PEAKS.get(key)
    if hit is None:
        hit = float(locked_peak(n, p))
        if len(_PEAKS) >= 64:
            _PEAKS.pop(next(iter(_PEAKS)))
        _PEAKS[key] = hit
    return hit


def _interpolate_signed(c: FloatArray, h: float, reach: float, coef: FloatArray
                        ) -> FloatArray:
    """E(c) from the signed table of :func:`_folded_table` (its per-interval
    polynomials; position 0 is c = −(half the table))."""
    half = coef.shape[1] // 2
    inside = np.abs(c) < reach
    out = np.zeros(np.shape(c))
    out[inside] = np.exp(_horner(np.asarray(c)[inside] / h + half, coef))
    return out


def fold_cost(amplitudes: ArrayLike, sigma: float, peaks: Sequence[float],
              nodes: Sequence[int]) -> float:
    """Interpolations :func:`_folded_table` makes: table length × nodes, per folded group."""
    a = np.asarray(amplitudes, dtype=float).reshape(-1)
    reach = math.fsum(a[a > 0].tolist()) + 40.0 * sigma + math.fsum(peaks)
    length = 2.0 * reach * _TABLE_PER_SIGMA / sigma
    return length * float(sum(nodes))


def mixture_nodes(groups: Sequence[LockedGroup], amplitudes: ArrayLike,
                  sigma: float, swing: float | None = None) -> list[int]:
    """Midpoint nodes per group period for :func:`locked_mixture_excess` (σ > 0).

    The integrand is analytic at the scale σ, so the midpoint rule converges
    geometrically once each group has ``1.25·n_max·(8·peak/σ + (swing +
    peak)·peak/σ²) + 64`` nodes (the kernel's width against the group's swing,
    and the curvature of its Gaussian tail; the rule of the single group of
    :func:`locked_rectified_excess`), capped at 2^14. ``swing``: an upper bound to use
    instead of the sum of the peaks and the tones (more nodes, never fewer).
    """
    a = np.asarray(amplitudes, dtype=float).reshape(-1)
    peaks = [_peak(*_x3_coefficients(g)) for g in groups]
    if swing is None:
        swing = sum(peaks) + float(np.sum(a[a > 0]))
    out = []
    for g, peak in zip(groups, peaks, strict=True):
        need = 1.25 * g.n_max * (8.0 * peak / sigma + (swing + peak) * peak / sigma**2) + 64
        out.append(int(min(max(need, 64), 1 << 14)) if peak > 0 else 1)
    return out


def _mixture_cost_checked(live: list[tuple[LockedGroup, NDArray[np.int64], ComplexArray]],
                          a: FloatArray, sigma: float, near: NDArray[np.bool_],
                          nodes: list[int], count: int) -> None:
    """Refuse, before any work, a table of E_Y or a grid larger than gyrovib allows
    (``count``: the profile's groups, on the grid or folded)."""
    total = math.prod(nodes) * int(np.count_nonzero(near))
    if near.any() and table_size(a, sigma) > MAX_SHIFT_TABLE:
        raise ModelError(
            reason=f"E(Ω) for {count} phase-locked group{'s' if count != 1 else ''} "
            f"with {a.size} independent tone{'s' if a.size != 1 else ''} (largest "
            f"{float(a[0]) if a.size else 0.0:.4g}) on a random part of RMS {sigma:.4g} would "
            f"tabulate {table_size(a, sigma):,.0f} values of the tones' excess on the random "
            f"part (16 per σ), more than the {MAX_SHIFT_TABLE:,} gyrovib allows: the random part "
            "is too narrow against the tones to matter, yet too large to drop; drop it, "
            "or give the tones as orders of a group")
    if total > MAX_MIXTURE_NODES:
        raise ModelError(
            reason=f"E(Ω) for {len(live)} phase-locked group{'s' if len(live) != 1 else ''} "
            f"with {a.size} independent tone{'s' if a.size != 1 else ''} on a random part of "
            f"RMS {sigma:.4g} at {total // math.prod(nodes)} rate"
            f"{'s' if total != math.prod(nodes) else ''} within its reach would take "
            f"{total:,} grid points (the groups' periods on "
            f"{' × '.join(str(m) for m in nodes)} nodes, as the random part is narrow "
            f"against their swing), more than the {MAX_MIXTURE_NODES:,} gyrovib allows; "
            "give fewer rates, or the smaller group's orders as independent tones")


def _phase_shifts(live: list[tuple[LockedGroup, NDArray[np.int64], ComplexArray]],
                  nodes: list[int]) -> FloatArray:
    """x3 + y3 at every combination of the groups' midpoint nodes."""
    shift = np.zeros(1)
    for (_, n, p), m in zip(live, nodes, strict=True):
        theta = 2.0 * math.pi * (np.arange(m) + 0.5) / m
        x3 = _x3_at(n.astype(float), p, theta)[0]
        shift = (shift[:, None] + x3[None, :]).ravel()
    return shift


def _split_groups(groups: Sequence[LockedGroup], a: FloatArray, sigma: float
                  ) -> tuple[list[tuple[LockedGroup, NDArray[np.int64], ComplexArray]],
                             list[int], list[tuple[NDArray[np.int64], ComplexArray, int]],
                             int]:
    """The groups (with a part on x3) kept on the grid and their nodes, the folded ones
    with theirs, and how many there are: the group of most nodes stays on the grid (it
    would cost most to fold)."""
    coefficients = [_x3_coefficients(g) for g in groups]
    everything = [(g, n, p) for g, (n, p) in zip(groups, coefficients, strict=True)
                  if n.size]
    all_nodes = mixture_nodes([g for g, _, _ in everything], a, sigma)
    order = sorted(range(len(everything)), key=lambda k: -all_nodes[k])
    live = [everything[k] for k in order[:GRID_GROUPS]]
    nodes = [all_nodes[k] for k in order[:GRID_GROUPS]]
    # a folded group's nodes from a swing that does not move with the other groups'
    # phases (Σ|a_n| bounds each peak): its table is then reused while a phase
    # search moves only the other groups
    bound = sum(float(np.sum(np.abs(p))) for _, _, p in everything) + float(np.sum(a))
    folded = [(everything[k][1], everything[k][2],
               mixture_nodes([everything[k][0]], a, sigma, swing=bound)[0])
              for k in order[GRID_GROUPS:]]
    return live, nodes, folded, len(everything)


def _fold_checked(folded: Sequence[tuple[NDArray[np.int64], ComplexArray, int]],
                  a: FloatArray, sigma: float, count: int) -> None:
    """Refuse, before any work, a fold costlier than :data:`MAX_FOLD_INTERPOLATIONS`."""
    if not folded:
        return
    peaks = [_peak(n, p) for n, p, _ in folded]
    cost = fold_cost(a, sigma, peaks, [m for _, _, m in folded])
    if cost <= MAX_FOLD_INTERPOLATIONS:
        return
    raise ModelError(
        reason=f"E(Ω) for {count} phase-locked groups on a random part of RMS "
        f"{sigma:.4g} would fold the groups beyond the first into a table of "
        f"{fold_cost(a, sigma, [sum(peaks)], [1]):,.0f} values on "
        f"{' + '.join(str(m) for _, _, m in folded)} nodes, more than the "
        f"{MAX_FOLD_INTERPOLATIONS:,} interpolations gyrovib allows: the random part is "
        "narrow against the groups' swing; give the smaller groups' orders as "
        "independent tones")


def locked_mixture_excess(omega: ArrayLike, groups: Sequence[LockedGroup],
                          amplitudes: ArrayLike, sigma: float) -> FloatArray:
    """``E(Ω) = <|Ω + x3(θ1) [+ y3(θ2) + …] + Y|> − |Ω|``: locked groups, with
    independent tones ``amplitudes`` and a Gaussian part ``sigma`` > 0 in Y.

    The group of most nodes is averaged on its midpoint grid as below; every
    further group is independent of the rest and is folded into the table of E_Y
    first (:func:`_folded_table`), so that no number of groups multiplies the grid
    (cost: :func:`fold_cost` interpolations, once per table).

    The Gaussian part and the tones are integrated first, once: E_Y(c) =
    <|c + Y|> − |c| (:func:`~gyrovib.core.statistics.rectified_excess`) is
    tabulated in c (log E_Y, 16 steps per σ, local 8-point Lagrange
    interpolation) — it depends on c alone, not on the rate or the groups'
    phases. The mean over the groups' phases of the smooth F(s) = E_Y(s) + |s|
    at s = Ω + x3 + y3 is then a midpoint rule on the groups' periods
    (:func:`mixture_nodes`, geometric convergence): ``mean F − |Ω|`` where Ω
    + x3 + y3 may cross 0, ``mean E_Y`` (no cancellation) where it cannot.
    Cost: (Σa + 40σ)·16/σ values of E_Y, and rates × the product of the
    nodes interpolations; above :data:`MAX_MIXTURE_NODES` a
    :class:`~gyrovib.errors.ModelError` says so before any work (a Gaussian
    part tiny against the groups' swing).
    """
    w = np.asarray(omega, dtype=float)
    flat = w.ravel()
    a = np.asarray(amplitudes, dtype=float).reshape(-1)
    a = np.sort(a[a > 0])[::-1]
    live, nodes, folded, count = _split_groups(groups, a, sigma)
    peak = sum(_peak(n, p) for _, n, p in live)
    fold_peak = sum(_peak(n, p) for n, p, _ in folded)
    # beyond the swing by more than E_Y's reach, E underflows to 0: not computed
    near = np.abs(flat) < peak + fold_peak + math.fsum(a.tolist()) + 40.0 * sigma
    _mixture_cost_checked(live, a, sigma, near, nodes, count)
    _fold_checked(folded, a, sigma, count)
    out = np.zeros(flat.size)
    if not near.any():
        return out.reshape(w.shape)
    if folded:
        h, reach, table = _cached_fold(a, sigma, folded)
        interpolate = _interpolate_signed
    else:
        h, reach, table = _cached_table(a, sigma)
        interpolate = _interpolate
    out[near] = waveform_mean(flat[near], _phase_shifts(live, nodes), peak,
                              lambda s: interpolate(s, h, reach, table))
    result: FloatArray = out.reshape(w.shape)
    return result
