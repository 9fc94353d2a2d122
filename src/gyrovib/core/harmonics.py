"""Phase-locked harmonics of one source (docs/model.md section 10).

A locked group is ``x_i(θ) = Σ_n a_ni·sin(n·θ + φ_ni)`` per axis, θ = 2π·f0·t,
periodic in θ with period 2π. Its phasors ``p_ni = a_ni·exp(j·φ_ni)`` (rate
units, φ in radians) give ``x_i(θ) = Σ_n Im(p_ni·e^{jnθ})``. Unlike
independent tones its x3 need not be symmetric, so the odd moments
``M3 = <x3³>`` and ``M5 = <x3⁵>`` enter the error:

    Δ0 gains k3·M3 and k5·M5;  Δ(1) = 3k3·M2 + 4k4·M3 + 5k5·M4;
    Δ(2) = 6k4·M2 + 10k5·M3;    Δ(3) = 10k5·M2

Moments over one period are exact on a uniform grid of more than 5·n_max
points (the integrand is a trigonometric polynomial of degree ≤ 5·n_max).
Independent components (other tones, the Gaussian part, other groups)
combine by adding cumulants (:func:`combine_moments`). E(Ω) of the group
alone is exact through the zero crossings of Ω + x3(θ) (roots of a
polynomial in z = e^{jθ}) and the closed-form antiderivative; with other
components it is the mean over the group's period of their rectified mean
at Ω + x3(θ) (:func:`locked_rectified_excess`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import ComplexArray, FloatArray
from gyrovib.core.statistics import rectified_excess
from gyrovib.frozen import Frozen
from gyrovib.progress import advance

#: Most locked groups of a profile with no random part: E(Ω) averages over the joint
#: phases of the groups beyond the first (two groups alone: exactly; three would take
#: 256² nodes per rate, 12 s and 650 MB for a 401-rate sweep, minutes inside the swing).
#: With a random part, any number: the groups beyond the second are folded into its
#: table (core/harmonic_mixtures.py).
MAX_GROUPS = 2

#: Unit-circle tolerance for the roots of Ω + x3(θ); extra breakpoints are harmless.
_CIRCLE = 1e-5
#: Rates above this multiple of Σ|p_n| (a bound on |x3|) are beyond the swing: E = 0.
_BEYOND = 1.0 + 1e-9


@dataclass(frozen=True, eq=False, repr=False)
class LockedGroup(Frozen):
    """Harmonics of one fundamental with fixed relative phases.

    ``orders``: (N,) distinct positive integers n; ``phasors``: (N, 3) complex
    ``a·exp(jφ)`` per order and axis (rate units at the sensor, φ in rad);
    ``worst``: (N,) bool, the orders whose phase is unknown (``phase: worst``):
    their common offset ψ_n (added to every axis) is searched for the worst
    case. ``fundamental``: f0 in Hz (for reporting; the moments do not depend
    on it).
    """

    orders: NDArray[np.int64]
    phasors: ComplexArray
    worst: NDArray[np.bool_]
    fundamental: float = 1.0

    @property
    def n_max(self) -> int:
        return int(np.max(self.orders)) if self.orders.size else 0

    def shifted(self, offsets: ArrayLike) -> LockedGroup:
        """The group with order n's phases advanced by ``offsets[n]`` (rad, (N,))."""
        psi = np.asarray(offsets, dtype=float).reshape(-1)
        return replace(self, phasors=self.phasors * np.exp(1j * psi)[:, None])


