"""A ``phase: worst`` search's objective at many candidate phases in one array operation
(docs/model.md section 10).

:func:`gyrovib.core.analysis.profile_multipliers` evaluates one set of phases at a
time: per call it finds the groups' peaks (an eigenvalue problem each), picks node
counts from them, folds the smaller groups into the table of E_Y and averages the
largest group over its period. A search asks for thousands of phase points; here
everything that does not depend on the phases is done once per profile, and the
rest is broadcast over the candidates:

* the moments M2…M5, C31, C32 of each group (cumulants add across the independent
  tones, Gaussian part and groups) from the groups' phasors (C, N, 3) at once;
* E(Ω) = <F_Y'(Ω + x3(θ))>_θ − |Ω| for the group on the midpoint grid, with
  F = E + |·| and Y' the tones, the Gaussian part and the folded groups
  (:func:`gyrovib.core.harmonic_mixtures.locked_mixture_excess`), as one (C, m)
  interpolation. Node counts and the choice of the group on the grid come from
  the phase-free bound Σ|a_n| of each group's peak (never fewer nodes than the
  per-phase rule: the midpoint rule only converges further), so that every
  candidate shares one grid;
* the folded groups' table is built only on the window of c the grid group can
  reach from each rate (|c − Ω| ≤ its bound, plus the interpolation stencil), once
  per (phases of the folded groups, rate) and kept: a search moves one offset at
  a time, so most candidates share their folded groups' phases.

The values agree with the one-at-a-time path to the interpolation's precision
(~1e-12 relative); the search reports its result on that path
(:func:`gyrovib.core.phases.worst_phase_errors`). Profiles outside the mixture
route (no Gaussian part on the sensitive axis, a tone table too large) have no
batched form: :func:`batched` returns None and the search evaluates one point at a
time.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gyrovib.core._types import FloatArray
from gyrovib.core.analysis import Multipliers
from gyrovib.core.harmonic_mixtures import (
    _STENCIL,
    MAX_SHIFT_TABLE,
    _cached_table,
    _horner,
    _interpolate,
    _lagrange_to_power,
    table_size,
)
from gyrovib.core.harmonics import LockedGroup, combine_moments, group_signal, period_grid
from gyrovib.core.statistics import Vibration

#: Folded tables kept per batched profile (each a window of a few hundred values).
MAX_KEPT_FOLDS = 4096
#: Grid points evaluated at a time (rows × nodes): temporaries of 512 kB.
_BLOCK = 1 << 16


@dataclass(frozen=True)
class _Part:
    """One group as the batch sees it: its orders, base phasors (N, 3), the offsets it
    takes from the search's ψ (index into ψ per order, −1: none) and its phase-free
    bound on |x3| (Σ|a_n| on axis 3)."""

    orders: NDArray[np.int64]
    phasors: NDArray[np.complex128]
    take: NDArray[np.intp]
    bound: float

    def phasors_at(self, psi: FloatArray) -> NDArray[np.complex128]:
        """(C, N, 3) phasors at the offsets ``psi`` (C, D)."""
        offsets = np.zeros((psi.shape[0], self.orders.size))
        moved = self.take >= 0
        offsets[:, moved] = psi[:, self.take[moved]]
        out: NDArray[np.complex128] = self.phasors[None] * np.exp(1j * offsets)[:, :, None]
        return out


def _nodes(n_max: int, peak: float, swing: float, sigma: float) -> int:
    """The midpoint nodes of :func:`gyrovib.core.harmonic_mixtures.mixture_nodes` for a
    group of bound ``peak`` in a swing ``swing`` (both phase-free bounds)."""
    if peak <= 0:
        return 1
    need = 1.25 * n_max * (8.0 * peak / sigma + (swing + peak) * peak / sigma**2) + 64
    return int(min(max(need, 64), 1 << 14))


def _window(c_low: float, c_high: float, h: float) -> tuple[int, int]:
    """Table indices k (c = k·h) covering [c_low, c_high] with the 8-point stencil centred
    on every interval used, and at least 8 values on each side of 0 when it is crossed."""
    lo = math.floor(c_low / h) - _STENCIL // 2
    hi = math.ceil(c_high / h) + _STENCIL // 2 + 1
    if lo < 0 < hi:
        lo, hi = min(lo, -_STENCIL), max(hi, _STENCIL)
    if hi - lo + 1 < _STENCIL:
        hi = lo + _STENCIL - 1
    return lo, hi


def _polynomials(log: FloatArray) -> FloatArray:
    """:func:`gyrovib.core.harmonic_mixtures._interval_polynomials` (the same stencils and
    basis), the products by einsum: a window is short, and a BLAS call per fold would wake
    its threads."""
    intervals = log.size - 1
    base = np.clip(np.arange(intervals) - (_STENCIL // 2 - 1), 0, log.size - _STENCIL)
    offset = np.arange(intervals) - base
    windows = log[base[:, None] + np.arange(_STENCIL)[None, :]]
    coef = np.empty((_STENCIL, intervals))
    for d in np.unique(offset).tolist():
        rows = offset == d
        coef[:, rows] = np.einsum("pj,ij->pi", _lagrange_to_power(int(d)), windows[rows])
    return coef


def _window_polynomials(log: FloatArray, lo: int) -> FloatArray:
    """Per-interval polynomials of a window starting at index ``lo``; split at c = 0
    (E has a kink there) when the window holds it."""
    if lo < 0 < lo + log.size - 1:
        zero = -lo
        out: FloatArray = np.concatenate([_polynomials(log[:zero + 1]),
                                          _polynomials(log[zero:])], axis=1)
        return out
    return _polynomials(log)


class BatchedProfile:
    """One vibration and its locked groups, evaluated at many offsets ψ and rates at once.

    ``free``: (group, order index) of each searched offset (as
    :func:`gyrovib.core.phases.free_offsets`); ``acceleration``: the six moments of a
    linear vibration, or None.
    """

    def __init__(self, vibration: Vibration, groups: Sequence[LockedGroup],
                 free: Sequence[tuple[int, int]], acceleration: ArrayLike | None) -> None:
        self.vibration = vibration
        self.acceleration = None if acceleration is None else np.asarray(acceleration, float)
        a = vibration.tone_amplitudes
        self.tone_parts = (np.sum(a**2 / 2.0), np.sum(3.0 * a**4 / 8.0))
        amps = np.asarray(a, dtype=float).reshape(-1)
        self.amplitudes = np.sort(amps[amps > 0])[::-1]
        self.sigma = float(vibration.sigma[2])
        self.parts = []
        for g_index, g in enumerate(groups):
            take = np.full(g.orders.size, -1, dtype=np.intp)
            for d, (gi, oi) in enumerate(free):
                if gi == g_index:
                    take[oi] = d
            bound = float(np.sum(np.abs(g.phasors[:, 2])))
            self.parts.append(_Part(g.orders, g.phasors, take, bound))
        with_x3 = [p for p in self.parts if p.bound > 0]
        swing = sum(p.bound for p in with_x3) + float(np.sum(self.amplitudes))
        nodes = [_nodes(int(p.orders.max()), p.bound, swing, self.sigma) for p in with_x3]
        order = sorted(range(len(with_x3)), key=lambda k: -nodes[k])
        self.live = with_x3[order[0]] if with_x3 else None
        self.live_nodes = nodes[order[0]] if with_x3 else 1
        self.folded = [(with_x3[k], nodes[k]) for k in order[1:]]
        self.h, self.reach, self.base = _cached_table(self.amplitudes, self.sigma)
        self._folds: dict[tuple[bytes, float], tuple[int, FloatArray]] = {}
        m = self.live_nodes
        theta = 2.0 * math.pi * (np.arange(m) + 0.5) / m
        angles = (np.asarray(self.live.orders, float)[:, None] * theta[None, :]
                  if self.live is not None else None)
        self._live_basis = None if angles is None else (np.sin(angles), np.cos(angles))
        self._moment_grids = [np.exp(1j * p.orders.astype(float)[:, None]
                                     * period_grid(int(p.orders.max()))[None, :])
                              for p in self.parts]

    def folded_offsets(self) -> list[int]:
        """The searched offsets that move a folded group (each value costs a table)."""
        return sorted({int(d) for part, _ in self.folded for d in part.take if d >= 0})

    # ------------------------------------------------------------------ moments

    def _moments(self, psi: FloatArray) -> tuple[FloatArray, ...]:
        """M2…M5, C31, C32 at each row of ``psi`` (each (C,))."""
        a2, a4 = self.tone_parts
        s3 = self.sigma
        p2: list[ArrayLike] = [a2, s3**2]
        p3: list[ArrayLike] = [0.0, 0.0]
        p4: list[ArrayLike] = [a4, 3.0 * s3**4]
        p5: list[ArrayLike] = [0.0, 0.0]
        c31 = self.vibration.cross(1) + np.zeros(psi.shape[0])
        c32 = self.vibration.cross(2) + np.zeros(psi.shape[0])
        for part, grid in zip(self.parts, self._moment_grids, strict=True):
            p = part.phasors_at(psi)                                   # (C, N, 3)
            x = np.einsum("cna,nt->cat", p, grid).imag                 # (C, 3, T)
            x3 = x[:, 2, :]
            sq = x3 * x3
            p2.append(sq.mean(axis=-1))
            p3.append((sq * x3).mean(axis=-1))
            p4.append((sq * sq).mean(axis=-1))
            p5.append((sq * sq * x3).mean(axis=-1))
            c31 = c31 + (x3 * x[:, 0, :]).mean(axis=-1)
            c32 = c32 + (x3 * x[:, 1, :]).mean(axis=-1)
        m2, m3, m4, m5 = combine_moments(p2, p3, p4, p5)
        ones = np.ones(psi.shape[0])
        return m2 * ones, m3 * ones, m4 * ones, m5 * ones, c31, c32

    # ------------------------------------------------------------------- E(Ω)

    def _fold(self, psi_row: FloatArray, omega: float) -> tuple[int, FloatArray]:
        """The table of log E_Y' (Y' = Y + the folded groups at ``psi_row``) on the window
        the grid group reaches from ``omega``: its first index and its polynomials."""
        key = (np.asarray(psi_row, float)[self.folded_offsets()].tobytes(), float(omega))
        hit = self._folds.get(key)
        if hit is not None:
            return hit
        h = self.h
        live = self.live.bound if self.live is not None else 0.0
        later = sum(p.bound for p, _ in self.folded)
        start, coef = 0, self.base
        for step, (part, m) in enumerate(self.folded):
            later -= part.bound
            lo, hi = _window(omega - live - later, omega + live + later, h)
            c: FloatArray = h * np.arange(lo, hi + 1, dtype=float)
            theta = 2.0 * math.pi * (np.arange(m) + 0.5) / m
            phasors = part.phasors_at(np.asarray(psi_row, float)[None, :])[0]
            y = group_signal(part.orders, phasors[:, 2:3], theta)[0]       # (m,)
            s = c[:, None] + y[None, :]
            # the first fold reads E_Y from the tones' and Gaussian part's own table
            e_s = (_interpolate(s, h, self.reach, self.base) if step == 0
                   else self._signed(s, start, coef))
            inside = np.mean(e_s + np.abs(s), axis=1) - np.abs(c)
            new = np.where(np.abs(c) < part.bound, inside, np.mean(e_s, axis=1))
            coef = _window_polynomials(np.log(np.maximum(new, 1e-300)), lo)
            start = lo
        if len(self._folds) >= MAX_KEPT_FOLDS:
            self._folds.pop(next(iter(self._folds)))
        self._folds[key] = (start, coef)
        return start, coef

    def _signed(self, c: FloatArray, start: int, coef: FloatArray) -> FloatArray:
        """E at ``c`` from a window table starting at index ``start`` (0 past the reach,
        where E underflows)."""
        c = np.asarray(c, dtype=float)
        x = c / self.h
        x -= start
        np.maximum(x, 0.0, out=x)
        out = _horner(x, coef)
        np.exp(out, out=out)
        far = np.abs(c) >= self.reach
        if far.any():
            out[far] = 0.0
        return out

    def _excess(self, psi: FloatArray, omega: FloatArray) -> FloatArray:
        """E(Ω) of each row of ``psi`` at its rate ``omega`` (C,): rows sharing their
        folded groups' offsets and rate on one table, a few at a time (each block's
        temporaries stay small enough for the cache)."""
        out = np.zeros(psi.shape[0])
        if self.live is None:
            out[:] = _interpolate(omega, self.h, self.reach, self.base)
            return out
        if self.folded:
            keys = np.concatenate([psi[:, self.folded_offsets()], omega[:, None]], axis=1)
            _, inverse, counts = np.unique(keys, axis=0, return_inverse=True,
                                           return_counts=True)
            order = np.argsort(inverse.reshape(-1), kind="stable")
            sets = np.split(order, np.cumsum(counts)[:-1])
        else:
            sets = [np.arange(psi.shape[0])]
        step = max(1, _BLOCK // self.live_nodes)
        for rows in sets:
            table = (self._fold(psi[rows[0]], float(omega[rows[0]])) if self.folded
                     else None)
            for lo in range(0, rows.size, step):
                part = rows[lo:lo + step]
                out[part] = self._block_excess(psi[part], omega[part], table)
        return out

    def _block_excess(self, psi: FloatArray, omega: FloatArray,
                      table: tuple[int, FloatArray] | None) -> FloatArray:
        """E(Ω) of a few rows on the folded ``table`` (None: the table of E_Y itself)."""
        assert self.live is not None and self._live_basis is not None
        p = self.live.phasors_at(psi)[:, :, 2]                              # (C, N)
        # Im(p·e^{jnθ}) = Re p·sin nθ + Im p·cos nθ, by einsum's own loops: a BLAS call
        # per block would wake its threads, about 10 ms each on a loaded machine
        sin, cos = self._live_basis
        s = np.einsum("cn,nm->cm", np.ascontiguousarray(p.real), sin)        # (C, m)
        s += np.einsum("cn,nm->cm", np.ascontiguousarray(p.imag), cos)
        s += omega[:, None]
        if table is None:
            e = _interpolate(s, self.h, self.reach, self.base)
        else:
            e = self._signed(s, *table)
        mean_e: FloatArray = np.mean(e, axis=1)
        crossing = np.abs(omega) < self.live.bound
        if not crossing.any():
            return mean_e
        inside = np.mean(e + np.abs(s), axis=1) - np.abs(omega)
        out: FloatArray = np.where(crossing, inside, mean_e)
        return out

    def multipliers(self, psi: ArrayLike, omega: ArrayLike) -> Multipliers:
        """The multipliers at each row of ``psi`` (C, D) and its rate ``omega`` (C,)."""
        x = np.atleast_2d(np.asarray(psi, dtype=float))
        w = np.broadcast_to(np.asarray(omega, dtype=float), (x.shape[0],)).copy()
        m2, m3, m4, m5, c31, c32 = self._moments(x)
        asym = 0.5 * self._excess(x, w)
        acc = None if self.acceleration is None else np.broadcast_to(
            self.acceleration, (x.shape[0], 6)).copy()
        return Multipliers(asymmetry=asym, m2=m2, m4=m4, c31=c31, c32=c32, omega=w,
                           m3=m3, m5=m5, acceleration=acc)


def batched(vibration: Vibration, groups: Sequence[LockedGroup],
            free: Sequence[tuple[int, int]], acceleration: ArrayLike | None
            ) -> BatchedProfile | None:
    """The batched form of a profile, where the one-at-a-time path takes the mixture
    route (a Gaussian part on the sensitive axis, and more than one group or a tone table
    within :data:`~gyrovib.core.harmonic_mixtures.MAX_SHIFT_TABLE`); else None."""
    a = vibration.tone_amplitudes
    s3 = float(vibration.sigma[2])
    if not groups or s3 <= 0:
        return None
    if not (len(groups) > 1 or (a.size and table_size(a, s3) <= MAX_SHIFT_TABLE)):
        return None
    if table_size(a, s3) > MAX_SHIFT_TABLE:
        return None
    return BatchedProfile(vibration, groups, free, acceleration)