def locked_group(
    orders: Sequence[int],
    amplitudes: ArrayLike,
    phases: ArrayLike,
    *,
    worst: Sequence[bool] | None = None,
    fundamental: float = 1.0,
    gains: ArrayLike | None = None,
) -> LockedGroup:
    """Build a :class:`LockedGroup` from per-order amplitudes (N, 3) and phases (N, 3) in degrees.

    ``gains``: optional (N,) transmissibility ν(n·f0) scaling each order (mount,
    input-side response). Raises ValueError on a non-positive fundamental, an
    order that is not a positive integer or repeats, or non-finite values.
    """
    raw = np.asarray(orders, dtype=float).reshape(-1)
    if not (math.isfinite(fundamental) and fundamental > 0):
        raise ValueError("the fundamental frequency must be positive")
    if raw.size == 0 or np.any(raw != np.round(raw)) or np.any(raw < 1):
        raise ValueError("orders must be positive integers")
    n = raw.astype(np.int64)
    ordered = np.sort(n)  # not np.unique: it imports numpy.ma (~7 ms at start-up)
    if np.any(ordered[1:] == ordered[:-1]):
        raise ValueError("an order may appear only once in a group")
    amp = np.asarray(amplitudes, dtype=float).reshape(n.size, 3)
    ph = np.deg2rad(np.asarray(phases, dtype=float).reshape(n.size, 3))
    if not (np.all(np.isfinite(amp)) and np.all(np.isfinite(ph)) and np.all(amp >= 0)):
        raise ValueError("amplitudes must be finite and ≥ 0, phases finite")
    if gains is not None:
        amp = amp * np.asarray(gains, dtype=float).reshape(n.size, 1)
    w = np.zeros(n.size, dtype=bool) if worst is None else np.asarray(worst, dtype=bool)
    return LockedGroup(orders=n, phasors=amp * np.exp(1j * ph), worst=w.reshape(n.size),
                       fundamental=float(fundamental))


def period_grid(n_max: int, factor: int = 6) -> FloatArray:
    """θ of a uniform grid on one period with ``factor·n_max + 2`` points (> 5·n_max)."""
    m = factor * max(n_max, 1) + 2
    grid: FloatArray = 2.0 * math.pi * np.arange(m) / m
    return grid


def group_signal(orders: ArrayLike, phasors: ArrayLike, theta: ArrayLike) -> FloatArray:
    """``x(θ) = Σ_n Im(p_n·e^{jnθ})``.

    ``phasors``: (..., N, A) for A axes (or signals), ``theta``: (T,).
    Returns (..., A, T).
    """
    n = np.asarray(orders, dtype=float)
    p = np.asarray(phasors, dtype=complex)
    t = np.asarray(theta, dtype=float)
    e = np.exp(1j * n[:, None] * t[None, :])  # (N, T)
    out: FloatArray = np.einsum("...na,nt->...at", p, e).imag
    return out


@dataclass(frozen=True, eq=False, repr=False)
class GroupMoments(Frozen):
    """Moments of a locked group over one period (rate^n units); shape (...,) each.

    ``m2..m5``: <x3^n>; ``c31``, ``c32``: <x3·x1>, <x3·x2>.
    """

    m2: FloatArray
    m3: FloatArray
    m4: FloatArray
    m5: FloatArray
    c31: FloatArray
    c32: FloatArray


def group_moments(orders: ArrayLike, phasors: ArrayLike) -> GroupMoments:
    """Exact period averages of a group, batched: ``phasors`` (..., N, 3).

    The uniform grid of :func:`period_grid` integrates the degree-5·n_max
    trigonometric polynomials x3^n, x3·xi exactly.
    """
    n = np.asarray(orders, dtype=np.int64)
    x = group_signal(n, phasors, period_grid(int(np.max(n)) if n.size else 1))
    x3 = x[..., 2, :]
    sq = x3 * x3
    return GroupMoments(
        m2=sq.mean(axis=-1), m3=(sq * x3).mean(axis=-1), m4=(sq * sq).mean(axis=-1),
        m5=(sq * sq * x3).mean(axis=-1), c31=(x3 * x[..., 0, :]).mean(axis=-1),
        c32=(x3 * x[..., 1, :]).mean(axis=-1),
    )


def combine_moments(
    parts2: Sequence[ArrayLike], parts3: Sequence[ArrayLike],
    parts4: Sequence[ArrayLike], parts5: Sequence[ArrayLike],
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """M2..M5 of a sum of independent zero-mean parts from each part's moments.

    Cumulants add: κ2 = M2, κ3 = M3, κ4 = M4 − 3·M2², κ5 = M5 − 10·M3·M2 per
    part; the sum has M2 = Σκ2, M3 = Σκ3, M4 = Σκ4 + 3(Σκ2)²,
    M5 = Σκ5 + 10·(Σκ3)(Σκ2). (With M3 = M5 = 0 this is section 4's
    M4 = ΣM4c + 3[(ΣM2c)² − ΣM2c²].)
    """
    m2 = [np.asarray(v, dtype=float) for v in parts2]
    m3 = [np.asarray(v, dtype=float) for v in parts3]
    m4 = [np.asarray(v, dtype=float) for v in parts4]
    m5 = [np.asarray(v, dtype=float) for v in parts5]
    k2 = sum(m2, np.zeros(()))
    k3 = sum(m3, np.zeros(()))
    k4 = sum((b - 3.0 * a * a for a, b in zip(m2, m4, strict=True)), np.zeros(()))
    k5 = sum((d - 10.0 * c * a for a, c, d in zip(m2, m3, m5, strict=True)), np.zeros(()))
    return k2, k3, k4 + 3.0 * k2 * k2, k5 + 10.0 * k3 * k2


def _x3_coefficients(group: LockedGroup) -> tuple[NDArray[np.int64], ComplexArray]:
    keep = np.abs(group.phasors[:, 2]) > 0
    return group.orders[keep], group.phasors[keep, 2]


def trig_roots(orders: ArrayLike, coefficients: ArrayLike, offset: ArrayLike) -> FloatArray:
    """Zeros in [0, 2π) of ``f(θ) = c + Σ_n Im(p_n·e^{jnθ})`` for each offset c.

    ``coefficients``: (N,) complex p_n; ``offset``: (W,). Multiplying by
    z^D (z = e^{jθ}, D = max n) gives a polynomial of degree 2D whose roots on
    the unit circle are the zeros; they are found as companion-matrix
    eigenvalues (all offsets at once) and polished by Newton steps (``p`` must
    not be all zero). Returns
    (W, 2D) angles, NaN where a root is off the circle; a root counted twice
    or slightly off is harmless for the piecewise integrals that use it.
    """
    n = np.asarray(orders, dtype=np.int64)
    p = np.asarray(coefficients, dtype=complex)
    c = np.atleast_1d(np.asarray(offset, dtype=float))
    # orders below 1e-14 of the largest move the zeros by less than that: leave them
    # out of the polynomial, whose leading coefficient must not be (sub)normal-tiny
    keep = np.abs(p) > 1e-14 * float(np.max(np.abs(p)))
    n, p = n[keep], p[keep]
    d = int(np.max(n))
    poly = np.zeros(2 * d + 1, dtype=complex)  # poly[k]: coefficient of z^k
    for nn, pp in zip(n, p, strict=True):
        poly[d + nn] += pp / 2j
        poly[d - nn] -= np.conj(pp) / 2j
    lead = poly[-1]
    deg = 2 * d
    comp = np.zeros((c.size, deg, deg), dtype=complex)
    comp[:, np.arange(1, deg), np.arange(deg - 1)] = 1.0
    b = poly[:-1] / lead
    comp[:, :, -1] = -b[None, :]
    comp[:, d, -1] = -(poly[d] + c) / lead
    z = np.linalg.eigvals(comp)
    theta = np.mod(np.angle(z), 2.0 * math.pi)
    on = np.abs(np.abs(z) - 1.0) < _CIRCLE
    nf = n.astype(float)
    for _ in range(3):
        e = np.exp(1j * nf[None, None, :] * theta[..., None])
        f = c[:, None] + np.sum((p * e).imag, axis=-1)
        df = np.sum((1j * nf * p * e).imag, axis=-1)
        ok = np.abs(df) > 1e-300
        step = np.where(ok, f / np.where(ok, df, 1.0), 0.0)
        theta = np.where(np.abs(step) < 1e-3, theta - step, theta)
    theta = np.mod(theta, 2.0 * math.pi)
    out: FloatArray = np.where(on, theta, np.nan)
    return out


def _antiderivative(orders: FloatArray, p: ComplexArray, c: FloatArray,
                    theta: FloatArray) -> FloatArray:
    """∫ f dθ = c·θ − Σ_n Re(p_n·e^{jnθ})/n at θ (W, T)."""
    e = np.exp(1j * orders[None, None, :] * theta[..., None])
    out: FloatArray = c[:, None] * theta - np.sum((p * e).real / orders, axis=-1)
    return out


def locked_abs_excess(omega: ArrayLike, orders: ArrayLike, coefficients: ArrayLike) -> FloatArray:
    """``<|Ω + x3(θ)|> − |Ω|`` over one period, exactly, for x3 = Σ Im(p_n·e^{jnθ}).

    ``omega``: any shape (rate); returns the same shape. With s = sign Ω (+1
    at Ω = 0) and <x3> = 0 this equals (1/π)·Σ |∫ f| over the pieces between
    zero crossings where sign f ≠ s, which keeps its relative precision.
    """
    w = np.asarray(omega, dtype=float)
    n = np.asarray(orders, dtype=np.int64)
    p = np.asarray(coefficients, dtype=complex)
    keep = np.abs(p) > 0
    n, p = n[keep], p[keep]
    out = np.zeros(w.size)
    if n.size == 0 or w.size == 0:
        return out.reshape(w.shape)
    # beyond the swing, |Ω| > Σ|p_n| ≥ max|x3|, Ω + x3 keeps the sign of Ω and the
    # excess is exactly 0 (what the pieces below give there): only the others are solved
    inside = ~(np.abs(w.ravel()) > _BEYOND * float(np.sum(np.abs(p))))
    if inside.any():
        out[inside] = _abs_excess(w.ravel()[inside], n, p)
    return out.reshape(w.shape)


def stationary_points(orders: ArrayLike, coefficients: ArrayLike) -> FloatArray:
    """Sorted distinct θ in [0, 2π) where x3'(θ) = 0, x3 = Σ Im(p_n·e^{jnθ}) (``p`` not all 0).

    The zeros of the derivative ``Σ Im(j·n·p_n·e^{jnθ})`` (:func:`trig_roots`,
    one eigenvalue problem of degree 2·n_max): between two consecutive ones x3 is
    monotone, so Ω + x3 has at most one zero there whatever Ω is. They do not
    depend on the rate, so a sweep solves them once.
    """
    n = np.asarray(orders, dtype=np.int64)
    p = np.asarray(coefficients, dtype=complex)
    theta = trig_roots(n, 1j * n * p, np.zeros(1))[0]
    theta = np.sort(theta[~np.isnan(theta)])
    if theta.size > 1:
        theta = theta[np.concatenate([[True], np.diff(theta) > 1e-13])]
    if theta.size < 2:  # (a nonconstant periodic x3 has a maximum and a minimum)
        theta = np.concatenate([theta, period_grid(int(n.max()), 16)])
        theta = np.sort(np.mod(theta, 2.0 * math.pi))
    out: FloatArray = theta
    return out


def _x3_at(nf: FloatArray, p: ComplexArray, theta: FloatArray) -> tuple[FloatArray, FloatArray]:
    """x3 and dx3/dθ at ``theta`` (any shape)."""
    e = p * np.exp(1j * nf * theta[..., None])
    return np.sum(e.imag, axis=-1), np.sum((1j * nf * e).imag, axis=-1)


#: Most (offset × piece) brackets solved at a time by :func:`monotone_roots`.
_ROOT_CHUNK = 1 << 16


def monotone_roots(orders: ArrayLike, coefficients: ArrayLike, offset: ArrayLike,
                   stationary: FloatArray | None = None) -> FloatArray:
    """Zeros of ``c + x3(θ)`` for each offset c (W,), one per monotone piece: (W, P).

    The pieces lie between consecutive :func:`stationary_points` (P of them,
    the last one wrapping past 2π); a piece holds a zero when c + x3 changes
    sign over it, found by Newton's method kept inside the bracket (bisection
    where a Newton step would leave it) to the last bit. NaN where a piece has
    none. Cost: one eigenvalue problem for the pieces, then O(W·P·N) per
    iteration — no eigenvalue problem per rate, unlike :func:`trig_roots`.
    """
    n = np.asarray(orders, dtype=np.int64)
    p = np.asarray(coefficients, dtype=complex)
    c = np.atleast_1d(np.asarray(offset, dtype=float)).ravel()
    t = stationary_points(n, p) if stationary is None else stationary
    nf = n.astype(float)
    ends = np.concatenate([t, t[:1] + 2.0 * math.pi])
    v = _x3_at(nf, p, ends)[0]
    out = np.full((c.size, t.size), np.nan)
    fa = c[:, None] + v[None, :-1]
    fb = c[:, None] + v[None, 1:]
    has = (fa == 0.0) | ((fa < 0.0) != (fb < 0.0))
    rows, cols = np.nonzero(has)
    for start in range(0, rows.size, _ROOT_CHUNK):
        r, k = rows[start:start + _ROOT_CHUNK], cols[start:start + _ROOT_CHUNK]
        lo, hi = ends[k].copy(), ends[k + 1].copy()
        cc = c[r]
        f_lo = fa[r, k]
        at_lo = f_lo == 0.0
        x = 0.5 * (lo + hi)
        for _ in range(80):
            f, df = _x3_at(nf, p, x)
            f = f + cc
            same = (f < 0.0) == (f_lo < 0.0)
            lo = np.where(same, x, lo)
            hi = np.where(same, hi, x)
            f_lo = np.where(same, f, f_lo)
            with np.errstate(divide="ignore", invalid="ignore"):
                newton = x - f / df
            inside = (newton >= lo) & (newton <= hi)
            nxt = np.where(inside, newton, 0.5 * (lo + hi))
            nxt = np.where(f == 0.0, x, nxt)
            done = np.abs(nxt - x) <= 4e-16 * (1.0 + np.abs(x))
            x = nxt
            if done.all():
                break
        out[r, k] = np.where(at_lo, ends[k], np.mod(x, 2.0 * math.pi))
    return out


def _abs_excess(flat: FloatArray, n: NDArray[np.int64], p: ComplexArray,
                stationary: FloatArray | None = None) -> FloatArray:
    """:func:`locked_abs_excess` at the rates ``flat`` (W,), the pieces integrated.

    The pieces run between the zeros of Ω + x3 and x3's stationary points (a
    split where f does not change sign is harmless); rates are taken in
    chunks so that a long sweep holds a bounded amount of memory.
    """
    t = stationary_points(n, p) if stationary is None else stationary
    out: FloatArray = np.empty(flat.size)
    chunk = max(1, _ROOT_CHUNK // (2 * t.size + 2))
    for lo in range(0, flat.size, chunk):
        part = flat[lo:lo + chunk]
        out[lo:lo + chunk] = _abs_excess_chunk(part, n, p, t)
    return out


def _abs_excess_chunk(flat: FloatArray, n: NDArray[np.int64], p: ComplexArray,
                      t: FloatArray) -> FloatArray:
    roots = monotone_roots(n, p, flat, t)
    pts = np.concatenate([np.zeros((flat.size, 1)), np.where(np.isnan(roots), 2 * math.pi, roots),
                          np.broadcast_to(t, (flat.size, t.size)),
                          np.full((flat.size, 1), 2 * math.pi)], axis=1)
    pts.sort(axis=1)
    nf = n.astype(float)
    big = _antiderivative(nf, p, flat, pts)
    integral = np.diff(big, axis=1)
    mid = 0.5 * (pts[:, 1:] + pts[:, :-1])
    fmid = flat[:, None] + np.sum((p * np.exp(1j * nf * mid[..., None])).imag, axis=-1)
    s = np.where(flat >= 0, 1.0, -1.0)
    wrong = (np.sign(fmid) != s[:, None]) & (np.diff(pts, axis=1) > 0)
    out: FloatArray = np.sum(np.where(wrong, np.abs(integral), 0.0), axis=1) / math.pi
    return out


def locked_peak(orders: ArrayLike, coefficients: ArrayLike) -> float:
    """``max_θ |x3(θ)|`` exactly: x3 at the zeros of its derivative (and a grid as a check)."""
    n = np.asarray(orders, dtype=np.int64)
    p = np.asarray(coefficients, dtype=complex)
    keep = np.abs(p) > 0
    n, p = n[keep], p[keep]
    if n.size == 0:
        return 0.0
    stationary = trig_roots(n, 1j * n * p, np.zeros(1))[0]
    theta = np.concatenate([stationary[~np.isnan(stationary)], period_grid(int(n.max()), 16)])
    x = np.sum((p[None, :] * np.exp(1j * n[None, :] * theta[:, None])).imag, axis=1)
    return float(np.max(np.abs(x)))


def _others_nodes(peak: float, n_max: int, amplitudes: FloatArray, sigma: float) -> int:
    """Grid size over the group's period for the smooth mean of the other components."""
    if sigma > 0:
        swing = peak + float(np.sum(amplitudes))
        need = 1.25 * n_max * (8.0 * peak / sigma + (swing + peak) * peak / sigma**2) + 64
        return int(min(max(need, 64), 1 << 14))
    return 1 << 14


def locked_rectified_excess(
    omega: ArrayLike,
    group: LockedGroup,
    amplitudes: ArrayLike = (),
    sigma: float = 0.0,
) -> FloatArray:
    """``E(Ω) = <|Ω + x3|> − |Ω|`` for one locked group plus independent parts.

    ``omega``: any shape (rate); ``amplitudes``: x3 amplitudes of independent
    tones (K,); ``sigma``: the Gaussian part's σ3. Group alone: exact
    (:func:`locked_abs_excess`). Otherwise, with Y the other components and
    F(s) = <|s + Y|> (smooth in s when σ > 0), the mean over the period of
    F(Ω + x3(θ)) on a uniform grid (geometric convergence): where Ω + x3
    crosses 0 as ``mean F − |Ω|``; where it does not, as the mean of
    ``rectified_excess(Ω + x3(θ))`` (no cancellation). (Adding the exact
    group-alone mean to a grid mean of the others' excess would not do: each
    of the two has a kink where Ω + x3 = 0, only their sum is smooth.) With
    tones only the arcsine kernel's edges make convergence algebraic: 2^14
    nodes give ~1e-8 relative for one other tone. Cost: the nodes times the
    cost of one ``rectified_excess`` point, which is large for two or more
    independent tones with a narrow Gaussian part.
    """
    w = np.asarray(omega, dtype=float)
    a = np.asarray(amplitudes, dtype=float).reshape(-1)
    a = a[a > 0]
    n, p = _x3_coefficients(group)
    if n.size == 0:
        return rectified_excess(w.ravel(), a, sigma).reshape(w.shape)
    if a.size == 0 and sigma <= 0:
        return locked_abs_excess(w, n, p)
    peak = locked_peak(n, p)
    m = _others_nodes(peak, int(n.max()), a, sigma)
    theta = 2.0 * math.pi * (np.arange(m) + 0.5) / m
    x3 = np.sum((p[None, :] * np.exp(1j * n[None, :] * theta[:, None])).imag, axis=1)
    out = waveform_mean(w.ravel(), x3, peak,
                        lambda s: rectified_excess(s.ravel(), a, sigma).reshape(s.shape))
    return out.reshape(w.shape)


def waveform_mean(rates: FloatArray, x3: FloatArray, peak: float,
                  excess: Callable[[FloatArray], FloatArray],
                  label: str | None = "E(Ω) of locked harmonics") -> FloatArray:
    """Per rate Ω (R,), the mean over a locked waveform's nodes ``x3`` (M,) of the smooth
    F(Ω + x3) = E_Y(Ω + x3) + |Ω + x3|, less |Ω|: computed so where Ω + x3 can cross 0
    (|Ω| < ``peak``), as the mean of E_Y (no cancellation) where it cannot. ``excess``
    gives E_Y on an (R, M) array; rates a block at a time (memory bounded whatever the
    sweep), each block's progress reported under ``label`` (None: not reported)."""
    out: FloatArray = np.empty(rates.size)
    step = max(1, (1 << 20) // x3.size)
    for lo in range(0, rates.size, step):
        if label is not None:
            advance(label, lo, rates.size)
        part = rates[lo:lo + step]
        s = part[:, None] + x3[None, :]
        e = excess(s)
        inside = np.mean(e + np.abs(s), axis=1) - np.abs(part)
        out[lo:lo + step] = np.where(np.abs(part) < peak, inside, np.mean(e, axis=1))
    if label is not None:
        advance(label, rates.size, rates.size)
    return out
